"""Validated, frozen inputs: the wing, the flight condition and the solver options, each field
declared once (`solver.fields`) with its unit, limits, default and description.

A wing is described on the right half-span at N structural stations; the left half is its mirror
image. Every array has shape (N,) and SI units; angles are in degrees, as in the design study.
Validation happens once, here, so the numerics never see bad data, and the web service's request
schema is derived from the same declarations, so what the API accepts is what the solver does.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from functools import cached_property
from typing import Any, ClassVar, Literal

import numpy as np

from solver import fields
from solver.airfoil import MAX_CAMBER, CamberLine, camber_line
from solver.controls import ControlSurface, symmetric_camber, validate_surfaces
from solver.errors import InvalidInput
from solver.fields import parameter, spec_of
from solver.mass import MassModel
from solver.spar import SparDesign, ThicknessFraction, TubeSpar

__all__ = [
    "FLIGHT_RULE",
    "ISA_SEA_LEVEL_DENSITY",
    "MAX_CAMBER",
    "MAX_CHORDWISE_PANELS",
    "MIN_SPACING",
    "MIN_STATIONS",
    "FlightCondition",
    "OperatingPoint",
    "InitialGuess",
    "SolverOptions",
    "StationSpacing",
    "ValidityLimits",
    "VelocityRange",
    "Wing",
    "velocity_for",
]

MIN_STATIONS = 3
MIN_SPACING = 1e-4  # [-] of the semispan, between consecutive stations
MIN_SEMISPAN = 0.01  # [m]
MAX_CHORDWISE_PANELS = 8
ISA_SEA_LEVEL_DENSITY = 1.225  # [kg/m^3]


@dataclass(frozen=True)
class StationSpacing:
    """`stations` evenly spaced stations from the root (y = 0) to the tip (y = semispan)."""

    semispan: float = parameter(
        "m", "tip station", ge=MIN_SEMISPAN, le=1000.0, why="1 cm to 1 km", example=5.0
    )
    stations: int = parameter(
        "-",
        "number of stations N, root and tip included",
        ge=MIN_STATIONS,
        form="integer",
        example=30,
    )

    def positions(self) -> np.ndarray:
        """(N,) [m]"""
        return np.linspace(0.0, self.semispan, self.stations)


def _positions(y: object) -> np.ndarray:
    """The stations as given (a list, or a `StationSpacing`), checked."""
    if isinstance(y, StationSpacing):
        with fields.prefixed("y"):
            fields.number("semispan", y.semispan, spec_of(StationSpacing, "semispan"))
            fields.integer("stations", y.stations, spec_of(StationSpacing, "stations"))
        y = y.positions()
    array = fields.stations("y", y, None)
    n = array.shape[0]
    if n < MIN_STATIONS:
        raise InvalidInput("y", f"needs at least {MIN_STATIONS} stations, got {n}")
    if array[0] != 0.0:
        raise InvalidInput("y", "the first station must be the root, y[0] = 0")
    gaps = np.diff(array)
    narrowest = float(gaps.min())
    if not narrowest > 0:
        raise InvalidInput("y", "stations must be strictly increasing")
    if array[-1] < MIN_SEMISPAN:
        raise InvalidInput(
            "y", f"the semispan (the last station) must be at least {MIN_SEMISPAN} m"
        )
    # Increasing from 0: within the range when the last station is.
    if not fields.spec_of(Wing, "y").limits.admits(float(array[-1])):
        raise InvalidInput("y", "stations must lie from 0 to 1000 m")
    if narrowest < MIN_SPACING * array[-1]:
        # Panels narrower than this are round-off to the lattice's geometry.
        raise InvalidInput("y", f"stations must be at least {MIN_SPACING:g} of the semispan apart")
    return array


def _airfoil(airfoil: object, n: int) -> tuple[CamberLine, ...]:
    """One camber line for every station, or one per station."""
    if isinstance(airfoil, list | tuple):
        if len(airfoil) != n:
            raise InvalidInput("airfoil", f"has {len(airfoil)} sections but y has {n} stations")
        return tuple(camber_line(a, f"airfoil[{i}]") for i, a in enumerate(airfoil))
    return (camber_line(airfoil),) * n


def _tube(design: SparDesign, chord: np.ndarray, airfoil: tuple[CamberLine, ...]) -> TubeSpar:
    """The design's tube, its outer diameter resolved station by station."""
    if not isinstance(design, SparDesign):
        raise InvalidInput("spar", "must be a solver.SparDesign")
    n = chord.shape[0]
    with fields.prefixed("spar"):
        if isinstance(design.outer_diameter, ThicknessFraction):
            thickness = [line.thickness for line in airfoil]
            if any(t is None for t in thickness):
                raise InvalidInput(
                    "outer_diameter",
                    "a fraction of the airfoil thickness needs sections whose thickness is known "
                    "(NACA 4-digit designations); give the diameter in metres instead",
                )
            outer = design.outer_diameter.fraction * np.array(thickness, dtype=float) * chord
        else:
            outer = fields.stations(
                "outer_diameter",
                design.outer_diameter,
                n,
                spec_of(SparDesign, "outer_diameter"),
            )
        wall = fields.stations(
            "wall_thickness", design.wall_thickness, n, spec_of(SparDesign, "wall_thickness")
        )
    return TubeSpar(outer, wall, design.material)


