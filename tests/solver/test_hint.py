"""A hint may only save time: the answer is the one a solve without it gives."""

from __future__ import annotations

import numpy as np
import pytest

from solver import FlightCondition, NoEquilibrium, Wing, find_fold, solve
from solver.divergence import clear_branch_cache

RHO = 1.2249991558876672  # AeroSandbox's sea-level ISA density [kg/m^3]
ALPHA = 5.0  # [deg]


@pytest.fixture(scope="module")
def wing() -> Wing:
    """The design study's wing (fold at 21.44 m/s; a nose-down unstable branch from ~16 m/s)."""
    chord = np.sqrt(np.linspace(2, 0.02, 30))
    return Wing.create(np.linspace(0, 5, 30), chord, 0.4, 2e4 * chord**3, 1e3 * chord**3)


def _nose_down_state(wing: Wing) -> np.ndarray:
    """Heave and slope reversed, twist nose-down: near the unstable branch's equilibria."""
    state = solve(wing, FlightCondition(10.0, ALPHA, RHO)).state.copy()
    n = wing.n_stations
    state[: 2 * n] *= -1
    state[2 * n : 3 * n] *= -8
    return state


def test_a_good_hint_saves_iterations_and_keeps_the_answer(wing: Wing) -> None:
    flight = FlightCondition(15.0, ALPHA, RHO)
    cold = solve(wing, flight)
    near = solve(wing, FlightCondition(14.8, ALPHA, RHO))
    hinted = solve(wing, flight, hint=near.state)
    assert hinted.warm_start and not cold.warm_start
    assert hinted.iterations < cold.iterations
    # Two roots within the 1e-10 residual tolerance: the same equilibrium to ~1e-9.
    np.testing.assert_allclose(hinted.twist, cold.twist, rtol=1e-8, atol=1e-10)
    assert hinted.lift == pytest.approx(cold.lift, rel=1e-9)


def _rect_public() -> Wing:
    """shared/reference/case_rect_public.json: fold at 15.66 m/s at 4 deg."""
    n = 24
    return Wing.create(np.linspace(0, 4, n), np.full(n, 0.8), 0.35, np.full(n, 5e3), 400.0)


def test_a_hint_on_the_unstable_branch_does_not_change_the_answer() -> None:
    wing, alpha = _rect_public(), 4.0
    flight = FlightCondition(20.0, alpha, RHO)
    state = solve(wing, FlightCondition(10.0, alpha, RHO)).state.copy()
    n = wing.n_stations
    state[: 2 * n] *= -1
    state[2 * n : 3 * n] *= -8
    # As a caller's initial guess, this start reaches AeroSandbox's nose-down "equilibrium"
    # (-520.44 N), returned flagged unstable...
    flagged = solve(wing, flight, state)
    assert not flagged.stability.stable
    assert flagged.lift == pytest.approx(-520.442301323639, rel=1e-6)
    # ...as a hint it changes nothing: no equilibrium on the jig's branch, as a plain solve says.
    clear_branch_cache()  # else the fold found above answers before the hint is even tried
    with pytest.raises(NoEquilibrium) as hinted:
        solve(wing, flight, hint=state)
    with pytest.raises(NoEquilibrium) as plain:
        solve(wing, flight)
    assert hinted.value.fold_velocity == plain.value.fold_velocity


def test_a_hint_beyond_the_fold_still_gets_no_equilibrium(wing: Wing) -> None:
    fold = find_fold(wing, ALPHA, RHO)
    flight = FlightCondition(1.05 * fold.velocity, ALPHA, RHO)
    with pytest.raises(NoEquilibrium) as raised:
        solve(wing, flight, hint=_nose_down_state(wing))
    assert raised.value.fold_velocity == pytest.approx(fold.velocity, rel=1e-12)


def test_a_hint_and_an_initial_guess_are_exclusive(wing: Wing) -> None:
    state = solve(wing, FlightCondition(10.0, ALPHA, RHO)).state
    with pytest.raises(ValueError, match="not both"):
        solve(wing, FlightCondition(11.0, ALPHA, RHO), state, hint=state)
