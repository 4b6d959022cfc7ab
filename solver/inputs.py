"""Validated, frozen inputs: the wing, the flight condition and the solver options.

A wing is described on the right half-span at N structural stations; the left half is its mirror
image. Every array has shape (N,) and SI units; angles are in degrees, as in the design study.
Validation happens once, here, so the numerics never see bad data.
"""

from __future__ import annotations

import hashlib
import math
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any, Literal

import numpy as np

from solver.airfoil import CamberLine, camber_line
from solver.controls import ControlSurface, symmetric_camber, validate_surfaces
from solver.errors import InvalidInput
from solver.spar import Material, SparDesign, ThicknessFraction, TubeSpar

__all__ = [
    "ISA_SEA_LEVEL_DENSITY",
    "MAX_CHORDWISE_PANELS",
    "MAX_SWEEP",
    "MIN_SPACING",
    "MIN_STATIONS",
    "FlightCondition",
    "SolverOptions",
    "TrimCondition",
    "ValidityLimits",
    "Wing",
]

MIN_STATIONS = 3
MIN_SPACING = 1e-4  # [-] of the semispan, between consecutive stations
MAX_SWEEP = 60.0  # [deg] |sweep| below this: the streamwise sections' strips stay sensible
MAX_CHORDWISE_PANELS = 8
ISA_SEA_LEVEL_DENSITY = 1.225  # [kg/m^3]


def _is_number(value: object) -> bool:
    """A real number: bool (a Python int) and strings are not."""
    return isinstance(value, int | float | np.integer | np.floating) and not isinstance(
        value, bool | np.bool_
    )


def _station_array(name: str, values: object, n: int | None) -> np.ndarray:
    """(n,) float array from one number or n numbers, finite, read-only."""
    if isinstance(values, np.ndarray):
        if not np.issubdtype(values.dtype, np.integer) and not np.issubdtype(
            values.dtype, np.floating
        ):
            raise InvalidInput(name, "must contain only numbers")
        array = values.astype(float)
    elif _is_number(values):
        array = np.asarray(float(values))  # type: ignore[arg-type]
    elif isinstance(values, list | tuple) and all(_is_number(v) for v in values):
        array = np.asarray(values, dtype=float)
    else:
        raise InvalidInput(name, "must be a number or a list of numbers")
    if array.ndim == 0 and n is not None:
        array = np.full(n, float(array))
    if array.ndim != 1:
        raise InvalidInput(name, "must be a one-dimensional list of numbers")
    if n is not None and array.shape[0] != n:
        raise InvalidInput(name, f"has {array.shape[0]} values but y has {n} stations")
    if not np.all(np.isfinite(array)):
        raise InvalidInput(name, "must contain only finite numbers")
    array.setflags(write=False)
    return array


def _tube_spar(design: SparDesign, chord: np.ndarray, camber: tuple[CamberLine, ...]) -> TubeSpar:
    """The design's tube, its outer diameter resolved station by station."""
    if not isinstance(design, SparDesign):
        raise InvalidInput("spar", "must be a solver.SparDesign")
    if not isinstance(design.material, Material):
        raise InvalidInput("spar.material", "must be a solver.Material")
    n = chord.shape[0]
    if isinstance(design.outer_diameter, ThicknessFraction):
        thickness = [line.thickness for line in camber]
        if any(t is None for t in thickness):
            raise InvalidInput(
                "spar.outer_diameter",
                "a fraction of the airfoil thickness needs sections whose thickness is known "
                "(NACA 4-digit designations); give the diameter in metres instead",
            )
        outer = design.outer_diameter.fraction * np.array(thickness, dtype=float) * chord
    else:
        outer = _station_array("spar.outer_diameter", design.outer_diameter, n)
    wall = _station_array("spar.wall_thickness", design.wall_thickness, n)
    return TubeSpar(outer, wall, design.material)


