"""solver.numerics.evaluation: one model evaluation serves every dynamic pressure (r and J are
affine in q)."""

from __future__ import annotations

import numpy as np

from solver.numerics.evaluation import Evaluation
from solver.statics.system import CoupledSystem
from tests.study import study_wing


def _evaluation() -> Evaluation:
    system = CoupledSystem(study_wing(12), 5.0)
    state = np.random.default_rng(3).normal(scale=0.01, size=system.layout.n_unknowns)
    return system.evaluate(state)


def test_residual_and_jacobian_at_q_are_the_parts_combined():
    evaluation, q = _evaluation(), 123.0
    np.testing.assert_array_equal(evaluation.residual(q), evaluation.r0 + q * evaluation.r1)
    np.testing.assert_array_equal(
        evaluation.jacobian(q), evaluation.jacobian0 + q * evaluation.jacobian1
    )
    np.testing.assert_array_equal(evaluation.residual(0.0), evaluation.r0)


def test_the_jacobian_at_q_is_a_new_array_each_time():
    """LAPACK factorises it in place (`solver.numerics.factors`): it must never alias the parts."""
    evaluation = _evaluation()
    first = evaluation.jacobian(10.0)
    first[:] = 0.0
    assert np.any(evaluation.jacobian(10.0) != 0.0)
    assert not np.shares_memory(evaluation.jacobian(0.0), evaluation.jacobian0)


def test_read_only_freezes_every_part_and_its_size_counts_them_all():
    evaluation = _evaluation().read_only()
    parts = (evaluation.r0, evaluation.r1, evaluation.jacobian0, evaluation.jacobian1)
    assert not any(part.flags.writeable for part in parts)
    assert evaluation.nbytes == sum(part.nbytes for part in parts)
