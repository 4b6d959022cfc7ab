"""solver.numerics.newton: damped Newton on r0 + q r1 converges quadratically to the tolerance, and
says why when it does not."""

from __future__ import annotations

import itertools

import numpy as np
import pytest

from solver.numerics.evaluation import Evaluation
from solver.numerics.newton import newton
from solver.statics.jig import jig
from solver.statics.system import CoupledSystem
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
    """Each step squares the residual (7e-2, 5e-4, 2e-9 from the jig at 10 m/s, in the residual's
    mixed units, where the constant is 0.1 and less)."""
    norms = [_from_jig(system, 10.0, max_iterations=k).residual_norm for k in range(3)]
    assert norms[0] > 1e-3  # far enough from the root for the squaring to show
    for before, after in itertools.pairwise(norms):
        assert after <= before**2


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
