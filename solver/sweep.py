"""Airspeed sweeps: each point warm-started from the previous equilibrium on the branch."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from solver.equilibrium import Equilibrium, SolverOptions, solve
from solver.errors import SolverError
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
    points: list[SweepPoint]

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

    Each solve starts from the last converged equilibrium: its stored Jacobian, re-targeted to the
    new dynamic pressure, gives the first Newton step (the branch-tangent predictor) for free.
    A point that fails is recorded with its error and the next one starts from the last success.
    """
    points: list[SweepPoint] = []
    previous: Equilibrium | None = None
    for velocity in velocities:
        flight = FlightCondition(velocity=velocity, alpha=alpha, density=density)
        try:
            equilibrium = solve(wing, flight, previous, options)
        except SolverError as error:
            points.append(SweepPoint(velocity, None, error))
            continue
        points.append(SweepPoint(velocity, equilibrium, None))
        previous = equilibrium
    return SweepResult(points)
