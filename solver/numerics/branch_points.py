"""What a traced branch is: its points (state, dynamic pressure, tangent, orientation), the
branch as far as it was followed, read anywhere along it by cubic Hermite interpolation, the
scaled coordinates it is traced in (`branch_scales`: see `solver.numerics.continuation`'s
docstring), and the continuation's settings; `solver.numerics.continuation` traces it."""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass
from typing import TypeVar

import numpy as np

from solver.model.layout import Layout

__all__ = [
    "Branch",
    "BranchPoint",
    "ContinuationSettings",
    "branch_scales",
    "scaled",
    "scaled_norm",
]

# A scaled state (n + 1,) or one of its components: cubic Hermite interpolation serves both.
_Value = TypeVar("_Value", float, np.ndarray)
# Where the interpolating cubic reaches a requested q: Newton in tau in [0, 1] until its step is
# round-off, safeguarded by bisection (which alone needs the 60 to reach round-off).
_HERMITE_ITERATIONS = 60
_HERMITE_TOLERANCE = 1e-15


@dataclass(frozen=True)
class ContinuationSettings:
    """Step control of the continuation, in scaled coordinates (see the module docstring).

    tolerance: max-norm of r at a corrected point (units in `solver.model.residual`).
    initial_step, min_step, max_step: arclength steps [-].
    max_corrector_iterations: Newton iterations before a step is rejected and halved.
    target_correction: the first corrector update we aim for, relative to the step: the
        predictor's error grows as ds^2 times the branch curvature, so this bounds the curvature
        per step.
    max_turn: [rad] largest angle between consecutive tangents of an accepted step (so a step
        cannot jump across the fold onto a distant part of the curve unnoticed).
    max_displacement: largest corrector displacement of an accepted step, relative to the step.
    max_steps: steps, accepted or rejected (each rejection halves the step), before giving
        up.
    fold_tolerance: |dq/ds| at which the fold counts as located. q is quadratic in arclength
        there, so q's relative error is about this squared; so tight that Newton from the
        branch still finds the stable side 1e-6 below the fold (costs one or two evaluations).
    """

    tolerance: float = 1e-10
    initial_step: float = 0.2
    min_step: float = 1e-6
    max_step: float = 2.0
    max_corrector_iterations: int = 6
    target_correction: float = 0.05
    max_turn: float = 0.35
    max_displacement: float = 0.5
    max_steps: int = 200
    fold_tolerance: float = 1e-6
    max_fold_iterations: int = 12


@dataclass(frozen=True)
class BranchPoint:
    """A converged equilibrium on the branch.

    state: (n,) x at this point, n = 3N + M unknowns (units in `solver.model.layout`).
    dynamic_pressure: q [Pa].
    tangent: (n + 1,) unit tangent dw/ds in scaled coordinates, oriented along the branch.
    arclength: s [-] from the jig, in scaled coordinates (chord lengths between points).
    """

    state: np.ndarray
    dynamic_pressure: float
    tangent: np.ndarray
    arclength: float
    evaluations: int = 0  # model evaluations spent from the jig to this point

    @property
    def dq_ds(self) -> float:
        """The tangent's q-component (scaled): positive before the fold, negative after."""
        return float(self.tangent[-1])