@dataclass(frozen=True, eq=False)
class Wing:
    """A symmetric flexible wing (right half; the left half is mirrored).

    Attributes:
        y: (N,) [m] spanwise station positions, y[0] = 0 at the root, strictly increasing.
        chord: (N,) [m] streamwise chord length at each station, > 0.
        elastic_axis: (N,) [-] elastic-axis position as a fraction of chord from the leading edge.
            Each section is placed so that this point lies on the elastic axis.
        bending_stiffness: (N,) [N m^2] flapwise EI, > 0, of the section normal to the axis.
        torsional_stiffness: (N,) [N m^2] GJ, > 0.
        sweep: [deg] of the elastic axis, the straight line x = y tan(sweep), positive aft,
            |sweep| < 60. Sections stay streamwise.
        jig_twist: (N,) [deg] built-in twist of each section, nose-up > 0.
        camber: (N,) the sections' camber lines (`solver.airfoil`).
        spar: the tube spar EI and GJ come from (`solver.spar`), or None when they were given.
        cl_max: (N,) [-] the sections' maximum lift coefficient, > 0, or None: then
            `ValidityLimits.cl_max` applies. Says when a section stalls (`solver.validity`);
            the equilibrium does not depend on it (an inviscid lattice never stalls).
        control_surfaces: the flaps and ailerons (`solver.controls`); the flaps' deflected
            camber is part of `camber_at`, the ailerons' acts in the antisymmetric problem
            (`solver.roll`).
    """

    y: np.ndarray
    chord: np.ndarray
    elastic_axis: np.ndarray
    bending_stiffness: np.ndarray
    torsional_stiffness: np.ndarray
    sweep: float = 0.0
    jig_twist: np.ndarray | None = None
    camber: tuple[CamberLine, ...] = ()
    spar: TubeSpar | None = None
    cl_max: np.ndarray | None = None
    control_surfaces: tuple[ControlSurface, ...] = ()

    @classmethod
    def create(
        cls,
        y: object,
        chord: object,
        elastic_axis: object,
        bending_stiffness: object = None,
        torsional_stiffness: object = None,
        *,
        sweep: object = 0.0,
        jig_twist: object = 0.0,
        airfoil: object = None,
        spar: SparDesign | None = None,
        cl_max: object = None,
        control_surfaces: object = None,
    ) -> Wing:
        """Validate and normalise inputs; any per-station input may be one number for all, and
        `airfoil` one camber line for all (None, "naca4412", {"x": [...], "camber": [...]}) or
        a list of N. Give the stiffnesses, or a `spar` they follow from, not both. `cl_max`:
        the sections' maximum lift coefficient (one number or N), or None for the default of
        `ValidityLimits`. `control_surfaces`: a list of `solver.ControlSurface` (or mappings of
        their fields)."""
        y_arr = _station_array("y", y, None)
        n = y_arr.shape[0]
        if n < MIN_STATIONS:
            raise InvalidInput("y", f"needs at least {MIN_STATIONS} stations, got {n}")
        if y_arr[0] != 0.0:
            raise InvalidInput("y", "the first station must be the root, y[0] = 0")
        if not np.all(np.diff(y_arr) > 0):
            raise InvalidInput("y", "stations must be strictly increasing")
        if np.min(np.diff(y_arr)) < MIN_SPACING * y_arr[-1]:
            # Panels narrower than this are round-off to the lattice's geometry.
            raise InvalidInput(
                "y", f"stations must be at least {MIN_SPACING:g} of the semispan apart"
            )
        chord_arr = _station_array("chord", chord, n)
        elastic_axis_arr = _station_array("elastic_axis", elastic_axis, n)
        if isinstance(airfoil, list | tuple):
            if len(airfoil) != n:
                raise InvalidInput("airfoil", f"has {len(airfoil)} sections but y has {n} stations")
            camber = tuple(camber_line(a, f"airfoil[{i}]") for i, a in enumerate(airfoil))
        else:
            camber = (camber_line(airfoil),) * n
        tube = None
        if spar is not None:
            if bending_stiffness is not None or torsional_stiffness is not None:
                raise InvalidInput(
                    "spar", "give a spar or bending_stiffness and torsional_stiffness, not both"
                )
            tube = _tube_spar(spar, chord_arr, camber)
            bending_stiffness, torsional_stiffness = (
                tube.bending_stiffness,
                tube.torsional_stiffness,
            )
        for name, given in (
            ("bending_stiffness", bending_stiffness),
            ("torsional_stiffness", torsional_stiffness),
        ):
            if given is None:
                raise InvalidInput(name, "is required unless a spar is given")
        ei = _station_array("bending_stiffness", bending_stiffness, n)
        gj = _station_array("torsional_stiffness", torsional_stiffness, n)
        for name, values in (
            ("chord", chord_arr),
            ("bending_stiffness", ei),
            ("torsional_stiffness", gj),
        ):
            if not np.all(values > 0):
                raise InvalidInput(name, "must be positive at every station")
        if not np.all((elastic_axis_arr >= 0) & (elastic_axis_arr <= 1)):
            # A fraction of chord from the leading edge: the axis must lie on the section.
            raise InvalidInput("elastic_axis", "must lie between 0 and 1 (fraction of chord)")
        if not _is_number(sweep) or not math.isfinite(float(sweep)):  # type: ignore[arg-type]
            raise InvalidInput("sweep", "must be a finite number")
        if not abs(float(sweep)) < MAX_SWEEP:  # type: ignore[arg-type]
            raise InvalidInput(
                "sweep", f"must lie strictly between -{MAX_SWEEP:g} and {MAX_SWEEP:g} deg"
            )
        jig = _station_array("jig_twist", jig_twist, n)
        stall = None if cl_max is None else _station_array("cl_max", cl_max, n)
        if stall is not None and not np.all(stall > 0):
            raise InvalidInput("cl_max", "must be positive at every station")
        surfaces = validate_surfaces(control_surfaces, y_arr)
        return cls(
            y_arr,
            chord_arr,
            elastic_axis_arr,
            ei,
            gj,
            float(sweep) + 0.0,  # type: ignore[arg-type]
            jig,
            camber,
            tube,
            stall,
            surfaces,
        )

    @property
    def n_stations(self) -> int:
        return int(self.y.shape[0])

    @property
    def semispan(self) -> float:
        """[m]"""
        return float(self.y[-1])

    @cached_property
    def planform_area(self) -> float:
        """Jig planform area of both halves [m^2] (trapezoidal panels between stations)."""
        return float(np.sum((self.chord[1:] + self.chord[:-1]) * np.diff(self.y)))

    @property
    def mean_chord(self) -> float:
        """[m] planform area over span."""
        return self.planform_area / (2 * self.semispan)

    @cached_property
    def key(self) -> str:
        """A canonical identity of the wing: equal for equal numbers (-0.0 and 0.0 alike), so
        `elastic_axis=0.4` and thirty 0.4s are one wing. Every cache, the solver's and the
        service's, keys a wing by it."""
        digest = hashlib.blake2b(digest_size=16)
        for array in (*self.arrays(), np.array([self.sweep])):
            # + 0.0 turns -0.0 into 0.0, so equal numbers hash equally.
            digest.update(np.ascontiguousarray(array + 0.0, dtype=np.float64).tobytes())
        for line in self.camber:
            digest.update(line.key)
        if self.spar is not None:
            digest.update(self.spar.key)
        if self.cl_max is not None:  # what is said about the answer, so a part of its identity
            digest.update(b"cl_max")
            digest.update(np.ascontiguousarray(self.cl_max + 0.0, dtype=np.float64).tobytes())
        for surface in self.control_surfaces:
            digest.update(b"control_surface")
            digest.update(surface.key)
        return digest.hexdigest()

    def arrays(self) -> tuple[np.ndarray, ...]:
        """The station arrays in the order of the model's parameter vector: y, chord,
        elastic_axis, EI, GJ, jig_twist."""
        jig = np.zeros(self.n_stations) if self.jig_twist is None else self.jig_twist
        return (
            self.y,
            self.chord,
            self.elastic_axis,
            self.bending_stiffness,
            self.torsional_stiffness,
            jig,
        )

    def camber_at(self, x: np.ndarray) -> np.ndarray:
        """(N, len(x)) [-] camber / chord of each station's section at x / chord, the flaps'
        deflection included (`solver.controls`; refused where x cannot carry a flap)."""
        flaps = symmetric_camber(self.control_surfaces, self.y, x)
        if not self.camber:
            return flaps
        # One airfoil for the whole wing is one line repeated: evaluate each line once.
        lines = {id(line): line for line in self.camber}
        values = {key: line.at(x) for key, line in lines.items()}
        return np.array([values[id(line)] for line in self.camber]) + flaps


