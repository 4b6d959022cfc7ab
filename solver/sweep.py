"""Airspeed sweeps: each point warm-started from the previous equilibrium on the branch, and the
wing's divergence reported alongside (linear, the study's fit, and the fold of the branch)."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from solver.divergence import (
    DivergenceSummary,
    equilibrium_branch,
    find_fold,
    fit_divergence,
    linear_divergence,
    search_velocity_limit,
)
from solver.equilibrium import Equilibrium, SolverOptions, solve
from solver.errors import NoEquilibrium, SolverError
from solver.wing import FlightCondition, Wing

__all__ = ["SweepPoint", "SweepResult", "sweep"]


@dataclass(frozen=True)
class SweepPoint:
    """One requested airspeed: an equilibrium, or the typed reason there is none."""

    velocity: float
    equilibrium: Equilibrium | None
    error: SolverError | None


@dataclass(frozen=True)
class SweepResult:
    """The points in the requested order and the wing's divergence.

    divergence.fold is searched to at least 1.5 times the fastest requested speed and past the
    linear divergence speed; divergence.fit uses the sweep's stable equilibria.
    """

    points: list[SweepPoint]
    divergence: DivergenceSummary

    @property
    def equilibria(self) -> list[Equilibrium]:
        return [point.equilibrium for point in self.points if point.equilibrium is not None]


def sweep(
    wing: Wing,
    velocities: Sequence[float],
    alpha: float,
    density: float,
    options: SolverOptions | None = None,
) -> SweepResult:
    """Solve at each airspeed [m/s] in the given order.

    The branch from the jig shape is followed first, to its fold: a speed beyond the fold is
    answered with `NoEquilibrium` without a solve (Newton would fail there, or land on another,
    unstable branch). Every other speed is solved with the branch's interpolated state as a
    `hint` (usually one Newton iteration; a hint cannot change the answer). A point that fails
    is recorded with its error.
    """
    limit = search_velocity_limit(wing, density, max(velocities, default=0.0))
    fold = find_fold(wing, alpha, density, limit)
    branch = equilibrium_branch(wing, alpha, 0.5 * density * limit**2)  # traced by find_fold
    points: list[SweepPoint] = []
    for velocity in velocities:
        flight = FlightCondition(velocity=velocity, alpha=alpha, density=density)
        if fold.velocity is not None and velocity > fold.velocity:
            points.append(SweepPoint(velocity, None, NoEquilibrium(velocity, fold.velocity)))
            continue
        try:
            # The branch's Hermite interpolation is within a Newton step or so of the answer.
            hint = branch.start_for(flight.dynamic_pressure)
            equilibrium = solve(wing, flight, options=options, hint=hint)
        except SolverError as error:
            points.append(SweepPoint(velocity, None, error))
            continue
        points.append(SweepPoint(velocity, equilibrium, None))
    stable = [point.equilibrium for point in points if point.equilibrium is not None]
    divergence = DivergenceSummary(
        linear=linear_divergence(wing, density),
        fit=fit_divergence(stable),
        fold=fold,
    )
    return SweepResult(points, divergence)
