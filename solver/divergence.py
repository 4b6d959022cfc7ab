"""Torsional divergence: three estimates that check each other (issue 3).

- linear: the classical eigenvalue at the unloaded jig (`solver.stability`).
- fit: the design study's estimate, 1/A against q over a sweep's stable points, extrapolated.
- fold: where the equilibrium branch from the jig shape ends (pseudo-arclength continuation,
  `solver.continuation`). This is the limit that matters: no equilibrium on the branch exists
  beyond it, and it lies below the other two for a wing at positive lift (the study's wing:
  fold 21.44 m/s, linear 24.22 m/s, fit 26.2 m/s).

CONTRACT (used by app/): the dataclasses below and `find_fold`, `divergence_summary`.
"""

from __future__ import annotations

import math
import threading
from collections import OrderedDict
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from solver.compiled import model_for
from solver.continuation import Branch, branch_scales, trace_branch
from solver.equilibrium import Equilibrium, linear_divergence_pressure, rigid_solution
from solver.wing import FlightCondition, Wing

__all__ = [
    "LinearDivergence",
    "FitDivergence",
    "Fold",
    "DivergenceSummary",
    "linear_divergence",
    "fit_divergence",
    "find_fold",
    "equilibrium_branch",
    "clear_branch_cache",
    "known_fold_pressure",
    "search_velocity_limit",
    "divergence_summary",
]


@dataclass(frozen=True)
class LinearDivergence:
    """Classical linear divergence at the unloaded jig; None values with a reason if none."""

    dynamic_pressure: float | None  # [Pa]
    velocity: float | None  # [m/s] at the sweep's density
    reason: str | None = None


@dataclass(frozen=True)
class FitDivergence:
    """The study's fit 1/A = intercept + slope q over stable sweep points.

    amplification: which ratio A is, "CL" (the study's: CL on the deformed planform area over the
        rigid CL on the jig area) or "lift" (L / L_rigid).
    points_used: how many stable equilibria entered the fit.
    """

    slope: float | None  # [1/Pa]
    intercept: float | None  # [-]
    dynamic_pressure: float | None  # [Pa] where 1/A -> 0
    velocity: float | None  # [m/s]
    reason: str | None = None
    amplification: str = "CL"
    points_used: int = 0


@dataclass(frozen=True)
class Fold:
    """The fold of the equilibrium branch from the jig shape (its last equilibrium).

    tip_heave: [m] at the fold. evaluations: model evaluations the continuation spent.
    """

    velocity: float | None  # [m/s]
    dynamic_pressure: float | None  # [Pa]
    tip_twist: float | None  # [deg] at the fold
    lift: float | None  # [N] at the fold
    searched_to_velocity: float  # [m/s] how far the branch was followed
    reason: str | None = None
    tip_heave: float | None = None
    evaluations: int = 0


@dataclass(frozen=True)
class DivergenceSummary:
    linear: LinearDivergence
    fit: FitDivergence
    fold: Fold

    @property
    def limit_velocity(self) -> float | None:
        """[m/s] the speed users should see first: the fold, where equilibria end."""
        return self.fold.velocity


def linear_divergence(wing: Wing, density: float) -> LinearDivergence:
    """The classical eigenvalue q_div at the unloaded jig (alpha = 0), and V at `density`."""
    q_div = linear_divergence_pressure(wing)
    if q_div is None:
        return LinearDivergence(
            None,
            None,
            "no positive real divergence eigenvalue: aerodynamic torque never overcomes the "
            "structure (e.g. the elastic axis lies ahead of the aerodynamic centre)",
        )
    return LinearDivergence(q_div, FlightCondition.velocity_for(q_div, density))


