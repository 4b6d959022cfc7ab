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
the branch predictor and the stability eigenproblem use. With `ChordSteps` the Jacobians are
kept (chord steps on their factors) while the iterate stays close to where they were evaluated
and the steps contract; the converged point's Jacobians are then at most that distance away.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from solver.evaluation import Evaluation
from solver.factors import Factors, factorise, solve_with

__all__ = ["ChordSteps", "NewtonResult", "newton"]

_ARMIJO = 1e-4
_MIN_STEP = 1.0 / 256
_CHORD_CONTRACTION = 0.1  # a chord step at most this times the step before it (a digit gained)


@dataclass(frozen=True)
class ChordSteps:
    """Newton may keep its Jacobians while the iterate stays within `jacobian_distance` of where
    they were evaluated, measured as |dx / scale| (undamped steps only), and each chord step is
    at most a tenth of the step before it: chord steps on their factors then cost a residual
    instead of a Jacobian and a factorisation per iteration, and gain a digit each.

    Close to a root a full Newton step leaves an error of about its own length squared, and a
    chord step from there contracts it by about the Jacobians' drift, so a start that Newton's
    first step left just above the tolerance needs one chord step, not one more Newton step.
    The converged point then carries Jacobians at most `jacobian_distance` away (what the
    stability verdict is judged on, as on the path's landing points).

    scale: (n,) the state's scales; jacobian_distance: [-] in those units.
    """

    scale: np.ndarray
    jacobian_distance: float


@dataclass
class NewtonResult:
    x: np.ndarray
    evaluation: Evaluation  # residual parts at x; Jacobians at x, at the previous iterate or,
    # with chord steps, at most their jacobian_distance away
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
    chord: ChordSteps | None = None,
) -> NewtonResult:
    """Solve r0(x) + q r1(x) = 0 from x0.

    `evaluate` gives residual parts and Jacobians, `residual` the parts alone; `evaluation0`, if
    given, is an evaluation at x0 (or one whose Jacobians approximate those at x0); `chord`:
    when (and how far) the Jacobians may be kept for a chord step (see `ChordSteps`).
    """
    x = np.array(x0, dtype=float)
    ev = evaluation0 if evaluation0 is not None else evaluate(x)
    r = ev.residual(q)
    norm = float("nan")
    factors: Factors | None = None
    drift = 0.0  # scaled distance from x to where ev's Jacobians were evaluated
    previous_move = math.inf  # the last step's scaled length (inf: the Jacobians are fresh)
    for iteration in range(max_iterations + 1):
        if not np.all(np.isfinite(r)):
            return NewtonResult(x, ev, iteration, float("nan"), False, "non-finite residual")
        norm = float(np.max(np.abs(r)))
        if norm <= tolerance:
            return NewtonResult(x, ev, iteration, norm, True, "converged")
        if iteration == max_iterations:
            break
        if factors is None:
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
        moved = math.inf
        if chord is not None and length == 1.0:
            moved = float(np.linalg.norm(step / chord.scale))
        drift += moved
        # A chord step must contract like Newton close to a root, or the Jacobians are renewed.
        keep = chord is not None and drift <= chord.jacobian_distance
        keep = keep and moved <= _CHORD_CONTRACTION * previous_move
        previous_move = moved
        converged = np.all(np.isfinite(r)) and np.max(np.abs(r)) <= tolerance
        if converged or keep:
            # Keep the last Jacobians (and their factors), pair them with the residual here.
            ev = Evaluation(r0, r1, ev.jacobian0, ev.jacobian1)
        else:
            ev, factors, drift, previous_move = evaluate(x), None, 0.0, math.inf
    return NewtonResult(x, ev, max_iterations, norm, False, "iteration limit reached")
