"""Newton's method on the coupled system: it converges from the jig shape, a warm start saves
iterations, and a solve that does not converge says so with a typed error instead of returning
a state that is not an equilibrium."""

from __future__ import annotations

import numpy as np
import pytest

import solver
from solver import compiled

AEROSANDBOX_SEA_LEVEL_DENSITY = 1.2249991558876672  # [kg/m^3]
N = 30
CHORDS = np.sqrt(np.linspace(2, 0.02, N))
DEFAULT_TOLERANCE = solver.SolverOptions().tolerance


@pytest.fixture(scope="module")
def wing() -> solver.Wing:
    """The design study's wing: wash-in, fold of the branch near 21.4 m/s."""
    return solver.Wing.create(np.linspace(0, 5, N), CHORDS, 0.40, 2e4 * CHORDS**3, 1e3 * CHORDS**3)


def flight(velocity: float) -> solver.FlightCondition:
    return solver.FlightCondition(velocity, alpha=5.0, density=AEROSANDBOX_SEA_LEVEL_DENSITY)


def residual_norm_at(e: solver.Equilibrium) -> float:
    """max |r| of the coupled equations at the returned state, evaluated afresh."""
    model = compiled.model_for(e.wing.n_stations)
    evaluation = model.evaluate(e.state, e.wing.parameters(e.flight.alpha))
    return float(np.max(np.abs(evaluation.residual(e.dynamic_pressure))))


@pytest.mark.parametrize("velocity", [6.0, 12.0, 18.0, 21.0])
def test_converges_from_the_jig_shape(wing, velocity: float):
    """Up to 98 % of the fold speed, without any help: the returned state solves the equations."""
    e = solver.solve(wing, flight(velocity))
    assert not e.warm_start
    assert e.iterations >= 1  # the unloaded jig is not an equilibrium at alpha = 5 deg
    assert e.residual_norm <= DEFAULT_TOLERANCE
    assert residual_norm_at(e) <= DEFAULT_TOLERANCE


@pytest.mark.parametrize(
    ("previous_velocity", "velocity"),
    [pytest.param(11.0, 12.0, id="11-to-12"), pytest.param(19.0, 20.0, id="19-to-20")],
)
def test_a_warm_start_from_a_neighbouring_airspeed_takes_fewer_iterations(
    wing, previous_velocity: float, velocity: float
):
    """The neighbour's state and Jacobian (re-targeted to the new q) start Newton next to the
    answer; from the jig it has the whole deformation to find. Same answer either way."""
    cold = solver.solve(wing, flight(velocity))
    neighbour = solver.solve(wing, flight(previous_velocity))
    warm = solver.solve(wing, flight(velocity), initial_guess=neighbour)
    assert warm.warm_start and not cold.warm_start
    assert warm.iterations < cold.iterations
    assert np.max(np.abs(warm.twist - cold.twist)) / np.max(np.abs(cold.twist)) < 1e-9


def test_a_warm_start_from_the_answer_itself_needs_no_iteration(wing):
    e = solver.solve(wing, flight(15.0))
    again = solver.solve(wing, flight(15.0), initial_guess=e)
    assert again.iterations == 0
    np.testing.assert_array_equal(again.state, e.state)


def test_no_iterations_allowed_raises_a_typed_convergence_error(wing):
    """max_iterations = 0: the jig is not the answer, so the solve must fail, and say where.

    (With max_iterations = 1 the solve succeeds: when Newton fails, `solve` retries from the
    continuation branch, whose interpolated state converges in one step.)
    """
    with pytest.raises(solver.ConvergenceError) as raised:
        solver.solve(wing, flight(15.0), options=solver.SolverOptions(max_iterations=0))
    error = raised.value
    assert isinstance(error, solver.SolverError)
    assert error.velocity == 15.0
    assert error.iterations == 0
    assert np.isfinite(error.residual_norm) and error.residual_norm > DEFAULT_TOLERANCE
    assert error.reason
    assert "15" in str(error)


def test_an_unreachable_tolerance_stops_at_the_iteration_limit(wing):
    """A tolerance below round-off (the residual bottoms out near 1e-15) is never met: Newton
    runs to its limit, the branch retry too, and the error carries the limit and the small but
    non-zero residual it reached."""
    options = solver.SolverOptions(tolerance=1e-300, max_iterations=4)
    with pytest.raises(solver.ConvergenceError) as raised:
        solver.solve(wing, flight(15.0), options=options)
    error = raised.value
    assert error.velocity == 15.0
    assert error.iterations == 4
    assert 1e-300 < error.residual_norm < 1e-8


@pytest.mark.parametrize("max_iterations", range(6))
@pytest.mark.parametrize("velocity", [10.0, 20.0])
def test_only_converged_states_are_returned(wing, velocity: float, max_iterations: int):
    """Whatever the iteration budget: an equilibrium that meets the tolerance, or an error."""
    options = solver.SolverOptions(max_iterations=max_iterations)
    try:
        e = solver.solve(wing, flight(velocity), options=options)
    except solver.SolverError:
        return
    # The budget bounds each Newton run: the caller's start, then at most one retry from the
    # branch from the jig (solver.recovery); `iterations` reports both.
    assert e.iterations <= 2 * max_iterations
    assert e.residual_norm <= options.tolerance
    assert residual_norm_at(e) <= options.tolerance


@pytest.mark.parametrize(
    "guess",
    [
        pytest.param(np.zeros(4 * N - 2), id="wrong-length"),
        pytest.param(np.full(4 * N - 1, np.nan), id="not-finite"),
    ],
)
def test_a_malformed_initial_guess_is_rejected(wing, guess: np.ndarray):
    with pytest.raises(ValueError):
        solver.solve(wing, flight(10.0), initial_guess=guess)
