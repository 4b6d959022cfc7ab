"""Request and response models of the HTTP API. Units are SI, angles in degrees.

The examples are the design study's wing (shared/seed, chapter 14): y = linspace(0, 5, 30) m,
chord = sqrt(linspace(2, 0.02, 30)) m, elastic axis at 40 % chord, EI = 2e4 c^3, GJ = 1e3 c^3,
alpha 5 deg, 10 m/s; `/docs` runs them as they are.

Every number has the physical and numerical limits the API enforces (`LIMITS`), and they are in
the OpenAPI document as minimum/maximum: what the document allows is what the API accepts, apart
from rules JSON Schema cannot state (the lists of one wing have one length, stations increase
from y = 0), which the descriptions give. Limits set by the service's settings (most stations,
most sweep points) are marked with `x-flexwing-limit` here and written into the document by
`app.main` from the running configuration; they are checked when a request becomes solver
inputs (`app.inputs`).

The response models are derived from the solver's result types (`app.results`).
"""

from __future__ import annotations

import dataclasses
import math
from typing import Annotated, Any, Literal, NamedTuple, TypeVar

from pydantic import BaseModel, BeforeValidator, ConfigDict, Discriminator, Field, Tag

import solver
from app.results import OptimizeResponse, SolveResponse, SweepResponse
from app.settings import MAX_ARRAY_LENGTH
from solver import ISA_SEA_LEVEL_DENSITY, MIN_STATIONS

__all__ = [
    "LIMITS",
    "SOLVE_EXAMPLES",
    "SWEEP_EXAMPLES",
    "ClusterWorker",
    "FLIGHT_RULE",
    "Flight",
    "FlightAtAlpha",
    "FlightAtLift",
    "FlightAtWeight",
    "HealthResponse",
    "InitialGuess",
    "ReadyResponse",
    "OPTIMIZE_EXAMPLES",
    "Design",
    "DesignConstraints",
    "OptimizeFlight",
    "OptimizeFlightAtLift",
    "OptimizeFlightAtWeight",
    "OptimizeRequest",
    "OptimizeResponse",
    "SolveRequest",
    "SolveResponse",
    "SolverOptions",
    "SparMaterial",
    "StationSpacing",
    "SweepFlight",
    "SweepFlightAtAlpha",
    "SweepFlightAtLift",
    "SweepFlightAtWeight",
    "SweepRequest",
    "ThicknessFraction",
    "TubeSpar",
    "TwistDesign",
    "WallDesign",
    "SweepResponse",
    "ValidityLimits",
    "VelocityRange",
    "Wing",
    "study_wing",
]


def _significant(x: float) -> float:
    return float(f"{x:.10g}")


def study_wing() -> dict[str, Any]:
    """The design study's wing, to 10 significant digits."""
    n = 30
    y = [_significant(5.0 * i / (n - 1)) for i in range(n)]
    chord = [math.sqrt(2.0 + (0.02 - 2.0) * i / (n - 1)) for i in range(n)]
    return {
        "y": y,
        "chord": [_significant(c) for c in chord],
        "elastic_axis": 0.4,
        "bending_stiffness": [_significant(2e4 * c**3) for c in chord],
        "torsional_stiffness": [_significant(1e3 * c**3) for c in chord],
    }


