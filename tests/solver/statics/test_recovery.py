"""solver.statics.recovery: where the path to the requested airspeed fails, the branch from the jig
decides: NoEquilibrium beyond its fold or where it is unstable, its own equilibrium below."""

from __future__ import annotations

import numpy as np
import pytest

from solver import FlightCondition, NoEquilibrium, SolverOptions, airspeed_sweep, find_fold, solve
from tests.study import DENSITY as RHO
from tests.study import rect_public, study_wing

CASES = {"study": (study_wing, 5.0), "rect_public": (rect_public, 4.0)}


@pytest.fixture(scope="module", params=CASES.values(), ids=CASES.keys())
def case(request):
    make_wing, alpha = request.param
    wing = make_wing()
    return wing, alpha, find_fold(wing, alpha, RHO, 30.0)


def test_a_path_that_gives_up_below_the_fold_is_finished_from_the_branch(case):
    wing, alpha, fold = case
    flight = FlightCondition(0.999 * fold.velocity, alpha, RHO)
    # Two Newton iterations per step: the path from the jig stalls this close to the fold; the
    # branch's own state converges in one or two.
    equilibrium = solve(wing, flight, options=SolverOptions(max_iterations=2))
    assert equilibrium.stability.stable
    # The path from the jig gave up (2 iterations per step) and the branch's state finished it:
    # more iterations than one attempt allows, and no caller's start was used.
    assert equilibrium.solver.iterations > 2
    assert not equilibrium.solver.warm_start
    reference = solve(wing, flight)
    # Two roots within the 1e-10 residual tolerance differ by up to tolerance x condition
    # number, which near the fold is ~1e4 (sigma_min / sigma_max ~ 2e-4 at 0.999 V_fold).
    assert equilibrium.lift == pytest.approx(reference.lift, rel=1e-6)


@pytest.mark.parametrize("factor", [1.0001, 1.01, 1.1, 1.5, 2.0])
def test_no_equilibrium_beyond_the_fold(case, factor):
    wing, alpha, fold = case
    velocity = factor * fold.velocity
    with pytest.raises(NoEquilibrium) as raised:
        solve(wing, FlightCondition(velocity, alpha, RHO))
    assert raised.value.fold_velocity == pytest.approx(fold.velocity, rel=1e-12)
    assert f"{fold.velocity:.6g} m/s" in str(raised.value)
    point = airspeed_sweep(wing, [velocity], FlightCondition(None, alpha, RHO)).points[0]
    assert point.equilibrium is None and isinstance(point.error, NoEquilibrium)
    assert point.status == "no_equilibrium"
    assert point.no_equilibrium is not None
    assert point.no_equilibrium.fold_velocity == raised.value.fold_velocity


def test_rect_public_sweep_past_the_fold_is_not_answered_plainly():
    result = airspeed_sweep(rect_public(), [10, 20, 25], FlightCondition(None, 4.0, RHO))
    below, *beyond = result.points
    assert below.equilibrium is not None and below.equilibrium.stability.stable
    # AeroSandbox: 172.48854420335485 N at 10 m/s (shared/reference/ref_rect_public.json).
    assert below.equilibrium.lift == pytest.approx(172.48854420335485, rel=1e-6)
    fold_velocity = result.divergence.fold.velocity
    assert fold_velocity == pytest.approx(15.66, abs=0.005)
    for point in beyond:
        assert point.equilibrium is None
        assert isinstance(point.error, NoEquilibrium)
        assert point.error.fold_velocity == fold_velocity
        assert "15.66" in str(point.error)


def test_at_zero_alpha_the_unloaded_jig_is_the_answer_until_the_linear_divergence():
    wing = study_wing()
    fold = find_fold(wing, 0.0, RHO, 30.0)
    below = solve(wing, FlightCondition(0.95 * fold.velocity, 0.0, RHO))
    assert below.stability.stable and below.lift == 0.0
    assert np.all(below.stations.twist == 0.0)
    with pytest.raises(NoEquilibrium):
        solve(wing, FlightCondition(1.05 * fold.velocity, 0.0, RHO))
