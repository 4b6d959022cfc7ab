"""Torsional divergence: three estimates that check each other.

- linear: the classical eigenvalue at the unloaded jig (`solver.statics.jig`,
  `solver.numerics.stability`).
- fit: the design study's estimate, 1/A against q over a sweep's stable points, extrapolated.
- fold: where the equilibrium branch from the jig shape ends (`solver.statics.branch`). This is
  the limit that matters: no equilibrium on the branch exists beyond it, and it lies below the
  other two for a wing at positive lift (the study's wing: fold 21.44 m/s, linear 24.22 m/s,
  fit 26.2 m/s).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Literal

import numpy as np

from solver.errors import ConvergenceError, numerical_failures_as
from solver.inputs.flight import velocity_for
from solver.inputs.options import SolverOptions
from solver.inputs.wing import Wing
from solver.results.equilibrium import Equilibrium, Fold
from solver.results.sweep import DivergenceSummary, FitDivergence, LinearDivergence
from solver.statics.branch import default_search_limit, fold, search_velocity_limit
from solver.statics.jig import at_rest, linear_pressure
from solver.statics.system import CoupledSystem

__all__ = [
    "divergence_summary",
    "find_fold",
    "fit_divergence",
    "linear_divergence",
    "linear_divergence_pressure",
]


def linear_divergence_pressure(wing: Wing, options: SolverOptions | None = None) -> float | None:
    """[Pa] the classical linear divergence dynamic pressure of the undeformed, unloaded wing
    (as modelled by `options`: chordwise panels, torque axis), or None if it cannot diverge."""
    return linear_pressure(CoupledSystem.of(wing, 0.0, options or SolverOptions()))


def linear_divergence(
    wing: Wing, density: float, options: SolverOptions | None = None
) -> LinearDivergence:
    """The classical eigenvalue q_div of the unloaded jig, and V at `density`."""
    system = CoupledSystem.of(wing, 0.0, options or SolverOptions())
    try:
        with numerical_failures_as(0.0):
            rest = at_rest(system)
            if not np.all(np.isfinite(rest.evaluation.jacobian1)):
                raise FloatingPointError("the jig's loads are not finite numbers")
            q_div = linear_pressure(system)
    except ConvergenceError as error:
        return LinearDivergence(None, None, f"it could not be computed: {error.reason}")
    if q_div is None:
        return LinearDivergence(
            None,
            None,
            "no positive real divergence eigenvalue: aerodynamic torque never overcomes the "
            "structure (e.g. the elastic axis lies ahead of the aerodynamic centre)",
        )
    return LinearDivergence(q_div, velocity_for(q_div, density))


def fit_divergence(
    equilibria: Sequence[Equilibrium],
    amplification: Literal["CL", "lift", "lift_effectiveness"] = "CL",
) -> FitDivergence:
    """The study's fit: least squares 1/A = intercept + slope q over the stable equilibria.

    amplification "CL": A = CL / CL_rigid with CL on the deformed planform area and CL_rigid on
    the jig area, as the study computes it (its numbers: intercept 0.998, q_div 419 Pa); "lift":
    A = L / L_rigid; "lift_effectiveness": A = the trimmed wing's flexible over rigid lift-curve
    slope. V_div uses the density of the stable equilibrium of lowest q.
    """
    if amplification not in ("CL", "lift", "lift_effectiveness"):
        raise ValueError(
            f"amplification must be 'CL', 'lift' or 'lift_effectiveness', got {amplification!r}"
        )
    # In order of q: the fit's round-off must not depend on the order the points were asked in.
    stable = sorted(
        (e for e in equilibria if e.stability.stable and _amplification(e, amplification) > 0),
        key=lambda e: e.dynamic_pressure,
    )

    def none(reason: str, slope: float | None = None, intercept: float | None = None):
        return FitDivergence(slope, intercept, None, None, reason, amplification, len(stable))

    pressures = np.array([e.dynamic_pressure for e in stable])
    if np.unique(pressures).size < 2:
        return none(
            f"the fit needs stable, lifting equilibria at two or more airspeeds, got {len(stable)}"
        )
    inverse = np.array([1.0 / _amplification(e, amplification) for e in stable])
    slope, intercept = (float(c) for c in np.polyfit(pressures, inverse, 1))
    if not (math.isfinite(slope) and math.isfinite(intercept)):
        return none("the fit is not finite")
    if slope >= 0:
        return none("1/A does not fall with q: the fit predicts no divergence", slope, intercept)
    q_div = -intercept / slope
    density = stable[0].flight.density
    velocity = velocity_for(q_div, density) if q_div > 0 else None
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
    """A [-]: lift or CL (deformed area) over the rigid jig's; NaN where it does not exist.

    A wing at (nearly) zero lift has no meaningful amplification: Newton may stop on the
    unloaded jig when the whole residual lies within tolerance.
    """
    totals = equilibrium.totals
    if amplification == "lift_effectiveness":
        ratio = totals.lift_effectiveness
        return ratio if ratio is not None and math.isfinite(ratio) else math.nan
    if totals.lift_amplification is None:
        return math.nan
    ratio = totals.lift_amplification
    if amplification == "CL":
        ratio *= totals.reference_area / totals.deformed_area
    return ratio if math.isfinite(ratio) else math.nan


def find_fold(
    wing: Wing,
    alpha: float,
    density: float,
    velocity_limit: float | None = None,
    options: SolverOptions | None = None,
) -> Fold:
    """The fold of the equilibrium branch from the jig shape at `alpha` [deg].

    The branch is searched up to `velocity_limit` [m/s] (default: 1.25 times the linear
    divergence speed, or, for a wing without one, the speed at which the linear theory's
    deformation reaches a tenth of the semispan or 0.1 rad of twist: see
    `solver.statics.branch.default_search_limit`); speeds are at `density` [kg/m^3].
    """
    system = CoupledSystem.of(wing, alpha, options or SolverOptions())
    try:
        with numerical_failures_as(velocity_limit or 0.0):
            if velocity_limit is None:
                velocity_limit = default_search_limit(system, density)
            return fold(system, density, velocity_limit)
    except ConvergenceError as error:
        reason = f"the branch could not be traced: {error.reason}"
        return Fold(None, None, None, None, 0.0, reason)


def divergence_summary(
    wing: Wing,
    alpha: float,
    density: float,
    equilibria: Sequence[Equilibrium] = (),
    velocity_limit: float | None = None,
    options: SolverOptions | None = None,
) -> DivergenceSummary:
    """All three estimates: linear at the jig, the study's fit over `equilibria` (its stable
    ones), and the fold searched up to `velocity_limit` [m/s] (default: `find_fold`'s, and at
    least 1.5 times the fastest equilibrium given)."""
    options = options or SolverOptions()
    if velocity_limit is None:
        fastest = max((e.flight.velocity for e in equilibria), default=0.0)
        system = CoupledSystem.of(wing, alpha, options)
        try:
            with numerical_failures_as(fastest):
                velocity_limit = max(
                    search_velocity_limit(system, density, fastest),
                    default_search_limit(system, density),
                )
        except ConvergenceError:
            velocity_limit = None  # find_fold says why the branch cannot be traced
    return DivergenceSummary(
        linear=linear_divergence(wing, density, options),
        fit=fit_divergence(equilibria),
        fold=find_fold(wing, alpha, density, velocity_limit, options),
    )