_STUDY_WING = study_wing()
_STUDY_SWEEP: list[Any] = [6.0, 10.0, 12.0, 15.0, 18.0, 20.0]
_STUDY_SOLVE: dict[str, Any] = {
    "wing": _STUDY_WING,
    "flight": {"velocity": 10.0, "alpha": 5.0, "density": ISA_SEA_LEVEL_DENSITY},
}
_STUDY_SWEEP_REQUEST: dict[str, Any] = {
    "wing": _STUDY_WING,
    "flight": {"alpha": 5.0, "density": ISA_SEA_LEVEL_DENSITY},
    "velocities": _STUDY_SWEEP,
}
_STUDY_OPTIMIZE: dict[str, Any] = {
    "wing": _STUDY_WING,
    "flight": {"velocity": 12.0, "weight": 300.0, "density": ISA_SEA_LEVEL_DENSITY},
    "design": {"jig_twist": {"control_points": 6}},
    "objective": "induced_drag",
}
# Request-body examples for the OpenAPI document (what /docs pre-fills).
SOLVE_EXAMPLES: dict[str, Any] = {
    "study": {
        "summary": "The design study's wing at 10 m/s, alpha 5 deg",
        "value": _STUDY_SOLVE,
    },
    "beyond_divergence": {
        "summary": "The same wing at 23 m/s: no equilibrium (422, with the fold speed)",
        "value": _STUDY_SOLVE | {"flight": _STUDY_SOLVE["flight"] | {"velocity": 23.0}},
    },
    "at_its_weight": {
        "summary": "The same wing trimmed to carry its 300 N at 12 m/s: alpha is solved for",
        "value": _STUDY_SOLVE
        | {
            "flight": {
                "velocity": 12.0,
                "weight": 300.0,
                "load_factor": 1.0,
                "density": ISA_SEA_LEVEL_DENSITY,
            }
        },
    },
    "tube_spar": {
        "summary": "A carbon tube spar in NACA 0012 sections at its weight: stresses, margin, mass",
        "value": {
            "wing": {k: v for k, v in _STUDY_WING.items() if not k.endswith("stiffness")}
            | {
                "airfoil": "naca0012",
                "spar": {
                    "outer_diameter": {"fraction_of_thickness": 0.8},
                    "wall_thickness": 0.001,
                    "material": {
                        "youngs_modulus": 70e9,
                        "shear_modulus": 27e9,
                        "density": 1600.0,
                        "yield_stress": 600e6,
                    },
                },
            },
            "flight": {"velocity": 12.0, "weight": 300.0, "load_factor": 2.5},
            "options": {"safety_factor": 1.5},
        },
    },
    "pull_up": {
        "summary": "A 2 g pull-up at 15 m/s: twice the lift",
        "value": _STUDY_SOLVE | {"flight": {"velocity": 15.0, "weight": 300.0, "load_factor": 2.0}},
    },
}
SWEEP_EXAMPLES: dict[str, Any] = {
    "study": {
        "summary": "The design study's sweep: 6 to 20 m/s, alpha 5 deg",
        "value": _STUDY_SWEEP_REQUEST,
    },
    "to_the_fold": {
        "summary": "Past the fold: 22 and 23 m/s have no equilibrium",
        "value": _STUDY_SWEEP_REQUEST | {"velocities": [10.0, 15.0, 20.0, 21.0, 22.0, 23.0]},
    },
    "at_its_weight": {
        "summary": "The study's wing trimmed to its 300 N from 8 to 26 m/s: alpha per airspeed, "
        "and the trimmed divergence limit",
        "value": _STUDY_SWEEP_REQUEST
        | {
            "flight": {"weight": 300.0, "density": ISA_SEA_LEVEL_DENSITY},
            "velocities": [8.0, 10.0, 12.0, 14.0, 16.0, 18.0, 20.0, 22.0, 24.0, 26.0],
        },
    },
}


class Limit(NamedTuple):
    """An inclusive range [minimum, maximum] and why it is there."""

    minimum: float
    maximum: float
    unit: str
    why: str


LIMITS: dict[str, Limit] = {
    "y": Limit(0.0, 1000.0, "m", "a semispan of up to 1 km"),
    "semispan": Limit(0.01, 1000.0, "m", "1 cm to 1 km"),
    "chord": Limit(1e-3, 100.0, "m", "1 mm to 100 m"),
    "elastic_axis": Limit(0.0, 1.0, "-", "a fraction of the chord: on the section"),
    "stiffness": Limit(1e-3, 1e12, "N m^2", "a foam model wing to a steel bridge"),
    "velocity": Limit(0.01, 1000.0, "m/s", "the lattice is incompressible: Mach 3 is far past it"),
    "alpha": Limit(-30.0, 30.0, "deg", "an attached-flow lattice means nothing beyond"),
    "density": Limit(1e-4, 2000.0, "kg/m^3", "the stratosphere to sea water (hydrofoils)"),
    "lift": Limit(-1e9, 1e9, "N", "up to a thousand airliners' weight, either sign; not 0"),
    "weight": Limit(1e-6, 1e9, "N", "a milligram to a thousand airliners"),
    "load_factor": Limit(-10.0, 10.0, "-", "past any aircraft's manoeuvre envelope; not 0"),
    "design_lift": Limit(1e-6, 1e9, "N", "a milligram to a thousand airliners' weight"),
    "design_load_factor": Limit(1e-3, 10.0, "-", "positive, past any aircraft's manoeuvres"),
    "heave": Limit(-1e4, 1e4, "m", "a starting deformation"),
    "slope": Limit(-1e3, 1e3, "-", "a starting deformation"),
    "twist": Limit(-360.0, 360.0, "deg", "a starting deformation"),
    "jig_twist": Limit(-30.0, 30.0, "deg", "a built-in twist the lattice can mean"),
    "camber_x": Limit(0.0, 1.0, "-", "fractions of the chord"),
    "camber": Limit(-0.2, 0.2, "-", "a thin airfoil's mean line"),
    "spar_diameter": Limit(1e-4, 10.0, "m", "a model's carbon rod to a bridge girder"),
    "wall_thickness": Limit(1e-5, 5.0, "m", "10 micrometres to a solid 10 m rod"),
    "thickness_fraction": Limit(0.01, 1.0, "-", "the tube fits inside the section"),
    "modulus": Limit(1e6, 1e13, "Pa", "foam to diamond"),
    "material_density": Limit(1.0, 25000.0, "kg/m^3", "foam to osmium"),
    "yield_stress": Limit(1e3, 1e11, "Pa", "foam to the strongest fibres"),
    "safety_factor": Limit(1.0, 10.0, "-", "none to very conservative"),
    "cl_max": Limit(0.1, 10.0, "-", "a stalled flat plate's to past any high-lift system's"),
    "heave_fraction": Limit(1e-4, 10.0, "-", "a hair's breadth to ten semispans"),
    "validity_slope": Limit(1e-4, 10.0, "-", "from 0.006 deg to 84 deg"),
    "validity_twist": Limit(0.01, 180.0, "deg", "a hundredth of a degree to a half turn"),
    "divergence_margin": Limit(0.01, 1.0, "-", "1: only at divergence itself"),
    "smoothness_weight": Limit(0.0, 1e3, "N/deg^2", "none to a twist held straight"),
    "design_twist": Limit(-45.0, 45.0, "deg", "a built-in twist the lattice can mean, and more"),
    "tip_heave_limit": Limit(1e-6, 1e3, "m", "a micrometre to a kilometre"),
    "stability_limit": Limit(0.01, 0.999, "-", "q / divergence pressure below 1: stable"),
}


