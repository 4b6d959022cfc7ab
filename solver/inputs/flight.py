"""The flight condition: an airspeed, the air's density, and an angle of attack or a lift to
carry (trimmed); a range of airspeeds; each field declared once (`solver.fields`).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import ClassVar, Literal

import numpy as np

from solver import fields
from solver.errors import InvalidInput
from solver.fields import parameter
from solver.inputs import atmosphere
from solver.inputs.atmosphere import ALTITUDE_LIMITS

__all__ = [
    "FLIGHT_RULE",
    "ISA_SEA_LEVEL_DENSITY",
    "FlightCondition",
    "OperatingPoint",
    "VelocityRange",
    "check_over_airspeeds",
    "dynamic_pressure",
    "velocity_for",
]
ISA_SEA_LEVEL_DENSITY = atmosphere.SEA_LEVEL_DENSITY  # [kg/m^3] 1.225


FLIGHT_RULE = (
    "give exactly one of alpha (at a given angle of attack), lift, or weight (trimmed: the "
    "angle of attack is solved for), with an optional load_factor"
)


def dynamic_pressure(density: float, velocity: float) -> float:
    """q = rho V^2 / 2 [Pa] of an airspeed V [m/s] in air of density rho [kg/m^3] (every
    operation's, written once; inf past the float range, not OverflowError)."""
    return 0.5 * density * velocity * velocity


def velocity_for(dynamic_pressure: float, density: float) -> float:
    """V = sqrt(2 q / rho) [m/s] of a dynamic pressure q [Pa] at density rho [kg/m^3]."""
    return math.sqrt(2.0 * dynamic_pressure / density)


@dataclass(frozen=True)
class FlightCondition:
    """Steady, symmetric flight, in one of three ways (`WAYS`): at a given angle of attack
    `alpha`, or trimmed, carrying `lift` (or `weight` times `load_factor`) with alpha solved
    for. `velocity` None: at each airspeed of a sweep (`at_velocity`).

    The dynamic pressure rho V^2 / 2 must be a positive, finite number.
    """

    velocity: float | None = parameter(
        "m/s",
        "true airspeed (or give equivalent_airspeed)",
        ge=0.01,
        le=1000.0,
        why="the lattice is incompressible: Mach 3 is far past it",
        default=None,
        example=10.0,
    )
    alpha: float | None = parameter(
        "deg",
        "angle of attack of the jig (undeformed) shape",
        ge=-30.0,
        le=30.0,
        why="an attached-flow lattice means nothing beyond",
        default=None,
        example=5.0,
    )
    density: float = parameter(
        "kg/m^3",
        "air (or water) density (or give altitude)",
        ge=1e-4,
        le=2000.0,
        why="the stratosphere to sea water (hydrofoils)",
        default=ISA_SEA_LEVEL_DENSITY,
        example=ISA_SEA_LEVEL_DENSITY,
    )
    lift: float | None = parameter(
        "N",
        "lift of both halves to carry, nonzero; the angle of attack is solved for",
        ge=-1e9,
        le=1e9,
        why="up to a thousand airliners' weight, either sign; not 0",
        default=None,
        kw_only=True,
        example=300.0,
    )
    weight: float | None = parameter(
        "N",
        "weight to carry; lift = load_factor * weight and the angle of attack is solved for",
        ge=1e-6,
        le=1e9,
        why="a milligram to a thousand airliners",
        default=None,
        kw_only=True,
        example=300.0,
    )
    load_factor: float | None = parameter(
        "-",
        "load factor n, nonzero: trimmed to a weight, the lift carried is n times it (null: "
        "1); the wing's own mass (wing.mass) weighs n g against the lift in trimmed flight "
        "(null: 1 g), and at a given alpha only when n is given (inertia relief)",
        ge=-10.0,
        le=10.0,
        why="past any aircraft's manoeuvre envelope; not 0",
        default=None,
        kw_only=True,
        example=2.5,
    )

    altitude: float | None = parameter(
        "m",
        "geopotential altitude in the ICAO standard atmosphere: the density is the ISA's there "
        "(give it or density, not both)",
        **dataclasses.asdict(ALTITUDE_LIMITS),
        default=None,
        kw_only=True,
        example=3000.0,
    )
    equivalent_airspeed: float | None = parameter(
        "m/s",
        "equivalent airspeed EAS: the true airspeed is EAS sqrt(rho0 / rho), rho0 = 1.225 "
        "kg/m^3 (give it or velocity, not both)",
        ge=0.01,
        le=1000.0,
        why="the lattice is incompressible: Mach 3 is far past it",
        default=None,
        kw_only=True,
        example=30.0,
    )

    # The fields that give the airspeed: a flight over airspeeds leaves them out.
    AIRSPEEDS: ClassVar[tuple[str, ...]] = ("velocity", "equivalent_airspeed")
    # Fields of which one at most is given, whatever the way (the air: its density, or the
    # altitude whose ISA density it is).
    ALTERNATIVES: ClassVar[tuple[tuple[str, ...], ...]] = (AIRSPEEDS, ("density", "altitude"))

    # The ways a condition is given: each names the fields it takes beside the airspeed and the
    # air (velocity or equivalent_airspeed, density or altitude).
    WAYS: ClassVar[dict[str, tuple[str, ...]]] = {
        "alpha": ("alpha", "load_factor"),
        "lift": ("lift", "load_factor"),
        "weight": ("weight", "load_factor"),
    }
    RULE: ClassVar[str] = FLIGHT_RULE

    def __post_init__(self) -> None:
        for name, spec in fields.specs(FlightCondition).items():
            value = getattr(self, name)
            if value is not None:
                fields.number(name, value, spec)
        if self.altitude is not None:
            if self.density != ISA_SEA_LEVEL_DENSITY:
                raise InvalidInput("altitude", "give density or altitude, not both")
            object.__setattr__(self, "density", float(atmosphere.density(self.altitude)))
        if self.equivalent_airspeed is not None:
            if self.velocity is not None:
                raise InvalidInput(
                    "equivalent_airspeed", "give velocity or equivalent_airspeed, not both"
                )
            ratio = atmosphere.SEA_LEVEL_DENSITY / self.density
            object.__setattr__(self, "velocity", self.equivalent_airspeed * math.sqrt(ratio))
            fields.number(
                "equivalent_airspeed", self.velocity, fields.spec_of(FlightCondition, "velocity")
            )
        ways = [way for way in ("alpha", "lift", "weight") if getattr(self, way) is not None]
        if len(ways) != 1:
            raise InvalidInput("", FLIGHT_RULE)
        if self.lift == 0:
            raise InvalidInput(
                "lift", "must be nonzero (zero lift is the jig at its zero-lift alpha)"
            )
        if self.load_factor == 0:
            raise InvalidInput("load_factor", "must be nonzero")
        if self.velocity is not None:
            q = self.dynamic_pressure
            if not (math.isfinite(q) and q > 0):
                raise InvalidInput(
                    "velocity",
                    f"the dynamic pressure rho V^2 / 2 = {q:g} Pa is not a positive number",
                )

    @property
    def way(self) -> Literal["alpha", "lift", "weight"]:
        if self.alpha is not None:
            return "alpha"
        return "lift" if self.lift is not None else "weight"

    @property
    def trimmed(self) -> bool:
        """The angle of attack is solved for (a lift or a weight is given)."""
        return self.alpha is None

    @property
    def required_lift(self) -> float | None:
        """[N] the lift a trimmed condition holds (lift, or load_factor * weight); None at a
        given alpha."""
        if self.lift is not None:
            return self.lift
        if self.weight is not None:
            return (1.0 if self.load_factor is None else self.load_factor) * self.weight
        return None

    @property
    def inertial_load_factor(self) -> float | None:
        """The load factor the wing's own mass carries (`solver.statics.inertia`): trimmed,
        the one given or 1; at a given alpha, the one given or None (no inertial load)."""
        if self.trimmed and self.load_factor is None:
            return 1.0
        return self.load_factor

    @property
    def dynamic_pressure(self) -> float:
        """q = rho V^2 / 2 [Pa]."""
        if self.velocity is None:
            raise ValueError("a condition without an airspeed has no dynamic pressure")
        return dynamic_pressure(self.density, self.velocity)

    def at_velocity(self, velocity: float) -> FlightCondition:
        return dataclasses.replace(self, velocity=velocity)

    def at_alpha(self, alpha: float) -> OperatingPoint:
        """The point the model solves at this airspeed and density and `alpha` [deg] (a
        trimmed condition at its trimmed alpha)."""
        if self.velocity is None:
            raise InvalidInput("velocity", "is required: the airspeed to solve at")
        return OperatingPoint(self.velocity, alpha, self.density, self.inertial_load_factor)

    velocity_for = staticmethod(velocity_for)


def check_over_airspeeds(alpha: float | None, load_factor: float | None, has_mass: bool) -> None:
    """Refuse a load factor on the wing's mass at a given alpha over airspeeds (a sweep, a
    control sweep, flutter about the loaded wing): it loads one flight condition; over airspeeds
    the wing flies trimmed (naming `flight.load_factor`)."""
    if alpha is not None and load_factor is not None and has_mass:
        raise InvalidInput(
            "flight.load_factor",
            "at a given alpha a load factor loads the wing's mass for one flight condition "
            "(/solve, /roll); over airspeeds fly trimmed: lift or weight, with the load factor",
        )


@dataclass(frozen=True)
class OperatingPoint:
    """The point the model solves: an airspeed [m/s], the jig's angle of attack [deg] and the
    density [kg/m^3]. Not an input: the solver makes it from a `FlightCondition` (a trimmed
    one at its trimmed alpha), already validated."""

    velocity: float
    alpha: float
    density: float = ISA_SEA_LEVEL_DENSITY
    # The load factor the wing's own mass carries at this point (`solver.statics.inertia`);
    # None: no inertial load.
    load_factor: float | None = None

    @property
    def dynamic_pressure(self) -> float:
        """q = rho V^2 / 2 [Pa]."""
        return dynamic_pressure(self.density, self.velocity)

    def at_velocity(self, velocity: float) -> OperatingPoint:
        return OperatingPoint(velocity, self.alpha, self.density, self.load_factor)


@dataclass(frozen=True)
class VelocityRange:
    """`count` airspeeds evenly spaced from `start` to `stop`, both included."""

    start: float = parameter(
        "m/s",
        "first airspeed",
        ge=0.01,
        le=1000.0,
        why="the lattice is incompressible: Mach 3 is far past it",
    )
    stop: float = parameter(
        "m/s",
        "last airspeed",
        ge=0.01,
        le=1000.0,
        why="the lattice is incompressible: Mach 3 is far past it",
    )
    count: int = parameter("-", "number of airspeeds", ge=1, form="integer")

    def velocities(self) -> tuple[float, ...]:
        """[m/s]"""
        if self.count == 1:
            return (float(self.start),)
        return tuple(np.linspace(self.start, self.stop, self.count).tolist())
