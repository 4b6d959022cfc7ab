"""solver.numerics.factors: LU factors that solve what the matrix solves, and None where there are
none."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.linalg

from solver.numerics.factors import factorise, solve_with


def test_the_factors_solve_the_system_they_came_from():
    rng = np.random.default_rng(0)
    matrix = rng.standard_normal((40, 40)) + 40 * np.eye(40)
    rhs = rng.standard_normal(40)
    factors = factorise(matrix.copy(order="F"))
    assert factors is not None
    x = solve_with(factors, rhs)
    # Backward stable: the residual is round-off of |A| |x| (cond(A) ~ 1.5 here).
    assert (
        np.max(np.abs(matrix @ x - rhs)) < 1e-12 * np.max(np.abs(matrix)) * np.max(np.abs(x)) * 40
    )


@pytest.mark.parametrize(
    "matrix",
    [
        pytest.param(np.zeros((3, 3)), id="zero"),
        pytest.param(np.array([[1.0, 2.0], [2.0, 4.0]]), id="rank-deficient"),
        pytest.param(np.array([[1.0, np.nan], [0.0, 1.0]]), id="nan"),
        pytest.param(np.array([[np.inf, 0.0], [0.0, 1.0]]), id="inf"),
    ],
)
def test_a_singular_or_non_finite_matrix_has_no_factors(matrix):
    assert factorise(matrix.copy()) is None


@pytest.mark.parametrize("order", ["F", "C"])
@pytest.mark.parametrize("columns", [None, 3], ids=["vector", "matrix"])
def test_the_factors_and_solutions_are_scipys_bit_for_bit(order, columns):
    """The module calls LAPACK directly only to skip scipy's checks: nothing else may change."""
    rng = np.random.default_rng(1)
    matrix = rng.standard_normal((30, 30))
    rhs = rng.standard_normal(30 if columns is None else (30, columns))
    reference = scipy.linalg.lu_factor(matrix, check_finite=False)
    factors = factorise(matrix.copy(order=order))
    assert factors is not None
    assert np.array_equal(factors[0], reference[0])
    assert np.array_equal(factors[1], reference[1])
    expected = scipy.linalg.lu_solve(reference, rhs, check_finite=False)
    assert np.array_equal(solve_with(factors, rhs), expected)
