"""Shared helpers of the tests (not tests themselves): the repository's folders and fixture files, the
command line run in a subprocess, and the five-bar's singular inputs."""

from __future__ import annotations

import os
import subprocess
import sys
import sysconfig
from pathlib import Path

import numpy as np
from scipy.optimize import brentq

#: The repository's root (the checkout the tests run from).
ROOT = Path(__file__).resolve().parents[1]
#: The description files the tests read (tests/fixtures).
FIXTURES = ROOT / "tests" / "fixtures"
#: example-robot-data's robots, as its wheel installs them (a test dependency).
ROBOTS = Path(sysconfig.get_paths()["purelib"]) / "cmeel.prefix" / "share" / "example-robot-data" / "robots"
#: Franka's Panda: a tree with a mimic coupling on its fingers.
PANDA = ROBOTS / "panda_description" / "urdf" / "panda.urdf"
#: example-robot-data's Cassie SDFormat files.
CASSIE_SDF = ROBOTS / "cassie_description" / "robots"
#: cassie.sdf's two 1 g foot-reference rotors have an inertia no body can have (izz 9.4e-6 > ixx + iyy =
#: 1.88e-6 kg m^2): mechkit refuses the file; its kinematics tests read it with izz = 1.8e-6 (ours).
IMPOSSIBLE_IZZ, POSSIBLE_IZZ = "<izz>9.4e-6</izz>", "<izz>1.8e-6</izz>"


def physical_cassie_sdf(folder: Path) -> Path:
    """example-robot-data's cassie.sdf with its foot rotors' inertia made possible (`POSSIBLE_IZZ`), in folder."""
    out = folder / "cassie.sdf"
    out.write_text((CASSIE_SDF / "cassie.sdf").read_text().replace(IMPOSSIBLE_IZZ, POSSIBLE_IZZ))
    return out


#: The slider-crank fixture's URDF text (loops, transmission, home), which many bad-file tests alter.
SLIDER_CRANK = (FIXTURES / "slider_crank.urdf").read_text()

#: Distances (rad) from the five-bar's collinear input at which the singularity tests look.
DISTANCES = (0.0, 1e-14, 1e-12, 1e-11, 1e-10, 1e-9, 1e-8, 1e-6, 1e-4, 1e-2)


def singular_inputs(m) -> list[tuple[float, float]]:
    """prox2 angles (rad) where the five-bar's distal links are collinear at prox1 = 2.6, and the side
    (+1, -1) from which the assembly approaches each."""
    p = m.params
    b1 = p.prox1 * np.array([np.cos(2.6), np.sin(2.6)])

    def gap(t):
        return np.linalg.norm(np.array([p.ground + p.prox2 * np.cos(t), p.prox2 * np.sin(t)]) - b1) - (
            p.dist1 + p.dist2
        )

    return [(brentq(gap, -1.5, -0.5, xtol=1e-16), -1.0), (brentq(gap, 0.5, 1.0, xtol=1e-16), 1.0)]


def written(folder: Path, text: str, name: str = "bad.urdf") -> Path:
    """`text` written to `folder / name`; the path."""
    path = folder / name
    path.write_text(text)
    return path


def run_mechkit(*args: str, cwd: Path | None = None) -> subprocess.CompletedProcess:
    """`python -m mechkit ARGS` in a subprocess, on this checkout, its output captured (300 s at most)."""
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    return subprocess.run(
        [sys.executable, "-m", "mechkit", *args],
        capture_output=True,
        text=True,
        env=env,
        cwd=cwd,
        check=False,
        timeout=300,
    )


def refused(out: subprocess.CompletedProcess, *words: str) -> None:
    """A command-line refusal: exit status 2, one line on stderr starting "mechkit: error: " and naming every
    word, no traceback."""
    assert out.returncode == 2, out.stderr
    assert "Traceback" not in out.stderr and out.stderr.startswith("mechkit: error: ")
    assert len(out.stderr.strip().splitlines()) == 1, out.stderr
    for word in words:
        assert word in out.stderr, out.stderr