def _check_airspeed(condition: FlightCondition | TrimCondition, other: str) -> None:
    """What every flight condition needs: velocity, `other` and density finite numbers, velocity
    and density positive, and a positive, finite dynamic pressure."""
    for name in ("velocity", other, "density"):
        value = getattr(condition, name)
        if not _is_number(value):
            raise InvalidInput(name, "must be a number")
        if not math.isfinite(value):
            raise InvalidInput(name, "must be a finite number")
    if condition.velocity <= 0:
        raise InvalidInput("velocity", "must be positive")
    if condition.density <= 0:
        raise InvalidInput("density", "must be positive")
    q = condition.dynamic_pressure
    if not (math.isfinite(q) and q > 0):
        raise InvalidInput(
            "velocity", f"the dynamic pressure rho V^2 / 2 = {q:g} Pa is not a positive number"
        )


@dataclass(frozen=True)
class FlightCondition:
    """Steady, symmetric flight.

    Attributes:
        velocity: [m/s] airspeed, > 0.
        alpha: [deg] angle of attack of the jig shape, -90 < alpha < 90.
        density: [kg/m^3] air density, > 0.
    The dynamic pressure rho V^2 / 2 must be a positive, finite number.
    """

    velocity: float
    alpha: float
    density: float = ISA_SEA_LEVEL_DENSITY

    def __post_init__(self) -> None:
        _check_airspeed(self, "alpha")
        if not -90.0 < self.alpha < 90.0:
            raise InvalidInput("alpha", "must lie strictly between -90 and 90 degrees")

    @property
    def dynamic_pressure(self) -> float:
        """q = rho V^2 / 2 [Pa]."""
        return 0.5 * self.density * self.velocity * self.velocity  # inf, not OverflowError

    def at_velocity(self, velocity: float) -> FlightCondition:
        return FlightCondition(velocity=velocity, alpha=self.alpha, density=self.density)

    @staticmethod
    def velocity_for(dynamic_pressure: float, density: float) -> float:
        """V = sqrt(2 q / rho) [m/s]."""
        return math.sqrt(2.0 * dynamic_pressure / density)


