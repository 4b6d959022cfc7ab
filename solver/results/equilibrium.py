"""One flight condition's answer: the deformation and internal loads at the stations, the strips'
loads, the totals, the static-stability verdict, how the solver got there, and the fold when
asked for.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

import numpy as np

from solver.inputs.flight import OperatingPoint
from solver.inputs.options import SolverOptions
from solver.inputs.wing import Wing
from solver.numerics.evaluation import Evaluation
from solver.results.findings import Finding
from solver.results.quantities import internal, quantity

__all__ = ["Equilibrium", "Fold", "Panels", "SolveInfo", "Stability", "Stations", "Totals"]


@dataclass(frozen=True, eq=False)
class Stations:
    """Deformation and internal loads at the N structural stations, root to tip."""

    y: np.ndarray = quantity("m", "station positions")
    heave: np.ndarray = quantity("m", "vertical displacement, positive up")
    slope: np.ndarray = quantity("-", "heave slope du/ds along the elastic axis")
    twist: np.ndarray = quantity(
        "deg",
        "elastic twist the flow sees (streamwise, nose-up > 0): axis_twist cos(sweep) - "
        "degrees(slope) sin(sweep); the jig twist comes on top of it",
    )
    axis_twist: np.ndarray = quantity(
        "deg", "twist about the elastic axis, nose-up > 0 (equal to twist when unswept)"
    )
    shear: np.ndarray = quantity(
        "N",
        "vertical shear force carried at the station: the lift's, less the wing's own mass's "
        "under the load factor (inertia relief, with wing.mass)",
    )
    bending_moment: np.ndarray = quantity(
        "N m", "flapwise bending moment (the lift's, less the wing's own mass's)"
    )
    torque: np.ndarray = quantity(
        "N m", "torque about the elastic axis, nose up (the lift's, with the wing's own mass's)"
    )
    bending_stiffness: np.ndarray | None = quantity(
        "N m^2", "EI: as given, or from the spar", default=None
    )
    torsional_stiffness: np.ndarray | None = quantity(
        "N m^2", "GJ: as given, or from the spar", default=None
    )
    bending_stress: np.ndarray | None = quantity(
        "Pa",
        "spar only (else null): bending stress at the outer fibre, M (D/2) / I; positive where "
        "the tip bends up (lower fibre in tension, upper in compression by as much)",
        default=None,
    )
    shear_stress: np.ndarray | None = quantity(
        "Pa",
        "spar only (else null): torsional shear stress at the outer fibre, T (D/2) / J",
        default=None,
    )
    von_mises_stress: np.ndarray | None = quantity(
        "Pa",
        "spar only (else null): von Mises stress at the outer fibre, "
        "sqrt(bending_stress^2 + 3 shear_stress^2); with lag bending the tube's share of "
        "the in-plane moment (EI_spar / EI_lag of lag_bending_moment) bends it too, and its "
        "stress adds to bending_stress as a vector at the round tube's outer fibre",
        default=None,
    )
    inertial_shear: np.ndarray | None = quantity(
        "N",
        "the part of shear the wing's own mass carries under the load factor (negative: its "
        "weight relieves the lift's); null without an inertial load",
        default=None,
    )
    inertial_bending_moment: np.ndarray | None = quantity(
        "N m", "the part of bending_moment the wing's own mass carries; null without", default=None
    )
    inertial_torque: np.ndarray | None = quantity(
        "N m",
        "the part of torque the wing's own mass carries (nose up where its centre of gravity "
        "lies aft of the elastic axis); null without",
        default=None,
    )
    axis_x: np.ndarray | None = quantity(
        "m",
        "the deformed elastic axis's points in geometry axes (x aft, y right, z up; the wing's "
        "plane turned by its dihedral): x. Under options.structure 'geometrically_exact' the "
        "bent reference line (a bent wing's stations move inboard); under 'linear' the jig "
        "axis heaved normal to the plane. Static answers (null in a roll answer)",
        default=None,
    )
    axis_y: np.ndarray | None = quantity("m", "the deformed elastic axis's points: y", default=None)
    axis_z: np.ndarray | None = quantity("m", "the deformed elastic axis's points: z", default=None)
    bending_rotation: np.ndarray | None = quantity(
        "deg",
        "the section's bending rotation about the axis across the elastic axis in the wing's "
        "plane, tip up > 0: the exact beam's rotation beta (slope = sin(beta)), the linear "
        "beam's small-angle degrees(slope). Static answers (null in a roll answer)",
        default=None,
    )
    lag: np.ndarray | None = quantity(
        "m",
        "with lag bending (wing.in_plane_bending_stiffness, the exact beam's): the elastic "
        "axis's displacement in the wing's plane normal to the jig axis, along e_c = e_s x n "
        "(aft at zero sweep; a tip swept back by drag has lag > 0); null without",
        default=None,
    )
    lag_rotation: np.ndarray | None = quantity(
        "deg",
        "with lag bending: the section's lag rotation psi about the wing's normal, positive "
        "turning the axis forward (a tip swept back by drag has lag_rotation < 0); null without",
        default=None,
    )
    lag_bending_moment: np.ndarray | None = quantity(
        "N m",
        "with lag bending: the moment about the bent axis's lag axis n'' (the wing's normal "
        "turned by the flap rotation) of every load outboard, about the deformed station; "
        "positive turns the axis forward. bending_moment is then the moment about the flap "
        "axis e_c' (e_c turned by the lag rotation), torque about the deformed tangent; null "
        "without",
        default=None,
    )


@dataclass(frozen=True, eq=False)
class Panels:
    """Aerodynamic loads on the N - 1 right-half strips between stations (each the sum of its
    chordwise panels), root to tip."""

    y: np.ndarray = quantity(
        "m", "spanwise load location (mean of the strip's deformed force points)"
    )
    lift: np.ndarray = quantity("N", "vertical force on the strip")
    lift_per_span: np.ndarray = quantity("N/m", "vertical force per jig strip width")
    torque: np.ndarray = quantity(
        "N m",
        "torque about the elastic axis: the undeformed one, or the heaved one with "
        "options.torque_axis = 'deformed'",
    )
    rigid_lift_per_span: np.ndarray = quantity(
        "N/m",
        "the rigid jig's vertical force per strip width at the same condition (trimmed: the "
        "rigid jig trimmed to the same lift)",
    )


@dataclass(frozen=True)
class Totals:
    """Whole-wing results (both halves)."""

    lift: float = quantity("N", "lift, perpendicular to the freestream")
    induced_drag: float = quantity("N", "induced drag, along the freestream (near field)")
    CL: float = quantity("-", "lift coefficient on the jig planform area")
    CDi: float = quantity("-", "induced-drag coefficient on the jig planform area")
    CL_deformed_area: float = quantity(
        "-",
        "lift coefficient on the deformed wing's planform area, the convention of AeroSandbox "
        "and of the design study",
    )
    reference_area: float = quantity("m^2", "jig planform area, both halves")
    deformed_area: float = quantity("m^2", "deformed planform area, both halves")
    rigid_lift: float = quantity(
        "N",
        "lift of the rigid jig shape at the same condition: at the same alpha, or trimmed to "
        "the same lift (then equal to lift)",
    )
    lift_amplification: float | None = quantity(
        "-",
        "lift / rigid_lift; null when the rigid wing carries no lift (alpha = 0 on an "
        "uncambered, untwisted wing, or within 1e-10 rad of it); trimmed: 1, see "
        "lift_effectiveness",
    )
    tip_heave: float = quantity("m", "heave at the tip")
    tip_twist: float = quantity("deg", "elastic twist the flow sees at the tip (streamwise)")
    root_bending_moment: float = quantity("N m", "bending moment at the root")
    root_torque: float = quantity("N m", "torque at the root")
    pitching_moment: float = quantity(
        "N m",
        "pitching moment (about y, nose-up > 0) of both halves about the root's elastic axis point",
    )
    alpha: float = quantity(
        "deg", "angle of attack of the jig: as asked, or the trimmed one", default=0.0
    )
    rigid_root_bending_moment: float = quantity(
        "N m",
        "root bending moment of the rigid jig at the same condition (trimmed: at the same lift)",
        default=0.0,
    )
    rigid_alpha: float | None = quantity(
        "deg", "trimmed flight: the rigid jig's angle of attack for the same lift", default=None
    )
    max_von_mises_stress: float | None = quantity(
        "Pa", "spar only (else null): the largest von Mises stress in the spar", default=None
    )
    max_von_mises_y: float | None = quantity(
        "m", "spar only (else null): the station where it acts", default=None
    )
    failure_margin: float | None = quantity(
        "-",
        "spar only (else null): yield_stress / (safety_factor * max_von_mises_stress) - 1; "
        "negative: the spar yields",
        default=None,
    )
    spar_mass: float | None = quantity(
        "kg", "spar only (else null): mass of the spar, both halves", default=None
    )
    root_bending_stress: float | None = quantity(
        "Pa", "spar only (else null): bending stress at the root's outer fibre", default=None
    )
    rigid_root_bending_stress: float | None = quantity(
        "Pa",
        "spar only (else null): the same for the rigid jig at the same condition (trimmed: at "
        "the same lift, where the difference is what flexibility costs the spar)",
        default=None,
    )
    lift_effectiveness: float | None = quantity(
        "-",
        "trimmed flight: the flexible wing's lift-curve slope over the rigid wing's at this "
        "angle of attack (below 1: flexibility costs lift per degree)",
        default=None,
    )
    load_factor: float | None = quantity(
        "-",
        "the load factor n the wing's own mass carries (its weight n g against the lift: "
        "inertia relief); null without wing.mass, or at a given alpha without a load factor",
        default=None,
    )
    wing_mass: float | None = quantity(
        "kg",
        "the wing's own mass, both halves, spar and concentrated masses included; null "
        "without wing.mass",
        default=None,
    )


@dataclass(frozen=True)
class Stability:
    """Static aeroelastic stability of this equilibrium, and the wing's linear divergence."""

    stable: bool = quantity("", "the equilibrium is statically stable: local pressure > q")
    margin: float = quantity(
        "-",
        "q / local divergence pressure at this equilibrium; 1 at instability, 0 when the "
        "deformed wing cannot diverge",
    )
    local_divergence_pressure: float | None = quantity(
        "Pa",
        "divergence dynamic pressure linearised at this equilibrium (smallest positive real "
        "lambda with J0 + lambda J1 singular), or null when none is meaningfully positive; "
        "computed on the Jacobians of Newton's last iterate, within ~1e-5 (relative, typical; "
        "<= 2e-4 measured) of the linearisation at the converged state itself",
    )
    divergence_dynamic_pressure: float | None = quantity(
        "Pa", "classical linear divergence at the unloaded jig (alpha = 0), or null if none"
    )
    divergence_velocity: float | None = quantity(
        "m/s", "airspeed of that divergence at this density, or null"
    )
    branch: Literal["jig", "other"] = quantity(
        "",
        "jig: the equilibrium on the branch from the jig shape (every answer without an "
        "initial guess); other: a different equilibrium reached from the caller's initial guess",
    )


