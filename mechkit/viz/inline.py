"""Mechanisms in Jupyter: inline static views (a pose, or a scene playing), no server.

`show(mechanism, q=None, scene=None)` returns an `InlineView`, which a notebook displays as the
self-contained meshcat page of `mechkit.viz.pages` in a frame (it also works in a notebook saved and
opened offline). `register()` makes a `Mechanism` display the same way as a cell's result: `Mechanism`
is core and knows nothing of drawing, so its rich display is added here, by IPython's formatter for the
class, rather than as a `_repr_html_` method. For a live view that updates, see `mechkit.viz.live`.
"""

from __future__ import annotations

from html import escape
from typing import Any

import numpy as np

from mechkit.base.exceptions import InvalidParameters
from mechkit.mechanism import Mechanism
from mechkit.viz.meshes import MeshSearch
from mechkit.viz.pages import animation, snapshot

HEIGHT = 420  # px, height of the frame in the notebook


class InlineView:
    """A self-contained page shown in a notebook cell's frame.

    Attributes:
        html: the page (`mechkit.viz.pages`), also writable to a file.
        height: the frame's height (px).
    """

    def __init__(self, html: str, height: int = HEIGHT) -> None:
        self.html, self.height = html, int(height)

    def _repr_html_(self) -> str:
        """The page in an iframe (its own document, so several views in one notebook do not clash)."""
        return (
            f'<iframe srcdoc="{escape(self.html, quote=True)}" style="width: 100%; height: {self.height}px; '
            f'border: 0" title="mechkit view"></iframe>'
        )


def show(
    mechanism: Mechanism,
    q: np.ndarray | None = None,
    scene: str | None = None,
    meshes: MeshSearch | None = None,
    height: int = HEIGHT,
) -> InlineView:
    """The mechanism at q (default: its home assembly), or one of its scenes playing, for a notebook.

    Args:
        mechanism: the mechanism.
        q: a configuration (size nq), assembled.
        scene: a scene name (`mechkit.scenes.scenes`), played ping-pong.
        meshes: where mesh files are looked for.
        height: the frame's height (px).

    Returns:
        The view (a notebook shows it as an iframe).

    Raises:
        InvalidParameters: both q and scene, or an unknown scene.
    """
    if q is not None and scene is not None:
        raise InvalidParameters("q", "given", "give either q (one pose) or scene (an animation), not both")
    if scene is not None:
        return InlineView(animation(mechanism, scene, meshes=meshes), height)
    return InlineView(snapshot(mechanism, q, meshes=meshes), height)


def register(shell: Any = None) -> bool:
    """Display every `Mechanism` that is a cell's result as its inline view (text stays `repr`).

    Args:
        shell: the IPython shell (default: the running one).

    Returns:
        Whether a shell was found and the display registered.
    """
    if shell is None:
        try:
            from IPython import get_ipython
        except ImportError:
            return False
        shell = get_ipython()
    if shell is None:
        return False
    shell.display_formatter.formatters["text/html"].for_type(Mechanism, lambda m: show(m)._repr_html_())
    return True
