"""Loading a mechanism from a file against loading the same mechanism by its registered name.

For each mechanism, `load_times` writes the same linkage as files (`file_versions`: a URDF with its
loops, `<transmission>`s and `<mechkit:home>`; an Extended URDF with its sidecar; mechkit's MJCF)
and times, interleaved in one process, `mechkit.load(name)` and `mechkit.load(path)` for each file
(warm: after one untimed load of each, so imports and the xacro cache of the name are warm; the
file readers parse, check and analyse the file every time). Same mechanism, same size: the ratio
is the cost of the file route.
"""

from __future__ import annotations

import tempfile
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from mechkit.export import to_extended_urdf, to_mjcf
from mechkit.loading import load
from mechkit.mechanism import Mechanism

NAMES = ("four_bar", "parallel_2t1r", "tetra_3rr3uru")


@dataclass(frozen=True)
class LoadTime:
    """Warm load times of one mechanism by one route.

    Attributes:
        name: the registered mechanism; route: "name", "urdf", "extended-urdf" or "mjcf".
        nv: its joint velocities; loops: its cuts.
        median_s: median wall time (s) of `mechkit.load`; ratio: median_s / the name's median_s.
    """

    name: str
    route: str
    nv: int
    loops: int
    median_s: float
    ratio: float


def file_versions(mech: Mechanism, folder: Path) -> dict[str, tuple[Path, dict[str, Any]]]:
    """The mechanism written as files in `folder`: route -> (path, keyword arguments of `load`).

    Args:
        mech: the mechanism.
        folder: where the files go.

    Returns:
        Route ("urdf", "extended-urdf", "mjcf") -> (the file, the keyword arguments `load` needs for it: a guess
            and the home inputs, for the URDFs).
    """
    guess = mech.joint_values(mech.home_q)
    home = {j: guess[j] for j in mech.actuated}
    extra = "".join(
        f'<transmission name="{j}_motor"><joint name="{j}"/></transmission>'
        f'<mechkit:home joint="{j}" value="{float(v)!r}"/>'
        for j, v in home.items()
    )
    (folder / "loops.urdf").write_text(mech.urdf.replace("</robot>", extra + "</robot>"))
    (folder / "ext").mkdir(exist_ok=True)
    urdf, sidecar = to_extended_urdf(mech)
    (folder / "ext" / "tree.urdf").write_text(urdf)
    (folder / "ext" / "tree.yaml").write_text(sidecar)
    (folder / "model.xml").write_text(to_mjcf(mech))
    return {
        "urdf": (folder / "loops.urdf", {"guess": guess}),
        "extended-urdf": (folder / "ext" / "tree.urdf", {"home": home, "guess": guess}),
        "mjcf": (folder / "model.xml", {}),
    }


def load_times(names: tuple[str, ...] = NAMES, repeats: int = 7) -> list[LoadTime]:
    """Median warm load times by name and by each file route (see the module docstring).

    Args:
        names: the registered mechanisms.
        repeats: timed loads per route.

    Returns:
        One row per mechanism and route (by name first), with its median load time (s) and its ratio to the load
            by name.
    """
    out = []
    for name in names:
        mech = load(name)
        with tempfile.TemporaryDirectory() as tmp:
            routes: dict[str, tuple[Any, dict[str, Any]]] = {"name": (name, {})} | file_versions(mech, Path(tmp))
            for source, kwargs in routes.values():
                load(source, **kwargs)  # untimed: imports, caches
            samples: dict[str, list[float]] = {route: [] for route in routes}
            for _ in range(repeats):
                for route, (source, kwargs) in routes.items():
                    start = time.perf_counter()
                    load(source, **kwargs)
                    samples[route].append(time.perf_counter() - start)
        base = float(np.median(samples["name"]))
        for route, times in samples.items():
            median = float(np.median(times))
            out.append(LoadTime(name, route, mech.model.nv, len(mech.closures), median, median / base))
    return out


def lines(rows: list[LoadTime]) -> list[str]:
    """A markdown table of the rows.

    Args:
        rows: the load times.

    Returns:
        Markdown lines.
    """
    table = ["| mechanism | nv | loops | route | median load (ms) | / by name |", "|---|---|---|---|---|---|"]
    table += [f"| {r.name} | {r.nv} | {r.loops} | {r.route} | {r.median_s * 1e3:.2f} | {r.ratio:.2f} |" for r in rows]
    return table
