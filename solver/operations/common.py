"""What every operation input shares: its identity (what the service caches its answers
by), and the checks of a wing's control surfaces and of airspeeds."""

from __future__ import annotations

import dataclasses

from solver import fields
from solver.errors import InvalidInput
from solver.inputs.control_surfaces import check_resolution
from solver.inputs.flight import FlightCondition, VelocityRange
from solver.inputs.options import SolverOptions
from solver.inputs.wing import Wing
from solver.model.geometry import chordwise_nodes

__all__ = ["airspeeds_of", "check_airspeeds", "check_meshed", "identity"]


def identity(operation: object, **in_force: object) -> bytes:
    """What an operation input's answers are cached by (`fields.digest`): its fields, those
    given as None by the values in force (`in_force`): no options and the default options
    are one question, answered once."""
    values = {f.name: getattr(operation, f.name) for f in dataclasses.fields(operation)}  # type: ignore[arg-type]
    return fields.digest((type(operation).__name__, values | in_force))


def check_meshed(wing: Wing, options: SolverOptions | None) -> None:
    """Every control surface carried by the chordwise panels of `options`, refused before the
    work starts (naming `wing.control_surfaces[i].hinge`)."""
    if wing.control_surfaces:
        k = (options or SolverOptions()).chordwise_panels
        with fields.prefixed("wing"):
            check_resolution(wing.control_surfaces, chordwise_nodes(k))


def check_airspeeds(velocities: tuple[float, ...] | VelocityRange) -> None:
    """Each listed airspeed within a flight condition's, at least one."""
    if isinstance(velocities, VelocityRange):
        return
    spec = fields.spec_of(FlightCondition, "velocity")
    for index, velocity in enumerate(velocities):
        fields.number(f"velocities[{index}]", velocity, spec)
    if not velocities:
        raise InvalidInput("velocities", "needs at least one airspeed")


def airspeeds_of(velocities: tuple[float, ...] | VelocityRange) -> tuple[float, ...]:
    """[m/s] the airspeeds a list or a range gives, in order."""
    if isinstance(velocities, VelocityRange):
        return velocities.velocities()
    return tuple(float(v) for v in velocities)
