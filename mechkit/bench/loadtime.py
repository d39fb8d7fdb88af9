"""First load of a mechanism in a fresh Python process, and which mechanism modules it imports.

`first_load` runs `import mechkit; mechkit.load(name)` in new interpreters (one untimed run first,
so that the bytecode cache is warm), and records per run the whole process's wall time (interpreter
start, imports, xacro, assembly), the time of the import and the load measured inside the process,
and the `mechkit.mechanisms.*` modules the process imported: the registry is lazy, so loading one
mechanism must import no other.
"""

from __future__ import annotations

import json
import subprocess
import sys
import time
from dataclasses import dataclass

import numpy as np

from mechkit.base.exceptions import MethodUnavailable
from mechkit.catalog.registry import entry, names

_SCRIPT = """\
import json, sys, time
start = time.perf_counter()
import mechkit
mechkit.load({name!r})
seconds = time.perf_counter() - start
modules = sorted(m for m in sys.modules if m.startswith("mechkit.mechanisms"))
print(json.dumps({{"seconds": seconds, "modules": modules}}))
"""


@dataclass(frozen=True)
class FirstLoad:
    """Fresh-process loads of one mechanism.

    Attributes:
        name: the mechanism loaded.
        process_s: wall time (s) of each timed process, as its parent sees it.
        inside_s: time (s) of `import mechkit` and `mechkit.load(name)` inside each process.
        modules: the `mechkit.mechanisms*` modules the (last) process imported, sorted.
        others: those of them that belong to another registered mechanism (should be none).
    """

    name: str
    process_s: tuple[float, ...]
    inside_s: tuple[float, ...]
    modules: tuple[str, ...]
    others: tuple[str, ...]


def quartiles(values: tuple[float, ...]) -> tuple[float, float, float]:
    """The median and the quartiles of some values.

    Args:
        values: the values.

    Returns:
        (median, 25th percentile, 75th percentile).
    """
    p25, median, p75 = np.percentile(values, [25, 50, 75])
    return float(median), float(p25), float(p75)


def _owner(module: str) -> str | None:
    """The registered mechanism whose package a `mechkit.mechanisms.*` module belongs to, if any."""
    for name in names():
        package = entry(name).package
        if module == package or module.startswith(package + "."):
            return name
    return None


def _one(name: str) -> tuple[float, float, list[str]]:
    start = time.perf_counter()
    done = subprocess.run(
        [sys.executable, "-c", _SCRIPT.format(name=name)], capture_output=True, text=True, check=False
    )
    wall = time.perf_counter() - start
    if done.returncode != 0:
        raise MethodUnavailable(
            "first load", f"python -c 'mechkit.load({name!r})' failed: {done.stderr.strip()[-300:]}"
        )
    found = json.loads(done.stdout.splitlines()[-1])
    return wall, float(found["seconds"]), list(found["modules"])


def first_load(name: str = "four_bar", runs: int = 5) -> FirstLoad:
    """Time `runs` fresh processes loading `name`, after one untimed run that warms the bytecode cache.

    Args:
        name: a registered mechanism.
        runs: timed processes.

    Returns:
        The wall times of the processes and the times inside them (s), the mechanism modules they imported, and
            those of other mechanisms (none expected).

    Raises:
        MethodUnavailable: a process failed (its stderr's end is in the message).
    """
    _one(name)
    process, inside, modules = [], [], []
    for _ in range(runs):
        wall, seconds, modules = _one(name)
        process.append(wall)
        inside.append(seconds)
    others = tuple(m for m in modules if _owner(m) not in (None, name))
    return FirstLoad(name, tuple(process), tuple(inside), tuple(modules), others)
