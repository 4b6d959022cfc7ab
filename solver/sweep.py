"""Airspeed sweeps: every point from the branch from the jig shape, and the wing's divergence
reported alongside (linear, the study's fit, and the fold of the branch)."""

from __future__ import annotations

import time
from collections.abc import Sequence

from solver.branch import search_velocity_limit
from solver.divergence import find_fold, fit_divergence, linear_divergence
from solver.errors import NoEquilibrium, SolverError, numerical_failures_as
from solver.inputs import FlightCondition, SolverOptions, Wing
from solver.jig import jig
from solver.recovery import from_branch
from solver.results import (
    DivergenceSummary,
    SweepInfo,
    SweepPoint,
    SweepResult,
)
from solver.solve import solve
from solver.system import CoupledSystem
from solver.validity import onsets

__all__ = ["sweep"]


def sweep(
    wing: Wing,
    velocities: Sequence[float],
    alpha: float,
    density: float,
    options: SolverOptions | None = None,
) -> SweepResult:
    """Solve at each airspeed [m/s], answered in the given order.

    The branch from the jig shape is followed first, to its fold (or to 1.5 times the fastest
    speed and past the linear divergence speed): a speed beyond the fold is answered with
    `NoEquilibrium` without a solve; every other one by Newton from the branch's state at its q
    (usually one iteration). The answers depend on the wing, alpha, density and each speed only,
    never on the order or on what was solved before; each agrees with `solve` at that speed to
    the residual tolerance.
    """
    started = time.perf_counter()
    options = options or SolverOptions()
    system = CoupledSystem.of(wing, alpha, options)
    fastest = max(velocities, default=0.0)
    limit = search_velocity_limit(system, density, fastest)
    found = find_fold(wing, alpha, density, limit, options)
    points: list[SweepPoint] = []
    for velocity in velocities:
        flight = FlightCondition(velocity=velocity, alpha=alpha, density=density)
        try:
            if found.velocity is not None and velocity > found.velocity:
                raise NoEquilibrium(velocity, found.velocity)
            with numerical_failures_as(velocity):
                if jig(system).unloaded:
                    equilibrium = solve(wing, flight, options=options)
                else:
                    equilibrium = from_branch(system, flight, options, 0, velocity_limit=limit)
        except SolverError as error:
            points.append(SweepPoint.failed(velocity, error))
            continue
        points.append(SweepPoint(None, velocity, "equilibrium", equilibrium, None))
    stable = [p.equilibrium for p in points if p.equilibrium is not None]
    divergence = DivergenceSummary(
        linear=linear_divergence(wing, density, options),
        fit=fit_divergence(stable),
        fold=found,
    )
    return SweepResult(
        points, divergence, SweepInfo(time.perf_counter() - started), validity=onsets(points)
    )
