"""solver.sizing.envelope: the loads envelope is the extremes of the cases solved one by one,
exactly; the correlated loads' hull holds every case; the spar's margins are the envelope's
stresses against the material's yield, at limit and at 1.5 times limit."""

from __future__ import annotations

import dataclasses
import functools

import numpy as np
import pytest

import solver
from solver.sizing.envelope import (
    ULTIMATE_FACTOR,
    correlated_loads,
    spanwise_envelope,
    spar_envelope,
)
from tests.solver.sizing import loads_wings

# With lag: the exact beam, the wing twice as stiff in its plane as in flap.
EXACT = solver.SolverOptions(structure="geometrically_exact")


def _wing(spar: bool, lag: bool) -> solver.Wing:
    wing = loads_wings.spar_wing() if spar else loads_wings.wing()
    if lag:
        return dataclasses.replace(wing, in_plane_bending_stiffness=2 * wing.bending_stiffness)
    return wing


@functools.cache
def _one_by_one(
    spar: bool = False, lag: bool = False
) -> tuple[solver.Wing, list[solver.Equilibrium]]:
    wing, options = _wing(spar, lag), EXACT if lag else None
    return wing, [solver.solve(wing, case.flight, options=options) for case in loads_wings.CASES]


@functools.cache
def _answer(spar: bool = False, lag: bool = False) -> solver.LoadsEnvelope:
    options = EXACT if lag else None
    return solver.LoadsInput(wing=_wing(spar, lag), cases=loads_wings.CASES, options=options).run()


QUANTITIES = [
    *((quantity, False) for quantity in ("shear", "bending_moment", "torque")),
    *((quantity, True) for quantity in ("shear", "bending_moment", "torque", "lag_bending_moment")),
]


@pytest.mark.parametrize(
    ("quantity", "lag"), QUANTITIES, ids=[f"{q}{'-lag' if lag else ''}" for q, lag in QUANTITIES]
)
def test_the_envelope_is_the_extremes_of_the_cases_solved_one_by_one(
    quantity: str, lag: bool
) -> None:
    """1e-12 of the largest load: each extreme is one case's own number, the cases the same
    solves as /solve's (the issue's tolerance; the two agree to the last digit). With lag
    bending (the exact beam) the in-plane moment too; without, none."""
    _, equilibria = _one_by_one(lag=lag)
    per_case = [getattr(e.stations, quantity) for e in equilibria]
    largest, smallest = loads_wings.extremes(per_case)
    envelope = _answer(lag=lag).envelope
    assert envelope is not None
    assert (envelope.max_lag_bending_moment is not None) == lag
    assert envelope is not None
    scale = np.max(np.abs(per_case))
    np.testing.assert_allclose(getattr(envelope, f"max_{quantity}"), largest, atol=1e-12 * scale)
    np.testing.assert_allclose(getattr(envelope, f"min_{quantity}"), smallest, atol=1e-12 * scale)
    # The case named at each station gives that extreme there.
    for station, case in enumerate(getattr(envelope, f"max_{quantity}_case")):
        assert per_case[case][station] == pytest.approx(largest[station], abs=1e-12 * scale)


def test_the_pull_up_is_the_root_bending_case_and_the_push_over_its_least() -> None:
    envelope = _answer().envelope
    assert envelope is not None
    names = [case.name for case in loads_wings.CASES]
    assert names[envelope.max_bending_moment_case[0]] == "pull-up"
    assert names[envelope.min_bending_moment_case[0]] == "push-over"
    assert envelope.min_bending_moment[0] < 0.0 < envelope.max_bending_moment[0]


def test_the_correlated_loads_hull_holds_every_case() -> None:
    """Every (bending moment, torque) point lies inside or on the hull (counter-clockwise: no
    point right of an edge, to round-off of the scaled coordinates)."""
    y = loads_wings.wing().y
    (root,) = correlated_loads(y, _answer().cases, [0])
    points = np.column_stack([root.bending_moment, root.torque])
    points = points / np.ptp(points, axis=0)
    hull = points[root.hull]
    for a, b in zip(hull, np.roll(hull, -1, axis=0), strict=True):
        edge, to_points = b - a, points - a
        cross = edge[0] * to_points[:, 1] - edge[1] * to_points[:, 0]
        assert np.all(cross >= -1e-12)
    assert root.station == 0 and root.y == 0.0 and len(root.cases) == len(loads_wings.CASES)


def test_two_cases_hull_is_both_points_and_collinear_ones_their_ends() -> None:
    answers = _answer().cases
    y = loads_wings.wing().y
    (two,) = correlated_loads(y, answers[:2], [0])
    assert sorted(two.hull) == [0, 1]
    # Three cases scaled copies of one (torque proportional to bending): a line, its two ends.
    base = answers[0]
    scaled = [
        solver.CaseLoads(
            name=str(k),
            kind="given",
            status="equilibrium",
            shear=k * base.shear,
            bending_moment=k * base.bending_moment,
            torque=k * base.torque,
        )
        for k in (1.0, -0.5, 2.0)
    ]
    (line,) = correlated_loads(y, scaled, [0])
    assert sorted(line.hull) == [1, 2]


@pytest.mark.parametrize("lag", [False, True], ids=["planar", "lag"])
def test_the_spars_margins_are_its_largest_stress_against_yield(lag: bool) -> None:
    """Per station the largest von Mises stress over the cases (each case's bending and torque
    together; with lag bending the tube's share of the in-plane moment too: each case's own
    /solve answer's stress), margin = yield / (factor x stress) - 1 at limit (1) and ultimate
    (1.5)."""
    wing, equilibria = _one_by_one(spar=True, lag=lag)
    spar = _answer(spar=True, lag=lag).spar
    assert spar is not None and wing.spar is not None
    stresses = np.vstack(
        [
            e.stations.von_mises_stress
            if lag
            else wing.spar.stresses(e.stations.bending_moment, e.stations.torque).von_mises
            for e in equilibria
        ]
    )
    limit = stresses.max(axis=0)
    np.testing.assert_allclose(spar.limit_von_mises, limit, rtol=1e-12)
    yield_stress = loads_wings.CARBON.yield_stress
    loaded = limit > 0
    ultimate = yield_stress / (ULTIMATE_FACTOR * limit[loaded]) - 1
    np.testing.assert_allclose(np.array(spar.ultimate_margin)[loaded].astype(float), ultimate)
    np.testing.assert_allclose(
        np.array(spar.limit_margin)[loaded].astype(float), yield_stress / limit[loaded] - 1
    )
    assert spar.least_ultimate_margin == pytest.approx(ultimate.min(), rel=1e-12)
    assert spar.ultimate_factor == 1.5
    # The root, where the bending is largest, is where the margin is least; the tip carries
    # nothing and has none.
    assert spar.least_margin_station == 0 and spar.ultimate_margin[-1] is None


def test_nothing_flown_has_no_envelope_and_no_margins() -> None:
    failed = [solver.CaseLoads(name="x", kind="given", status="no_equilibrium", reason="diverged")]
    wing = loads_wings.spar_wing()
    assert spanwise_envelope(wing.y, failed) is None
    assert spar_envelope(wing, failed) is None
    (root,) = correlated_loads(wing.y, failed, [0])
    assert root.cases == [] and root.hull == []