@dataclass(frozen=True)
class Branch:
    """The branch from the jig shape up to its fold or to the search limit.

    points: jig first, ordered along the branch; if `folded`, the last point is the fold.
    scale: (n + 1,) z = scale * w.
    q_limit: [Pa] the search limit it was traced for.
    evaluations: model evaluations spent.
    reason: why it stopped short of both the fold and q_limit (None otherwise).
    """

    points: tuple[BranchPoint, ...]
    folded: bool
    scale: np.ndarray
    q_limit: float
    evaluations: int
    reason: str | None = None

    @property
    def fold(self) -> BranchPoint | None:
        return self.points[-1] if self.folded else None

    @property
    def reached_pressure(self) -> float:
        """[Pa] the largest q on the branch that was followed."""
        return max(point.dynamic_pressure for point in self.points)

    def start_for(self, q: float) -> np.ndarray:
        """(n,) a starting state for Newton at q [Pa] on the stable part of the branch.

        Cubic Hermite interpolation in arclength between the two branch points that bracket q
        (error O(ds^4), so Newton starts well inside its basin even close to the fold); beyond
        the branch's reach, its last point.
        """
        points = self.points
        for left, right in itertools.pairwise(points):
            if left.dynamic_pressure <= q <= right.dynamic_pressure and right.dq_ds >= 0:
                return self._interpolate(left, right, q)
        return points[-1].state.copy()

    def _interpolate(self, left: BranchPoint, right: BranchPoint, q: float) -> np.ndarray:
        w_left = scaled(left.state, left.dynamic_pressure, self.scale)
        w_right = scaled(right.state, right.dynamic_pressure, self.scale)
        h = right.arclength - left.arclength

        def hermite(
            tau: float, start: _Value, start_slope: _Value, end: _Value, end_slope: _Value
        ) -> _Value:
            tau2, tau3 = tau * tau, tau * tau * tau
            return (
                (2 * tau3 - 3 * tau2 + 1) * start
                + (tau3 - 2 * tau2 + tau) * h * start_slope
                + (-2 * tau3 + 3 * tau2) * end
                + (tau3 - tau2) * h * end_slope
            )

        def hermite_slope(
            tau: float, start: float, start_slope: float, end: float, end_slope: float
        ) -> float:
            """d/dtau of `hermite`."""
            tau2 = tau * tau
            return (
                (6 * tau2 - 6 * tau) * start
                + (3 * tau2 - 4 * tau + 1) * h * start_slope
                + (-6 * tau2 + 6 * tau) * end
                + (3 * tau2 - 2 * tau) * h * end_slope
            )

        ends = (w_left, left.tangent, w_right, right.tangent)
        q_ends = [float(end[-1]) for end in ends]
        target = q / self.scale[-1]
        # q(tau) rises from the left end to the right end of a pre-fold segment: solve
        # q(tau) = target on the q component alone by Newton, kept inside a bisection bracket
        # (a few iterations where bisection took sixty), then build the state once.
        low, high = 0.0, 1.0
        span = q_ends[2] - q_ends[0]
        tau = min(max((target - q_ends[0]) / span, 0.0), 1.0) if span > 0 else 0.5
        for _ in range(_HERMITE_ITERATIONS):
            excess = hermite(tau, *q_ends) - target
            if excess == 0:
                break
            if excess < 0:
                low = tau
            else:
                high = tau
            slope = hermite_slope(tau, *q_ends)
            step = excess / slope if slope > 0 else math.inf
            following = tau - step
            if not low < following < high:
                following = 0.5 * (low + high)
            if abs(following - tau) <= _HERMITE_TOLERANCE:
                break
            tau = following
        state_ends = [end[:-1] for end in ends]
        return hermite(tau, *state_ends) * self.scale[:-1]


def branch_scales(layout: Layout, semispan: float, mean_chord: float, q_scale: float) -> np.ndarray:
    """(n + 1,) scale factors z = scale * w (see the module docstring)."""
    rms_stations, rms_panels = math.sqrt(layout.n), math.sqrt(layout.n_panels)
    scale = np.empty(layout.n_unknowns + 1)
    scale[layout.heave] = semispan * rms_stations
    scale[layout.slope] = rms_stations
    scale[layout.twist] = math.degrees(1.0) * rms_stations
    scale[layout.lag_displacement] = semispan * rms_stations  # with lag (empty without)
    scale[layout.lag_rotation] = rms_stations
    scale[layout.circulation] = mean_chord * rms_panels
    scale[-1] = q_scale
    return scale


def scaled(x: np.ndarray, q: float, scale: np.ndarray) -> np.ndarray:
    return np.append(x, q) / scale


def scaled_norm(dx: np.ndarray, scale: np.ndarray) -> float:
    """Euclidean norm of a state difference (n,) in the scaled coordinates of `scale` (n + 1,).

    sqrt(v . v), the number `np.linalg.norm` gives for a vector, without its per-call overhead:
    the path takes several norms per step."""
    scaled = dx / scale[:-1]
    return math.sqrt(float(scaled @ scaled))
