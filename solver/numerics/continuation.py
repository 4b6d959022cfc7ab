"""Pseudo-arclength continuation of the equilibrium branch from the jig shape, and its fold.

The branch is the curve of solutions z = (x, q) of r(x, q) = r0(x) + q r1(x) = 0 that starts at
the rigid jig solution (q = 0) and follows q upward. Along it, the augmented Jacobian
[dr/dx, dr/dq] = [J0 + q J1, r1] has full row rank, so the unit tangent t is defined even where
J = J0 + q J1 alone is singular. That is the fold: the tangent's q-component dq/ds changes sign,
the branch turns back to lower q, and no equilibrium on it exists beyond q_fold.

Coordinates. x mixes metres, degrees and circulations, and q is in pascals, so arclength is
measured in scaled coordinates w = z / scale: heave per semispan, slope, twist in radians,
circulation per mean chord (each block divided by the square root of its length, N stations or
M panels, so it counts as its RMS), q per a characteristic pressure. Only the step sizes depend
on this choice, not the branch or its fold.

Each step: predictor w + ds t; corrector Newton on the bordered system
    [J, r1 ] dw = -[ r(x, q)                ]
    [ t^T   ]       [ t^T (w - w_predicted) ]
(columns scaled). The first correction uses the previous point's Jacobians (a chord step: the
prediction needs only its residual), the next one Jacobians evaluated at the first corrected
point, and a step finishes with a chord correction on those same factors: one Jacobian per step.
The tangent at the converged point (and the orientation, the sign of the bordered determinant)
comes from the last factorisation with one more triangular solve. The fold, once bracketed by a
sign change of dq/ds, is located along the hyperplanes of the last step, first where the cubic
through the bracket ends' q and dq/ds turns, then by regula falsi (Illinois) on dq/ds, each
trial on freshly evaluated Jacobians: near a fold dq/ds is linear in arclength and q quadratic,
so two or three trials give q to ~1e-10 relative.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from solver.numerics.branch_points import Branch, BranchPoint, ContinuationSettings, scaled
from solver.numerics.evaluation import Evaluation
from solver.numerics.factors import Factors, factorise, solve_with

__all__ = ["BranchTracer"]


def _bordered(evaluation: Evaluation, q: float, scale: np.ndarray, row: np.ndarray) -> np.ndarray:
    """(n + 1, n + 1) [[J scale_x, r1 scale_q], [row]]: the scaled augmented Jacobian,
    bordered."""
    n = evaluation.r0.size
    matrix = np.empty((n + 1, n + 1))
    matrix[:n, :n] = evaluation.jacobian(q) * scale[:-1]
    matrix[:n, n] = evaluation.r1 * scale[-1]
    matrix[n] = row
    return matrix


def _tangent_and_orientation(factors: Factors) -> tuple[np.ndarray, int] | None:
    """From the factors of B = [[J scale_x, r1 scale_q], [previous^T]]: the unit tangent at
    (x, q), oriented so that its projection on `previous` is positive, and the orientation,
    the sign of det [[J, r1], [t^T]]: constant along a branch, flips across a bifurcation.

    With u = B^{-1} e_last the tangent is t = u / |u|, and previous . u = 1; the orientation's
    matrix is B with its last row moved by (t - previous)^T, so by the matrix determinant lemma
    its determinant is det(B) (1 + (t - previous) . u) = det(B) |u|: the sign of det(B), which
    the LU factors give for free (a second factorisation saved per branch point).

    (A fold does not flip the orientation: there the augmented Jacobian keeps full rank. dq/ds,
    which equals det J over this determinant, flips through det J instead.)

    None if the factors overflowed (a tangent that is not finite).
    """
    lu, pivots = factors
    last = np.zeros(lu.shape[0])
    last[-1] = 1.0
    u = solve_with(factors, last)
    length = float(np.linalg.norm(u))
    if not math.isfinite(length):
        return None
    swaps = int(np.count_nonzero(pivots != np.arange(pivots.size)))
    sign = (-1) ** swaps * int(np.prod(np.sign(np.diag(lu))))
    return u / length, sign


@dataclass
class _Corrected:
    w: np.ndarray
    evaluation: Evaluation
    tangent: np.ndarray
    first_correction: float  # [-] norm of the first Newton update (the predictor's error)
    displacement: float  # [-] distance from the start of the corrector
    orientation: int  # sign of det [[J, r1], [tangent^T]] (scaled)


class _Tracer:
    """State of one continuation run: the model, its scaling and the evaluation count."""

    def __init__(
        self,
        evaluate: Callable[[np.ndarray], Evaluation],
        residual: Callable[[np.ndarray], tuple[np.ndarray, np.ndarray]],
        scale: np.ndarray,
        settings: ContinuationSettings,
    ) -> None:
        self.evaluate_x = evaluate
        self.residual_x = residual
        self.scale = scale
        self.settings = settings
        self.evaluations = 0

    def evaluate(self, w: np.ndarray) -> Evaluation:
        self.evaluations += 1
        return self.evaluate_x(w[:-1] * self.scale[:-1])

    def correct(
        self,
        w_start: np.ndarray,
        normal: np.ndarray,
        offset: float,
        jacobians: Evaluation | None = None,
        chord_finish: bool = False,
    ) -> _Corrected | None:
        """Newton on r = 0 within the hyperplane normal . w = offset, from w_start.

        `jacobians`: an evaluation whose Jacobians the first correction may use (the previous
        branch point's, for a predictor step from it: a chord step, which spares evaluating
        them at the prediction); the Jacobians are then evaluated at the first corrected point.
        After later corrections the residual alone is checked first; the Jacobians are evaluated
        only where it has not converged, so the corrected point carries those of the iterate
        one correction before it (which its tangent uses: an error of the order of that last,
        small correction).

        `chord_finish`: where the residual has not converged after a Newton correction, first
        try one more correction on the same factors (a chord step, a residual's cost) before
        evaluating Jacobians there. Newton has already squared the error, so the chord step
        usually converges; the point then carries the Jacobians of the iterate two corrections
        back, and its tangent is good to ~1e-4 instead of ~1e-8. A continuation step takes one
        Jacobian instead of two, and the branch's Hermite starts still converge in the same
        Newton iterations (measured on 72 wings: 602 Jacobians for their known-wing sweeps
        against 610). The fold's trials do not take it: the fold is located on exact tangents."""
        w = w_start.copy()
        first_correction = 0.0
        if jacobians is None:
            evaluation, stale = self.evaluate(w), False
        else:
            r0, r1 = self.residual_x(w[:-1] * self.scale[:-1])
            evaluation, stale = Evaluation(r0, r1, jacobians.jacobian0, jacobians.jacobian1), True
        # The factors of the last correction's bordered matrix, and whose Jacobians they hold:
        # a point that converges on those Jacobians takes its tangent from the same factors.
        factors: Factors | None = None
        factored: np.ndarray | None = None
        for iteration in range(self.settings.max_corrector_iterations + 1):
            q = w[-1] * self.scale[-1]
            residual = evaluation.residual(q)
            if not np.all(np.isfinite(residual)):
                return None
            if np.max(np.abs(residual)) <= self.settings.tolerance and iteration > 0:
                if factors is None or factored is not evaluation.jacobian0:
                    factors = factorise(_bordered(evaluation, q, self.scale, normal))
                found = None if factors is None else _tangent_and_orientation(factors)
                if found is None:
                    return None
                tangent, orientation = found
                displacement = float(np.linalg.norm(w - w_start))
                return _Corrected(
                    w, evaluation, tangent, first_correction, displacement, orientation
                )
            if iteration == self.settings.max_corrector_iterations:
                return None
            factors = factorise(_bordered(evaluation, q, self.scale, normal))
            if factors is None:
                return None
            factored = evaluation.jacobian0
            rhs = np.append(residual, normal @ w - offset)
            update = solve_with(factors, rhs)
            if iteration == 0:
                first_correction = float(np.linalg.norm(update))
            w = w - update
            if stale:  # the chord step's Jacobians are a whole step away: evaluate them here
                evaluation, stale = self.evaluate(w), False
                continue
            r0, r1, q = self._residual(w)
            if chord_finish and not self._converged(r0, r1, q):
                chord = solve_with(factors, np.append(r0 + q * r1, normal @ w - offset))
                w_chord = w - chord
                chord_r0, chord_r1, chord_q = self._residual(w_chord)
                if self._converged(chord_r0, chord_r1, chord_q):
                    w, r0, r1, q = w_chord, chord_r0, chord_r1, chord_q
            if self._converged(r0, r1, q):
                evaluation = Evaluation(r0, r1, evaluation.jacobian0, evaluation.jacobian1)
            else:
                evaluation = self.evaluate(w)
        return None

    def _residual(self, w: np.ndarray) -> tuple[np.ndarray, np.ndarray, float]:
        """r0, r1 at the scaled point w, and its q [Pa]."""
        r0, r1 = self.residual_x(w[:-1] * self.scale[:-1])
        return r0, r1, float(w[-1] * self.scale[-1])

    def _converged(self, r0: np.ndarray, r1: np.ndarray, q: float) -> bool:
        r = r0 + q * r1
        return bool(np.all(np.isfinite(r)) and np.max(np.abs(r)) <= self.settings.tolerance)


class BranchTracer:
    """The branch from (jig_state, q = 0), traced lazily and resumably.

    `extend(q_limit)` follows the branch until a point reaches q_limit, the fold, or a stall;
    a later `extend` to a higher limit continues from the stored step state exactly where a
    single longer trace would be. The points traced are therefore a function of the wing and
    alpha alone, never of the limits asked for or their order: `view(q_limit)` is the canonical
    prefix a fresh trace to q_limit would have produced.

    `evaluate(x)` returns r0, r1, J0, J1 at x for the wing and alpha of interest, `residual(x)`
    r0 and r1 alone; `jig_state` must solve r0 = 0 (the rigid solution, exact at q = 0), and
    `jig_evaluation`, if given, is `evaluate(jig_state)` already made (the jig's own: one
    evaluation fewer, the same bits).
    """

    def __init__(
        self,
        evaluate: Callable[[np.ndarray], Evaluation],
        residual: Callable[[np.ndarray], tuple[np.ndarray, np.ndarray]],
        jig_state: np.ndarray,
        scale: np.ndarray,
        settings: ContinuationSettings | None = None,
        jig_evaluation: Evaluation | None = None,
    ) -> None:
        self._tracer = _Tracer(evaluate, residual, scale, settings or ContinuationSettings())
        self.scale = scale
        w = scaled(jig_state, 0.0, scale)
        evaluation = jig_evaluation if jig_evaluation is not None else self._tracer.evaluate(w)
        upward = np.zeros(w.size)
        upward[-1] = 1.0
        factors = factorise(_bordered(evaluation, 0.0, scale, upward))
        found = None if factors is None else _tangent_and_orientation(factors)
        if found is None:
            raise np.linalg.LinAlgError("the augmented Jacobian at the jig is singular")
        tangent, self._orientation = found
        # The last point's evaluation: its Jacobians serve the next predictor step's first
        # correction (part of the step state, like the step length).
        self._evaluation = evaluation
        self.points: list[BranchPoint] = [
            BranchPoint(jig_state.copy(), 0.0, tangent, 0.0, self._tracer.evaluations)
        ]
        self._step = self._tracer.settings.initial_step
        self._steps = 0
        self.folded = False
        self.reason: str | None = None  # why tracing stopped for good short of the fold

    @property
    def finished(self) -> bool:
        return self.folded or self.reason is not None

    @property
    def nbytes(self) -> int:
        points = sum(point.state.nbytes + point.tangent.nbytes for point in self.points)
        return points + self._evaluation.nbytes

    def extend(self, q_limit: float) -> None:
        """Trace on until the last point reaches q_limit [Pa], the fold, or a stall."""
        settings = self._tracer.settings
        while not self.finished and self.points[-1].dynamic_pressure < q_limit:
            if self._steps >= settings.max_steps:
                self.reason = f"no fold within {settings.max_steps} continuation steps"
                return
            self._steps += 1
            self._advance()

    def view(self, q_limit: float) -> Branch:
        """The canonical branch up to q_limit: points to the first at or beyond it (or the
        fold, or the stall), exactly as a fresh trace to q_limit would hold them."""
        self.extend(q_limit)
        points = self.points
        for index, point in enumerate(points):
            if point.dynamic_pressure >= q_limit:
                is_last = index == len(points) - 1
                return Branch(
                    tuple(points[: index + 1]),
                    self.folded and is_last,
                    self.scale,
                    q_limit,
                    point.evaluations,
                    self.reason if is_last else None,
                )
        return Branch(
            tuple(points), self.folded, self.scale, q_limit, points[-1].evaluations, self.reason
        )

    def _advance(self) -> None:
        """One predictor-corrector step (or a rejected one, which halves the step)."""
        settings = self._tracer.settings
        current = self.points[-1]
        step = self._step
        w = scaled(current.state, current.dynamic_pressure, self.scale)
        predicted = w + step * current.tangent
        corrected = self._tracer.correct(
            predicted,
            current.tangent,
            float(current.tangent @ predicted),
            self._evaluation,
            chord_finish=True,
        )
        turn = (
            math.acos(min(1.0, float(corrected.tangent @ current.tangent)))
            if corrected is not None
            else math.inf
        )
        # Reject a step that turned too far, moved too far from its prediction, or crossed a
        # bifurcation: near-bifurcations (a wing at small alpha, whose branch folds just short
        # of the linear divergence) let a long step land on another branch whose tangent looks
        # like ours; only the orientation flip tells.
        # ...or left the physical half-plane: the branch from the jig rises from q = 0, and a
        # point at q <= 0 means the corrector lost it (absurd pressure scales do that).
        if (
            corrected is None
            or turn > settings.max_turn
            or corrected.displacement > settings.max_displacement * step
            or corrected.orientation != self._orientation
            or corrected.w[-1] <= 0
        ):
            self._step = step / 2
            if self._step < settings.min_step:
                self.reason = _stalled(current)
            return
        point = _point(corrected, self.scale, current, self._tracer.evaluations)
        if point.dq_ds <= 0:
            fold = _locate_fold(self._tracer, current, point, self._orientation)
            self.points.append(dataclasses.replace(fold, evaluations=self._tracer.evaluations))
            self.folded = True
            return
        self.points.append(point)
        self._evaluation = corrected.evaluation
        # Aim the next predictor error and turn at their targets; the predictor's error grows
        # as step^2, the turn as step.
        growth = min(
            math.sqrt(settings.target_correction * step / max(corrected.first_correction, 1e-300)),
            settings.max_turn / 2 / max(turn, 1e-300),
            2.0,
        )
        self._step = min(max(growth, 0.5) * step, settings.max_step)


def _stalled(point: BranchPoint) -> str:
    return (
        f"continuation stalled at q = {point.dynamic_pressure:.6g} Pa (step below minimum: "
        "a bifurcation or a corner of the branch)"
    )


def _point(
    corrected: _Corrected, scale: np.ndarray, previous: BranchPoint, evaluations: int
) -> BranchPoint:
    """A branch point from a corrected one; arclength accumulates chord lengths."""
    x = corrected.w[:-1] * scale[:-1]
    q = float(corrected.w[-1] * scale[-1])
    chord = np.linalg.norm(corrected.w - scaled(previous.state, previous.dynamic_pressure, scale))
    return BranchPoint(x, q, corrected.tangent, previous.arclength + float(chord), evaluations)


def _locate_fold(
    tracer: _Tracer, before: BranchPoint, after: BranchPoint, orientation: int
) -> BranchPoint:
    """The fold between `before` (dq/ds > 0) and `after` (dq/ds <= 0).

    Points are parameterised by their offset sigma along `before`'s tangent (the hyperplanes of
    the step that bracketed the fold); dq/ds(sigma) changes sign on [0, sigma_after], and
    Illinois regula falsi finds its root, each trial point started from the chord between the
    current bracket ends. The first trial is where the cubic through both ends' q and
    dq/dsigma turns: near a fold q is quadratic in sigma, which a straight line through the
    ends' dq/ds (regula falsi's first guess) misses by far more.
    """
    scale = tracer.scale
    normal = before.tangent
    w_before = scaled(before.state, before.dynamic_pressure, scale)
    w_after = scaled(after.state, after.dynamic_pressure, scale)
    low = (0.0, before.dq_ds, w_before)
    high = (float(normal @ (w_after - w_before)), after.dq_ds, w_after)
    best = after if abs(after.dq_ds) < before.dq_ds else before
    first = _turning_point(
        high[0],
        float(w_after[-1] - w_before[-1]),
        before.dq_ds,
        after.dq_ds / float(normal @ after.tangent),
    )
    side = 0
    for _ in range(tracer.settings.max_fold_iterations):
        (s_low, f_low, w_low), (s_high, f_high, w_high) = low, high
        if abs(best.dq_ds) <= tracer.settings.fold_tolerance:
            break
        if not s_high - s_low > 0:  # the bracket has no width left in floating point
            break
        if first is not None:
            sigma, first = first, None
        else:
            sigma = s_low - f_low * (s_high - s_low) / (f_high - f_low)
        fraction = (sigma - s_low) / (s_high - s_low)
        start = w_low + fraction * (w_high - w_low)
        corrected = tracer.correct(start, normal, float(normal @ w_before) + sigma)
        if corrected is None or corrected.orientation != orientation:
            break
        # Hyperplanes orthogonal to `normal` keep the orientation of `before`'s tangent.
        trial = _point(corrected, scale, before, tracer.evaluations)
        if abs(trial.dq_ds) < abs(best.dq_ds):
            best = trial
        if trial.dq_ds > 0:
            low = (sigma, trial.dq_ds, corrected.w)
            if side == 1:  # Illinois: halve the stale end's weight so both ends move
                high = (s_high, f_high / 2, w_high)
            side = 1
        else:
            high = (sigma, trial.dq_ds, corrected.w)
            if side == -1:
                low = (s_low, f_low / 2, w_low)
            side = -1
    return best


def _turning_point(width: float, rise: float, slope_start: float, slope_end: float) -> float | None:
    """Where the cubic Hermite q(sigma) on [0, width] through q(0) = 0, q(width) = rise,
    q'(0) = slope_start > 0 and q'(width) = slope_end <= 0 has q' = 0 (scaled units), or None
    if that is not strictly inside. With t = sigma / width, q'(sigma) = a t^2 + b t + c."""
    if not (width > 0 and slope_start > 0 >= slope_end):
        return None
    chord = rise / width
    a = 3 * (slope_start + slope_end) - 6 * chord
    b = 6 * chord - 4 * slope_start - 2 * slope_end
    c = slope_start
    if abs(a) <= 1e-12 * (abs(b) + abs(c)):
        t = -c / b if b != 0 else math.nan
    else:
        root = math.sqrt(max(b * b - 4 * a * c, 0.0))
        # The root in (0, 1): q' falls from c > 0 to a + b + c <= 0 across it (numerically
        # stable form of the two roots).
        half = -0.5 * (b + math.copysign(root, b))
        candidates = [half / a, c / half if half != 0 else math.nan]
        inside = [t for t in candidates if 0 < t < 1]
        t = min(inside) if inside else math.nan
    return t * width if 0 < t < 1 else None
