"""Airspeed sweeps: one wing over several airspeeds, every point from the branch from the jig
shape, and the wing's divergence reported alongside (linear, the study's fit, and the fold of
the branch; trimmed, the trimmed divergence limit: `solver.trim`)."""

from __future__ import annotations

import time
from collections.abc import Sequence

from solver.errors import NoEquilibrium, SolverError, numerical_failures_as
from solver.inputs.flight import FlightCondition, OperatingPoint, check_over_airspeeds
from solver.inputs.options import SolverOptions
from solver.inputs.wing import Wing
from solver.results.quantities import Progress
from solver.results.sweep import AirspeedPoint, AirspeedSweep, AirspeedSweepInfo, DivergenceSummary
from solver.statics.branch import search_velocity_limit
from solver.statics.divergence import find_fold, fit_divergence, linear_divergence
from solver.statics.jig import jig
from solver.statics.recovery import from_branch
from solver.statics.solve import solve
from solver.statics.system import CoupledSystem
from solver.statics.trim import trimmed_airspeed_sweep
from solver.statics.validity import onsets

__all__ = ["airspeed_sweep"]


def airspeed_sweep(
    wing: Wing,
    velocities: Sequence[float],
    flight: FlightCondition,
    options: SolverOptions | None = None,
    progress: Progress | None = None,
) -> AirspeedSweep:
    """Solve at each airspeed [m/s], answered in the given order, flying as `flight` says (its
    own velocity, if any, is not used): at its angle of attack, or trimmed to its lift
    (`solver.statics.trim.trimmed_airspeed_sweep`). `progress(done, total)` is called as each
    airspeed is answered.

    At an angle of attack the branch from the jig shape is followed first, to its fold (or to
    1.5 times the fastest speed and past the linear divergence speed): a speed beyond the fold
    is answered with `NoEquilibrium` without a solve; every other one by Newton from the
    branch's state at its q (usually one iteration). The answers depend on the wing, the flight
    condition and each speed only, never on the order or on what was solved before; each
    agrees with `solve` at that speed to the residual tolerance.
    """
    options = options or SolverOptions()
    lift = flight.required_lift
    if lift is not None:
        return trimmed_airspeed_sweep(
            wing,
            velocities,
            lift,
            flight.density,
            options,
            progress,
            load_factor=flight.load_factor,
        )
    assert flight.alpha is not None
    check_over_airspeeds(flight.alpha, flight.load_factor, wing.mass is not None)
    return _at_alpha(wing, velocities, flight.alpha, flight.density, options, progress)


def _at_alpha(
    wing: Wing,
    velocities: Sequence[float],
    alpha: float,
    density: float,
    options: SolverOptions,
    progress: Progress | None,
) -> AirspeedSweep:
    started = time.perf_counter()
    system = CoupledSystem.of(wing, alpha, options)
    fastest = max(velocities, default=0.0)
    limit = search_velocity_limit(system, density, fastest)
    found = find_fold(wing, alpha, density, limit, options)
    points: list[AirspeedPoint] = []
    for velocity in velocities:
        point = OperatingPoint(velocity, alpha, density)
        try:
            if found.velocity is not None and velocity > found.velocity:
                raise NoEquilibrium(velocity, found.velocity)
            with numerical_failures_as(velocity):
                if jig(system).unloaded:
                    equilibrium = solve(
                        wing, FlightCondition(velocity, alpha, density), options=options
                    )
                else:
                    equilibrium = from_branch(system, point, options, 0, velocity_limit=limit)
        except SolverError as error:
            points.append(AirspeedPoint.failed(velocity, error))
        else:
            points.append(AirspeedPoint(None, velocity, "equilibrium", equilibrium, None))
        if progress is not None:
            progress(len(points), len(velocities))
    stable = [p.equilibrium for p in points if p.equilibrium is not None]
    divergence = DivergenceSummary(
        linear=linear_divergence(wing, density, options),
        fit=fit_divergence(stable),
        fold=found,
    )
    return AirspeedSweep(
        points,
        divergence,
        AirspeedSweepInfo(time.perf_counter() - started),
        validity=onsets(points),
    )