def _ranged(name: str, description: str, **kwargs: Any) -> Any:
    """A number field within LIMITS[name], its range stated in the description."""
    limit = LIMITS[name]
    return Field(
        ge=limit.minimum,
        le=limit.maximum,
        allow_inf_nan=False,
        description=f"[{limit.unit}] {description} {limit.minimum:g} to {limit.maximum:g} "
        f"({limit.why}).",
        **kwargs,
    )


def _described(name: str, description: str, **kwargs: Any) -> Any:
    """The field of a number-or-list input: the range sits on its items."""
    limit = LIMITS[name]
    return Field(
        description=f"[{limit.unit}] {description} each {limit.minimum:g} to {limit.maximum:g} "
        f"({limit.why}); one number for every station, or N values.",
        **kwargs,
    )


def _range(name: str) -> Any:
    """The Field constraint of one number within LIMITS[name]."""
    limit = LIMITS[name]
    return Field(ge=limit.minimum, le=limit.maximum, allow_inf_nan=False)


YNumber = Annotated[float, _range("y")]
ChordNumber = Annotated[float, _range("chord")]
ElasticAxisNumber = Annotated[float, _range("elastic_axis")]
StiffnessNumber = Annotated[float, _range("stiffness")]
VelocityNumber = Annotated[float, _range("velocity")]
JigTwistNumber = Annotated[float, _range("jig_twist")]
CamberXNumber = Annotated[float, _range("camber_x")]
CamberNumber = Annotated[float, _range("camber")]
ClMaxNumber = Annotated[float, _range("cl_max")]
HeaveNumber = Annotated[float, _range("heave")]
SlopeNumber = Annotated[float, _range("slope")]
TwistNumber = Annotated[float, _range("twist")]

# Up to one value per station: the limit is the service's (`x-flexwing-limit`).
PerStation = Field(
    max_length=MAX_ARRAY_LENGTH, json_schema_extra={"x-flexwing-limit": "max_stations"}
)
Number = TypeVar("Number")
# One number for every station, or a list of N (the station arrays of a wing).
StationValues = Annotated[
    Annotated[Number, Tag("@number")]
    | Annotated[list[Number], Field(min_length=MIN_STATIONS), PerStation, Tag("@list")],
    Discriminator(lambda value: "@list" if isinstance(value, list) else "@number"),
]


def _list_or_object(value: Any) -> str:
    return "@list" if isinstance(value, list) else "@object"


class _Model(BaseModel):
    # Strict: a JSON value of another type than documented ("10" or true for a number) is
    # invalid input, not converted. Integers are still accepted for numbers.
    model_config = ConfigDict(extra="forbid", strict=True)


def _whole_number(value: object) -> object:
    """30.0 is the integer 30 to JSON Schema (and to JSON: one number type), so it is to us."""
    if type(value) is float and value.is_integer():
        return int(value)
    return value


# A count or an index: JSON Schema's "integer", which 30.0 is; 30.5, "30" and true are not.
Integer = Annotated[int, BeforeValidator(_whole_number)]


# ----------------------------------------------------------------------------------- requests


