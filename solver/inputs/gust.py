"""What a gust analysis asks (`GustSettings`): the regulation's gust at which speed and
altitude, the gradients searched for the tuned gust, the flight profile alleviation, the modes
kept, the clamped option and continuous turbulence, each field declared once
(`solver.fields`). The gusts themselves are `solver.gusts.profiles`'s (CS-25.341)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Literal

from solver import fields
from solver.errors import InvalidInput
from solver.fields import parameter
from solver.inputs.atmosphere import ALTITUDE_LIMITS
from solver.inputs.flight import FlightCondition

__all__ = ["GustCondition", "GustSettings"]

_GRADIENT: dict[str, Any] = {
    "ge": 0.1,
    "le": 10_000.0,
    "why": "a tenth of a metre to ten kilometres",
}


@dataclass(frozen=True)
class GustSettings:
    """The gusts to fly through. Values outside CS-25.341's ranges (gradients outside 9 to
    107 m) are answered, and said so in the answer's `findings`."""

    altitude: float = parameter(
        "m",
        "altitude of U_ref and U_sigma_ref (CS-25.341(a)(5), (b)(3)); the air's density is "
        "the flight's",
        ge=ALTITUDE_LIMITS.ge,
        le=ALTITUDE_LIMITS.le,
        why=ALTITUDE_LIMITS.why,
        default=0.0,
    )
    speed: Literal["cruise", "dive"] = parameter(
        "",
        "the design speed the flight is at: cruise (V_C, the full gust) or dive (V_D, half)",
        form="choice",
        choices=("cruise", "dive"),
        default="cruise",
    )
    alleviation: float = parameter(
        "-",
        "F_g, the flight profile alleviation factor (CS-25.341(a)(6)); 1: none; ignored when "
        "`weights` and `max_altitude` give it",
        ge=0.01,
        le=1.0,
        why="the regulation's factor lies between 0 and 1",
        default=1.0,
    )
    weights: tuple[float, ...] | None = parameter(
        "N",
        "F_g from the aircraft (CS-25.341(a)(6)): its maximum take-off, landing and zero-fuel "
        "weights, in this order (with max_altitude); null: `alleviation` as given",
        ge=1e-6,
        le=1e9,
        why="a milligram to a thousand airliners",
        form="values",
        default=None,
        example=[700_000.0, 600_000.0, 560_000.0],
    )
    max_altitude: float | None = parameter(
        "m",
        "the maximum operating altitude Z_mo of F_g (with weights)",
        ge=1.0,
        le=30_000.0,
        why="up to the stratosphere's airliners and beyond",
        default=None,
    )
    min_gradient: float = parameter(
        "m", "shortest gust gradient H searched (CS-25.341(a): 9)", **_GRADIENT, default=9.0
    )
    max_gradient: float = parameter(
        "m", "longest gust gradient H searched (CS-25.341(a): 107)", **_GRADIENT, default=107.0
    )
    gradients: int = parameter(
        "-",
        "how many gradients, evenly spaced from min_gradient to max_gradient (the tuned "
        "gust's search)",
        ge=1,
        le=100,
        why="one gust to a fine search",
        form="integer",
        default=20,
    )
    modes: int = parameter(
        "-",
        "the wing's lowest natural modes kept (at most 2 (N - 1))",
        ge=1,
        le=1000,
        why="one mode to every degree of freedom of the largest mesh",
        form="integer",
        default=4,
    )
    clamped: bool = parameter(
        "", "hold the root (no plunge): a wind-tunnel model", form="flag", default=False
    )
    profile_time: tuple[float, ...] | None = parameter(
        "s",
        "a gust of your own: times from the moment the gust reaches the wing's foremost "
        "leading edge, increasing, 2 to 2000 values (with profile_velocity)",
        ge=0.0,
        le=3600.0,
        why="up to an hour of flight",
        form="values",
        default=None,
        example=[0.0, 0.5, 1.0],
    )
    profile_velocity: tuple[float, ...] | None = parameter(
        "m/s",
        "its vertical velocity (TAS, up positive) at each time, linear between them and zero "
        "after the last (with profile_time)",
        ge=-200.0,
        le=200.0,
        why="past any atmospheric gust",
        form="values",
        default=None,
        example=[0.0, 5.0, 0.0],
    )
    turbulence: bool = parameter(
        "",
        "also continuous turbulence (CS-25.341(b)): A-bar and its design loads",
        form="flag",
        default=True,
    )

    def __post_init__(self) -> None:
        for name, spec in fields.specs(GustSettings).items():
            value = getattr(self, name)
            if value is None:
                continue
            if spec.form == "number":
                fields.number(name, value, spec)
            elif spec.form == "integer":
                fields.integer(name, value, spec)
            elif spec.form == "flag" and not isinstance(value, bool):
                raise InvalidInput(name, "must be true or false")
            elif spec.form == "choice" and value not in spec.choices:
                raise InvalidInput(name, "must be one of " + ", ".join(map(repr, spec.choices)))
            elif spec.form == "values":
                values = tuple(fields.stations(name, value, None, spec).tolist())
                object.__setattr__(self, name, values)
        if (self.weights is None) != (self.max_altitude is None):
            raise InvalidInput("max_altitude", "give weights and max_altitude together")
        if self.weights is not None and len(self.weights) != 3:
            raise InvalidInput("weights", "must be the take-off, landing and zero-fuel weights")
        if (self.profile_time is None) != (self.profile_velocity is None):
            raise InvalidInput(
                "profile_velocity", "give profile_time and profile_velocity together"
            )
        if self.profile_time is not None and self.profile_velocity is not None:
            if not 2 <= len(self.profile_time) <= 2000:
                raise InvalidInput("profile_time", "must have 2 to 2000 values")
            if len(self.profile_velocity) != len(self.profile_time):
                raise InvalidInput("profile_velocity", "must have as many values as profile_time")
            if any(b <= a for a, b in zip(self.profile_time, self.profile_time[1:], strict=False)):
                raise InvalidInput("profile_time", "must increase")
        if self.weights is not None and self.max_altitude is not None:
            takeoff, landing, zero_fuel = self.weights
            if not zero_fuel <= takeoff >= landing:
                raise InvalidInput("weights", "the take-off weight is the largest")
        if self.max_gradient < self.min_gradient:
            raise InvalidInput("max_gradient", "must not be below min_gradient")


@dataclass(frozen=True)
class GustCondition:
    """A flight whose gust loads join a loads envelope (`solver.operations.sizing.LoadsInput`
    `gusts`): the flexible wing's 1-cos gusts at `flight`, total loads up and down."""

    name: str = parameter(
        "",
        "the condition's name; the envelope's cases are '<name> up' and '<name> down'",
        form="text",
        le=80,
        example="V_C gusts",
    )
    flight: FlightCondition = parameter(
        "",
        "the flight: airspeed, density, the aircraft's weight (trimmed to it)",
        form="nested",
        given=FlightCondition,
    )
    gust: GustSettings | None = parameter(
        "", "optional gust settings", form="nested", given=GustSettings, default=None
    )

    def __post_init__(self) -> None:
        if self.flight.weight is None or self.flight.velocity is None:
            raise InvalidInput(
                "flight.weight", "a gust condition flies at an airspeed, trimmed to a weight"
            )
