"""Natural-parameter path following: from an equilibrium at q0 to the one at q on the same branch.

The equilibrium branch from the jig shape rises in q until its fold, so below the fold each q has
exactly one point on it, and following q is enough to stay on it. Each step predicts along the
branch tangent dx/dq = -J^{-1} r1 (J = J0 + q J1 at the current point, whose Jacobians are
already known) and corrects with Newton at the new q, its first iteration on the current point's
Jacobians re-targeted to the new q (free, the residual is affine in q).

A step is accepted only if its corrector behaves like Newton close to a root: the first
correction small against the predicted move, every later one contracting (measured in the scaled
coordinates of `solver.numerics.continuation`). Then the landing point lies close to the prediction,
on the branch the prediction followed; Newton from a poor prediction that wanders (towards a
nose-down branch, or the other side of a bistable wing) is stopped at its first large or
non-contracting correction, and the step is halved and tried again. A step's predicted move is
also capped. Steps shrink approaching a fold, where the predictor's error grows without bound;
below `min_step` times the wing's pressure scale the path stops, and the caller decides with the
branch's pseudo-arclength continuation.

Everything here is a deterministic function of the start and the target: the same request gives
the same sequence of steps, hence the same bits, whatever was asked before.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from solver.numerics.branch_points import scaled_norm
from solver.numerics.evaluation import Evaluation
from solver.numerics.factors import factorise, solve_with

__all__ = ["PathResult", "PathSettings", "follow"]


@dataclass(frozen=True)
class PathSettings:
    """Step control, in the scaled coordinates of `solver.numerics.continuation`.

    max_corrector_iterations: Newton iterations of one step before it is rejected.
    max_first_correction: largest first Newton correction, relative to the predicted move.
    max_contraction: largest ratio of consecutive Newton corrections: Newton that does not
        contract at least this fast is not converging to the point the step predicted.
    correction_floor: corrections this small are accepted whatever the move (round-off and the
        residual tolerance, in scaled units).
    max_move: largest predicted move of one step; a longer step is shortened to it.
    jacobian_distance: a landing point farther than this from where its Jacobians were last
        evaluated gets them evaluated afresh (the stability verdict is judged on them).
    min_step: smallest step [-], relative to the wing's pressure scale (the scale of q in the
        scaled coordinates), before the path stops.
    max_steps: accepted and rejected steps before the path stops.
    """

    max_corrector_iterations: int = 8
    max_first_correction: float = 0.8
    max_contraction: float = 0.5
    correction_floor: float = 1e-7
    max_move: float = 0.5
    jacobian_distance: float = 1e-4
    min_step: float = 1e-4
    max_steps: int = 80


@dataclass(frozen=True)
class PathResult:
    """Where the path ended.

    x: (n,) state at `dynamic_pressure` [Pa]; evaluation: r0, r1 at x with Jacobians at x or at
    Newton's last iterate (one step of ~sqrt(tolerance) away). reached: x is the equilibrium at
    the requested q. iterations: Newton iterations over every step; steps: accepted steps.
    """

    x: np.ndarray
    dynamic_pressure: float
    evaluation: Evaluation
    reached: bool
    iterations: int
    residual_norm: float
    steps: int
    reason: str


def follow(
    evaluate: Callable[[np.ndarray], Evaluation],
    residual: Callable[[np.ndarray], tuple[np.ndarray, np.ndarray]],
    start: np.ndarray,
    start_pressure: float,
    start_evaluation: Evaluation,
    q: float,
    scale: np.ndarray,
    tolerance: float,
    settings: PathSettings | None = None,
) -> PathResult:
    """Follow the branch through (start, start_pressure) to q [Pa].

    `start` must be an equilibrium at `start_pressure` (to the tolerance) with
    `start_evaluation` its exact evaluation; `scale` (n + 1,) the scaled coordinates.
    """
    settings = settings or PathSettings()
    x, q_now, evaluation = start, start_pressure, start_evaluation
    smallest = settings.min_step * scale[-1]  # [Pa]
    step = q - start_pressure
    iterations = steps = attempts = 0
    norm = float(np.max(np.abs(evaluation.residual(q_now))))
    while True:
        remaining = q - q_now
        if remaining == 0 and norm <= tolerance:
            return PathResult(x, q_now, evaluation, True, iterations, norm, steps, "reached")
        if attempts >= settings.max_steps:
            return PathResult(
                x, q_now, evaluation, False, iterations, norm, steps, "too many steps"
            )
        attempts += 1
        dq = remaining if abs(step) >= abs(remaining) else step
        landed = _step(evaluate, residual, x, evaluation, q_now, dq, scale, tolerance, settings)
        iterations += landed.iterations
        if landed.shorten is not None:
            step = dq * landed.shorten  # the predicted move was too long: shorten, not a failure
            continue
        if landed.accepted:
            x, q_now, evaluation = landed.x, q_now + dq, landed.evaluation
            norm = landed.residual_norm
            steps += 1
            step = dq * (2.0 if landed.iterations <= 3 else 1.0)
            continue
        step = dq / 2
        if abs(step) < smallest:
            return PathResult(
                x,
                q_now,
                evaluation,
                False,
                iterations,
                norm,
                steps,
                f"path stalled at q = {q_now:.6g} Pa ({landed.reason})",
            )


@dataclass(frozen=True)
class _Landing:
    accepted: bool
    x: np.ndarray
    evaluation: Evaluation
    iterations: int
    residual_norm: float
    reason: str
    shorten: float | None = None  # the step's predicted move is too long: shorten by this


def _step(
    evaluate: Callable[[np.ndarray], Evaluation],
    residual: Callable[[np.ndarray], tuple[np.ndarray, np.ndarray]],
    x: np.ndarray,
    evaluation: Evaluation,
    q_now: float,
    dq: float,
    scale: np.ndarray,
    tolerance: float,
    settings: PathSettings,
) -> _Landing:
    """Predict over dq, correct with Newton, judge every correction.

    Predictor: one Newton step from the current equilibrium at the new q, on its Jacobians
    re-targeted there (free: the residual is affine in q); to first order it is the tangent
    predictor x + dq dx/dq. The first correction reuses the same factors. A corrected point
    farther than `jacobian_distance` from where the Jacobians were evaluated gets them evaluated
    there (with the residual, in one call): the next correction needs them, or, if the point has
    converged, the stability verdict. A nearer point is checked by its residual alone and keeps
    them unless it has not converged. So the landing point carries Jacobians at most a small
    correction away.

    The corrector is plain Newton (no damping: a step that needs damping is too long). Its first
    correction must be small against the predicted move and each later one must contract: then
    the landing point lies within first / (1 - contraction) of the prediction, on the branch the
    prediction followed (Deuflhard's monotonicity test for continuation correctors).
    """
    q_next = q_now + dq
    factors = factorise(evaluation.jacobian(q_next))
    if factors is None:
        return _Landing(False, x, evaluation, 0, np.inf, "singular Jacobian")
    predicted = x - solve_with(factors, evaluation.residual(q_next))
    move = scaled_norm(predicted - x, scale)
    if not np.isfinite(move):
        return _Landing(False, x, evaluation, 0, np.inf, "non-finite prediction")
    if move > settings.max_move:
        return _Landing(False, x, evaluation, 0, np.inf, "long", settings.max_move / move)
    point, jacobians_at = predicted, x
    r0, r1 = residual(point)
    current = Evaluation(r0, r1, evaluation.jacobian0, evaluation.jacobian1)
    previous = np.inf
    for iteration in range(settings.max_corrector_iterations + 1):
        r = current.residual(q_next)
        if not np.all(np.isfinite(r)):
            return _Landing(False, x, evaluation, iteration, np.inf, "non-finite residual")
        norm = float(np.max(np.abs(r)))
        if norm <= tolerance:
            if scaled_norm(point - jacobians_at, scale) > settings.jacobian_distance:
                current = evaluate(point)  # judge stability on Jacobians at the landing point
            return _Landing(True, point, current, iteration + 1, norm, "accepted")
        if iteration == settings.max_corrector_iterations:
            break
        if iteration > 0:
            factors = factorise(current.jacobian(q_next))
            if factors is None:
                return _Landing(False, x, evaluation, iteration, np.inf, "singular Jacobian")
        correction = solve_with(factors, r)
        size = scaled_norm(correction, scale)
        limit = (
            settings.max_first_correction * move
            if iteration == 0
            else settings.max_contraction * previous
        )
        if size > limit + settings.correction_floor:
            reason = (
                f"first correction {size:.3g} against a predicted move of {move:.3g}"
                if iteration == 0
                else f"Newton does not contract ({size:.3g} after {previous:.3g})"
            )
            return _Landing(False, x, evaluation, iteration + 1, np.inf, reason)
        previous = size
        point = point - correction
        if scaled_norm(point - jacobians_at, scale) > settings.jacobian_distance:
            # Jacobians are needed here either way: for the next correction, or for the verdict
            # if this point has converged, so the residual alone would be computed twice.
            current, jacobians_at = evaluate(point), point
            continue
        r0, r1 = residual(point)
        if np.max(np.abs(r0 + q_next * r1)) <= tolerance:
            current = Evaluation(r0, r1, current.jacobian0, current.jacobian1)
        else:
            current, jacobians_at = evaluate(point), point
    return _Landing(
        False, x, evaluation, settings.max_corrector_iterations, np.inf, "iteration limit"
    )