class StationSpacing(_Model):
    """`stations` evenly spaced stations from the root (y = 0) to the tip (y = semispan)."""

    semispan: float = _ranged("semispan", "tip station,")
    stations: Integer = Field(
        ge=MIN_STATIONS,
        le=MAX_ARRAY_LENGTH,
        description="[-] number of stations N, root and tip included.",
        json_schema_extra={"x-flexwing-limit": "max_stations"},
    )


StationPositions = Annotated[
    Annotated[list[YNumber], Field(min_length=MIN_STATIONS), PerStation, Tag("@list")]
    | Annotated[StationSpacing, Tag("@object")],
    Discriminator(_list_or_object),
]


class CamberTable(_Model):
    """A camber line as points, linear between them: x / chord from 0 to 1 (increasing), and
    camber / chord at each."""

    x: Annotated[list[CamberXNumber], Field(min_length=2, max_length=MAX_ARRAY_LENGTH)] = Field(
        description="[-] x / chord of the points, 0 first and 1 last, strictly increasing."
    )
    camber: Annotated[list[CamberNumber], Field(min_length=2, max_length=MAX_ARRAY_LENGTH)] = Field(
        description="[-] camber / chord at each point, -0.2 to 0.2; as many as x."
    )


NacaDesignation = Annotated[
    str,
    Field(
        pattern=r"^[nN][aA][cC][aA][0-9]{4}$",
        description="A NACA 4-digit section, e.g. 'naca4412' (its analytic mean line).",
    ),
]
CamberSpec = Annotated[
    Annotated[NacaDesignation, Tag("@string")] | Annotated[CamberTable, Tag("@object")],
    Discriminator(lambda value: "@string" if isinstance(value, str) else "@object"),
]


def _one_or_per_station(value: Any) -> str:
    return "@list" if isinstance(value, list) else "@one"


SparDiameterNumber = Annotated[float, _range("spar_diameter")]
WallThicknessNumber = Annotated[float, _range("wall_thickness")]


class SparMaterial(_Model):
    """An isotropic spar material (e.g. carbon-fibre tube: E 70 GPa, G 27 GPa, 1600 kg/m^3,
    yield 600 MPa; aluminium 7075: 71.7 GPa, 26.9 GPa, 2810 kg/m^3, 503 MPa)."""

    youngs_modulus: float = _ranged("modulus", "Young's modulus E,", examples=[70e9])
    shear_modulus: float = _ranged("modulus", "shear modulus G,", examples=[27e9])
    density: float = _ranged("material_density", "density,", examples=[1600.0])
    yield_stress: float = _ranged(
        "yield_stress", "von Mises stress at which it yields,", examples=[600e6]
    )


class ThicknessFraction(_Model):
    """The outer diameter as a fraction of each section's airfoil thickness (known for NACA
    4-digit sections)."""

    fraction_of_thickness: float = _ranged(
        "thickness_fraction", "outer diameter over the airfoil's thickness,", examples=[0.8]
    )


def _diameter_kind(value: Any) -> str:
    if isinstance(value, list):
        return "@list"
    return "@fraction" if isinstance(value, dict) else "@number"


class TubeSpar(_Model):
    """A circular tube spar per station: EI = E pi/64 (D^4 - d^4), GJ = G pi/32 (D^4 - d^4) with
    d = D - 2t (thick-walled); stresses at the outer fibre and the spar's mass are reported."""

    outer_diameter: Annotated[
        Annotated[SparDiameterNumber, Tag("@number")]
        | Annotated[
            list[SparDiameterNumber], Field(min_length=MIN_STATIONS), PerStation, Tag("@list")
        ]
        | Annotated[ThicknessFraction, Tag("@fraction")],
        Discriminator(_diameter_kind),
    ] = Field(
        description="[m] outer diameter D, each 1e-4 to 10: one number for every station, N "
        "values, or {fraction_of_thickness} of a NACA 4-digit section's thickness.",
        examples=[0.04, {"fraction_of_thickness": 0.8}],
    )
    wall_thickness: StationValues[WallThicknessNumber] = _described(
        "wall_thickness", "wall thickness t, at most D / 2 (a solid rod),", examples=[0.001]
    )
    material: SparMaterial


