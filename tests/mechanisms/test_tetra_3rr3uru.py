"""The 3RR-3URU unit as a mechanism: mobility 3 without redundancy (4 with equal base links), and why
its drives are not the paper's."""

from __future__ import annotations


def test_unit_mobility_is_3_without_redundancy(unit, unit_fold):
    for sample in unit_fold:
        mob = unit.mobility(sample.q)
        assert (mob.dof, mob.redundant, mob.rows) == (3, 0, 15)
        assert mob.singular_values[-1] > 1e-6 * mob.singular_values[0]  # weak (see docs) but regular


def test_equal_links_make_the_unit_degenerate(load_cached):
    """With l1 = l2 (equilateral base) the three URU forces along the middle hinges become
    coplanar and concurrent: DOF 4 with one redundant row. The paper's l1 = 0.2504 m, l2 = 0.250 m
    restores DOF 3, hence the small last singular value of the default unit."""
    mob = load_cached("tetra_3rr3uru", l1=0.25).mobility()
    assert (mob.dof, mob.redundant) == (4, 1)


def test_paper_attitude_drives_at_b_and_e_do_not_determine_the_unit(unit):
    assert unit.singularity(unit.home_q, ("AH_H", "BH_B", "EH_E")) > 1e10
    assert unit.singularity(unit.home_q) < 1e7
