"""The flight envelope to size a wing for: the aircraft's weights and altitudes, its
certification category, its stall lines and the design speeds, each field declared once
(`solver.fields`). `solver.sizing.vn` turns it into the V-n diagrams and their load cases; the
rules it applies are `solver.sizing.regulations` (load factors, design speeds) and
`solver.sizing.gusts` (CS-23.341's gust load factors).

Airspeeds are equivalent airspeeds (EAS), as the rules state them (CS-23.335, CS-25.335: "the
selected design airspeeds are equivalent airspeeds"); altitudes are geopotential
(`solver.inputs.atmosphere`). Weights are forces [N], the aircraft's, both wings' lift
carrying them.

The wing area, its mean geometric chord and the lift-curve slope are the aircraft's: given
here, or (null) taken from the wing by the caller (`solver.sizing.vn.load_cases`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Literal

from solver import fields
from solver.errors import InvalidInput
from solver.fields import parameter
from solver.inputs.atmosphere import ALTITUDE_LIMITS

__all__ = ["CATEGORIES", "Category", "FlightEnvelope"]

Category = Literal["normal", "utility", "aerobatic", "commuter", "cs25"]
CATEGORIES: tuple[Category, ...] = ("normal", "utility", "aerobatic", "commuter", "cs25")

_SPEED: dict[str, Any] = {
    "ge": 0.01,
    "le": 1000.0,
    "why": "the lattice is incompressible: Mach 3 is far past it",
}


def _speed(description: str) -> Any:
    """An optional design speed: EAS [m/s], null to derive it (where the rules allow)."""
    return parameter("m/s", description, **_SPEED, default=None)


@dataclass(frozen=True)
class FlightEnvelope:
    """Weights, altitudes and category, and from them (or as given) the manoeuvre and gust
    envelope of CS-23 (pre-Amendment 5: CS-23.333 to 23.341, as FAR 23) or CS-25 (25.333 to
    25.337).

    Lists (`weights`, `altitudes`) are normalised to tuples of floats.
    """

    # A list of numbers, each within the limits: "deformation" is the one form the service
    # derives such a list from today (solver.fields.FORMS; its API text says "N values").
    weights: tuple[float, ...] = parameter(
        "N",
        "the aircraft's weights to size for (mass states: maximum take-off, zero fuel, "
        "minimum flying...), each its own V-n diagram",
        ge=1e-6,
        le=1e9,
        why="a milligram to a thousand airliners",
        form="values",
        example=[19_620.0, 15_000.0],
    )
    cl_max: float = parameter(
        "-",
        "maximum lift coefficient of the aircraft, flaps retracted (C_N max: the positive stall "
        "line n = q S cl_max / W)",
        gt=0.0,
        le=5.0,
        why="positive; past any high-lift system",
        example=1.5,
    )
    cl_min: float = parameter(
        "-",
        "minimum (most negative) lift coefficient, flaps retracted (the negative stall line)",
        ge=-5.0,
        lt=0.0,
        why="negative; past any wing inverted",
        example=-0.8,
    )
    category: Category = parameter(
        "",
        "certification category: normal, utility, aerobatic or commuter (CS-23 before "
        "Amendment 5, as FAR 23), or cs25 (transport)",
        form="choice",
        choices=CATEGORIES,
        default="normal",
    )
    altitudes: tuple[float, ...] = parameter(
        "m",
        "geopotential altitudes (ISA) to size at, each with every weight",
        ge=ALTITUDE_LIMITS.ge,
        le=ALTITUDE_LIMITS.le,
        why=ALTITUDE_LIMITS.why,
        form="values",
        default=(0.0,),
        example=[0.0, 3000.0],
    )
    max_takeoff_weight: float | None = parameter(
        "N",
        "design maximum take-off weight W of CS-23.337 / CS-25.337 (n_max) and CS-23.335(a) "
        "(V_C's minimum); null: the largest of weights",
        ge=1e-6,
        le=1e9,
        why="a milligram to a thousand airliners",
        default=None,
    )
    wing_area: float | None = parameter(
        "m^2",
        "reference wing area S of the wing loading W/S (both halves); null: the wing's",
        ge=1e-4,
        le=1e4,
        why="a square centimetre to ten times an airliner's wing",
        default=None,
    )
    mean_chord: float | None = parameter(
        "m",
        "mean geometric chord S / b of the gust mass ratio (CS-23.341); null: the wing's",
        ge=1e-3,
        le=100.0,
        why="a millimetre to ten times an airliner's root chord",
        default=None,
    )
    lift_slope: float | None = parameter(
        "1/rad",
        "lift-curve slope a = dC_L/dalpha of the gust load factor (CS-23.341: the airplane's "
        "normal force coefficient slope, or the wing's); null: the flexible wing's",
        gt=0.0,
        le=10.0,
        why="positive; above thin-airfoil theory's 2 pi of an infinite wing",
        default=None,
    )
    load_factor_max: float | None = parameter(
        "-",
        "positive limit manoeuvring load factor n_max; null: the rule's minimum (CS-23.337(a), "
        "CS-25.337(b))",
        ge=1.0,
        le=10.0,
        why="level flight at least; past any aircraft's manoeuvre envelope",
        default=None,
    )
    load_factor_min: float | None = parameter(
        "-",
        "negative limit manoeuvring load factor n_min, up to V_C; null: the rule's "
        "(CS-23.337(b), CS-25.337(c))",
        ge=-10.0,
        le=0.0,
        why="negative or zero; past any aircraft's manoeuvre envelope",
        default=None,
    )
    manoeuvring_speed: float | None = _speed(
        "design manoeuvring speed V_A (EAS), at least V_S sqrt(n_max) at every weight unless "
        "V_C is less (CS-23.335(c), CS-25.335(c)); null: V_S sqrt(n_max) at each weight"
    )
    cruise_speed: float | None = _speed(
        "design cruising speed V_C (EAS); null: CS-23.335(a)'s minimum (required for cs25)"
    )
    dive_speed: float | None = _speed(
        "design dive speed V_D (EAS), above V_C; null: CS-23.335(b)'s minimum, or "
        "V_C / 0.8 for cs25 (CS-25.335(b))"
    )
    rough_air_speed: float | None = _speed(
        "design speed for maximum gust intensity V_B (EAS), commuter only; null: CS-23.335(d) "
        "at each weight and altitude"
    )

    def __post_init__(self) -> None:
        for name, spec in fields.specs(FlightEnvelope).items():
            value = getattr(self, name)
            if value is None:
                continue
            if spec.form == "number":
                fields.number(name, value, spec)
            elif spec.form == "choice" and value not in spec.choices:
                raise InvalidInput(name, "must be one of " + ", ".join(spec.choices))
            elif spec.form == "values":
                values = tuple(fields.stations(name, value, None, spec).tolist())
                for i, item in enumerate(values):
                    if item in values[:i]:
                        raise InvalidInput(f"{name}[{i}]", f"repeats {name}[{values.index(item)}]")
                object.__setattr__(self, name, values)
        heaviest = max(self.weights)
        if self.max_takeoff_weight is not None and heaviest > self.max_takeoff_weight:
            raise InvalidInput(
                "weights",
                f"{heaviest:g} N exceeds max_takeoff_weight = {self.max_takeoff_weight:g} N",
            )
        if self.category == "cs25" and self.cruise_speed is None:
            raise InvalidInput(
                "cruise_speed",
                "is required for cs25: CS-25.335(a) derives no minimum from the wing loading",
            )
        if self.rough_air_speed is not None and self.category != "commuter":
            raise InvalidInput(
                "rough_air_speed", "is the commuter category's V_B (CS-23.335(d)) only"
            )
        self._ordered()

    def _ordered(self) -> None:
        """The given speeds in the envelope's order: V_B <= V_C < V_D, V_A <= V_D."""
        given = {
            name: getattr(self, name)
            for name in ("rough_air_speed", "manoeuvring_speed", "cruise_speed", "dive_speed")
        }
        rules = [
            ("dive_speed", "cruise_speed", "must be above cruise_speed (V_C < V_D)", False),
            ("manoeuvring_speed", "dive_speed", "must not exceed dive_speed (V_A <= V_D)", True),
            ("rough_air_speed", "cruise_speed", "must not exceed cruise_speed (V_B <= V_C)", True),
        ]
        for name, other, reason, below in rules:
            value, bound = given[name], given[other]
            if value is None or bound is None:
                continue
            if (value > bound) if below else (value <= bound):
                raise InvalidInput(name, reason)

    @property
    def design_weight(self) -> float:
        """W [N] of the rules' load factor and V_C: the maximum take-off weight."""
        return self.max_takeoff_weight if self.max_takeoff_weight is not None else max(self.weights)
