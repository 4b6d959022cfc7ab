"""solver.newton: damped Newton on r0 + q r1 converges quadratically to the tolerance, and says
why when it does not."""

from __future__ import annotations

import numpy as np
import pytest

from solver.branch import pressure_scale
from solver.evaluation import Evaluation
from solver.jig import jig
from solver.newton import ChordSteps, newton
from solver.system import CoupledSystem
from tests.study import DENSITY, study_wing

TOLERANCE = 1e-10


@pytest.fixture(scope="module")
def system() -> CoupledSystem:
    return CoupledSystem(study_wing(), 5.0)


def _from_jig(system: CoupledSystem, velocity: float, max_iterations: int = 30):
    start = jig(system)
    return newton(
        system.evaluate,
        system.residual,
        start.state,
        0.5 * DENSITY * velocity**2,
        TOLERANCE,
        max_iterations,
        start.evaluation,
    )


@pytest.mark.parametrize("velocity", [6.0, 12.0, 18.0])
def test_converges_from_the_rigid_jig_to_the_tolerance(system, velocity):
    result = _from_jig(system, velocity)
    assert result.converged and result.reason == "converged"
    r0, r1 = system.residual(result.x)
    assert np.max(np.abs(r0 + 0.5 * DENSITY * velocity**2 * r1)) <= TOLERANCE
    assert result.residual_norm <= TOLERANCE


def test_the_last_steps_converge_quadratically(system):
    """Each converged digit doubles: with the 1e-10 tolerance, 10 m/s takes 3 iterations."""
    assert _from_jig(system, 10.0).iterations == 3


def test_an_iteration_limit_ends_in_a_typed_reason_and_no_claim(system):
    result = _from_jig(system, 18.0, max_iterations=1)
    assert not result.converged
    assert result.reason == "iteration limit reached"
    assert result.residual_norm > TOLERANCE


def test_zero_iterations_only_check_the_start(system):
    result = _from_jig(system, 10.0, max_iterations=0)
    assert not result.converged and result.iterations == 0


def test_a_singular_jacobian_is_reported_not_raised():
    n = 3
    zeros = np.zeros((n, n))
    evaluation = Evaluation(np.ones(n), np.zeros(n), zeros, zeros)
    result = newton(
        lambda x: evaluation, lambda x: (evaluation.r0, evaluation.r1), np.zeros(n), 1.0, 1e-10, 5
    )
    assert not result.converged and result.reason == "singular Jacobian"


def test_a_non_finite_residual_is_reported_not_returned():
    n = 2
    evaluation = Evaluation(np.array([np.nan, 1.0]), np.zeros(n), np.eye(n), np.zeros((n, n)))
    result = newton(
        lambda x: evaluation, lambda x: (evaluation.r0, evaluation.r1), np.zeros(n), 1.0, 1e-10, 5
    )
    assert not result.converged and result.reason == "non-finite residual"


class _Counted:
    """`evaluate` that counts its calls (Jacobian evaluations)."""

    def __init__(self, evaluate):
        self._evaluate, self.calls = evaluate, 0

    def __call__(self, x):
        self.calls += 1
        return self._evaluate(x)


@pytest.mark.parametrize("distance", [1e-5, 8e-5], ids=["1e-5", "8e-5"])
def test_chord_steps_finish_a_close_start_with_one_jacobian_instead_of_two(system, distance):
    """A start `distance` (scaled) from the root: plain Newton's first step leaves the residual
    just above the tolerance and evaluates the Jacobians again; a chord step on the first
    factors converges instead, to the same root, carrying the start's Jacobians."""
    q = 0.5 * DENSITY * 12.0**2
    scale = system.scale(pressure_scale(system))[:-1]
    root = _from_jig(system, 12.0).x
    direction = np.random.default_rng(3).standard_normal(root.size)
    x0 = root + distance * scale * direction / np.linalg.norm(direction)
    plain, chorded = _Counted(system.evaluate), _Counted(system.evaluate)
    newtons = newton(plain, system.residual, x0, q, TOLERANCE, 30)
    chords = newton(chorded, system.residual, x0, q, TOLERANCE, 30, chord=ChordSteps(scale, 1e-4))
    assert newtons.converged and chords.converged
    assert (plain.calls, chorded.calls) == (2, 1)
    # Both lie within the tolerance times the conditioning of the root (~1e-11 scaled here).
    assert np.linalg.norm((chords.x - newtons.x) / scale) < 1e-9
    assert np.array_equal(chords.evaluation.jacobian0, system.evaluate(x0).jacobian0)


def test_a_start_beyond_the_chord_distance_gets_fresh_jacobians(system):
    q = 0.5 * DENSITY * 12.0**2
    scale = system.scale(pressure_scale(system))[:-1]
    start = jig(system)
    counted = _Counted(system.evaluate)
    result = newton(
        counted,
        system.residual,
        start.state,
        q,
        TOLERANCE,
        30,
        start.evaluation,
        chord=ChordSteps(scale, 1e-4),
    )
    assert result.converged and counted.calls >= 1
    assert np.linalg.norm((result.x - _from_jig(system, 12.0).x) / scale) < 1e-9
    assert not np.array_equal(result.evaluation.jacobian0, start.evaluation.jacobian0)


def test_chord_steps_that_stop_contracting_renew_the_jacobian():
    """r(x) = exp(x) - 1 from x = 3: chord steps on J(3) = e^3 would contract by only
    1 - e^-3 per step near the root (hundreds of steps); the contraction test renews J
    instead, so Newton converges within 20 iterations even with no distance limit."""

    def parts(x):
        return np.exp(x) - 1.0, np.zeros(1)

    def evaluate(x):
        r0, r1 = parts(x)
        return Evaluation(r0, r1, np.diag(np.exp(x)), np.zeros((1, 1)))

    counted = _Counted(evaluate)
    result = newton(
        counted, parts, np.array([3.0]), 1.0, TOLERANCE, 20, chord=ChordSteps(np.ones(1), np.inf)
    )
    assert result.converged and abs(result.x[0]) < 1e-9
    assert counted.calls >= 3  # the start's, and at least two renewals
