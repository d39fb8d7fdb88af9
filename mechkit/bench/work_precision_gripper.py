"""The field robot of the work-precision page: the Robotiq 2F-85 gripper of MuJoCo Menagerie, the same
model in mechkit and in MuJoCo.

Both read one copy of the Menagerie file (`stripped_file`) with its actuator removed: `fingers_actuator`,
a position servo on the tendon `split` (kp 100, kv 10 through its affine bias), has no counterpart in
mechkit's free motion. Everything else is the file's: the armature (0.005 on the drivers, 0.001 on the
other joints), the joint damping (0.1 on the drivers, 0.00125 on the spring links) and the spring links'
springs (stiffness 0.05, springref 2.62), the two connect closures and the drivers' joint equality, the
mesh-inferred inertia of the silicone pads. The file has no frictionloss. MuJoCo runs it with contacts
and joint limits disabled (mechkit: no contact, `limits=None`); its equalities at the file's own
solref/solimp ("file") or at the export's stiff rule (`stiff_equality`).

`same_model` checks, before any timing, that the two codes hold the same model: at the initial state
(home, at rest) the rigid accelerations solved on MuJoCo's own mass matrix, bias, passive forces and
constraint Jacobian against mechkit's forward dynamics, and MuJoCo's soft accelerations at both settings.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path
from typing import Any

import numpy as np

from mechkit.export.mjcf import SOLIMP, SOLREF_DIVISOR, smallest_link_period
from mechkit.loading import load
from mechkit.mechanism import Mechanism

#: The Menagerie file, relative to the repository's tests/fixtures/field folder.
GRIPPER = Path("menagerie") / "robotiq_2f85" / "2f85.xml"
#: What the copy leaves out, in words (the page states it).
STRIPPED = (
    "its actuator `fingers_actuator` removed (a position servo on the tendon `split`: gain 0.3137, bias "
    "-100 q - 10 v); MuJoCo's contacts and joint limits disabled (mechkit: no contact, `limits=None`); "
    "armature, joint damping, the spring links' springs, the closures and the drivers' coupling kept as the "
    "file writes them (the file has no frictionloss)"
)

#: The motion, in words.
MOTION = (
    "The motion: released at rest at the file's qpos0 (every joint 0: the drivers at the open end of their "
    "0-0.8 rad range) under gravity and the spring links' preloaded springs (springref 2.62 rad): the damped "
    "fingers close, the followers swinging past their +-0.87 rad range (limits off)."
)


def stripped_file(fixtures: Path, folder: Path) -> Path:
    """Write the gripper's file without its actuator, its meshes read from the original's folder.

    Args:
        fixtures: the repository's tests/fixtures/field folder.
        folder: an existing folder to write the copy in.

    Returns:
        The copy's path (`folder`/2f85.xml).
    """
    original = (fixtures / GRIPPER).resolve()
    root = ET.parse(original).getroot()
    root.find("compiler").set("meshdir", str(original.parent / "assets"))
    for actuator in root.findall("actuator"):
        root.remove(actuator)
    path = folder / original.name
    path.write_text(ET.tostring(root, encoding="unicode"))
    return path


def stiff_equality(mech: Mechanism) -> tuple[list[float], list[float]]:
    """The export's stiff equality settings for a mechanism (`mechkit.export.mjcf`: solref = its smallest link
    period / `SOLREF_DIVISOR`, critically damped; solimp `SOLIMP`).

    Args:
        mech: the mechanism.

    Returns:
        (solref, solimp).
    """
    return [smallest_link_period(mech.model) / SOLREF_DIVISOR, 1.0], list(SOLIMP)


def mujoco_model(xml: str, equality: tuple[list[float], list[float]] | None = None) -> Any:
    """MuJoCo's model of an MJCF text, contacts and joint limits disabled.

    Args:
        xml: the MJCF text (meshes at absolute paths).
        equality: (solref, solimp) for every equality, or None: as written.

    Returns:
        The `mujoco.MjModel`.
    """
    import mujoco

    model = mujoco.MjModel.from_xml_string(xml)
    model.opt.disableflags |= mujoco.mjtDisableBit.mjDSBL_CONTACT | mujoco.mjtDisableBit.mjDSBL_LIMIT
    if equality is not None:
        model.eq_solref[:], model.eq_solimp[:] = equality
    return model


def same_model(mech: Mechanism, xml: str) -> dict[str, float]:
    """The initial accelerations (home, at rest) of mechkit and MuJoCo on the same file.

    Args:
        mech: the mechanism read from the file.
        xml: the file's MJCF text.

    Returns:
        The largest difference from mechkit's accelerations relative to their largest: "rigid" (the rigid
        solve M a + J^T f = passive - bias, J a = 0 on MuJoCo's own matrices; least squares: the out-of-plane
        connect rows are redundant), "file" and "stiff" (MuJoCo's soft `qacc` at the file's settings and at
        `stiff_equality`).
    """
    import mujoco

    nv = mech.model.nv
    ours = mech.forward_dynamics(mech.home_q, np.zeros(nv), np.zeros(nv), method="kkt").a
    out = {}
    for label, equality in (("file", None), ("stiff", stiff_equality(mech))):
        model = mujoco_model(xml, equality)
        data = mujoco.MjData(model)
        data.qpos[:] = mech.home_q
        mujoco.mj_forward(model, data)
        out[label] = float(np.max(np.abs(data.qacc - ours)) / np.max(np.abs(ours)))
    mass = np.zeros((nv, nv))
    mujoco.mj_fullM(model, data, mass)
    jac = data.efc_J.reshape(data.nefc, nv)
    kkt = np.block([[mass, jac.T], [jac, np.zeros((len(jac), len(jac)))]])
    rhs = np.r_[data.qfrc_passive - data.qfrc_bias, np.zeros(len(jac))]
    rigid = np.linalg.lstsq(kkt, rhs, rcond=None)[0][:nv]
    out["rigid"] = float(np.max(np.abs(rigid - ours)) / np.max(np.abs(ours)))
    return out


def case(fixtures: Path, folder: Path) -> tuple[Mechanism, str, dict[str, Any], dict[str, Any], tuple[str, ...]]:
    """The gripper as a work-precision problem: its stripped file read by both codes, MuJoCo at the export's
    stiff rule and at the file's own settings, and the page's notes (what was stripped, the motion, the
    `same_model` check).

    Args:
        fixtures: the repository's tests/fixtures/field folder.
        folder: an existing folder for the stripped copy (it must outlast the runs: they read it).

    Returns:
        (mechanism, MJCF text, equality label -> (solref, solimp) or None, `Mechanism.simulate` options, notes).
    """
    path = stripped_file(fixtures, folder)
    mech, xml = load(path), path.read_text()
    check = same_model(mech, xml)
    notes = (
        f"The Menagerie file `{GRIPPER.as_posix()}` (tests/fixtures/field) read by both: {STRIPPED}.",
        MOTION,
        (
            f"Same model, checked before timing: at home at rest the rigid accelerations solved on MuJoCo's own mass "
            f"matrix, bias, passive forces and constraint Jacobian equal mechkit's to {check['rigid']:.1g} (relative); "
            f"MuJoCo's soft accelerations differ by {check['stiff']:.1g} (stiff) and {check['file']:.1g} (`file`: "
            "its own solref 0.005 s, solimp 0.95 0.99), the softness of its closures. The page's rows: MuJoCo at both."
        ),
    )
    return mech, xml, {"stiff": stiff_equality(mech), "file": None}, {"source": path}, notes