class Wing(_Model):
    """A symmetric wing described on its right half at N stations from the root.

    Every per-station input is one number for all stations or a list of N values. Stations must
    increase strictly from y[0] = 0, each gap at least 1e-4 of the semispan.
    """

    model_config = ConfigDict(
        extra="forbid", strict=True, json_schema_extra={"examples": [_STUDY_WING]}
    )

    y: StationPositions = Field(
        description=(
            "[m] spanwise station positions from the root, 0 to 1000: a list with y[0] = 0, "
            "strictly increasing, its last (the semispan) at least 0.01, or {semispan, stations} "
            "for evenly spaced ones. N stations, "
            f"{MIN_STATIONS} <= N <= FLEXWING_MAX_STATIONS (default 150)."
        ),
        examples=[_STUDY_WING["y"]],
    )
    chord: StationValues[ChordNumber] = _described(
        "chord", "chord length at each station,", examples=[_STUDY_WING["chord"]]
    )
    elastic_axis: StationValues[ElasticAxisNumber] = _described(
        "elastic_axis",
        "elastic-axis position as a fraction of chord from the leading edge,",
        examples=[0.4],
    )
    bending_stiffness: StationValues[StiffnessNumber] | None = _described(
        "stiffness",
        "flapwise bending stiffness EI at each station (required unless `spar` is given),",
        default=None,
        examples=[_STUDY_WING["bending_stiffness"]],
    )
    torsional_stiffness: StationValues[StiffnessNumber] | None = _described(
        "stiffness",
        "torsional stiffness GJ at each station (required unless `spar` is given),",
        default=None,
        examples=[_STUDY_WING["torsional_stiffness"]],
    )
    spar: TubeSpar | None = Field(
        default=None,
        description="A tube spar EI and GJ follow from, instead of bending_stiffness and "
        "torsional_stiffness (give one or the other); with it the response adds stresses, "
        "failure margin and spar mass.",
    )
    sweep: float = Field(
        default=0.0,
        gt=-60.0,
        lt=60.0,
        allow_inf_nan=False,
        description=(
            "[deg] sweep of the elastic axis (the straight line x = y tan(sweep)), positive aft, "
            "strictly between -60 and 60. Sections stay streamwise; the beam runs along the axis."
        ),
    )
    jig_twist: StationValues[JigTwistNumber] = _described(
        "jig_twist",
        "built-in twist of each section (nose-up > 0), on top of which the wing deforms,",
        default=0.0,
    )
    airfoil: (
        Annotated[
            Annotated[CamberSpec, Tag("@one")]
            | Annotated[list[CamberSpec], PerStation, Tag("@list")],
            Discriminator(_one_or_per_station),
        ]
        | None
    ) = Field(
        default=None,
        description=(
            "The sections' camber lines: one for every station or one per station (N), each a "
            "NACA 4-digit designation or {x, camber}; null: no camber (flat or symmetric "
            "sections). With one chordwise panel only the camber at x = 0 and 1 matters."
        ),
    )
    cl_max: StationValues[ClMaxNumber] | None = _described(
        "cl_max",
        "the sections' maximum lift coefficient (null: options.validity.cl_max), past which a "
        "section stalls (the finding section_stall; the answer's numbers do not depend on it),",
        default=None,
        examples=[1.4],
    )


def _velocity() -> Any:
    return _ranged("velocity", "airspeed,", examples=[10.0])


def _alpha() -> Any:
    return _ranged("alpha", "angle of attack of the jig (undeformed) shape,", examples=[5.0])


def _density() -> Any:
    return _ranged(
        "density",
        "air (or water) density,",
        default=ISA_SEA_LEVEL_DENSITY,
        examples=[ISA_SEA_LEVEL_DENSITY],
    )


class FlightAtAlpha(_Model):
    """Steady, symmetric flight at a given angle of attack."""

    velocity: float = _velocity()
    alpha: float = _alpha()
    density: float = _density()


def _lift() -> Any:
    return _ranged(
        "lift",
        "lift of both halves to carry, nonzero; the angle of attack is solved for,",
        examples=[300.0],
    )


def _weight() -> Any:
    return _ranged(
        "weight",
        "weight to carry; lift = load_factor * weight and the angle of attack is solved for,",
        examples=[300.0],
    )


def _load_factor() -> Any:
    return _ranged("load_factor", "load factor n, nonzero,", default=1.0, examples=[1.0])


class FlightAtLift(_Model):
    """Trimmed flight: the angle of attack at which the flexible wing carries `lift`."""

    velocity: float = _velocity()
    lift: float = _lift()
    density: float = _density()


class FlightAtWeight(_Model):
    """Trimmed flight: the angle of attack at which the flexible wing carries
    `load_factor * weight`."""

    velocity: float = _velocity()
    weight: float = _weight()
    load_factor: float = _load_factor()
    density: float = _density()


_FLIGHT_WAYS = ("alpha", "lift", "weight")
FLIGHT_RULE = (
    "give exactly one of alpha (at a given angle of attack), lift, or weight with an optional "
    "load_factor (trimmed: the angle of attack is solved for)"
)


def _flight_way(value: Any) -> str | None:
    """The tag of the one way the flight is given; None if none or several are."""
    if not isinstance(value, dict):
        return "@alpha"  # not an object at all: let the model say so
    given = [way for way in _FLIGHT_WAYS if way in value]
    if "load_factor" in value and "weight" not in value:
        return None
    return f"@{given[0]}" if len(given) == 1 else None


