"""The wing: N structural stations on the right half-span (the left half is its mirror image),
each with its chord, elastic axis, stiffness, jig twist and airfoil, and its optional parts (a
tube spar, mass, control surfaces), each field declared once (`solver.fields`).

Every array has shape (N,) and SI units; angles are in degrees, as in the design study.
Validation happens once, here, so the numerics never see bad data, and the web service's request
schema is derived from the same declarations, so what the API accepts is what the solver does.
"""

from __future__ import annotations

import dataclasses
import math
import warnings
from collections.abc import Mapping
from dataclasses import dataclass
from functools import cached_property
from typing import Any

import numpy as np

from solver import fields
from solver.errors import InvalidInput
from solver.fields import parameter, spec_of
from solver.inputs.airfoil import CamberLine, camber_line
from solver.inputs.control_surfaces import ControlSurface, symmetric_camber, validate_surfaces
from solver.inputs.mass import MassModel
from solver.inputs.spar import SparDesign, ThicknessFraction, TubeSpar

__all__ = [
    "MIN_SPACING",
    "MIN_STATIONS",
    "StationSpacing",
    "Wing",
    "require_control_surfaces",
    "require_mass",
]

MIN_STATIONS = 3
MIN_SPACING = 1e-4  # [-] of the semispan, between consecutive stations
MIN_SEMISPAN = 0.01  # [m]


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
        compiled=True,
    )
    chord: np.ndarray = parameter(
        "m",
        "chord length at each station",
        ge=1e-3,
        le=100.0,
        why="1 mm to 100 m",
        per_station=True,
        compiled=True,
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
        compiled=True,
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
        compiled=True,
    )
    torsional_stiffness: np.ndarray = parameter(
        "N m^2",
        "torsional stiffness GJ at each station (required unless `spar` is given)",
        ge=1e-3,
        le=1e12,
        why="a foam model wing to a steel bridge",
        per_station=True,
        default=None,
        compiled=True,
    )
    spar: TubeSpar | None = parameter(
        "",
        "a tube spar EI and GJ follow from, instead of bending_stiffness and "
        "torsional_stiffness (give one or the other); with it the response adds stresses, "
        "failure margin and spar mass",
        form="nested",
        given=SparDesign,
        default=None,
        example={
            "outer_diameter": 0.08,
            "wall_thickness": 0.002,
            "material": {
                "youngs_modulus": 70e9,
                "shear_modulus": 27e9,
                "density": 1600.0,
                "yield_stress": 600e6,
            },
        },
    )
    sweep: float = parameter(
        "deg",
        "sweep of the elastic axis (the straight line x = y tan(sweep)), positive aft; sections "
        "stay streamwise, the beam runs along the axis",
        gt=-60.0,
        lt=60.0,
        why="the streamwise sections' strips stay sensible",
        default=0.0,
        example=15.0,
        compiled=True,
    )
    dihedral: float = parameter(
        "deg",
        "dihedral of the wing's plane, positive tips up: the flat (swept) half-wing turned about "
        "the x axis through the root, the left half its mirror image. y and the heave stay in "
        "the wing's plane: y is a station's distance from the root along it (projected on the "
        "ground, y cos(dihedral)), the heave is normal to it",
        gt=-45.0,
        lt=45.0,
        why="within 45 deg of level the wing is a wing, not a fin: its lift stays above half "
        "the flat wing's (cos^2)",
        default=0.0,
        example=5.0,
        compiled=True,
        kw_only=True,
    )
    jig_twist: np.ndarray = parameter(
        "deg",
        "built-in twist of each section (nose-up > 0), on top of which the wing deforms",
        ge=-30.0,
        le=30.0,
        why="a built-in twist the lattice can mean",
        per_station=True,
        default=0.0,
        example=2.0,
        compiled=True,
    )
    bending_torsion_coupling: np.ndarray = parameter(
        "N m^2",
        "bending-torsion coupling stiffness K of the section (the K23 term of a composite or "
        "built-up section: aeroelastic tailoring): the section's moments are M = EI kappa + K "
        "theta' and T = K kappa + GJ theta' (kappa = d2u/ds2, curvature bending the tip up; "
        "theta' = dphi/ds, twist rate nose up). Positive K: bending the tip up twists the "
        "section nose down (washes it out), twisting it nose up bends it down. |K| < "
        "sqrt(EI GJ) at every station (the section's stiffness positive definite); default 0 "
        "(uncoupled)",
        ge=-1e12,
        le=1e12,
        why="within the stiffnesses' own range; the section's positive definiteness is checked "
        "against EI and GJ",
        per_station=True,
        default=0.0,
        example=0.0,
        compiled=True,
        kw_only=True,
    )
    in_plane_bending_stiffness: np.ndarray | None = parameter(
        "N m^2",
        "in-plane (lag, chordwise) bending stiffness EI_lag of the section about its own normal "
        "(the section's stiffer axis for a wing; null: rigid in its plane, the planar beam). "
        "Needs options.structure = geometrically_exact, which then adds the lag displacement "
        "and rotation to its unknowns (/solve, /sweep, /flutter, /controls, /roll and /loads "
        "take it for now; /gust, /loads' gust conditions and /optimize refuse it). "
        "Compiled in the lag layouts only (solver.model.layout.LAG_SLOTS)",
        ge=1e-3,
        le=1e12,
        why="a foam model wing to a steel bridge, as EI",
        per_station=True,
        default=None,
        example=5e5,
        kw_only=True,
    )
    airfoil: tuple[CamberLine, ...] = parameter(
        "",
        "the sections' camber lines: one for every station or one per station (N), each a "
        "NACA 4-digit designation or {x, camber}; null: no camber (flat or symmetric "
        "sections). With one chordwise panel only the camber at x = 0 and 1 matters",
        form="airfoil",
        default=(),
        example="naca2412",
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
        example=[
            {"name": "flap", "start": 0.0, "end": 0.45, "hinge": 0.5, "deflection": 5.0},
            {"name": "aileron", "start": 0.55, "end": 0.95, "deflection": 5.0, "kind": "aileron"},
        ],
    )
    mass: MassModel | None = parameter(
        "",
        "the wing's mass, per station like the stiffnesses, for its vibration modes and "
        "flutter (POST /flutter needs it; every other operation ignores it)",
        form="nested",
        given=MassModel,
        default=None,
        example={"mass_per_length": 3.0, "center_of_gravity": 0.45, "inertia_per_length": 0.1},
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
        mass: MassModel | Mapping[str, Any] | None = None,
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
        _check_definite(
            normal["bending_stiffness"],
            normal["torsional_stiffness"],
            normal["bending_torsion_coupling"],
        )
        if mass is not None:
            mass = MassModel.resolved(mass, n)
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
        """Deprecated: y, chord, elastic_axis, EI, GJ and jig_twist, the station arrays the
        compiled model's parameter vector once held in this order. The model now reads every
        field it needs by name (`solver.model.layout.Layout.pack`)."""
        warnings.warn(
            "Wing.arrays() is deprecated: the compiled model reads the wing's fields by name "
            "(solver.Layout.pack, Layout.wing_values)",
            DeprecationWarning,
            stacklevel=2,
        )
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
        deflection included (`solver.inputs.control_surfaces`; refused where x cannot carry a
        flap)."""
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


def _check_definite(ei: np.ndarray, gj: np.ndarray, coupling: np.ndarray) -> None:
    """Refuse a section whose 2 x 2 stiffness [[EI, K], [K, GJ]] is not positive definite
    (K^2 >= EI GJ: a section that bends or twists for free), naming its station."""
    bad = np.flatnonzero(coupling * coupling >= ei * gj)
    if bad.size:
        i = int(bad[0])
        raise InvalidInput(
            f"bending_torsion_coupling[{i}]",
            f"|K| = {abs(coupling[i]):.6g} N m^2 must stay below sqrt(EI GJ) = "
            f"{math.sqrt(ei[i] * gj[i]):.6g} N m^2 (the section's stiffness positive definite)",
        )


def _checked(name: str, value: Any, spec: fields.Spec, n: int) -> Any:
    """A wing input checked and normalised by its declared form."""
    if value is None:
        return None
    if spec.form == "per_station":
        return fields.stations(name, value, n, spec)
    if spec.form == "number":
        return fields.number(name, value, spec)
    raise TypeError(f"Wing.{name}: form {spec.form!r} needs resolving by hand")


def require_control_surfaces(wing: Wing, what: str) -> None:
    """Refuse `wing` for `what` (a phrase: "effectiveness is a control surface's") when it has
    no control surfaces, naming `wing.control_surfaces` (the operations and the analyses
    alike: one check, one path)."""
    if not wing.control_surfaces:
        raise InvalidInput("wing.control_surfaces", f"needs at least one surface: {what}")


def require_mass(wing: Wing, what: str) -> None:
    """Refuse `wing` for `what` (a phrase: "vibration and flutter need it") without its mass
    model, naming `wing.mass`."""
    if wing.mass is None:
        raise InvalidInput(
            "wing.mass",
            f"is required: {what} (mass per unit length, centre of gravity and inertia per "
            "station)",
        )
