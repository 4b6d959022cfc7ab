"""A design problem: what to design, for what flight, under which constraints (`solver.optimize`
solves it). Every field is declared once (`solver.fields`), as the web service's /optimize
request takes it.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import Any, ClassVar, Literal

from solver import fields
from solver.errors import InvalidInput
from solver.fields import parameter
from solver.inputs.flight import ISA_SEA_LEVEL_DENSITY, FlightCondition, dynamic_pressure

__all__ = [
    "DESIGN_FLIGHT_CASE",
    "DESIGN_FLIGHT_RULE",
    "Design",
    "DesignCondition",
    "DesignConstraints",
    "DesignLoadCase",
    "DesignProblem",
    "TwistDesign",
    "WallDesign",
]

Objective = Literal["induced_drag", "trefftz_drag", "spar_mass"]
DESIGN_FLIGHT_RULE = "give lift, or weight with an optional load_factor"
# The design flight's name among a multipoint problem's cases (its answers and failures).
DESIGN_FLIGHT_CASE = "flight"


def _checked(instance: object) -> None:
    """Every declared number, count and choice of `instance` within its limits."""
    for name, spec in fields.specs(type(instance)).items():
        value = getattr(instance, name)
        if value is None:
            continue
        if spec.form == "number":
            fields.number(name, value, spec)
        elif spec.form == "integer":
            fields.integer(name, value, spec)
        elif spec.form == "choice" and value not in spec.choices:
            raise InvalidInput(name, "must be one of " + ", ".join(spec.choices))


def _as_declared(cls: type, name: str, description: str, **changes: Any) -> Any:
    """A field declared like `cls`'s `name` (its unit and limits), described for its place."""
    spec = fields.spec_of(cls, name)
    limits = dataclasses.asdict(spec.limits)
    return parameter(spec.unit, description, **limits, example=spec.example, **changes)


@dataclass(frozen=True)
class DesignCondition:
    """The flight the design is for: `lift` (or `weight` times `load_factor`) at `velocity`, at
    a fixed jig angle of attack `alpha` (the twist does the trimming)."""

    velocity: float = _as_declared(FlightCondition, "velocity", "airspeed")
    lift: float | None = parameter(
        "N",
        "lift of both halves to carry",
        ge=1e-6,
        le=1e9,
        why="a milligram to a thousand airliners' weight",
        default=None,
        example=300.0,
    )
    weight: float | None = _as_declared(
        FlightCondition, "weight", "weight to carry; lift = load_factor * weight", default=None
    )
    load_factor: float = parameter(
        "-",
        "load factor n",
        ge=1e-3,
        le=10.0,
        why="positive, past any aircraft's manoeuvres",
        default=1.0,
        example=1.0,
    )
    alpha: float = _as_declared(
        FlightCondition,
        "alpha",
        "angle of attack of the jig, fixed (the twist does the trimming)",
        default=0.0,
    )
    density: float = _as_declared(
        FlightCondition, "density", "air (or water) density", default=ISA_SEA_LEVEL_DENSITY
    )

    WAYS: ClassVar[dict[str, tuple[str, ...]]] = {
        "lift": ("lift",),
        "weight": ("weight", "load_factor"),
    }
    RULE: ClassVar[str] = DESIGN_FLIGHT_RULE

    def __post_init__(self) -> None:
        _checked(self)
        given = [way for way in ("lift", "weight") if getattr(self, way) is not None]
        if len(given) != 1 or (self.load_factor != 1.0 and self.weight is None):
            raise InvalidInput("", DESIGN_FLIGHT_RULE)

    @property
    def required_lift(self) -> float:
        """[N] the lift to carry."""
        return self.lift if self.lift is not None else self.load_factor * float(self.weight or 0)

    @property
    def dynamic_pressure(self) -> float:
        """q = rho V^2 / 2 [Pa], as the equilibrium of the design is solved at (the two
        rounded differently in the last bit before)."""
        return dynamic_pressure(self.density, self.velocity)


