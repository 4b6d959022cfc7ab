"""Damped Newton's method on the coupled residual r(x) = r0(x) + q r1(x).

Convergence criterion: max_i |r_i| <= tolerance, on the residual in its physical units (heave rows
in m, slope rows dimensionless, twist rows in degrees, flow-tangency rows as normal velocity per
unit airspeed). The default 1e-10 sits far below the 1e-6 relative agreement promised with
AeroSandbox (whose own IPOPT stopping point leaves 4e-10), and Newton's quadratic convergence
makes the last factor of 1e4 cost at most one more iteration.

Each step is damped by backtracking on ||r||_2 (Armijo, halving), so a poor initial guess cannot
throw the iterate far outside the region where the model makes sense.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from solver.compiled import Evaluation

__all__ = ["NewtonResult", "newton"]

_ARMIJO = 1e-4
_MIN_STEP = 1.0 / 256


@dataclass
class NewtonResult:
    x: np.ndarray
    evaluation: Evaluation  # at x
    iterations: int
    residual_norm: float
    converged: bool
    reason: str


def newton(
    evaluate: Callable[[np.ndarray], Evaluation],
    x0: np.ndarray,
    q: float,
    tolerance: float,
    max_iterations: int,
    evaluation0: Evaluation | None = None,
) -> NewtonResult:
    """Solve r0(x) + q r1(x) = 0 from x0; `evaluation0`, if given, is the evaluation at x0."""
    x = np.array(x0, dtype=float)
    ev = evaluation0 if evaluation0 is not None else evaluate(x)
    residual = ev.residual(q)
    for iteration in range(max_iterations + 1):
        if not np.all(np.isfinite(residual)):
            return NewtonResult(x, ev, iteration, float("nan"), False, "non-finite residual")
        norm = float(np.max(np.abs(residual)))
        if norm <= tolerance:
            return NewtonResult(x, ev, iteration, norm, True, "converged")
        if iteration == max_iterations:
            break
        try:
            step = np.linalg.solve(ev.jacobian(q), residual)
        except np.linalg.LinAlgError:
            return NewtonResult(x, ev, iteration, norm, False, "singular Jacobian")
        merit = float(residual @ residual)
        length = 1.0
        while True:
            x_trial = x - length * step
            ev_trial = evaluate(x_trial)
            residual_trial = ev_trial.residual(q)
            merit_trial = float(residual_trial @ residual_trial)
            if np.isfinite(merit_trial) and merit_trial <= (1 - 2 * _ARMIJO * length) * merit:
                break
            if length <= _MIN_STEP:
                break  # accept the smallest step; the iteration limit bounds the outcome
            length /= 2
        x, ev, residual = x_trial, ev_trial, residual_trial
    return NewtonResult(x, ev, max_iterations, norm, False, "iteration limit reached")
