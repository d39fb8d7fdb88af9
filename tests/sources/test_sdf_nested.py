"""Nested SDFormat models, joints before links and `relative_to` any frame, as libsdformat reads them: the
flattened names and frames, the same kinematics as the file written flat in the usual order, and body poses
equal to Drake's (its parser is libsdformat) at the same joint values."""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest

import mechkit
from mechkit.base.exceptions import MalformedDescription
from mechkit.sources.sdf import read_sdf
from mechkit.sources.sdf_nested import flattened

from .description_reference import Statics

FIXTURES = Path(__file__).resolve().parents[1] / "fixtures" / "field" / "sdf"
LINKS = ("base", "crank", "coupler", "rocker")


def _poses(desc, q: np.ndarray, names) -> list[np.ndarray]:
    """The world placements (4x4) of the named BODY frames at q."""
    data = desc.model.createData()
    pin.framesForwardKinematics(desc.model, data, q)
    return [data.oMf[desc.model.getFrameId(n, pin.FrameType.BODY)].homogeneous for n in names]


def test_names_are_scoped_and_references_resolve_in_their_scope():
    """A nested model's link, joint and frame names get its prefix, the names they refer to too (its
    __model__ is its own frame, `world` stays), its frame is attached to its canonical link and placed
    relative to the enclosing model's frame; deeper nesting scopes twice; file order is kept."""
    model = ET.fromstring(
        '<model name="top"><link name="a"/>'
        '<model name="m" canonical_link="y"><pose>1 0 0 0 0 0</pose><link name="x"/>'
        '<link name="y"><pose relative_to="n::__model__"/></link>'
        '<joint name="j" type="revolute"><parent>world</parent><child>x</child>'
        '<axis><xyz expressed_in="__model__">0 0 1</xyz></axis></joint>'
        '<model name="n"><link name="z"><pose relative_to="__model__"/></link></model></model>'
        '<joint name="k" type="fixed"><parent>a</parent><child>m::n::z</child></joint></model>'
    )
    out = flattened(model, (1, 9))
    assert [(e.tag, e.get("name")) for e in out] == [
        ("link", "a"),
        ("frame", "m"),
        ("link", "m::x"),
        ("link", "m::y"),
        ("joint", "m::j"),
        ("frame", "m::n"),
        ("link", "m::n::z"),
        ("joint", "k"),
    ]
    m = out.find("frame[@name='m']")
    assert m.get("attached_to") == "m::y" and m.find("pose").get("relative_to") == "__model__"
    assert out.find("frame[@name='m::n']").find("pose").get("relative_to") == "m"
    assert out.find("frame[@name='m::n']").get("attached_to") == "m::n::z"
    joint = out.find("joint[@name='m::j']")
    assert joint.findtext("parent") == "world" and joint.findtext("child") == "m::x"
    assert joint.find("axis/xyz").get("expressed_in") == "m"
    assert out.find("link[@name='m::x']").find("pose").get("relative_to") == "m"
    assert out.find("link[@name='m::n::z']").find("pose").get("relative_to") == "m::n"
    assert out.find("link[@name='m::y']").find("pose").get("relative_to") == "m::n"
    assert flattened(model.find("model/model"), (1, 9)) is model.find("model/model")  # nothing nested: as is


@pytest.mark.parametrize(
    "text, needle",
    [
        ('<model name="m"/>', "a nested model without a link"),
        ('<model name="a::b"><link name="l"/></model>', "needs a name without '::'"),
        (
            '<model name="m"><model name="n"><link name="l"/><include><uri>x</uri></include></model></model>',
            "<include> is not",
        ),
    ],
)
def test_nested_models_mechkit_cannot_place_are_refused_by_name(text, needle):
    with pytest.raises(MalformedDescription, match=needle):
        flattened(ET.fromstring(f'<model name="top"><link name="a"/>{text}</model>'), (1, 9))


def test_the_nested_joints_first_four_bar_is_the_flat_one():
    """four_bar_nested.sdf (joints first, the moving links in a nested model placed relative_to a frame, a
    joint from the world) and four_bar_gearbox.sdf (flat, usual order): one freedom each, the same cut,
    and every link at the same place (1e-12) wherever the crank is put."""
    nested, flat = read_sdf(FIXTURES / "four_bar_nested.sdf"), read_sdf(FIXTURES / "four_bar_gearbox.sdf")
    assert [c.name for c in nested.closures] == ["linkage::pin_C"] and [c.name for c in flat.closures] == ["pin_C"]
    assert mechkit.load(FIXTURES / "four_bar_nested.sdf").home_mobility.dof == 1
    for crank in (0.0, 0.3, -0.5, 1.1):
        poses = []
        for desc, prefix in ((nested, "linkage::"), (flat, "")):
            st = Statics(desc)
            q = st.assemble(st.configuration(desc.guess), {"crank_joint": crank})
            assert np.max(np.abs(st.rows(q)[0])) < 1e-12 and st.mobility(q) == 1
            poses.append(_poses(desc, q, [prefix + n if n != "base" else n for n in LINKS]))
        np.testing.assert_allclose(poses[0], poses[1], atol=1e-12)


@pytest.mark.parametrize("file, bodies", [("nested_arm.sdf", 5), ("four_bar_nested.sdf", 4)])
def test_the_nested_files_agree_with_drakes_parser(file, bodies, tmp_path):
    """nested_arm.sdf, and four_bar_nested.sdf opened at its cut pin_C (Drake's plant is a tree), read by
    Drake (libsdformat): at random joint values every body's pose in the world equals the reader's to 1e-12
    (Drake names a nested body by its model instance, `nested_arm::arm::hand`, and the joint by the instance
    of its child)."""
    pytest.importorskip("pydrake")
    from pydrake.multibody.parsing import Parser
    from pydrake.multibody.plant import MultibodyPlant

    path = tmp_path / file
    path.write_text(re.sub(r'\s*<joint name="pin_C".*?</joint>', "", (FIXTURES / file).read_text(), flags=re.DOTALL))
    desc = read_sdf(path)
    assert desc.closures == ()
    plant = MultibodyPlant(0.0)
    top = Parser(plant).AddModels(str(path))[0]
    plant.Finalize()
    context = plant.CreateDefaultContext()
    joints = {plant.get_joint(j).name(): plant.get_joint(j) for j in plant.GetJointIndices()}
    links = [f.name for f in desc.model.frames if f.type == pin.FrameType.BODY and f.name != "world"]
    assert len(links) == plant.num_bodies() - 1 == bodies
    rng = np.random.default_rng(7)
    for _ in range(5):
        q = rng.uniform(-1.5, 1.5, desc.model.nq)
        for j in range(1, desc.model.njoints):
            joint = joints[desc.model.names[j].split("::")[-1]]
            value = float(q[desc.model.joints[j].idx_q])
            (joint.set_translation if joint.type_name() == "prismatic" else joint.set_angle)(context, value)
        for name, ours in zip(links, _poses(desc, q, links), strict=True):
            instance, _, body = f"{plant.GetModelInstanceName(top)}::{name}".rpartition("::")
            theirs = plant.EvalBodyPoseInWorld(
                context, plant.GetBodyByName(body, plant.GetModelInstanceByName(instance))
            )
            np.testing.assert_allclose(ours, theirs.GetAsMatrix4(), atol=1e-12, err_msg=name)