# What `Wing.create` resolves by hand; every other input field is checked by its form.
_RESOLVED = (
    "y",
    "bending_stiffness",
    "torsional_stiffness",
    "airfoil",
    "spar",
    "mass",
    "control_surfaces",
)


@fields.digested_once  # one wing, thousands of requests (a design loop)
@fields.pickled_once
@dataclass(frozen=True, eq=False)
class Wing:
    """A symmetric flexible wing (right half; the left half is mirrored). Build it with
    `Wing.create`, which validates and normalises every field (one number for every station
    becomes N; the stiffnesses follow from a spar when one is given)."""

    y: np.ndarray = parameter(
        "m",
        "spanwise station positions from the root: a list with y[0] = 0, strictly increasing, "
        f"its last (the semispan) at least {MIN_SEMISPAN}, each gap at least {MIN_SPACING:g} of "
        "the semispan; or {semispan, stations} for evenly spaced ones. N stations, "
        f"{MIN_STATIONS} <= N <= FLEXWING_MAX_STATIONS (default 150)",
        ge=0.0,
        le=1000.0,
        why="a semispan of up to 1 km",
        form="positions",
    )
    chord: np.ndarray = parameter(
        "m",
        "chord length at each station",
        ge=1e-3,
        le=100.0,
        why="1 mm to 100 m",
        per_station=True,
    )
    elastic_axis: np.ndarray = parameter(
        "-",
        "elastic-axis position as a fraction of chord from the leading edge (each section is "
        "placed so that this point lies on the elastic axis)",
        ge=0.0,
        le=1.0,
        why="a fraction of the chord: on the section",
        per_station=True,
        example=0.4,
    )
    bending_stiffness: np.ndarray = parameter(
        "N m^2",
        "flapwise bending stiffness EI of the section normal to the elastic axis (required "
        "unless `spar` is given)",
        ge=1e-3,
        le=1e12,
        why="a foam model wing to a steel bridge",
        per_station=True,
        default=None,
    )
    torsional_stiffness: np.ndarray = parameter(
        "N m^2",
        "torsional stiffness GJ at each station (required unless `spar` is given)",
        ge=1e-3,
        le=1e12,
        why="a foam model wing to a steel bridge",
        per_station=True,
        default=None,
    )
    spar: TubeSpar | None = parameter(
        "",
        "a tube spar EI and GJ follow from, instead of bending_stiffness and "
        "torsional_stiffness (give one or the other); with it the response adds stresses, "
        "failure margin and spar mass",
        form="nested",
        given=SparDesign,
        default=None,
    )
    sweep: float = parameter(
        "deg",
        "sweep of the elastic axis (the straight line x = y tan(sweep)), positive aft; sections "
        "stay streamwise, the beam runs along the axis",
        gt=-60.0,
        lt=60.0,
        why="the streamwise sections' strips stay sensible",
        default=0.0,
    )
    jig_twist: np.ndarray = parameter(
        "deg",
        "built-in twist of each section (nose-up > 0), on top of which the wing deforms",
        ge=-30.0,
        le=30.0,
        why="a built-in twist the lattice can mean",
        per_station=True,
        default=0.0,
    )
    airfoil: tuple[CamberLine, ...] = parameter(
        "",
        "the sections' camber lines: one for every station or one per station (N), each a "
        "NACA 4-digit designation or {x, camber}; null: no camber (flat or symmetric "
        "sections). With one chordwise panel only the camber at x = 0 and 1 matters",
        form="airfoil",
        default=(),
    )
    cl_max: np.ndarray | None = parameter(
        "-",
        "the sections' maximum lift coefficient (null: options.validity.cl_max), past which a "
        "section stalls (the finding section_stall; the answer's numbers do not depend on it)",
        ge=0.1,
        le=10.0,
        why="a stalled flat plate's to past any high-lift system's",
        per_station=True,
        default=None,
        example=1.4,
    )
    control_surfaces: tuple[ControlSurface, ...] = parameter(
        "",
        "the flaps and ailerons, none overlapping: a flap's deflection acts on both wings "
        "alike (every operation sees it), an aileron's antisymmetrically (roll, control "
        "effectiveness and reversal); the hinge must leave a whole chordwise panel aft of it",
        form="items",
        given=ControlSurface,
        default=(),
    )
    mass: MassModel | None = parameter(
        "",
        "the wing's mass, per station like the stiffnesses, for its vibration modes and "
        "flutter (POST /flutter needs it; every other operation ignores it)",
        form="nested",
        given=MassModel,
        default=None,
    )

    @classmethod
    def create(
        cls,
        y: object,
        chord: object,
        elastic_axis: object,
        bending_stiffness: object = None,
        torsional_stiffness: object = None,
        *,
        spar: SparDesign | None = None,
        airfoil: object = None,
        mass: MassModel | None = None,
        **given: Any,
    ) -> Wing:
        """Validate and normalise inputs; any per-station input may be one number for all, and
        `airfoil` one camber line for all (None, "naca4412", {"x": [...], "camber": [...]}) or
        a list of N. Give the stiffnesses, or a `spar` they follow from, not both. Every other
        field (`sweep`, `jig_twist`, `cl_max`, ...) by keyword, checked by its declaration."""
        y_arr = _positions(y)
        n = y_arr.shape[0]
        declared = fields.specs(cls)
        unknown = set(given) - set(declared) - set(_RESOLVED)
        if unknown:
            raise InvalidInput(sorted(unknown)[0], "is not a wing input")
        values: dict[str, Any] = {"y": y_arr, "chord": chord, "elastic_axis": elastic_axis}
        values |= given
        sections = _airfoil(airfoil, n)
        normal = {
            name: _checked(name, values[name] if name in values else _default(cls, name), spec, n)
            for name, spec in declared.items()
            if name not in _RESOLVED
        }
        tube = None
        if spar is not None:
            if bending_stiffness is not None or torsional_stiffness is not None:
                raise InvalidInput(
                    "spar", "give a spar or bending_stiffness and torsional_stiffness, not both"
                )
            tube = _tube(spar, normal["chord"], sections)
            bending_stiffness, torsional_stiffness = (
                tube.bending_stiffness,
                tube.torsional_stiffness,
            )
        for name, stiffness in (
            ("bending_stiffness", bending_stiffness),
            ("torsional_stiffness", torsional_stiffness),
        ):
            if stiffness is None:
                raise InvalidInput(name, "is required unless a spar is given")
            if tube is None:
                normal[name] = _checked(name, stiffness, declared[name], n)
            else:
                normal[name] = fields.stations(name, stiffness, n)
        if mass is not None:
            if not isinstance(mass, MassModel):
                raise InvalidInput("mass", "must be a solver.MassModel")
            mass = MassModel.create(
                n,
                mass.mass_per_length,
                mass.center_of_gravity,
                mass.inertia_per_length,
                mass.concentrated,
            )
        surfaces = validate_surfaces(given.get("control_surfaces"), y_arr)
        return cls(
            y=y_arr, spar=tube, airfoil=sections, mass=mass, control_surfaces=surfaces, **normal
        )

    @property
    def n_stations(self) -> int:
        return int(self.y.shape[0])

    @property
    def semispan(self) -> float:
        """[m]"""
        return float(self.y[-1])

    @cached_property
    def arc_length(self) -> np.ndarray:
        """(N,) [m] distance of each station from the root along the (straight, swept)
        elastic axis, y / cos(sweep)."""
        return self.y / math.cos(math.radians(self.sweep))

    @cached_property
    def planform_area(self) -> float:
        """Jig planform area of both halves [m^2] (trapezoidal panels between stations)."""
        return float(np.sum((self.chord[1:] + self.chord[:-1]) * np.diff(self.y)))

    @property
    def mean_chord(self) -> float:
        """[m] planform area over span."""
        return self.planform_area / (2 * self.semispan)

    @cached_property
    def key(self) -> bytes:
        """A canonical identity of the wing, from every field: equal for equal numbers (-0.0 and
        0.0 alike), so `elastic_axis=0.4` and thirty 0.4s are one wing. Every cache, the
        solver's and the service's, keys a wing by it."""
        return fields.digest(self)

    def arrays(self) -> tuple[np.ndarray, ...]:
        """The station arrays in the order of the model's parameter vector: y, chord,
        elastic_axis, EI, GJ, jig_twist."""
        return (
            self.y,
            self.chord,
            self.elastic_axis,
            self.bending_stiffness,
            self.torsional_stiffness,
            self.jig_twist,
        )

    def camber_at(self, x: np.ndarray) -> np.ndarray:
        """(N, len(x)) [-] camber / chord of each station's section at x / chord, the flaps'
        deflection included (`solver.controls`; refused where x cannot carry a flap)."""
        flaps = symmetric_camber(self.control_surfaces, self.y, x)
        if not self.airfoil:
            return flaps
        # One airfoil for the whole wing is one line repeated: evaluate each line once.
        lines = {id(line): line for line in self.airfoil}
        values = {key: line.at(x) for key, line in lines.items()}
        return np.array([values[id(line)] for line in self.airfoil]) + flaps