@dataclass(frozen=True)
class TrimCondition:
    """Steady, symmetric flight at a given lift: the angle of attack is solved for.

    Attributes:
        velocity: [m/s] airspeed, > 0.
        lift: [N] lift of both halves to carry (a weight times a load factor), finite, nonzero.
        density: [kg/m^3] air density, > 0.
    """

    velocity: float
    lift: float
    density: float = ISA_SEA_LEVEL_DENSITY

    def __post_init__(self) -> None:
        _check_airspeed(self, "lift")
        if self.lift == 0:
            raise InvalidInput(
                "lift", "must be nonzero (zero lift is the jig at its zero-lift alpha)"
            )

    @property
    def dynamic_pressure(self) -> float:
        """q = rho V^2 / 2 [Pa]."""
        return 0.5 * self.density * self.velocity * self.velocity  # inf, not OverflowError

    def at_velocity(self, velocity: float) -> TrimCondition:
        return TrimCondition(velocity=velocity, lift=self.lift, density=self.density)


def _limit(default: float, unit: str, description: str) -> Any:
    """A limit of `ValidityLimits`: its default, unit and why (the API's schema reads them)."""
    return field(default=default, metadata={"unit": unit, "description": description})


@dataclass(frozen=True)
class ValidityLimits:
    """Where an answer leaves the model's validity: the limits each finding is judged against
    (`solver.validity`). They change what is said about an answer, never its numbers.

    The model is a linear, small-displacement beam whose torque is taken about the elastic axis
    without its deformation (the study's; `torque_axis = "deformed"` follows its heave, never its
    twist), coupled to an inviscid lattice that never stalls (the design study, 14.7).
    Each default is where that idealisation starts to cost more than a few percent, or where a
    real wing would behave otherwise:

    heave_fraction: [-] largest |heave| / semispan (`large_deflection`). 0.1: geometrically
        nonlinear effects become significant beyond tip deflections of about 10 % of the
        semispan (the usual bound of linear aeroelastic analysis; e.g. Afonso et al., Prog.
        Aerosp. Sci. 89, 2017). The linear beam keeps every station at its jig span position.
    slope: [-] largest |du/ds| (`large_deflection`). 0.1 (5.7 deg): the beam takes sin and tan
        of the bending slope as the slope and its cosine as 1; at 0.1 these are off by 0.2-0.5 %,
        growing with the square of the slope (1.1 % at 0.15).
    twist: [deg] largest |twist about the elastic axis| (`large_twist`). 10: the beam's torsion
        is linear and uncoupled from bending about axes that stay put; a section twisted by
        phi turns its principal axes by phi (sin 10 deg = 0.17 of the chordwise bending
        couples into flap) and cos phi = 1 is off by 1.5 %.
    cl_max: [-] the sections' maximum lift coefficient where the wing gives none (`wing.cl_max`),
        for `section_stall`. 1.2: thin sections (NACA 0006 to 0012) reach cl_max 0.9 to 1.6
        with thickness and Reynolds number (Abbott and von Doenhoff, Theory of Wing Sections);
        1.2 is a middle value at the Reynolds numbers of small wings (1e5 to 1e6).
    divergence_margin: [-] the stability margin q / lambda beyond which the answer is reported
        `near_divergence`. 0.5: with one torsion mode the lift goes as 1 / (1 - q / q_div), so a
        relative error in the torsional stiffness, the lift slope or q comes out amplified by
        m / (1 - m) in the lift: more than one for one past m = 0.5.
    """

    heave_fraction: float = _limit(
        0.1,
        "-",
        "largest |heave| over the semispan (large_deflection); default 0.1: geometrically "
        "nonlinear effects become significant beyond tip deflections of about 10 % of the "
        "semispan, the usual bound of linear aeroelastic analysis",
    )
    slope: float = _limit(
        0.1,
        "-",
        "largest |bending slope du/ds| (large_deflection); default 0.1 (5.7 deg): the linear "
        "beam takes sin and tan of the slope as the slope and its cosine as 1, off by 0.2 to "
        "0.5 % at 0.1 and growing with its square",
    )
    twist: float = _limit(
        10.0,
        "deg",
        "largest |twist about the elastic axis| (large_twist); default 10: the beam's torsion is "
        "linear and uncoupled from bending about axes that stay put, while a twisted section "
        "turns its principal axes (sin 10 deg = 0.17) and cos 10 deg = 1 is off by 1.5 %",
    )
    cl_max: float = _limit(
        1.2,
        "-",
        "the sections' maximum lift coefficient where the wing gives none (wing.cl_max), for "
        "section_stall; default 1.2: thin sections (NACA 0006 to 0012) reach 0.9 to 1.6 with "
        "thickness and Reynolds number (Abbott and von Doenhoff), 1.2 is a middle value for "
        "small wings (Reynolds numbers 1e5 to 1e6)",
    )
    divergence_margin: float = _limit(
        0.5,
        "-",
        "stability margin q / lambda beyond which the answer is near_divergence; default 0.5: "
        "with one torsion mode the lift goes as 1 / (1 - m), so a relative error in the "
        "torsional stiffness, lift slope or q is amplified by m / (1 - m) in the lift, more than "
        "one for one past m = 0.5",
    )

    def __post_init__(self) -> None:
        for name in ("heave_fraction", "slope", "twist", "cl_max"):
            value = getattr(self, name)
            if not (_is_number(value) and math.isfinite(value) and value > 0):
                raise InvalidInput(f"validity.{name}", "must be a positive, finite number")
        margin = self.divergence_margin
        if not (_is_number(margin) and 0 < margin <= 1):
            raise InvalidInput("validity.divergence_margin", "must be a number in (0, 1]")


