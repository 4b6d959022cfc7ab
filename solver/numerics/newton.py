"""Damped Newton's method on the coupled residual r(x) = r0(x) + q r1(x).

Convergence criterion: max_i |r_i| <= tolerance, on the residual in its physical units (heave rows
in m, slope rows dimensionless, twist rows in degrees, flow-tangency rows as normal velocity per
unit airspeed). The default 1e-10 sits far below the 1e-6 relative agreement promised with
AeroSandbox (whose own IPOPT stopping point leaves 4e-10), and Newton's quadratic convergence
makes the last factor of 1e4 cost at most one more iteration.

Each step is damped by backtracking on ||r||_2 (Armijo, halving), so a poor initial guess cannot
throw the iterate far outside the region where the model makes sense. Trial points are judged by
the residual alone (about a quarter of the cost of residual plus Jacobian); the Jacobian is
evaluated only at accepted points that have not yet converged. The converged point therefore
carries the Jacobian of the last iterate, one Newton step (of size ~sqrt(tolerance)) away: what
the branch predictor and the stability eigenproblem use.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from solver.numerics.evaluation import Evaluation
from solver.numerics.factors import factorise, solve_with

__all__ = ["NewtonResult", "newton"]

_ARMIJO = 1e-4
_MIN_STEP = 1.0 / 256


@dataclass
class NewtonResult:
    x: np.ndarray
    evaluation: Evaluation  # residual parts at x; Jacobians at x or at the previous iterate
    iterations: int
    residual_norm: float
    converged: bool
    reason: str


def newton(
    evaluate: Callable[[np.ndarray], Evaluation],
    residual: Callable[[np.ndarray], tuple[np.ndarray, np.ndarray]],
    x0: np.ndarray,
    q: float,
    tolerance: float,
    max_iterations: int,
    evaluation0: Evaluation | None = None,
) -> NewtonResult:
    """Solve r0(x) + q r1(x) = 0 from x0.

    `evaluate` gives residual parts and Jacobians, `residual` the parts alone; `evaluation0`, if
    given, is an evaluation at x0 (or one whose Jacobians approximate those at x0).
    """
    x = np.array(x0, dtype=float)
    ev = evaluation0 if evaluation0 is not None else evaluate(x)
    r = ev.residual(q)
    norm = float("nan")
    for iteration in range(max_iterations + 1):
        if not np.all(np.isfinite(r)):
            return NewtonResult(x, ev, iteration, float("nan"), False, "non-finite residual")
        norm = float(np.max(np.abs(r)))
        if norm <= tolerance:
            return NewtonResult(x, ev, iteration, norm, True, "converged")
        if iteration == max_iterations:
            break
        factors = factorise(ev.jacobian(q))
        if factors is None:
            return NewtonResult(x, ev, iteration, norm, False, "singular Jacobian")
        step = solve_with(factors, r)
        merit = float(r @ r)
        length = 1.0
        while True:
            x_trial = x - length * step
            r0, r1 = residual(x_trial)
            r_trial = r0 + q * r1
            merit_trial = float(r_trial @ r_trial)
            if np.isfinite(merit_trial) and merit_trial <= (1 - 2 * _ARMIJO * length) * merit:
                break
            if length <= _MIN_STEP:
                break  # accept the smallest step; the iteration limit bounds the outcome
            length /= 2
        x, r = x_trial, r_trial
        if np.all(np.isfinite(r)) and np.max(np.abs(r)) <= tolerance:
            # Converged: keep the last Jacobians, pair them with the residual parts here.
            ev = Evaluation(r0, r1, ev.jacobian0, ev.jacobian1)
        else:
            ev = evaluate(x)
    return NewtonResult(x, ev, max_iterations, norm, False, "iteration limit reached")
