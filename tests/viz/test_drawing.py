"""`mechkit.viz.drawing`: what is drawn sits where the kinematics puts it; one colour per limb."""

from __future__ import annotations

import numpy as np
import pinocchio as pin

from mechkit import viz
from mechkit.viz import drawing


def test_drawn_poses_agree_with_the_kinematics(load_cached):
    """Joint markers lie along the world joint axes (from the Jacobian); cut markers sit on both frames."""
    m = load_cached("four_bar")
    drawn = viz.Drawing(m)
    q = m.assemble([1.1])
    placements = dict(zip((p.path for p in drawn.parts), drawn.placements(q)))
    data = m.model.createData()
    pin.computeJointJacobians(m.model, data, q)
    pin.framesForwardKinematics(m.model, data, q)
    for j in range(1, m.model.njoints):
        axis = pin.getJointJacobian(m.model, data, j, pin.ReferenceFrame.WORLD)[3:, m.model.joints[j].idx_v]
        T = placements[f"joints/{m.model.names[j]}"]
        assert np.allclose(T[:3, 1], axis / np.linalg.norm(axis), atol=1e-12)
        assert np.allclose(T[:3, 3], data.oMi[j].translation, atol=1e-12)
    for c in m.closures:
        T = placements[f"cuts/{c.name}"]
        for frame in (c.frame_a, c.frame_b):
            assert np.allclose(T[:3, 3], data.oMf[m.model.getFrameId(frame)].translation, atol=1e-10)


def test_one_colour_per_limb_when_the_urdf_gives_none(load_cached):
    m = load_cached("five_bar")
    visual = pin.buildGeomFromUrdfString(m.model, m.urdf, pin.GeometryType.VISUAL)
    for obj in visual.geometryObjects:
        obj.meshColor = np.array([0.9, 0.9, 0.9, 1.0])
    colours = dict(
        zip((m.model.names[g.parentJoint] for g in visual.geometryObjects), drawing._link_colours(m.model, visual))
    )
    # five-bar limbs: prox1 -> dist1 and prox2 -> dist2, cut at C
    assert colours["prox1"] == colours["dist1"] != colours["prox2"] == colours["dist2"]


def test_a_mechanism_on_a_base_is_drawn_with_its_links_visuals(load_cached):
    """The platform on a moving base is a built tree (no URDF text of its own): its links are still drawn from
    the URDF it was built from, each visual at its link's placement on the carried tree."""
    from mechkit.bases import with_base

    grounded = load_cached("spherical_2dof")
    moving = with_base(grounded, "moving")
    assert moving.urdf is None
    plain, carried = drawing.Drawing(grounded), drawing.Drawing(moving)
    names = sorted(p.path for p in carried.parts if p.path.startswith("links/"))
    assert names and names == sorted(p.path for p in plain.parts if p.path.startswith("links/"))
    data = moving.model.createData()
    pin.framesForwardKinematics(moving.model, data, moving.home_q)
    vdata = carried.visual.createData()
    pin.updateGeometryPlacements(moving.model, data, carried.visual, vdata)
    link = moving.model.getFrameId("platform")
    platform = [k for k, o in enumerate(carried.visual.geometryObjects) if o.parentFrame == link]
    assert platform
    for k in platform:  # a visual's placement is its link's times its own origin
        local = carried.visual.geometryObjects[k].placement
        assert np.allclose(vdata.oMg[k].homogeneous, (data.oMf[link] * local).homogeneous, atol=1e-12)