def _one_way() -> Any:
    return Discriminator(
        _flight_way,
        custom_error_type="flight_way",
        custom_error_message=FLIGHT_RULE,
    )


Flight = Annotated[
    Annotated[FlightAtAlpha, Tag("@alpha")]
    | Annotated[FlightAtLift, Tag("@lift")]
    | Annotated[FlightAtWeight, Tag("@weight")],
    _one_way(),
]


class SweepFlightAtAlpha(_Model):
    """Steady, symmetric flight at a given angle of attack; airspeeds from `velocities`."""

    alpha: float = _alpha()
    density: float = _density()


class SweepFlightAtLift(_Model):
    """Trimmed flight carrying `lift` at every airspeed of `velocities`."""

    lift: float = _lift()
    density: float = _density()


class SweepFlightAtWeight(_Model):
    """Trimmed flight carrying `load_factor * weight` at every airspeed of `velocities`."""

    weight: float = _weight()
    load_factor: float = _load_factor()
    density: float = _density()


SweepFlight = Annotated[
    Annotated[SweepFlightAtAlpha, Tag("@alpha")]
    | Annotated[SweepFlightAtLift, Tag("@lift")]
    | Annotated[SweepFlightAtWeight, Tag("@weight")],
    _one_way(),
]


_VALIDITY_FIELDS = {f.name: f for f in dataclasses.fields(solver.ValidityLimits)}


def _validity_limit(name: str, limit: str) -> Any:
    """A field of `ValidityLimits`: the solver's default and its reason, within LIMITS[limit]."""
    known = _VALIDITY_FIELDS[name]
    bounds = LIMITS[limit]
    text = str(known.metadata["description"])
    return Field(
        default=known.default,
        ge=bounds.minimum,
        le=bounds.maximum,
        allow_inf_nan=False,
        description=f"[{bounds.unit}] {text[:1].upper()}{text[1:]}. {bounds.minimum:g} to "
        f"{bounds.maximum:g} ({bounds.why}).",
    )


class ValidityLimits(_Model):
    """Where an answer leaves the model's validity (the response's `validity`): the limits each
    finding is judged against, with the reason of each default. They change what is said about
    an answer, never its numbers."""

    heave_fraction: float = _validity_limit("heave_fraction", "heave_fraction")
    slope: float = _validity_limit("slope", "validity_slope")
    twist: float = _validity_limit("twist", "validity_twist")
    cl_max: float = _validity_limit("cl_max", "cl_max")
    divergence_margin: float = _validity_limit("divergence_margin", "divergence_margin")


class SolverOptions(_Model):
    """How to solve; the defaults suit almost every wing."""

    tolerance: float = Field(
        default=1e-10,
        ge=1e-14,
        le=1e-3,
        allow_inf_nan=False,
        description=(
            "[mixed units] max-norm of the residual at convergence, 1e-14 to 1e-3: heave rows in "
            "m, twist rows in deg, flow-tangency rows per unit airspeed."
        ),
    )
    max_iterations: Integer = Field(
        default=30, ge=1, le=200, description="[-] Newton iterations of one attempt, 1 to 200."
    )
    find_fold: bool = Field(
        default=False,
        description=(
            "Also locate the fold of the equilibrium branch from the jig shape (where torsional "
            "divergence ends it) and report it in `fold`. Costs a continuation run."
        ),
    )
    chordwise_panels: Integer = Field(
        default=1,
        ge=1,
        le=8,
        description=(
            "[-] panels per strip, 1 to 8, cosine spaced (AeroSandbox's default): more resolve "
            "the camber's pitching moment; 1 is the design study's model. At most "
            "FLEXWING_MAX_PANELS (default 240) panels on each half wing, (N - 1) k."
        ),
    )
    safety_factor: float = _ranged(
        "safety_factor",
        "factor on the spar's largest von Mises stress in its failure margin, "
        "yield / (safety_factor * max von Mises) - 1,",
        default=1.0,
    )
    torque_axis: Literal["undeformed", "deformed"] = Field(
        default="undeformed",
        description=(
            "Axis of the torque the structure carries: 'undeformed' (the design study's, and "
            "AeroSandbox-comparable) or 'deformed' (arms from the heaved elastic-axis point, as "
            "codes that load the deformed beam do)."
        ),
    )
    validity: ValidityLimits = Field(
        default_factory=ValidityLimits,
        description=(
            "The limits of the findings in the response's `validity` (large deflection, large "
            "twist, section stall, near divergence); each default is documented with its reason."
        ),
    )