@dataclass(frozen=True)
class SolveInfo:
    """How the answer was obtained."""

    iterations: int = quantity("-", "Newton iterations, over every step of the path")
    residual_norm: float = quantity("mixed units", "max-norm of the final residual")
    warm_start: bool = quantity(
        "", "the path started from a supplied state (a hint or an initial guess), not the jig"
    )
    seconds: float = quantity("s", "solver time")


@dataclass(frozen=True)
class Fold:
    """The fold of the equilibrium branch from the jig shape: past it there is no equilibrium."""

    velocity: float | None = quantity("m/s", "airspeed at the fold, or null")
    dynamic_pressure: float | None = quantity("Pa", "dynamic pressure at the fold, or null")
    tip_twist: float | None = quantity("deg", "tip twist at the fold")
    lift: float | None = quantity("N", "lift at the fold")
    searched_to_velocity: float = quantity("m/s", "how far the branch was followed")
    reason: str | None = quantity("", "why the values are null, else null", default=None)
    tip_heave: float | None = quantity("m", "tip heave at the fold", default=None)
    evaluations: int = quantity(
        "-",
        "model evaluations the continuation spent to this speed (trimmed_stability_limit: "
        "Newton iterations of the trimmed solves that located it)",
        default=0,
    )
    kind: Literal["fold", "trimmed_stability_limit"] = quantity(
        "",
        "fold: the branch from the jig turns back here, no equilibrium on it beyond; "
        "trimmed_stability_limit: at a fixed lift, where the trimmed equilibrium loses static "
        "stability at fixed alpha (it exists beyond, unstable)",
        default="fold",
    )


