"""LU factors of a Jacobian, kept for more than one solve: the path's predictor and first
correction share them, and so do the continuation's corrector, chord step and tangent.

LAPACK's getrf and getrs are called directly: they are what `scipy.linalg.lu_factor` and
`lu_solve` run (the same bits), without those wrappers' argument checks, which cost as much as
the triangular solves themselves on the solver's 100-500 unknowns.
"""

from __future__ import annotations

import numpy as np
from scipy.linalg import lapack

__all__ = ["Factors", "factorise", "solve_with"]

# (LU, pivots) as `scipy.linalg.lu_factor` returns them (pivots 0-based).
Factors = tuple[np.ndarray, np.ndarray]

_getrf = lapack.dgetrf
_getrs = lapack.dgetrs


def factorise(matrix: np.ndarray) -> Factors | None:
    """LU factors of a square float64 matrix, or None if it is singular or not finite. The
    matrix is factorised in place when it is Fortran-ordered (as the model's Jacobians are):
    pass one nobody else holds (a fresh J0 + q J1)."""
    if not np.all(np.isfinite(matrix)):
        return None
    lu, pivots, info = _getrf(matrix, overwrite_a=True)
    # info > 0: an exactly zero pivot (singular); info < 0 cannot happen for a valid array.
    if info != 0 or not np.all(np.diag(lu) != 0):
        return None
    return lu, pivots


def solve_with(factors: Factors, rhs: np.ndarray) -> np.ndarray:
    """x with A x = rhs, A the matrix `factors` came from. rhs: (n,) or (n, k)."""
    lu, pivots = factors
    solution, info = _getrs(lu, pivots, rhs)
    if info != 0:  # only for malformed arguments, which the solver never passes
        raise ValueError(f"LAPACK getrs rejected its arguments (info = {info})")
    return solution  # type: ignore[no-any-return]
