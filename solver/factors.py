"""LU factors of a Jacobian, kept for more than one solve: the path's predictor and first
correction share them, and so do the continuation's corrector, chord step and tangent."""

from __future__ import annotations

import warnings

import numpy as np
import scipy.linalg

__all__ = ["Factors", "factorise", "solve_with"]

Factors = tuple[np.ndarray, np.ndarray]


def factorise(matrix: np.ndarray) -> Factors | None:
    """LU factors (scipy's) of a square matrix, or None if it is singular or not finite. The
    matrix is factorised in place: pass one nobody else holds (a fresh J0 + q J1)."""
    if not np.all(np.isfinite(matrix)):
        return None
    with warnings.catch_warnings():
        warnings.simplefilter("error", scipy.linalg.LinAlgWarning)
        try:
            factors = scipy.linalg.lu_factor(matrix, overwrite_a=True, check_finite=False)
        except (np.linalg.LinAlgError, ValueError, scipy.linalg.LinAlgWarning):
            return None
    return factors if np.all(np.diag(factors[0]) != 0) else None


def solve_with(factors: Factors, rhs: np.ndarray) -> np.ndarray:
    """x with A x = rhs, A the matrix `factors` came from."""
    return scipy.linalg.lu_solve(factors, rhs, check_finite=False)
