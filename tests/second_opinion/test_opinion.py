"""`mechkit.second_opinion.opinion`: what the SOC decomposition does not model is refused by name, not
answered wrongly (it is built and checked on every registered mechanism in test_decomposition.py and
test_agreement.py)."""

from __future__ import annotations

import pytest
from tests_support import written

import mechkit
from mechkit.base.exceptions import MethodUnavailable
from mechkit.second_opinion.opinion import SecondOpinion

INERTIAL = '<inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>'
GRIPPER = f"""<robot name="gripper">
  <link name="base"/><link name="finger1">{INERTIAL}</link><link name="finger2">{INERTIAL}</link>
  <joint name="j1" type="prismatic"><parent link="base"/><child link="finger1"/><axis xyz="0 1 0"/>
    <limit effort="10" lower="0" upper="0.04" velocity="1"/></joint>
  <joint name="j2" type="prismatic"><parent link="base"/><child link="finger2"/><axis xyz="0 -1 0"/>
    <limit effort="10" lower="0" upper="0.04" velocity="1"/>MIMIC</joint>
</robot>"""


def test_a_tree_without_loops_is_refused(tmp_path):
    """Nothing to cross-check: the SOCs of a tree are the tree (constrained RNEA is plain RNEA)."""
    mech = mechkit.load(written(tmp_path, GRIPPER.replace("MIMIC", "")), actuated=["j1", "j2"])
    with pytest.raises(MethodUnavailable, match="no loop closure"):
        SecondOpinion(mech)


def test_a_mechanism_with_a_coupling_is_refused(load_cached, tmp_path):
    """A mimic row ties two joints the decomposition treats as independent (on example-robot-data's Panda
    it disagreed with constrained RNEA by 70 %): refused, naming the coupling."""
    four_bar = load_cached("four_bar")
    assert SecondOpinion(four_bar).skcs  # the same kind of mechanism without a coupling is decomposed
    urdf = four_bar.urdf.replace(
        "</robot>",
        GRIPPER.split(">", 1)[1]
        .split("</robot>")[0]
        .replace('<link name="base"/>', "")
        .replace('link="base"', 'link="ground"')
        .replace("MIMIC", '<mimic joint="j1"/>')
        + f'<mechkit:home joint="crank" value="{float(four_bar.home_q[four_bar.q_index("crank")])!r}"/>'
        + "</robot>",
    )
    mech = mechkit.load(written(tmp_path, urdf), actuated=[*four_bar.actuated, "j1"])
    assert mech.closures and mech.closure_model.couplings
    with pytest.raises(MethodUnavailable, match="couplings \\(j2\\)"):
        SecondOpinion(mech)