def _default(cls: type, name: str) -> Any:
    field = next(f for f in dataclasses.fields(cls) if f.name == name)  # type: ignore[arg-type]
    if field.default is dataclasses.MISSING:
        raise InvalidInput(name, "is required")
    return field.default


def _checked(name: str, value: Any, spec: fields.Spec, n: int) -> Any:
    """A wing input checked and normalised by its declared form."""
    if value is None:
        return None
    if spec.form == "per_station":
        return fields.stations(name, value, n, spec)
    if spec.form == "number":
        return fields.number(name, value, spec)
    raise TypeError(f"Wing.{name}: form {spec.form!r} needs resolving by hand")


FLIGHT_RULE = (
    "give exactly one of alpha (at a given angle of attack), lift, or weight with an optional "
    "load_factor (trimmed: the angle of attack is solved for)"
)


@dataclass(frozen=True)
class FlightCondition:
    """Steady, symmetric flight, in one of three ways (`WAYS`): at a given angle of attack
    `alpha`, or trimmed, carrying `lift` (or `weight` times `load_factor`) with alpha solved
    for. `velocity` None: at each airspeed of a sweep (`at_velocity`).

    The dynamic pressure rho V^2 / 2 must be a positive, finite number.
    """

    velocity: float | None = parameter(
        "m/s",
        "airspeed",
        ge=0.01,
        le=1000.0,
        why="the lattice is incompressible: Mach 3 is far past it",
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
        "air (or water) density",
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
    load_factor: float = parameter(
        "-",
        "load factor n, nonzero",
        ge=-10.0,
        le=10.0,
        why="past any aircraft's manoeuvre envelope; not 0",
        default=1.0,
        kw_only=True,
        example=1.0,
    )

    # The ways a condition is given: each names the fields it takes beside velocity and density.
    WAYS: ClassVar[dict[str, tuple[str, ...]]] = {
        "alpha": ("alpha",),
        "lift": ("lift",),
        "weight": ("weight", "load_factor"),
    }
    RULE: ClassVar[str] = FLIGHT_RULE

    def __post_init__(self) -> None:
        for name, spec in fields.specs(FlightCondition).items():
            value = getattr(self, name)
            if value is not None:
                fields.number(name, value, spec)
        ways = [way for way in ("alpha", "lift", "weight") if getattr(self, way) is not None]
        if len(ways) != 1 or (self.load_factor != 1.0 and self.weight is None):
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
            return self.load_factor * self.weight
        return None

    @property
    def dynamic_pressure(self) -> float:
        """q = rho V^2 / 2 [Pa]."""
        if self.velocity is None:
            raise ValueError("a condition without an airspeed has no dynamic pressure")
        return 0.5 * self.density * self.velocity * self.velocity  # inf, not OverflowError

    def at_velocity(self, velocity: float) -> FlightCondition:
        return dataclasses.replace(self, velocity=velocity)

    def at_alpha(self, alpha: float) -> OperatingPoint:
        """The point the model solves at this airspeed and density and `alpha` [deg] (a
        trimmed condition at its trimmed alpha)."""
        if self.velocity is None:
            raise InvalidInput("velocity", "is required: the airspeed to solve at")
        return OperatingPoint(self.velocity, alpha, self.density)

    @staticmethod
    def velocity_for(dynamic_pressure: float, density: float) -> float:
        """V = sqrt(2 q / rho) [m/s]."""
        return velocity_for(dynamic_pressure, density)


def velocity_for(dynamic_pressure: float, density: float) -> float:
    """V = sqrt(2 q / rho) [m/s] of a dynamic pressure q [Pa] at density rho [kg/m^3]."""
    return math.sqrt(2.0 * dynamic_pressure / density)


@dataclass(frozen=True)
class OperatingPoint:
    """The point the model solves: an airspeed [m/s], the jig's angle of attack [deg] and the
    density [kg/m^3]. Not an input: the solver makes it from a `FlightCondition` (a trimmed
    one at its trimmed alpha), already validated."""

    velocity: float
    alpha: float
    density: float = ISA_SEA_LEVEL_DENSITY

    @property
    def dynamic_pressure(self) -> float:
        """q = rho V^2 / 2 [Pa]."""
        return 0.5 * self.density * self.velocity * self.velocity  # inf, not OverflowError

    def at_velocity(self, velocity: float) -> OperatingPoint:
        return OperatingPoint(velocity, self.alpha, self.density)


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


@dataclass(frozen=True)
class InitialGuess:
    """A deformation to start Newton from (e.g. `stations` of an earlier response), N values
    each. If Newton reaches another equilibrium than the one on the branch from the jig shape,
    that one is returned, flagged `stability.branch = "other"`; otherwise the answer is the same
    as without a guess."""

    heave: tuple[float, ...] = parameter(
        "m",
        "heave at each station",
        ge=-1e4,
        le=1e4,
        why="a starting deformation",
        form="deformation",
    )
    twist: tuple[float, ...] = parameter(
        "deg",
        "twist at each station, positive nose-up",
        ge=-360.0,
        le=360.0,
        why="a starting deformation",
        form="deformation",
    )
    slope: tuple[float, ...] | None = parameter(
        "-",
        "slope du/dy at each station (default: zeros)",
        ge=-1e3,
        le=1e3,
        why="a starting deformation",
        form="deformation",
        default=None,
    )

    def state(self, n: int, chordwise: int) -> np.ndarray:
        """(3N + M,) the solver state of this deformation on N stations with k chordwise panels
        per strip (unknowns as in `solver.layout`); circulations start at zero (Newton's first
        step, on the exact Jacobian, sets them)."""
        state = np.zeros(3 * n + (n - 1) * chordwise)
        for part, name in enumerate(("heave", "slope", "twist")):
            values = getattr(self, name)
            if values is None:
                continue
            spec = spec_of(InitialGuess, name)
            array = fields.stations(name, list(values), None, spec)
            if array.shape[0] != n:
                raise InvalidInput(name, f"has {array.shape[0]} values but y has {n}")
            state[part * n : (part + 1) * n] = array
        return state


def _limits(cls: type, instance: object) -> None:
    """Check every number, count, flag and choice of `instance` against its declaration."""
    for name, spec in fields.specs(cls).items():
        value = getattr(instance, name)
        if spec.form == "number":
            fields.number(name, value, spec)
        elif spec.form == "integer":
            fields.integer(name, value, spec)
        elif spec.form == "flag" and not isinstance(value, bool):
            raise InvalidInput(name, "must be true or false")
        elif spec.form == "choice" and value not in spec.choices:
            raise InvalidInput(name, "must be one of " + ", ".join(map(repr, spec.choices)))


@dataclass(frozen=True)
class ValidityLimits:
    """Where an answer leaves the model's validity (the response's `validity`): the limits each
    finding is judged against (`solver.validity`). They change what is said about an answer,
    never its numbers.

    The model is a linear, small-displacement beam whose torque is taken about the elastic axis
    without its deformation (the study's; `torque_axis = "deformed"` follows its heave, never its
    twist), coupled to an inviscid lattice that never stalls (the design study, 14.7). Each
    default is where that idealisation starts to cost more than a few percent, or where a real
    wing would behave otherwise; the descriptions give the reasons (heave fraction: Afonso et
    al., Prog. Aerosp. Sci. 89, 2017; cl_max: Abbott and von Doenhoff, Theory of Wing Sections).
    """

    heave_fraction: float = parameter(
        "-",
        "largest |heave| over the semispan (large_deflection); default 0.1: geometrically "
        "nonlinear effects become significant beyond tip deflections of about 10 % of the "
        "semispan, the usual bound of linear aeroelastic analysis",
        ge=1e-4,
        le=10.0,
        why="a hair's breadth to ten semispans",
        default=0.1,
    )
    slope: float = parameter(
        "-",
        "largest |bending slope du/ds| (large_deflection); default 0.1 (5.7 deg): the linear "
        "beam takes sin and tan of the slope as the slope and its cosine as 1, off by 0.2 to "
        "0.5 % at 0.1 and growing with its square",
        ge=1e-4,
        le=10.0,
        why="from 0.006 deg to 84 deg",
        default=0.1,
    )
    twist: float = parameter(
        "deg",
        "largest |twist about the elastic axis| (large_twist); default 10: the beam's torsion is "
        "linear and uncoupled from bending about axes that stay put, while a twisted section "
        "turns its principal axes (sin 10 deg = 0.17) and cos 10 deg = 1 is off by 1.5 %",
        ge=0.01,
        le=180.0,
        why="a hundredth of a degree to a half turn",
        default=10.0,
    )
    cl_max: float = parameter(
        "-",
        "the sections' maximum lift coefficient where the wing gives none (wing.cl_max), for "
        "section_stall; default 1.2: thin sections (NACA 0006 to 0012) reach 0.9 to 1.6 with "
        "thickness and Reynolds number (Abbott and von Doenhoff), 1.2 is a middle value for "
        "small wings (Reynolds numbers 1e5 to 1e6)",
        ge=0.1,
        le=10.0,
        why="a stalled flat plate's to past any high-lift system's",
        default=1.2,
    )
    divergence_margin: float = parameter(
        "-",
        "stability margin q / lambda beyond which the answer is near_divergence; default 0.5: "
        "with one torsion mode the lift goes as 1 / (1 - m), so a relative error in the "
        "torsional stiffness, lift slope or q is amplified by m / (1 - m) in the lift, more than "
        "one for one past m = 0.5",
        ge=0.01,
        le=1.0,
        why="1: only at divergence itself",
        default=0.5,
    )

    def __post_init__(self) -> None:
        _limits(ValidityLimits, self)


@dataclass(frozen=True)
class SolverOptions:
    """How to model and how to solve; the defaults suit almost every wing."""

    tolerance: float = parameter(
        "mixed units",
        "max-norm of the residual at convergence: heave rows in m, twist rows in deg, "
        "flow-tangency rows per unit airspeed",
        ge=1e-14,
        le=1e-3,
        why="round-off to a rough answer",
        default=1e-10,
    )
    max_iterations: int = parameter(
        "-",
        "Newton iterations of one attempt",
        ge=1,
        le=200,
        why="one step to far more than quadratic convergence needs",
        form="integer",
        default=30,
    )
    find_fold: bool = parameter(
        "",
        "also locate the fold of the equilibrium branch from the jig shape (where torsional "
        "divergence ends it) and report it in `fold`; costs a continuation run",
        form="flag",
        default=False,
    )
    chordwise_panels: int = parameter(
        "-",
        "panels per strip, cosine spaced (AeroSandbox's default): more resolve the camber's "
        "pitching moment; 1 is the design study's model. At most FLEXWING_MAX_PANELS (default "
        "240) panels on each half wing, (N - 1) k",
        ge=1,
        le=MAX_CHORDWISE_PANELS,
        why="the lattice's camber resolution, within a mesh the service can solve",
        form="integer",
        default=1,
    )
    safety_factor: float = parameter(
        "-",
        "factor on the spar's largest von Mises stress in its failure margin, "
        "yield / (safety_factor * max von Mises) - 1",
        ge=1.0,
        le=10.0,
        why="none to very conservative",
        default=1.0,
    )
    torque_axis: Literal["undeformed", "deformed"] = parameter(
        "",
        "axis of the torque the structure carries: 'undeformed' (the design study's, and "
        "AeroSandbox-comparable) or 'deformed' (arms from the heaved elastic-axis point, as "
        "codes that load the deformed beam do)",
        form="choice",
        choices=("undeformed", "deformed"),
        default="undeformed",
    )
    validity: ValidityLimits = parameter(
        "",
        "the limits of the findings in the response's `validity` (large deflection, large "
        "twist, section stall, near divergence); each default is documented with its reason",
        form="nested",
        given=ValidityLimits,
        default_factory=ValidityLimits,
    )
    aerodynamics: Literal["lattice", "strip"] = parameter(
        "",
        "the aerodynamic model: 'lattice' (the horseshoe vortex lattice, the design study's) or "
        "'strip' (strip theory: each strip a two-dimensional airfoil, lift slope 2 pi, no "
        "induced velocities from the other strips or the wake; the model of the classical "
        "divergence and flutter results); every operation runs on either",
        form="choice",
        choices=("lattice", "strip"),
        default="lattice",
    )

    def __post_init__(self) -> None:
        _limits(SolverOptions, self)
        if not isinstance(self.validity, ValidityLimits):
            raise InvalidInput("validity", "must be a solver.ValidityLimits")
        if self.aerodynamics not in ("lattice", "strip"):
            raise InvalidInput("aerodynamics", "must be 'lattice' or 'strip'")
