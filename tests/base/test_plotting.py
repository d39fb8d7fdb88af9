"""Figures for files (`mechkit.base.plotting`): the format by suffix, written atomically, always closed."""

from __future__ import annotations

import pytest

from mechkit.base.plotting import pyplot, save_figure


def _figure():
    plt = pyplot()
    fig, ax = plt.subplots()
    ax.plot([0, 1], [1, 0])
    return plt, fig


@pytest.mark.parametrize(("name", "head"), [("a.png", b"\x89PNG"), ("a.svg", b"<?xml"), ("a.pdf", b"%PDF")])
def test_the_suffix_names_the_format_and_the_folder_is_made(tmp_path, name, head):
    plt, fig = _figure()
    path = save_figure(fig, tmp_path / "new" / name)
    assert path.read_bytes().startswith(head)
    assert fig.number not in plt.get_fignums()


def test_a_failed_render_leaves_the_old_file_whole_and_the_figure_closed(tmp_path):
    """matplotlib fails before a byte is written (here an unknown format): the file already there keeps
    its content, no temporary file is left, and the figure does not leak."""
    old = tmp_path / "chart.xyz"
    old.write_bytes(b"the user's")
    plt, fig = _figure()
    with pytest.raises(ValueError, match="xyz"):
        save_figure(fig, old)
    assert old.read_bytes() == b"the user's" and sorted(p.name for p in tmp_path.iterdir()) == ["chart.xyz"]
    assert fig.number not in plt.get_fignums()