@dataclass(frozen=True)
class TwistDesign:
    """The jig twist as design variables."""

    control_points: int | None = parameter(
        "-",
        "values at evenly spaced fractions of the semispan, joined by a cubic spline with zero "
        "slope at the root (smooth: the default, 6); null: every station's jig twist is a "
        "variable (then the total twist's root slope is held at zero)",
        ge=2,
        le=50,
        why="a straight line to one per station of a fine mesh",
        form="integer",
        default=6,
    )
    lower: float = parameter(
        "deg",
        "lowest jig twist at any station",
        ge=-45.0,
        le=45.0,
        why="a built-in twist the lattice can mean, and more",
        default=-15.0,
    )
    upper: float = parameter(
        "deg",
        "highest jig twist at any station",
        ge=-45.0,
        le=45.0,
        why="a built-in twist the lattice can mean, and more",
        default=15.0,
    )

    def __post_init__(self) -> None:
        _checked(self)
        if not self.lower < self.upper:
            raise InvalidInput("", "lower must be below upper")


@dataclass(frozen=True)
class WallDesign:
    """The spar's wall thickness at every station as design variables (the wing needs a
    spar)."""

    lower: float = parameter(
        "m",
        "thinnest wall",
        ge=1e-5,
        le=5.0,
        why="10 micrometres to a solid 10 m rod",
        default=5e-4,
    )
    upper: float = parameter(
        "m",
        "thickest wall (also capped at half the outer diameter)",
        ge=1e-5,
        le=5.0,
        why="10 micrometres to a solid 10 m rod",
        default=0.05,
    )

    def __post_init__(self) -> None:
        _checked(self)
        if not self.lower < self.upper:
            raise InvalidInput("", "lower must be below upper")


@dataclass(frozen=True)
class Design:
    """What the optimiser may change."""

    jig_twist: TwistDesign = parameter(
        "",
        "the jig twist as design variables",
        form="nested",
        given=TwistDesign,
        default_factory=TwistDesign,
    )
    wall_thickness: WallDesign | None = parameter(
        "",
        "size the spar's wall too (null: keep the wing's spar)",
        form="nested",
        given=WallDesign,
        default=None,
    )


@dataclass(frozen=True)
class DesignConstraints:
    """Constraints beyond the lift (always held) and the twist bounds (in `design`)."""

    max_tip_heave: float | None = parameter(
        "m",
        "largest |tip heave| (null: none)",
        ge=1e-6,
        le=1e3,
        why="a micrometre to a kilometre",
        default=None,
    )
    max_stability_margin: float = parameter(
        "-",
        "largest q / local divergence pressure accepted at the optimum (checked there)",
        ge=0.01,
        le=0.999,
        why="q / divergence pressure below 1: stable",
        default=0.95,
    )

    def __post_init__(self) -> None:
        _checked(self)


@dataclass(frozen=True)
class DesignLoadCase:
    """A load case the designed wing must fly too: a named flight, trimmed (its angle of attack
    solved for, the lift `load_factor * weight` or `lift`), at an airspeed."""

    name: str = parameter(
        "",
        f"the case's name, unique ({DESIGN_FLIGHT_CASE!r} names the design flight)",
        form="text",
        le=80,
        example="pull-up",
    )
    flight: FlightCondition = parameter(
        "",
        "the flight, trimmed: weight and load_factor, or lift, at an airspeed (true or "
        "equivalent) in air (density or altitude); its angle of attack is the design's to find",
        form="nested",
        given=FlightCondition,
        without=("alpha",),
    )

    def __post_init__(self) -> None:
        if self.name == DESIGN_FLIGHT_CASE:
            raise InvalidInput("name", f"{DESIGN_FLIGHT_CASE!r} names the design flight")
        if not isinstance(self.flight, FlightCondition):
            raise InvalidInput("flight", "must be a solver.FlightCondition")
        if not self.flight.trimmed or self.flight.velocity is None:
            raise InvalidInput(
                "flight",
                "a design's load case flies trimmed (weight and load_factor, or lift) at an "
                "airspeed: its angle of attack is solved for",
            )

    @property
    def inertial_load_factor(self) -> float:
        """The load factor the wing's own mass carries in this case (1 for a lift)."""
        return self.flight.inertial_load_factor or 1.0