@dataclass(frozen=True)
class SolverOptions:
    """How to model and how to solve.

    tolerance: max-norm of the residual at convergence (units in `solver.residual`).
    max_iterations: Newton iterations of one attempt before it is given up.
    find_fold: also locate the fold of the branch from the jig shape (`Equilibrium.fold`).
    chordwise_panels: k, panels per strip (1 to 8, cosine spaced as AeroSandbox's).
    torque_axis: "undeformed" (the study's: torque about the undeformed elastic axis) or
        "deformed" (arms from the heaved elastic-axis point).
    safety_factor: [-] 1 to 10, what a spar's failure margin asks of it (`Totals`).
    validity: the limits the answer's validity is judged against (`ValidityLimits`); they
        change what is said about the answer, never its numbers.
    """

    tolerance: float = 1e-10
    max_iterations: int = 30
    find_fold: bool = False
    chordwise_panels: int = 1
    torque_axis: Literal["undeformed", "deformed"] = "undeformed"
    safety_factor: float = 1.0
    validity: ValidityLimits = field(default_factory=ValidityLimits)

    def __post_init__(self) -> None:
        if not (_is_number(self.tolerance) and 0 < self.tolerance < 1):
            raise InvalidInput("tolerance", "must be a number between 0 and 1")
        if not (isinstance(self.max_iterations, int) and self.max_iterations >= 0):
            raise InvalidInput("max_iterations", "must be a non-negative integer")
        k = self.chordwise_panels
        if not (isinstance(k, int) and 1 <= k <= MAX_CHORDWISE_PANELS):
            raise InvalidInput(
                "chordwise_panels", f"must be an integer from 1 to {MAX_CHORDWISE_PANELS}"
            )
        if self.torque_axis not in ("undeformed", "deformed"):
            raise InvalidInput("torque_axis", "must be 'undeformed' or 'deformed'")
        if not (_is_number(self.safety_factor) and 1 <= self.safety_factor <= 10):
            raise InvalidInput("safety_factor", "must be a number from 1 to 10")
        if not isinstance(self.validity, ValidityLimits):
            raise InvalidInput("validity", "must be a solver.ValidityLimits")
