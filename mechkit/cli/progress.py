"""Progress bars of the long commands (bench, the gallery), drawn by tqdm on stderr.

`ProgressBars` is a `mechkit.bench.run.Progress` callback, `(label, done, total, what)`: one bar per
label (a mechanism), advanced to `done` of `total` with `what` (the step just finished) beside it,
closed at `total`. Shown only on a terminal or when MECHKIT_PROGRESS=1, so logs and pipes stay clean.
"""

from __future__ import annotations

import os
import sys
from typing import TextIO

from tqdm import tqdm


def wanted(stream: TextIO | None = None) -> bool:
    """Whether to draw: `stream` (default stderr) is a terminal, or MECHKIT_PROGRESS=1.

    Args:
        stream: where the bars go (default stderr).

    Returns:
        Whether to draw.
    """
    return (stream or sys.stderr).isatty() or os.environ.get("MECHKIT_PROGRESS") == "1"


class ProgressBars:
    """One tqdm bar per label, on stderr; a `(label, done, total, what)` callback.

    Args:
        enabled: draw the bars (default: `wanted()`).
    """

    def __init__(self, enabled: bool | None = None) -> None:
        self.enabled = wanted() if enabled is None else enabled
        self._bars: dict[str, tqdm] = {}

    def __call__(self, label: str, done: int, total: int, what: str = "") -> None:
        """Advance `label`'s bar to `done` of `total` steps; `what` names the step just finished."""
        if not self.enabled:
            return
        bar = self._bars.get(label)
        if bar is None:
            bar = self._bars[label] = tqdm(total=total, desc=label, file=sys.stderr, leave=True, dynamic_ncols=True)
        bar.total = total
        bar.update(done - bar.n)
        bar.set_postfix_str(what[:40], refresh=True)
        if done >= total:
            bar.close()
            del self._bars[label]