@dataclass(frozen=True)
class DesignProblem:
    """A design problem: the jig twist (and spar wall) of the wing that flies.

    objective: "induced_drag" (near field, of the deformed wing, as AeroSandbox),
    "trefftz_drag" (far field: a zigzag twist cannot game it) or "spar_mass" (needs
    `design.wall_thickness`). smoothness_weight [N/deg^2]: w of the penalty on the total
    twist's second differences.

    With `load_cases` the problem is multipoint (`solver.optimization.multipoint`): one jig
    twist and one spar for the design flight and every case, each case at its own trimmed angle
    of attack. The objective, the drags and the twist's smoothness are the design flight's (it
    flies at its fixed jig alpha, the twist trimming it, as without cases); the lift, the
    spar's stress and the tip heave are held in every case, and the wing's own mass (wing.mass)
    weighs n g in each.
    """

    flight: DesignCondition = parameter(
        "", "the design flight", form="nested", given=DesignCondition
    )
    design: Design = parameter(
        "", "what the optimiser may change", form="nested", given=Design, default_factory=Design
    )
    objective: Objective = parameter(
        "",
        "what to minimise: induced_drag (near field, of the deformed wing, as AeroSandbox), "
        "trefftz_drag (far field: a zigzag twist cannot game it) or spar_mass (needs "
        "design.wall_thickness)",
        form="choice",
        choices=("induced_drag", "trefftz_drag", "spar_mass"),
        default="induced_drag",
    )
    smoothness_weight: float = parameter(
        "N/deg^2",
        "weight w of the penalty w * sum of squared second differences of the total twist",
        ge=0.0,
        le=1e3,
        why="none to a twist held straight",
        default=0.0,
    )
    constraints: DesignConstraints = parameter(
        "",
        "constraints beyond the lift and the twist bounds",
        form="nested",
        given=DesignConstraints,
        default_factory=DesignConstraints,
    )
    load_cases: tuple[DesignLoadCase, ...] = parameter(
        "",
        "further load cases the designed wing must fly (a multipoint design: at most "
        "FLEXWING_MAX_LOAD_CASES), each trimmed at its own angle of attack, with the lift, the "
        "spar's stress and the tip heave held in each and the wing's own mass (wing.mass) "
        "under each load factor; the objective stays the design flight's (none: the "
        "single-point problem)",
        form="items",
        given=DesignLoadCase,
        default=(),
        example=[
            {"name": "pull-up", "flight": {"velocity": 12.0, "weight": 300.0, "load_factor": 2.5}}
        ],
    )

    def __post_init__(self) -> None:
        _checked(self)
        if self.objective == "spar_mass" and self.design.wall_thickness is None:
            raise InvalidInput(
                "objective", "spar_mass needs the spar sized (design.wall_thickness)"
            )
        cases = tuple(self.load_cases or ())
        object.__setattr__(self, "load_cases", cases)
        names: list[str] = []
        for i, case in enumerate(cases):
            if not isinstance(case, DesignLoadCase):
                raise InvalidInput(f"load_cases[{i}]", "must be a solver.DesignLoadCase")
            if case.name in names:
                raise InvalidInput(f"load_cases[{i}].name", f"{case.name!r} names another case")
            names.append(case.name)

    # What the optimiser reads, by its own names.
    @property
    def lift(self) -> float:
        """[N]"""
        return self.flight.required_lift

    @property
    def velocity(self) -> float:
        """[m/s]"""
        return self.flight.velocity

    @property
    def density(self) -> float:
        """[kg/m^3]"""
        return self.flight.density

    @property
    def alpha(self) -> float:
        """[deg]"""
        return self.flight.alpha

    @property
    def dynamic_pressure(self) -> float:
        """[Pa]"""
        return self.flight.dynamic_pressure

    @property
    def control_points(self) -> int | None:
        return self.design.jig_twist.control_points

    @property
    def twist_bounds(self) -> tuple[float, float]:
        """[deg]"""
        return self.design.jig_twist.lower, self.design.jig_twist.upper

    @property
    def size_spar(self) -> bool:
        return self.design.wall_thickness is not None

    @property
    def wall_thickness_bounds(self) -> tuple[float, float]:
        """[m]"""
        walls = self.design.wall_thickness or WallDesign()
        return walls.lower, walls.upper

    @property
    def max_tip_heave(self) -> float | None:
        """[m]"""
        return self.constraints.max_tip_heave

    @property
    def max_stability_margin(self) -> float:
        return self.constraints.max_stability_margin

    @property
    def multipoint(self) -> bool:
        """The problem has load cases beside its design flight."""
        return bool(self.load_cases)

    def for_the_rigid_wing(self) -> DesignProblem:
        """The same problem for the rigid wing: the twist alone, no tip-heave limit, the design
        flight alone."""
        return dataclasses.replace(
            self,
            load_cases=(),
            design=dataclasses.replace(self.design, wall_thickness=None),
            constraints=dataclasses.replace(self.constraints, max_tip_heave=None),
            objective="induced_drag" if self.objective == "spar_mass" else self.objective,
        )
