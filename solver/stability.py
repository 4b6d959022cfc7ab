"""Static aeroelastic stability from the residual's affine structure in q.

With loads proportional to q, the Jacobian at a state x is J(x, q) = J0(x) + q J1(x) (in the
issue's words J_structure - q J_aero, with J_aero = -J1). The divergence dynamic pressure at x is
the smallest positive real lambda for which J0 + lambda J1 is singular:

    J0 v = -lambda J1 v.

J1 is non-zero only in the 2(N-1) bending and torsion rows (the loads enter nowhere else), so with
E selecting those rows (J1 = E K) the non-zero eigenvalues mu = 1/lambda of -J0^{-1} J1 are those
of the small (2(N-1))^2 matrix -K J0^{-1} E.
"""

from __future__ import annotations

import numpy as np

from solver.compiled import Evaluation
from solver.model import Layout

__all__ = ["divergence_pressure"]

# An eigenvalue counts as real when its imaginary part is this small relative to its modulus.
_REAL_TOLERANCE = 1e-8


def divergence_pressure(evaluation: Evaluation, layout: Layout) -> float | None:
    """Smallest positive real lambda [Pa] with J0 + lambda J1 singular, or None if there is none."""
    equations = np.arange(layout.n_unknowns)
    rows = np.r_[equations[layout.bending_rows], equations[layout.torsion_rows]]
    load_rows = evaluation.jacobian1[rows]
    selector = np.zeros((layout.n_unknowns, rows.size))
    selector[rows, np.arange(rows.size)] = 1.0
    try:
        inverse_columns = np.linalg.solve(evaluation.jacobian0, selector)
    except np.linalg.LinAlgError:
        return None
    mu = np.linalg.eigvals(-load_rows @ inverse_columns)
    scale = np.max(np.abs(mu)) if mu.size else 0.0
    real_positive = mu[(np.abs(mu.imag) <= _REAL_TOLERANCE * scale) & (mu.real > 0)].real
    if real_positive.size == 0:
        return None
    return float(1.0 / np.max(real_positive))
