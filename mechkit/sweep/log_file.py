"""A sweep's log file: while a sweep runs, the records of distributed's (and tornado's, asyncio's,
bokeh's, mechkit's) loggers and Python's warnings go to a file in the results folder instead of the
terminal, followed by the traceback of whatever stopped the sweep."""

from __future__ import annotations

import logging
import warnings
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

#: The log file of a sweep, in its results folder.
LOG = "sweep.log"
#: The loggers whose records go to the file.
LOGGERS = ("distributed", "tornado", "asyncio", "bokeh", "mechkit", "py.warnings")


@contextmanager
def log_to(path: str | Path) -> Iterator[Path]:
    """Send the records of distributed's, tornado's, asyncio's, bokeh's and mechkit's loggers to a file.

    For the duration, those loggers write to `path` (appended) instead of their handlers (distributed
    installs one on stderr), and so do Python's warnings (distributed warns, e.g., when the dashboard's
    port is taken); an exception leaving the block is written there with its traceback before it goes
    on. The handlers and the warnings' destination are restored afterwards.

    Args:
        path: the log file.

    Returns:
        A context manager giving the log file's path.
    """
    import dask
    import distributed  # noqa: F401  (registers its configuration, the log format among it)

    path = Path(path)
    handler = logging.FileHandler(path, delay=True)
    handler.setFormatter(logging.Formatter(dask.config.get("distributed.admin.log-format")))
    names = {n for n in logging.root.manager.loggerDict if n.split(".")[0] in LOGGERS} | set(LOGGERS)
    loggers = [logging.getLogger(n) for n in sorted(names)]
    saved = [(lg, lg.handlers[:], lg.propagate) for lg in loggers if lg.handlers or lg.name in LOGGERS]
    for lg, _, _ in saved:
        lg.handlers, lg.propagate = [handler], False
    try:
        with warnings.catch_warnings():  # restores warnings.showwarning on leaving
            warnings.showwarning = _log_warning
            yield path
    except BaseException:
        logging.getLogger("mechkit.sweep").exception("the sweep stopped")
        raise
    finally:
        for lg, handlers, propagate in saved:
            lg.handlers, lg.propagate = handlers, propagate
        handler.close()


def _log_warning(
    message: Warning | str,
    category: type[Warning],
    filename: str,
    lineno: int,
    file: object = None,
    line: str | None = None,
) -> None:
    """A `warnings.showwarning` that writes the warning to the "py.warnings" logger."""
    logging.getLogger("py.warnings").warning("%s", warnings.formatwarning(message, category, filename, lineno, line))