def fit_divergence(equilibria: Sequence[Equilibrium], amplification: str = "CL") -> FitDivergence:
    """The study's fit: least squares 1/A = intercept + slope q over the stable equilibria.

    amplification "CL": A = CL / CL_rigid with CL on the deformed planform area and CL_rigid on
    the jig area, as the study computes it (its numbers: intercept 0.998, q_div 419 Pa); "lift":
    A = L / L_rigid. V_div uses the density of the first equilibrium.
    """
    if amplification not in ("CL", "lift"):
        raise ValueError(f"amplification must be 'CL' or 'lift', got {amplification!r}")
    stable = [e for e in equilibria if e.stability.stable and _amplification(e, amplification) > 0]
    pressures = np.array([e.dynamic_pressure for e in stable])
    if np.unique(pressures).size < 2:
        return FitDivergence(
            None,
            None,
            None,
            None,
            f"the fit needs stable, lifting equilibria at two or more airspeeds, got {len(stable)}",
            amplification,
            len(stable),
        )
    inverse = np.array([1.0 / _amplification(e, amplification) for e in stable])
    slope, intercept = (float(c) for c in np.polyfit(pressures, inverse, 1))
    if not (math.isfinite(slope) and math.isfinite(intercept)):
        return FitDivergence(
            None, None, None, None, "the fit is not finite", amplification, len(stable)
        )
    if slope >= 0:
        return FitDivergence(
            slope,
            intercept,
            None,
            None,
            "1/A does not fall with q: the fit predicts no divergence",
            amplification,
            len(stable),
        )
    q_div = -intercept / slope
    density = stable[0].flight.density
    velocity = FlightCondition.velocity_for(q_div, density) if q_div > 0 else None
    return FitDivergence(
        slope,
        intercept,
        q_div,
        velocity,
        None if q_div > 0 else "the fitted line reaches 1/A = 0 at negative q",
        amplification,
        len(stable),
    )


def _amplification(equilibrium: Equilibrium, amplification: str) -> float:
    """A [-]: lift or CL (deformed area) over the rigid jig's; NaN where the rigid lift is 0.

    A wing at (nearly) zero lift has no meaningful amplification: Newton may stop on the
    unloaded jig when the whole residual lies within tolerance.
    """
    if equilibrium.rigid_lift == 0:
        return math.nan
    ratio = equilibrium.lift / equilibrium.rigid_lift
    if amplification == "CL":
        ratio *= equilibrium.reference_area / equilibrium.deformed_area
    return ratio if math.isfinite(ratio) else math.nan


# Past the linear divergence speed by this factor the search goes on: with a load on the jig the
# fold can lie above the alpha = 0 eigenvalue (the z Fx torque term makes it alpha-dependent).
_PAST_LINEAR = 1.25
# ... and at least this multiple of the largest requested speed.
_PAST_REQUESTED = 1.5


def search_velocity_limit(wing: Wing, density: float, velocity: float) -> float:
    """[m/s] how far to follow the branch when `velocity` is the largest speed asked for."""
    limit = _PAST_REQUESTED * velocity
    q_div = linear_divergence_pressure(wing)
    if q_div is not None:
        limit = max(limit, _PAST_LINEAR * FlightCondition.velocity_for(q_div, density))
    return limit


_CACHE_SIZE = 64
_branches: OrderedDict[bytes, Branch] = OrderedDict()
_branches_lock = threading.Lock()


def equilibrium_branch(wing: Wing, alpha: float, q_limit: float) -> Branch:
    """The branch from the jig shape at `alpha` [deg], followed to its fold or to q_limit [Pa].

    Cached per wing and alpha (a branch is density-free: everything depends on q): a cached
    branch serves any request it already answers (it folded, stalled, or went far enough).
    """
    key = wing.parameters(alpha).tobytes()
    with _branches_lock:
        cached = _branches.get(key)
        if cached is not None and (
            cached.folded or cached.reason is not None or cached.q_limit >= q_limit
        ):
            _branches.move_to_end(key)
            return cached
    model = model_for(wing.n_stations)
    p = wing.parameters(alpha)
    q_linear = linear_divergence_pressure(wing)
    # Scale q by the pressure the branch is expected to turn at, so steps are alike for all wings.
    q_scale = q_limit if q_linear is None else min(q_linear, q_limit)
    scale = branch_scales(model.layout, wing.semispan, _mean_chord(wing), q_scale)
    branch = trace_branch(
        lambda x: model.evaluate(x, p), np.array(rigid_solution(wing, alpha)), scale, q_limit
    )
    with _branches_lock:
        _branches[key] = branch
        while len(_branches) > _CACHE_SIZE:
            _branches.popitem(last=False)
    return branch


def known_fold_pressure(wing: Wing, alpha: float) -> float | None:
    """[Pa] the fold's dynamic pressure if a cached branch has already found it, else None.

    Never traces: `solve` uses it to answer a request beyond a known fold without Newton.
    """
    with _branches_lock:
        cached = _branches.get(wing.parameters(alpha).tobytes())
    fold = None if cached is None else cached.fold
    return None if fold is None else fold.dynamic_pressure


