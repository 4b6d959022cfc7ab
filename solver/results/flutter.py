"""What the vibration and flutter analyses return, each field with its unit (`quantity`), as
`solver.results` does for the static answers: the web service derives its response models from
these dataclasses.

Arrays over stations are (N,), root to tip. A flutter analysis tracks one root s = sigma + i
omega of the linearised equations of motion per mode (`solver.flutter`); its damping ratio is
-sigma / |s|: positive decays, negative grows. Flutter is the first airspeed at which an
oscillating root's damping ratio crosses to negative; divergence the one at which a real root
crosses zero.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

import numpy as np

from solver.results.quantities import internal, quantity

__all__ = [
    "DivergenceOnset",
    "FlutterInfo",
    "FlutterOnset",
    "FlutterPoint",
    "FlutterResult",
    "ModeShape",
    "NaturalModes",
    "NoFlutter",
]


@dataclass(frozen=True, eq=False)
class ModeShape:
    """One natural mode of the cantilever in vacuum."""

    frequency: float = quantity("rad/s", "natural frequency in vacuum")
    heave: np.ndarray = quantity(
        "m",
        "heave of the elastic axis at the stations, scaled so that the largest vertical "
        "displacement of a leading or trailing edge is 1 m (upward)",
    )
    twist: np.ndarray = quantity(
        "deg", "elastic twist the flow sees (streamwise, nose-up > 0), at the same scale"
    )
    axis_twist: np.ndarray = quantity(
        "deg", "twist about the elastic axis at the same scale (equal to twist when unswept)"
    )
    bending_share: float = quantity(
        "-",
        "share of the mode's kinetic energy in the heave of the elastic axis, the rest in the "
        "twist about it (1: pure bending, 0: pure torsion; the centre of gravity's offset "
        "couples them); with in-plane bending, of the total, lag_share the in-plane part",
    )
    lag: np.ndarray | None = quantity(
        "m",
        "in-plane displacement of the elastic axis across it (aft at zero sweep), at the same "
        "scale; null without an in-plane bending stiffness",
        default=None,
    )
    lag_share: float | None = quantity(
        "-",
        "share of the mode's kinetic energy in the in-plane (lag) motion; null without an "
        "in-plane bending stiffness",
        default=None,
    )


@dataclass(frozen=True, eq=False)
class NaturalModes:
    """The natural modes of the wing clamped at the root, in vacuum, lowest frequency first."""

    y: np.ndarray = quantity("m", "station positions")
    modes: list[ModeShape] = quantity("", "the modes, lowest frequency first")


@dataclass(frozen=True, eq=False)
class FlutterPoint:
    """The tracked roots at one airspeed, one per mode of `FlutterResult.modes`."""

    velocity: float = quantity("m/s", "airspeed")
    dynamic_pressure: float = quantity("Pa", "dynamic pressure")
    status: Literal["solved", "no_equilibrium"] = quantity(
        "",
        "solved: the roots are given; no_equilibrium: the static equilibrium to linearise "
        "about does not exist at this airspeed (beyond its fold; see `reason`)",
    )
    frequency: np.ndarray | None = quantity(
        "rad/s", "each mode's frequency, the imaginary part of its root (0 for a real root)"
    )
    damping: np.ndarray | None = quantity(
        "-",
        "each mode's damping ratio -Re(s) / |s|: positive decays, negative grows (an "
        "oscillating root: flutter; a real root: divergence)",
    )
    reduced_frequency: np.ndarray | None = quantity(
        "-", "each mode's frequency times the reference semichord over the airspeed"
    )
    divergence_rate: float | None = quantity(
        "1/s",
        "the largest real root of the equations at zero frequency (a non-oscillating motion, "
        "the circulation without lag): positive where the wing diverges statically, zero at "
        "divergence; null when they have no real root (every motion oscillates)",
        default=None,
    )
    reason: str | None = quantity("", "why there are no roots, else null", default=None)


@dataclass(frozen=True)
class FlutterOnset:
    """Where an oscillating root first crosses to negative damping (located between the two
    airspeeds of the sweep that bracket it)."""

    velocity: float = quantity("m/s", "flutter speed")
    dynamic_pressure: float = quantity("Pa", "dynamic pressure at the flutter speed")
    frequency: float = quantity("rad/s", "flutter frequency")
    reduced_frequency: float = quantity("-", "frequency times the reference semichord over V")
    mode: int = quantity("-", "index of the mode that flutters, into `modes`")


@dataclass(frozen=True)
class DivergenceOnset:
    """Where the wing loses static stability: a real root crosses zero (zero frequency)."""

    velocity: float = quantity("m/s", "divergence speed")
    dynamic_pressure: float = quantity("Pa", "dynamic pressure at divergence")
    within_range: bool = quantity("", "whether it lies within the airspeeds analysed")
    kind: Literal["linear", "fold", "trimmed_stability_limit"] = quantity(
        "",
        "linear: the unloaded jig's divergence eigenvalue (about the jig, the same number as "
        "the static linear divergence under the same aerodynamics); fold: where the "
        "equilibrium branch at the given alpha ends; trimmed_stability_limit: where the wing "
        "trimmed to the given lift loses static stability",
    )


@dataclass(frozen=True)
class NoFlutter:
    """No oscillating root crossed to negative damping over the airspeeds analysed."""

    searched_from: float = quantity("m/s", "lowest airspeed analysed")
    searched_to: float = quantity("m/s", "highest airspeed analysed with roots")
    least_damping: float = quantity(
        "-", "the smallest damping ratio of an oscillating root over the range"
    )
    least_damped_velocity: float = quantity("m/s", "where it occurs")
    least_damped_mode: int = quantity("-", "and in which mode (index into `modes`)")


@dataclass(frozen=True)
class FlutterInfo:
    """How the answer was obtained."""

    iterations: int = quantity("-", "p-k iterations over every mode and airspeed")
    seconds: float = quantity("s", "solver time")


@dataclass(frozen=True, eq=False)
class FlutterResult:
    """Damping and frequency of every mode against airspeed (the V-g and V-f diagrams), the
    flutter speed and frequency, the divergence speed, and the modes they belong to."""

    status: Literal["flutter", "no_flutter_in_range", "no_equilibrium"] = quantity(
        "",
        "flutter: `flutter` holds the onset; no_flutter_in_range: `no_flutter` says what was "
        "searched; no_equilibrium: no requested airspeed has a static equilibrium to linearise "
        "about (each point's `reason` says why)",
    )
    flutter: FlutterOnset | None = quantity(
        "",
        "the first flutter onset (an oscillating root's growth at a reduced frequency k up "
        "to 5; past it the mesh's highest modes, which no strip's or panel's loads describe, "
        "stay in the points), or null",
    )
    no_flutter: NoFlutter | None = quantity(
        "", "what was searched when no root fluttered (null otherwise)"
    )
    divergence: DivergenceOnset | None = quantity(
        "", "where the wing diverges (null: it cannot, or the loaded branch has no fold)"
    )
    modes: list[ModeShape] = quantity(
        "", "the natural modes tracked (lowest frequency first), one root per airspeed each"
    )
    static_correction: bool = quantity(
        "",
        "the part of the unloaded wing's divergence shape outside the modes is in the "
        "solution too, condensed statically: the zero-frequency equations are then the static "
        "model's exactly (false: the wing cannot diverge, or the modes hold that shape)",
    )
    points: list[FlutterPoint] = quantity("", "one per requested airspeed, in request order")
    y: np.ndarray = quantity("m", "station positions of the mode shapes")
    about: Literal["jig", "alpha", "trim"] = quantity(
        "",
        "what was linearised about: jig (the unloaded wing at rest), alpha (the static "
        "equilibrium at each airspeed at the given angle of attack) or trim (at the given lift)",
    )
    aerodynamics: Literal["lattice", "strip"] = quantity(
        "",
        "the steady aerodynamics the circulatory loads come from: strip, or the lattice (the "
        "statics' own, for options.aerodynamics lattice and unsteady_lattice alike)",
    )
    aerodynamic_model: Literal["strip_theory", "quasi_3d_lattice", "unsteady_lattice"] = quantity(
        "",
        "the unsteady aerodynamics that gave the answer (options.aerodynamics): strip_theory "
        "(Theodorsen's strip theory: each strip a two-dimensional airfoil with its wake's lag "
        "C(k)), quasi_3d_lattice (the lattice's steady 3D circulation, lagged strip by strip by "
        "Theodorsen's C(k): no 3D unsteady wake) or unsteady_lattice (the unsteady vortex "
        "lattice: the same panels with their 3D wake shed and convected, the doublet lattice's "
        "incompressible counterpart)",
    )
    unsteady: Literal["theodorsen", "quasi_steady"] = quantity(
        "", "the circulation's lag: Theodorsen's C(k), or none (C = 1)"
    )
    reference_semichord: float = quantity("m", "b of the reduced frequencies: half the mean chord")
    solver: FlutterInfo = quantity("", "how the answer was obtained")
    roots: np.ndarray | None = internal(default=None)  # (points, modes) complex s [1/s]
