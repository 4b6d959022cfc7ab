"""A load case as a user gives it: a named trimmed flight (weight and load factor, or a lift, at an
airspeed and an altitude or density), and for a rolling pull-out the ailerons' deflection and a
steady roll rate; each field declared once (`solver.fields`)."""

from __future__ import annotations

from dataclasses import dataclass

from solver.errors import InvalidInput
from solver.fields import parameter
from solver.inputs.flight import FlightCondition

__all__ = ["FlightCase"]


@dataclass(frozen=True)
class FlightCase:
    """One load case: `flight` trimmed (a weight and its load factor, or a lift), at an
    airspeed; with `aileron` or `roll_rate`, a rolling pull-out (both wings' loads)."""

    name: str = parameter(
        "", "the case's name, as the envelope reports it", form="text", le=80, example="A+"
    )
    flight: FlightCondition = parameter(
        "",
        "the flight: trimmed (weight and load_factor, or lift) at an airspeed",
        form="nested",
        given=FlightCondition,
        without=("alpha",),
    )
    aileron: float = parameter(
        "deg",
        "deflection of every aileron of the wing (the right's trailing edge down for a positive "
        "one): a rolling pull-out; 0 with no roll rate: a symmetric case",
        ge=-25.0,
        le=25.0,
        why="a plain flap's attached-flow range, as a control surface's",
        default=0.0,
    )
    roll_rate: float = parameter(
        "rad/s",
        "steady roll rate p, positive raising the right wing (a rolling pull-out's)",
        ge=-20.0,
        le=20.0,
        why="about 1,150 deg/s: past any aircraft's",
        default=0.0,
    )

    def __post_init__(self) -> None:
        if not self.flight.trimmed or self.flight.velocity is None:
            raise InvalidInput(
                "flight", "a load case flies trimmed (lift or weight) at an airspeed"
            )

    @property
    def rolling(self) -> bool:
        """A rolling pull-out: its wings are loaded apart."""
        return self.aileron != 0.0 or self.roll_rate != 0.0
