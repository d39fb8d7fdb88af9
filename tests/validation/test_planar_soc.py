"""`mechkit.validation.planar_soc`: the planar linkages' SKCs, by hand and generic, against planar
Newton-Euler; a singular SKC raises."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit.base.exceptions import SingularConfiguration
from mechkit.validation.planar_closed_form import five_bar, four_bar
from mechkit.validation.planar_motion import Bar, LinkageState, LinkState
from mechkit.validation.planar_newton_euler import newton_euler
from mechkit.validation.planar_soc import (
    Chain,
    body_load,
    free_chain,
    motor_column,
    pin_site,
    soc_skcs,
    whole_skc,
)
from mechkit.validation.soc import SKCInstant, WrenchSite, classic_virtual_work, solve_soc

G = np.array([0.0, 0.0, -9.81])


def _pin(joint: str, point: np.ndarray, chain: Chain, sign: float) -> WrenchSite:
    return pin_site(joint, point, chain, sign)


def _motor(joint: str, chain: Chain) -> tuple[str, np.ndarray]:
    """Unit motor torque about -y from the ground on the body of ``chain``."""
    return joint, motor_column(chain)


def _four_bar_skcs(links: dict[str, LinkState]) -> list[SKCInstant]:
    """SKC1 rocker + coupler ("coupler" pin released); then crank, coupler, rocker as free bodies."""
    crank, coupler, rocker = links["crank"], links["coupler"], links["rocker"]
    a, b, c, d = crank.origin, coupler.origin, coupler.tip, rocker.origin
    dyad = (d, c)
    return [
        SKCInstant(
            "rocker+coupler",
            2,
            (body_load(rocker, (d, None)), body_load(coupler, dyad)),
            released=(_pin("coupler", b, dyad, +1.0),),
        ),
        SKCInstant(
            "crank",
            3,
            (body_load(crank, free_chain(a)),),
            (_motor("crank", free_chain(a)),),
            released=(_pin("crank", a, free_chain(a), +1.0),),
            known=(_pin("coupler", b, free_chain(a), -1.0),),
        ),
        SKCInstant(
            "coupler",
            3,
            (body_load(coupler, free_chain(b)),),
            released=(_pin("C", c, free_chain(b), -1.0),),
            known=(_pin("coupler", b, free_chain(b), +1.0),),
        ),
        SKCInstant(
            "rocker",
            3,
            (body_load(rocker, free_chain(d)),),
            released=(_pin("rocker", d, free_chain(d), +1.0),),
            known=(_pin("C", c, free_chain(d), +1.0),),
        ),
    ]


def _five_bar_skcs(links: dict[str, LinkState]) -> list[SKCInstant]:
    """SKC1 the free distal dyad (pins "dist1", "dist2" released); then prox1, prox2, dist1 alone."""
    prox1, dist1, prox2, dist2 = (links[n] for n in ("prox1", "dist1", "prox2", "dist2"))
    b1, b2, c = dist1.origin, dist2.origin, dist1.tip
    left, right = ("x", "z", b1, None), ("x", "z", b1, c)
    skcs = [
        SKCInstant(
            "distal dyad",
            4,
            (body_load(dist1, left), body_load(dist2, right)),
            released=(_pin("dist1", b1, left, +1.0), _pin("dist2", b2, right, +1.0)),
        )
    ]
    for prox, distal in ((prox1, "dist1"), (prox2, "dist2")):
        a, chain = prox.origin, free_chain(prox.origin)
        skcs.append(
            SKCInstant(
                prox.name,
                3,
                (body_load(prox, chain),),
                (_motor(prox.name, chain),),
                released=(_pin(prox.name, a, chain, +1.0),),
                known=(_pin(distal, prox.tip, chain, -1.0),),
            )
        )
    skcs.append(
        SKCInstant(
            "dist1",
            3,
            (body_load(dist1, free_chain(b1)),),
            released=(_pin("C", c, free_chain(b1), -1.0),),
            known=(_pin("dist1", b1, free_chain(b1), +1.0),),
        )
    )
    return skcs


def _four_bar_motion(t: float) -> LinkageState:
    w = 2.0 * np.pi
    theta = 0.2 + w * t + 0.5 * np.sin(w * t)
    return four_bar(theta, w + 0.5 * w * np.cos(w * t), -0.5 * w**2 * np.sin(w * t))


def _five_bar_motion(t: float) -> LinkageState:
    w = 2.0 * np.pi
    thetas = (1.7 + 0.4 * np.sin(w * t), 1.1 + 0.35 * np.cos(w * t))
    rates = (0.4 * w * np.cos(w * t), -0.35 * w * np.sin(w * t))
    return five_bar(thetas, rates, (-0.4 * w**2 * np.sin(w * t), -0.35 * w**2 * np.cos(w * t)))


# decompositions declared by hand per linkage, and the generic planar one (`planar_soc.soc_skcs`)
CASES = [
    (_four_bar_motion, lambda st: _four_bar_skcs(st.links)),
    (_five_bar_motion, lambda st: _five_bar_skcs(st.links)),
    (_four_bar_motion, soc_skcs),
    (_five_bar_motion, soc_skcs),
]


@pytest.mark.parametrize(
    ("motion", "decompose"), CASES, ids=["four_bar", "five_bar", "four_bar-generic", "five_bar-generic"]
)
def test_soc_matches_newton_euler(motion, decompose) -> None:
    for t in np.linspace(0.0, 1.0, 13)[:-1]:
        state = motion(t)
        reference = newton_euler(state, G)
        soc = solve_soc(decompose(state), G)
        assert set(soc.reactions) == set(reference.reactions)
        scale = max(np.max(np.abs(w)) for w in reference.reactions.values())
        for name, wrench in reference.reactions.items():
            planar = wrench.copy()
            planar[4] = 0.0  # the motor torque is an effort in SOC, not a reaction unknown
            np.testing.assert_allclose(soc.reactions[name], planar, rtol=0, atol=1e-9 * scale)
        for name, u in reference.efforts.items():
            assert soc.efforts[name] == pytest.approx(u, rel=0, abs=1e-9 * scale)
        assert max(soc.consistency.values()) < 1e-9  # the over-determined single-body SKCs agree
        classic = classic_virtual_work(whole_skc(state), G)
        assert classic == pytest.approx(reference.efforts, rel=0, abs=1e-9 * scale)


def test_skc_at_singular_pose_raises() -> None:
    """Rocker and coupler collinear: the "coupler" pin force along them does no virtual work."""
    bar, d = Bar(0.22), np.array([0.30, 0.0])
    angle = 1.2
    rocker = LinkState("rocker", bar, d, angle, 0.5, 0.1, np.zeros(2), np.zeros(2))
    b = rocker.tip - 0.28 * np.array([np.cos(angle), np.sin(angle)])
    coupler = LinkState("coupler", Bar(0.28), b, angle, 0.5, 0.1, np.zeros(2), np.zeros(2))
    still = np.zeros(2)
    crank = LinkState("crank", Bar(np.hypot(*b)), still, np.arctan2(b[1], b[0]), 0.0, 0.0, still, still)
    skcs = _four_bar_skcs({"crank": crank, "coupler": coupler, "rocker": rocker})
    with pytest.raises(SingularConfiguration, match="rocker\\+coupler") as err:
        solve_soc(skcs, G)
    assert err.value.cond > 1e10
