"""matplotlib for files: pyplot on the Agg backend (no window), imported on use, with an install hint;
figures written atomically."""

from __future__ import annotations

import io
from pathlib import Path
from types import ModuleType
from typing import Any

from mechkit.base.atomic import write_bytes
from mechkit.base.exceptions import MethodUnavailable


def pyplot(what: str = "figures") -> ModuleType:
    """matplotlib.pyplot on the Agg backend.

    Args:
        what: what needs it, for the error message.

    Returns:
        The `matplotlib.pyplot` module.

    Raises:
        MethodUnavailable: matplotlib is not installed.
    """
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        raise MethodUnavailable(what, "matplotlib is not installed: pip install 'mechkit[bench]'") from None
    return plt


def figure_bytes(fig: Any, fmt: str, dpi: int = 90) -> bytes:
    """A figure rendered in memory.

    Args:
        fig: a matplotlib figure.
        fmt: "png", "svg", "pdf" (what matplotlib's savefig takes).
        dpi: resolution of a raster format, dots per inch.

    Returns:
        The file's bytes.
    """
    buffer = io.BytesIO()
    fig.savefig(buffer, format=fmt, dpi=dpi)
    return buffer.getvalue()


def save_figure(fig: Any, path: str | Path, dpi: int = 90, tight: bool = True) -> Path:
    """Lay the figure out, write it in the format its suffix names (none: PNG) atomically (creating the
    folder; `mechkit.base.atomic`), and close it.

    Args:
        fig: a matplotlib figure.
        path: the file to write.
        dpi: resolution of a raster format, dots per inch.
        tight: apply `tight_layout` first.

    Returns:
        The path written.

    Raises:
        OutputError: the file cannot be written.
    """
    try:
        if tight:
            fig.tight_layout()
        data = figure_bytes(fig, Path(path).suffix.lstrip(".").lower() or "png", dpi)
    finally:
        pyplot().close(fig)
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    return write_bytes(path, data)
