"""One wing over airspeeds: each airspeed's answer or why there is none, and the three divergence
estimates (linear, the study's fit, the branch's fold).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

from solver.errors import ConvergenceError, NoEquilibrium, SolverError
from solver.results.equilibrium import Equilibrium, Fold
from solver.results.findings import FindingOnset
from solver.results.quantities import internal, quantity

__all__ = [
    "DivergenceSummary",
    "FitDivergence",
    "LinearDivergence",
    "PointFailure",
    "AirspeedSweepInfo",
    "AirspeedPoint",
    "AirspeedSweep",
]


@dataclass(frozen=True)
class LinearDivergence:
    """Classical linear divergence at the unloaded jig (alpha = 0)."""

    dynamic_pressure: float | None = quantity("Pa", "divergence dynamic pressure, or null")
    velocity: float | None = quantity("m/s", "at the sweep's density, or null")
    reason: str | None = quantity("", "why the values are null, else null", default=None)


@dataclass(frozen=True)
class FitDivergence:
    """The design study's estimate: 1/A = intercept + slope q fitted over stable sweep points."""

    slope: float | None = quantity("1/Pa", "slope of 1/A against q")
    intercept: float | None = quantity("-", "intercept (single-mode theory: 1)")
    dynamic_pressure: float | None = quantity("Pa", "where 1/A reaches 0")
    velocity: float | None = quantity("m/s", "at the sweep's density")
    reason: str | None = quantity("", "why the values are null, else null", default=None)
    amplification: Literal["CL", "lift", "lift_effectiveness"] = quantity(
        "",
        "what A is: 'CL' (the study's: CL on the deformed area over the rigid CL on the jig "
        "area), 'lift' (L / L_rigid) or, trimmed, 'lift_effectiveness' (the flexible wing's "
        "lift-curve slope over the rigid wing's)",
        default="CL",
    )
    points_used: int = quantity("-", "stable equilibria in the fit", default=0)


@dataclass(frozen=True)
class DivergenceSummary:
    """Three torsional-divergence estimates that check each other."""

    linear: LinearDivergence = quantity("", "eigenvalue at the unloaded jig")
    fit: FitDivergence = quantity("", "the study's 1/A fit over the sweep")
    fold: Fold = quantity("", "where the branch from the jig ends")

    @property
    def limit_velocity(self) -> float | None:
        """[m/s] the speed users should see first: the fold, where equilibria end."""
        return self.fold.velocity


@dataclass(frozen=True)
class PointFailure:
    """Why a sweep point has no equilibrium."""

    reason: str = quantity("", "what the solver reported")
    fold_velocity: float | None = quantity("m/s", "where the equilibrium branch ends, when known")


@dataclass(frozen=True, eq=False)
class AirspeedPoint:
    """One requested airspeed: an equilibrium, or the typed reason there is none."""

    error: Exception | None = internal()  # the SolverError, for Python callers
    velocity: float = quantity("m/s", "requested airspeed")
    status: Literal["equilibrium", "no_equilibrium", "not_converged"] = quantity(
        "",
        "equilibrium: `equilibrium` holds the result; no_equilibrium: none on the branch from "
        "the jig (beyond its fold, or unstable there); not_converged: the solver failed. "
        "Both failures fill `no_equilibrium`",
    )
    equilibrium: Equilibrium | None = quantity("", "the equilibrium, as /solve returns it")
    no_equilibrium: PointFailure | None = quantity("", "why there is none")

    @classmethod
    def failed(cls, velocity: float, error: SolverError) -> AirspeedPoint:
        """The point at `velocity` [m/s] where the solver answered with `error`."""
        fold_velocity = error.fold_velocity if isinstance(error, NoEquilibrium) else None
        status: Literal["no_equilibrium", "not_converged"] = (
            "not_converged" if isinstance(error, ConvergenceError) else "no_equilibrium"
        )
        return cls(error, velocity, status, None, PointFailure(str(error), fold_velocity))


@dataclass(frozen=True)
class AirspeedSweepInfo:
    """How the sweep was obtained."""

    seconds: float = quantity("s", "solver time")


@dataclass(frozen=True, eq=False)
class AirspeedSweep:
    """One point per requested airspeed, in request order, and the divergence estimates."""

    points: list[AirspeedPoint] = quantity("", "one per requested airspeed, in request order")
    divergence: DivergenceSummary = quantity("", "three torsional-divergence estimates")
    solver: AirspeedSweepInfo = quantity("", "how the answer was obtained")
    validity: list[FindingOnset] = quantity(
        "",
        "from which airspeed on each finding of the points' `validity` appears, one entry per "
        "code found, in the order of FINDING_CODES; empty when no point has any",
        default_factory=list,
    )

    @property
    def equilibria(self) -> list[Equilibrium]:
        return [point.equilibrium for point in self.points if point.equilibrium is not None]
