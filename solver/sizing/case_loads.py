"""One load case's section loads: the flexible wing's trimmed equilibrium with its own mass under
the load factor (`solver.statics.inertia`), or, for a rolling pull-out, both wings with the
ailerons deflected and the roll rate (`solver.controls.roll`, linearised about the trimmed
symmetric equilibrium). A case that cannot be flown is a typed answer for that case, never a
failure of the others."""

from __future__ import annotations

import dataclasses
import math
import time

from solver.controls.roll import roll
from solver.errors import ConvergenceError, InvalidInput, NoEquilibrium, SolverError
from solver.inputs.atmosphere import SEA_LEVEL_DENSITY
from solver.inputs.flight import FlightCondition
from solver.inputs.options import SolverOptions
from solver.inputs.wing import Wing
from solver.results.sizing import CaseKind, CaseLoads, CaseStatus
from solver.statics.solve import solve
from solver.statics.trim import zero_lift_alpha

__all__ = ["case_loads"]


def case_loads(
    wing: Wing,
    name: str,
    kind: CaseKind,
    flight: FlightCondition,
    options: SolverOptions,
    *,
    weight: float,
    aileron: float = 0.0,
    roll_rate: float = 0.0,
) -> CaseLoads:
    """The loads on `wing` of the case `name` of an aircraft of `weight` [N] flying `flight`:
    trimmed to its lift, or (a flight at an angle of attack: a zero load factor, no lift to trim
    to) at the rigid wing's zero-lift alpha, with the ailerons at `aileron` [deg] and a roll rate
    [rad/s] for a rolling pull-out (`CaseLoads`: its status says whether it was flown)."""
    assert flight.velocity is not None
    started = time.perf_counter()
    described = CaseLoads(
        name=name,
        kind=kind,
        status="equilibrium",
        velocity=flight.velocity,
        equivalent_airspeed=flight.velocity * math.sqrt(flight.density / SEA_LEVEL_DENSITY),
        density=flight.density,
        weight=weight,
        load_factor=_load_factor(flight),
    )
    try:
        if not flight.trimmed:
            alpha = zero_lift_alpha(wing, options, flight.velocity)
            flight = dataclasses.replace(flight, alpha=alpha)
        if aileron != 0.0 or roll_rate != 0.0:
            flown = _rolling(wing, flight, options, aileron, roll_rate, described)
        else:
            flown = _symmetric(wing, flight, options, described)
    except SolverError as error:
        flown = _failed(described, error)
    except InvalidInput as error:
        reason = f"{error.field}: {error.reason}"
        flown = dataclasses.replace(described, status="invalid", reason=reason)
    return dataclasses.replace(flown, solve_time=time.perf_counter() - started)


def _symmetric(
    wing: Wing, flight: FlightCondition, options: SolverOptions, described: CaseLoads
) -> CaseLoads:
    """The trimmed symmetric equilibrium's section loads (those the right wing's and the
    left's alike carry)."""
    equilibrium = solve(wing, flight, options=options)
    stations = equilibrium.stations
    return dataclasses.replace(
        described,
        alpha=equilibrium.totals.alpha,
        shear=stations.shear,
        bending_moment=stations.bending_moment,
        torque=stations.torque,
        lag_bending_moment=stations.lag_bending_moment,
        tip_heave=equilibrium.totals.tip_heave,
        tip_twist=equilibrium.totals.tip_twist,
    )


def _load_factor(flight: FlightCondition) -> float:
    """The case's n: given, 1 trimmed without one, 0 at an angle of attack."""
    if flight.load_factor is not None:
        return flight.load_factor
    return 1.0 if flight.trimmed else 0.0


def _rolling(
    wing: Wing,
    flight: FlightCondition,
    options: SolverOptions,
    aileron: float,
    roll_rate: float,
    described: CaseLoads,
) -> CaseLoads:
    """Both wings of a rolling pull-out: every aileron at `aileron` [deg], at the roll rate."""
    if aileron != 0.0 and not any(not s.symmetric for s in wing.control_surfaces):
        raise InvalidInput("aileron", "the wing has no aileron to deflect")
    surfaces = tuple(
        s if s.symmetric else dataclasses.replace(s, deflection=aileron)
        for s in wing.control_surfaces
    )
    rolled = roll(
        dataclasses.replace(wing, control_surfaces=surfaces),
        flight,
        options,
        roll_rate=roll_rate,
        method="linearised",
    )
    right, left = rolled.right, rolled.left
    return dataclasses.replace(
        described,
        alpha=rolled.flight.alpha,
        shear=right.shear,
        bending_moment=right.bending_moment,
        torque=right.torque,
        left_shear=left.shear,
        left_bending_moment=left.bending_moment,
        left_torque=left.torque,
        lag_bending_moment=right.lag_bending_moment,
        left_lag_bending_moment=left.lag_bending_moment,
        tip_heave=float(right.heave[-1]),
        tip_twist=float(right.twist[-1]),
    )


def _failed(described: CaseLoads, error: SolverError) -> CaseLoads:
    status: CaseStatus = "no_equilibrium" if isinstance(error, NoEquilibrium) else "not_converged"
    if not isinstance(error, NoEquilibrium | ConvergenceError):
        status = "not_converged"
    return dataclasses.replace(described, status=status, reason=str(error))
