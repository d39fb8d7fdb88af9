"""`mechkit.mechanisms.deployable_9rr12uru.studies`: the fold against the paper, and its figures."""

from __future__ import annotations


def test_fold_study_matches_the_paper_and_draws_its_figures(mech, tmp_path):
    """The fold against eq. (6)-(13) every 50 s and its five figures."""
    from mechkit.mechanisms.deployable_9rr12uru.figures import fold_figures
    from mechkit.mechanisms.deployable_9rr12uru.studies import fold_study, worst_deviations

    study = fold_study(mech, step=50.0)
    worst = worst_deviations(study)
    assert worst["node_position"] < 1e-9 and worst["closure_residual"] < 1e-10
    assert worst["node_I_speed"] < 1e-10 and worst["node_B_rpy"] < 1e-9
    paths = fold_figures(study, tmp_path)
    for name in ("drives", "node_F", "node_I_speed", "node_B_rpy", "efforts"):
        assert (tmp_path / f"deployable_{name}.png").stat().st_size > 10_000
    assert len(paths) == 5