def _deformation(name: str, description: str, **kwargs: Any) -> Any:
    limit = LIMITS[name]
    return Field(
        description=f"[{limit.unit}] {description}, {limit.minimum:g} to {limit.maximum:g}; "
        "N values.",
        **kwargs,
    )


class InitialGuess(_Model):
    """A deformation to start Newton from (e.g. `stations` of an earlier response), N values each.

    If Newton reaches another equilibrium than the one on the branch from the jig shape, that
    one is returned, flagged `stability.branch = "other"`; otherwise the answer is the same as
    without a guess.
    """

    heave: Annotated[list[HeaveNumber], PerStation] = _deformation("heave", "heave at each station")
    slope: Annotated[list[SlopeNumber], PerStation] | None = _deformation(
        "slope", "slope du/dy at each station (default: zeros)", default=None
    )
    twist: Annotated[list[TwistNumber], PerStation] = _deformation(
        "twist", "twist at each station, positive nose-up"
    )


class SolveRequest(_Model):
    """One wing at one flight condition."""

    model_config = ConfigDict(
        extra="forbid",
        strict=True,
        json_schema_extra={"examples": [_STUDY_SOLVE]},
    )

    wing: Wing
    flight: Flight = Field(description=f"The flight condition: {FLIGHT_RULE}.")
    initial_guess: InitialGuess | None = Field(
        default=None, description="Optional starting deformation for Newton."
    )
    options: SolverOptions | None = Field(default=None, description="Optional solver options.")


class VelocityRange(_Model):
    """`count` airspeeds evenly spaced from `start` to `stop`, both included."""

    start: float = _ranged("velocity", "first airspeed,")
    stop: float = _ranged("velocity", "last airspeed,")
    count: Integer = Field(
        ge=1,
        le=MAX_ARRAY_LENGTH,
        description="[-] number of airspeeds, 1 to FLEXWING_MAX_SWEEP_POINTS (default 50).",
        json_schema_extra={"x-flexwing-limit": "max_sweep_points"},
    )


class SweepRequest(_Model):
    """One wing over several airspeeds; every point is the equilibrium on the branch from the
    jig shape at that airspeed, whatever the order."""

    model_config = ConfigDict(
        extra="forbid",
        strict=True,
        json_schema_extra={"examples": [_STUDY_SWEEP_REQUEST]},
    )

    wing: Wing
    flight: SweepFlight = Field(description=f"The flight condition: {FLIGHT_RULE}.")
    velocities: Annotated[
        Annotated[
            list[VelocityNumber],
            Tag("@list"),
            Field(
                min_length=1,
                max_length=MAX_ARRAY_LENGTH,
                json_schema_extra={"x-flexwing-limit": "max_sweep_points"},
            ),
        ]
        | Annotated[VelocityRange, Tag("@object")],
        Discriminator(_list_or_object),
    ] = Field(
        description=(
            "[m/s] airspeeds, 0.01 to 1000, answered in this order: a list (1 to "
            "FLEXWING_MAX_SWEEP_POINTS values, default 50) or {start, stop, count}."
        ),
        examples=[_STUDY_SWEEP],
    )
    options: SolverOptions | None = Field(default=None, description="Optional solver options.")


def _design_alpha() -> Any:
    return _ranged(
        "alpha",
        "angle of attack of the jig, fixed (the twist does the trimming),",
        default=0.0,
        examples=[0.0],
    )


class OptimizeFlightAtLift(_Model):
    """The flight the design is for: `lift` at `velocity`, at a fixed jig angle `alpha`."""

    velocity: float = _velocity()
    lift: float = _ranged("design_lift", "lift of both halves to carry,", examples=[300.0])
    alpha: float = _design_alpha()
    density: float = _density()


class OptimizeFlightAtWeight(_Model):
    """The flight the design is for: `load_factor * weight` at `velocity`, at a fixed `alpha`."""

    velocity: float = _velocity()
    weight: float = _ranged(
        "weight", "weight to carry; lift = load_factor * weight,", examples=[300.0]
    )
    load_factor: float = _ranged(
        "design_load_factor", "load factor n,", default=1.0, examples=[1.0]
    )
    alpha: float = _design_alpha()
    density: float = _density()


DESIGN_FLIGHT_RULE = "give lift, or weight with an optional load_factor"


def _design_way(value: Any) -> str | None:
    if not isinstance(value, dict):
        return "@lift"
    given = [way for way in ("lift", "weight") if way in value]
    if "load_factor" in value and "weight" not in value:
        return None
    return f"@{given[0]}" if len(given) == 1 else None