def clear_branch_cache() -> None:
    """Forget every traced branch (benchmarks, and callers that must bound memory)."""
    with _branches_lock:
        _branches.clear()


def _mean_chord(wing: Wing) -> float:
    return wing.planform_area / (2 * wing.semispan)


def find_fold(
    wing: Wing, alpha: float, density: float, velocity_limit: float | None = None
) -> Fold:
    """The fold of the equilibrium branch from the jig shape at `alpha` [deg].

    The branch is searched up to `velocity_limit` [m/s] (default: past the linear divergence
    speed, see `search_velocity_limit`); speeds are at `density` [kg/m^3].
    """
    if velocity_limit is None:
        velocity_limit = search_velocity_limit(wing, density, 0.0)
    if velocity_limit <= 0:
        return Fold(None, None, None, None, 0.0, "no search limit: no speed requested")
    if _jig_unloaded(wing, alpha):
        return _bifurcation(wing, density, velocity_limit)
    branch = equilibrium_branch(wing, alpha, 0.5 * density * velocity_limit**2)
    reached = FlightCondition.velocity_for(branch.reached_pressure, density)
    fold = branch.fold
    if fold is None:
        reason = branch.reason or (
            f"no fold up to {reached:.4g} m/s: the branch from the jig shape continues"
        )
        return Fold(None, None, None, None, reached, reason, evaluations=branch.evaluations)
    layout = model_for(wing.n_stations).layout
    return Fold(
        velocity=FlightCondition.velocity_for(fold.dynamic_pressure, density),
        dynamic_pressure=fold.dynamic_pressure,
        tip_twist=float(fold.state[layout.twist][-1]),
        lift=_lift(wing, alpha, fold.state, fold.dynamic_pressure),
        searched_to_velocity=reached,
        tip_heave=float(fold.state[layout.heave][-1]),
        evaluations=branch.evaluations,
    )


def _jig_unloaded(wing: Wing, alpha: float) -> bool:
    """At alpha = 0 an uncambered jig carries no circulation, hence no load, at any q."""
    circulation = rigid_solution(wing, alpha)[model_for(wing.n_stations).layout.circulation]
    return bool(np.all(circulation == 0.0))


def _bifurcation(wing: Wing, density: float, velocity_limit: float) -> Fold:
    """An unloaded jig stays an equilibrium at every q and loses stability at the eigenvalue."""
    q_div = linear_divergence_pressure(wing)
    if q_div is None:
        return Fold(
            None,
            None,
            None,
            None,
            velocity_limit,
            "the unloaded jig is a stable equilibrium at every speed",
        )
    return Fold(
        velocity=FlightCondition.velocity_for(q_div, density),
        dynamic_pressure=q_div,
        tip_twist=0.0,
        lift=0.0,
        searched_to_velocity=FlightCondition.velocity_for(q_div, density),
        reason=(
            "the jig carries no load at this angle of attack: it stays an equilibrium but loses "
            "stability at the linear divergence (a bifurcation, not a fold)"
        ),
        tip_heave=0.0,
    )


def _lift(wing: Wing, alpha: float, x: np.ndarray, q: float) -> float:
    """[N] lift of both halves at state x and dynamic pressure q."""
    force = model_for(wing.n_stations).panel_loads(x, wing.parameters(alpha))[0]
    a = math.radians(alpha)
    return float(2 * q * (force[2].sum() * math.cos(a) - force[0].sum() * math.sin(a)))


def divergence_summary(
    wing: Wing,
    alpha: float,
    density: float,
    equilibria: Sequence[Equilibrium] = (),
    velocity_limit: float | None = None,
) -> DivergenceSummary:
    """All three estimates: linear at the jig, the study's fit over `equilibria` (its stable
    ones), and the fold searched up to `velocity_limit` [m/s] (default: past linear divergence
    and 1.5 times the fastest equilibrium given)."""
    if velocity_limit is None:
        fastest = max((e.flight.velocity for e in equilibria), default=0.0)
        velocity_limit = search_velocity_limit(wing, density, fastest)
    return DivergenceSummary(
        linear=linear_divergence(wing, density),
        fit=fit_divergence(equilibria),
        fold=find_fold(wing, alpha, density, velocity_limit),
    )