@dataclass(frozen=True, eq=False)
class Equilibrium:
    """A converged, statically judged equilibrium of one wing at one flight condition."""

    wing: Wing = internal()
    flight: OperatingPoint = internal()
    options: SolverOptions = internal()  # how it was modelled and solved
    state: np.ndarray = internal()  # (n,) unknowns, see solver.layout
    evaluation: Evaluation = internal()  # r0, r1, J0, J1 at `state`
    stations: Stations = quantity("", "deformation and internal loads at the stations")
    panels: Panels = quantity("", "aerodynamic loads on the panels")
    totals: Totals = quantity("", "whole-wing results")
    stability: Stability = quantity("", "static stability and divergence")
    solver: SolveInfo = quantity("", "how the answer was obtained")
    fold: Fold | None = quantity(
        "", "the fold of the branch from the jig, when options.find_fold asked", default=None
    )
    validity: list[Finding] = quantity(
        "",
        "where this answer leaves the model's validity (large deflections, large twist, "
        "sections past stall, near divergence), judged against options.validity; an empty list "
        "when nothing is found. Never changes a number of the answer",
        default_factory=list,
    )

    # Shorthands for Python users; the data lives in the groups above.
    @property
    def dynamic_pressure(self) -> float:
        return self.flight.dynamic_pressure

    @property
    def lift(self) -> float:
        return self.totals.lift

    @property
    def tip_twist(self) -> float:
        return self.totals.tip_twist

    @property
    def tip_heave(self) -> float:
        return self.totals.tip_heave