OptimizeFlight = Annotated[
    Annotated[OptimizeFlightAtLift, Tag("@lift")]
    | Annotated[OptimizeFlightAtWeight, Tag("@weight")],
    Discriminator(
        _design_way, custom_error_type="flight_way", custom_error_message=DESIGN_FLIGHT_RULE
    ),
]


class TwistDesign(_Model):
    """The jig twist as design variables."""

    control_points: Annotated[int, Field(ge=2, le=50), BeforeValidator(_whole_number)] | None = (
        Field(
            default=6,
            description=(
                "[-] k values at evenly spaced fractions of the semispan, 2 to 50, joined by a "
                "cubic spline with zero slope at the root (smooth: the default, 6); null: every "
                "station's jig twist is a variable (then the total twist's root slope is held at "
                "zero)."
            ),
        )
    )
    lower: float = _ranged("design_twist", "lowest jig twist at any station,", default=-15.0)
    upper: float = _ranged("design_twist", "highest jig twist at any station,", default=15.0)


class WallDesign(_Model):
    """The spar's wall thickness at every station as design variables (the wing needs a spar)."""

    lower: float = _ranged("wall_thickness", "thinnest wall,", default=5e-4)
    upper: float = _ranged(
        "wall_thickness", "thickest wall (also capped at half the outer diameter),", default=0.05
    )


class Design(_Model):
    """What the optimiser may change."""

    jig_twist: TwistDesign = Field(default_factory=TwistDesign)
    wall_thickness: WallDesign | None = Field(
        default=None, description="Size the spar's wall too (null: keep the wing's spar)."
    )


class DesignConstraints(_Model):
    """Constraints beyond the lift (always held) and the twist bounds (in `design`)."""

    max_tip_heave: float | None = _ranged(
        "tip_heave_limit", "largest |tip heave| (null: none),", default=None
    )
    max_stability_margin: float = _ranged(
        "stability_limit",
        "largest q / local divergence pressure accepted at the optimum (checked there),",
        default=0.95,
    )


class OptimizeRequest(_Model):
    """A design problem: the jig twist (and spar wall) of the wing that flies."""

    model_config = ConfigDict(
        extra="forbid", strict=True, json_schema_extra={"examples": [_STUDY_OPTIMIZE]}
    )

    wing: Wing
    flight: OptimizeFlight = Field(description=f"The design flight: {DESIGN_FLIGHT_RULE}.")
    design: Design = Field(default_factory=Design)
    objective: Literal["induced_drag", "trefftz_drag", "spar_mass"] = Field(
        default="induced_drag",
        description=(
            "What to minimise: induced_drag (near field, of the deformed wing, as AeroSandbox), "
            "trefftz_drag (far field: a zigzag twist cannot game it) or spar_mass (needs "
            "design.wall_thickness)."
        ),
    )
    smoothness_weight: float = _ranged(
        "smoothness_weight",
        "weight w of the penalty w * sum of squared second differences of the total twist,",
        default=0.0,
    )
    constraints: DesignConstraints = Field(default_factory=DesignConstraints)
    options: SolverOptions | None = Field(default=None, description="Optional solver options.")


OPTIMIZE_EXAMPLES: dict[str, Any] = {
    "study": {
        "summary": "The study's closing sketch: the jig twist of its wing carrying 300 N at 12 m/s",
        "value": _STUDY_OPTIMIZE,
    },
    "aerosandbox_reference": {
        "summary": "The regularised sketch AeroSandbox solves: every station, penalty 0.01",
        "value": _STUDY_OPTIMIZE
        | {"design": {"jig_twist": {"control_points": None}}, "smoothness_weight": 0.01},
    },
}

# ---------------------------------------------------------------------------------- responses


class HealthResponse(BaseModel):
    status: Literal["ok"] = Field(description="The process is alive.")


class ClusterWorker(BaseModel):
    """One worker of a Dask cluster (FLEXWING_EXECUTOR=dask)."""

    address: str = Field(description="Its address, e.g. tcp://10.0.0.7:40123.")
    name: str = Field(description="Its name (dask worker --name).")
    threads: int = Field(description="[-] threads it runs tasks on.")
    warm: bool = Field(description="It has compiled or loaded the warm mesh sizes.")
    pid: int | None = Field(description="Its process id on its machine, once warm.")


class ReadyResponse(BaseModel):
    ready: bool = Field(description="Workers are warm and accepting solves.")
    workers: int = Field(description="[-] configured worker count.")
    pids: list[int] = Field(description="Process ids of the local workers (empty if remote).")
    warm_stations: list[int] = Field(description="Mesh sizes N warmed in every worker.")
    detail: str = Field(description="What the pool is doing.")
    cluster: list[ClusterWorker] | None = Field(
        default=None,
        description="FLEXWING_EXECUTOR=dask: the cluster's workers and whether each is warm.",
    )
