"""matplotlib for files: pyplot on the Agg backend (no window), imported on use, with an install hint."""

from __future__ import annotations

from pathlib import Path
from types import ModuleType
from typing import Any

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


def save_png(fig: Any, path: Path, dpi: int = 90) -> Path:
    """Lay the figure out tightly, write it as PNG (creating the folder) and close it.

    Args:
        fig: a matplotlib figure.
        path: the file to write.
        dpi: resolution, dots per inch.

    Returns:
        The path written.
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.tight_layout()
    fig.savefig(path, dpi=dpi)
    pyplot().close(fig)
    return path
