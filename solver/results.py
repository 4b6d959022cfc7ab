"""What the solver returns: every result type, defined once.

The web service's response models are derived from these dataclasses (`app.schemas`), so a field
added here appears in the API with its unit and description, and none can be dropped silently.
Each field's metadata carries its unit and a one-line description (`quantity`); fields marked
``internal`` (solver state for warm starts and continuation) stay in Python.

Arrays over stations are (N,), over right-half panels (N - 1,), root to tip. Totals are for
both halves of the wing.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any, Literal

import numpy as np

from solver.errors import ConvergenceError, NoEquilibrium, SolverError
from solver.evaluation import Evaluation
from solver.inputs import OperatingPoint, SolverOptions, Wing

__all__ = [
    "Progress",
    "ControlEffectiveness",
    "ControlSweep",
    "ControlSweepPoint",
    "DivergenceSummary",
    "Equilibrium",
    "FINDING_CODES",
    "Finding",
    "FindingCode",
    "FindingMeasure",
    "FindingOnset",
    "FindingWhere",
    "FitDivergence",
    "Fold",
    "HingeMoment",
    "LinearDivergence",
    "Panels",
    "PointFailure",
    "Reversal",
    "ReversalSummary",
    "RollResponse",
    "RollStability",
    "SolveInfo",
    "Stability",
    "Stations",
    "AirspeedSweepInfo",
    "AirspeedPoint",
    "AirspeedSweep",
    "Totals",
    "quantity",
]


# What long work reports as it goes: progress(done, total), e.g. airspeeds answered of a sweep's.
Progress = Callable[[int, int], None]


def quantity(unit: str, description: str, **kwargs: Any) -> Any:
    """A dataclass field documented with its unit ("-" for dimensionless, "" for none)."""
    return field(metadata={"unit": unit, "description": description}, **kwargs)


def internal(**kwargs: Any) -> Any:
    """A field kept in Python only: never sent by the web service."""
    return field(metadata={"internal": True}, **kwargs)


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
    shear: np.ndarray = quantity("N", "vertical shear force carried at the station")
    bending_moment: np.ndarray = quantity("N m", "flapwise bending moment")
    torque: np.ndarray = quantity("N m", "torque about the elastic axis")
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
        "sqrt(bending_stress^2 + 3 shear_stress^2)",
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


# What each finding of `Equilibrium.validity` means (`solver.validity` finds them).
FindingCode = Literal[
    "large_deflection", "large_twist", "section_stall", "near_divergence", "control_deflection"
]
FINDING_CODES: dict[FindingCode, str] = {
    "large_deflection": (
        "the heave (over the semispan) or the bending slope exceeds its limit: the beam is "
        "linear, for small displacements, and keeps each station at its jig span position"
    ),
    "large_twist": (
        "the twist about the elastic axis exceeds its limit: the beam's torsion is linear, with "
        "small-angle kinematics and the torque about an elastic axis that does not twist"
    ),
    "section_stall": (
        "a strip's section lift coefficient exceeds its airfoil's maximum (wing.cl_max, or "
        "options.validity.cl_max): the inviscid lattice never stalls, a real wing does there, "
        "and carries less lift and less nose-up torque than the answer says"
    ),
    "near_divergence": (
        "the stability margin q / lambda exceeds its limit: close to divergence the answer is "
        "sensitive to every input; `sensitivity` says how much, as d(lift)/d(q) at fixed alpha "
        "over the rigid wing's"
    ),
    "control_deflection": (
        "a control surface's |deflection| exceeds its limit: the lattice's flap lift grows "
        "linearly with the deflection, a real plain flap's falls behind as the flow starts to "
        "separate from it, so the answer overstates the surface's lift, its hinge moment and "
        "the twist they cause (a section pushed past its maximum lift coefficient by a "
        "deflection is section_stall, on either wing)"
    ),
}
FindingMeasure = Literal["heave_fraction", "slope", "twist", "section_cl", "margin", "deflection"]
FindingWhere = Literal["stations", "panels", "wing", "control_surfaces"]
_CODES = "; ".join(f"{code}: {meaning}" for code, meaning in FINDING_CODES.items())


@dataclass(frozen=True, eq=False)
class Finding:
    """Where this answer leaves the model's validity: one finding, its numbers against its limit.

    The answer's numbers are the model's either way; a finding says what they are worth."""

    code: FindingCode = quantity("", f"what was found. {_CODES}")
    message: str = quantity("", "the finding in a sentence, for a person")
    measure: FindingMeasure = quantity(
        "",
        "the quantity judged: heave_fraction (|heave| / semispan at a station), slope "
        "(|du/ds| at a station), twist (|twist about the elastic axis| at a station, deg), "
        "section_cl (a strip's lift per unit span over q and its mean chord), margin (q / lambda "
        "of the whole wing), deflection (|a control surface's deflection|, deg)",
    )
    where: FindingWhere = quantity(
        "",
        "what `indices` count: stations (the arrays of `stations`), panels (the strips of "
        "`panels`), control_surfaces (wing.control_surfaces), or the wing as a whole (no "
        "indices)",
    )
    indices: list[int] = quantity(
        "-", "the stations or strips concerned, root to tip (0 is the root station or strip)"
    )
    y: list[float] = quantity("m", "their spanwise positions (stations.y or panels.y)")
    value: float = quantity(
        "", "the worst value of the measure (the one furthest past its limit), in `unit`"
    )
    limit: float = quantity("", "the limit it is judged against there, in `unit`")
    unit: str = quantity("", "the unit of value and limit ('-' for none)")
    sensitivity: float | None = quantity(
        "-",
        "for near_divergence (else null): d(lift)/d(q) at fixed alpha over the rigid wing's "
        "L_rigid / q, from the equilibrium's tangent dx/dq = -J^-1 r1 (1 for a rigid wing; "
        "about 1 / (1 - margin)^2 for one torsion mode); null where the rigid wing carries no "
        "lift",
        default=None,
    )
    half: Literal["right", "left"] | None = quantity(
        "",
        "which wing the indices are on, in an answer that has both (a roll answer); null "
        "where both wings are alike",
        default=None,
    )


@dataclass(frozen=True, eq=False)
class FindingOnset:
    """From which airspeed on a sweep's equilibria carry a finding."""

    code: FindingCode = quantity("", "what was found (see Finding.code)")
    velocity: float = quantity("m/s", "the lowest airspeed of the sweep whose equilibrium has it")
    velocities: list[float] = quantity(
        "m/s", "every airspeed of the sweep whose equilibrium has it, ascending"
    )
    message: str = quantity("", "the onset in a sentence, for a person")


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


@dataclass(frozen=True)
class LinearDivergence:
    """Classical linear divergence at the unloaded jig (alpha = 0)."""

    dynamic_pressure: float | None = quantity("Pa", "divergence dynamic pressure, or null")
    velocity: float | None = quantity("m/s", "at the sweep's density, or null")
    reason: str | None = quantity("", "why the values are null, else null", default=None)


@dataclass(frozen=True)
class FitDivergence:
    """The design study's estimate: 1/A = intercept + slope q fitted over stable sweep points."""

    slope: float | None = quantity("1/Pa", "slope of 1/A against q")
    intercept: float | None = quantity("-", "intercept (single-mode theory: 1)")
    dynamic_pressure: float | None = quantity("Pa", "where 1/A reaches 0")
    velocity: float | None = quantity("m/s", "at the sweep's density")
    reason: str | None = quantity("", "why the values are null, else null", default=None)
    amplification: Literal["CL", "lift", "lift_effectiveness"] = quantity(
        "",
        "what A is: 'CL' (the study's: CL on the deformed area over the rigid CL on the jig "
        "area), 'lift' (L / L_rigid) or, trimmed, 'lift_effectiveness' (the flexible wing's "
        "lift-curve slope over the rigid wing's)",
        default="CL",
    )
    points_used: int = quantity("-", "stable equilibria in the fit", default=0)


@dataclass(frozen=True)
class DivergenceSummary:
    """Three torsional-divergence estimates that check each other."""

    linear: LinearDivergence = quantity("", "eigenvalue at the unloaded jig")
    fit: FitDivergence = quantity("", "the study's 1/A fit over the sweep")
    fold: Fold = quantity("", "where the branch from the jig ends")

    @property
    def limit_velocity(self) -> float | None:
        """[m/s] the speed users should see first: the fold, where equilibria end."""
        return self.fold.velocity


@dataclass(frozen=True)
class PointFailure:
    """Why a sweep point has no equilibrium."""

    reason: str = quantity("", "what the solver reported")
    fold_velocity: float | None = quantity("m/s", "where the equilibrium branch ends, when known")


@dataclass(frozen=True, eq=False)
class AirspeedPoint:
    """One requested airspeed: an equilibrium, or the typed reason there is none."""

    error: Exception | None = internal()  # the SolverError, for Python callers
    velocity: float = quantity("m/s", "requested airspeed")
    status: Literal["equilibrium", "no_equilibrium", "not_converged"] = quantity(
        "",
        "equilibrium: `equilibrium` holds the result; no_equilibrium: none on the branch from "
        "the jig (beyond its fold, or unstable there); not_converged: the solver failed. "
        "Both failures fill `no_equilibrium`",
    )
    equilibrium: Equilibrium | None = quantity("", "the equilibrium, as /solve returns it")
    no_equilibrium: PointFailure | None = quantity("", "why there is none")

    @classmethod
    def failed(cls, velocity: float, error: SolverError) -> AirspeedPoint:
        """The point at `velocity` [m/s] where the solver answered with `error`."""
        fold_velocity = error.fold_velocity if isinstance(error, NoEquilibrium) else None
        status: Literal["no_equilibrium", "not_converged"] = (
            "not_converged" if isinstance(error, ConvergenceError) else "no_equilibrium"
        )
        return cls(error, velocity, status, None, PointFailure(str(error), fold_velocity))


@dataclass(frozen=True)
class AirspeedSweepInfo:
    """How the sweep was obtained."""

    seconds: float = quantity("s", "solver time")


@dataclass(frozen=True, eq=False)
class AirspeedSweep:
    """One point per requested airspeed, in request order, and the divergence estimates."""

    points: list[AirspeedPoint] = quantity("", "one per requested airspeed, in request order")
    divergence: DivergenceSummary = quantity("", "three torsional-divergence estimates")
    solver: AirspeedSweepInfo = quantity("", "how the answer was obtained")
    validity: list[FindingOnset] = quantity(
        "",
        "from which airspeed on each finding of the points' `validity` appears, one entry per "
        "code found, in the order of FINDING_CODES; empty when no point has any",
        default_factory=list,
    )

    @property
    def equilibria(self) -> list[Equilibrium]:
        return [point.equilibrium for point in self.points if point.equilibrium is not None]


@dataclass(frozen=True)
class ConstraintValue:
    """One constraint of a design problem at the optimum."""

    name: Literal[
        "lift", "root_twist_slope", "jig_twist", "von_mises", "tip_heave", "stability_margin"
    ] = quantity(
        "",
        "lift: = the required lift; root_twist_slope: total twist equal at the first two "
        "stations; jig_twist: the bounds at every station; von_mises: safety_factor * von Mises "
        "<= yield at every station; tip_heave: |tip heave| <= the limit; stability_margin: "
        "q / local divergence pressure <= the limit (checked at the optimum)",
    )
    value: float = quantity("", "its value at the optimum (unit in `unit`); the worst station's")
    lower: float | None = quantity("", "lower limit, or null")
    upper: float | None = quantity("", "upper limit, or null")
    unit: str = quantity("", "unit of value and limits")
    active: bool = quantity("", "at a limit (within 1e-6 of its scale): it shapes the optimum")
    y: float | None = quantity("m", "the station where it binds, or null", default=None)


@dataclass(frozen=True)
class OptimizerInfo:
    """What IPOPT did."""

    iterations: int = quantity("-", "IPOPT iterations")
    evaluations: int = quantity("-", "equilibria solved along the way")
    status: str = quantity("", "IPOPT's return status")
    seconds: float = quantity("s", "wall time")


@dataclass(frozen=True, eq=False)
class RigidOptimum:
    """The same problem for the rigid wing (no deformation): what flexibility changes."""

    jig_twist: np.ndarray = quantity("deg", "optimal built-in twist at each station")
    induced_drag: float = quantity("N", "near-field induced drag")
    trefftz_drag: float = quantity("N", "far-field (Trefftz-plane) induced drag")
    span_efficiency: float = quantity("-", "L^2 / (q pi b^2 induced_drag)")
    trefftz_span_efficiency: float = quantity("-", "L^2 / (q pi b^2 trefftz_drag)")
    optimizer: OptimizerInfo = quantity("", "what IPOPT did")


@dataclass(frozen=True, eq=False)
class OptimalDesign:
    """The optimum of a design problem and the equilibrium the optimal wing flies in."""

    wing: Wing = internal()
    jig_twist: np.ndarray = quantity("deg", "optimal built-in twist at each station")
    control_points: np.ndarray | None = quantity(
        "deg", "the optimal control points (null: every station was a variable)"
    )
    wall_thickness: np.ndarray | None = quantity(
        "m", "the optimal spar wall thickness at each station (null: not sized)"
    )
    objective: Literal["induced_drag", "trefftz_drag", "spar_mass"] = quantity(
        "", "what was minimised"
    )
    objective_value: float = quantity(
        "", "its value at the optimum (N or kg), with the smoothness penalty [N] when asked"
    )
    induced_drag: float = quantity("N", "near-field induced drag of the deformed wing")
    trefftz_drag: float = quantity("N", "far-field (Trefftz-plane) induced drag")
    span_efficiency: float = quantity("-", "L^2 / (q pi b^2 induced_drag)")
    trefftz_span_efficiency: float = quantity("-", "L^2 / (q pi b^2 trefftz_drag)")
    spar_mass: float | None = quantity("kg", "spar mass of both halves, or null without spar")
    constraints: list[ConstraintValue] = quantity("", "every constraint at the optimum")
    equilibrium: Equilibrium = quantity("", "the optimal wing's equilibrium, as /solve answers")
    rigid: RigidOptimum | None = quantity(
        "", "the same problem's optimum for a rigid wing, or null (objective spar_mass)"
    )
    optimizer: OptimizerInfo = quantity("", "what IPOPT did")


# ------------------------------------------------------------------ control surfaces and roll


@dataclass(frozen=True)
class HingeMoment:
    """The aerodynamic moment about one surface's hinge line, on each wing."""

    name: str = quantity("", "the surface (wing.control_surfaces[].name)")
    right: float = quantity(
        "N m",
        "right wing's: moment of the loads aft of the hinge about the deformed hinge line, "
        "trailing edge down positive (a lifting surface pushes its trailing edge up: negative)",
    )
    left: float = quantity("N m", "left wing's, trailing edge down positive")


@dataclass(frozen=True)
class RollStability:
    """Static stability of the antisymmetric response."""

    stable: bool = quantity(
        "", "statically stable against antisymmetric divergence: local pressure > q"
    )
    margin: float = quantity(
        "-", "q / the antisymmetric divergence pressure at this state; 0 when it has none"
    )
    antisymmetric_divergence_pressure: float | None = quantity(
        "Pa",
        "smallest positive real lambda with the antisymmetric Jacobian J0 + lambda J1 "
        "singular, linearised at this state (antisymmetric divergence), or null",
    )
    antisymmetric_divergence_velocity: float | None = quantity(
        "m/s", "airspeed of that divergence at this density, or null"
    )


@dataclass(frozen=True, eq=False)
class RollResponse:
    """The wing's response to its ailerons and a steady roll rate: both halves, the rolling
    moment and the hinge moments.

    Axes and signs: geometry axes, x aft, y right, z up. The rolling moment is about the x axis
    through the root chord (the undeformed elastic axis's root point), positive when it raises
    the right wing (the body-axis rolling moment, x forward and z down, is its negative); the
    roll rate is about the same axis, positive raising the right wing. A positive aileron
    deflection (right trailing edge down, left up) gives a positive rolling moment on a rigid
    wing. The left wing's arrays are in its mirrored frame: y from the root outboard, heave
    up, twist nose-up, loads as the right wing's."""

    wing: Wing = internal()
    flight: OperatingPoint = internal()
    options: SolverOptions = internal()
    antisymmetric_state: np.ndarray = internal()  # (n,) the right half's antisymmetric part
    symmetric: Equilibrium | None = internal()  # the symmetric equilibrium linearised about
    method: Literal["antisymmetric", "linearised"] = quantity(
        "",
        "antisymmetric: the exact equilibrium of the antisymmetric flow (a wing with sections "
        "symmetric in z, no jig twist and no flap deflected, at alpha 0); linearised: the "
        "symmetric equilibrium at this alpha (flaps included) plus the antisymmetric "
        "disturbance of the ailerons and the roll rate linearised about it (exact to first "
        "order in them; Nastran's antisymmetric subcase linearises about the undeformed jig)",
    )
    roll_rate: float = quantity(
        "rad/s",
        "steady roll rate about x, positive raising the right wing: as given, or the free-roll "
        "rate at which the rolling moment vanishes",
    )
    helix_angle: float = quantity(
        "-",
        "p b / (2 V): the wing tip's helix angle [rad] (b the span), the rolling "
        "performance designers quote",
    )
    free_roll: bool = quantity("", "the roll rate was solved for: the rolling moment is zero")
    rolling_moment: float = quantity(
        "N m", "about the x axis through the root chord, positive raising the right wing"
    )
    rolling_moment_coefficient: float = quantity(
        "-", "rolling_moment / (q S b), S the jig planform area of both halves, b the span"
    )
    rigid_rolling_moment: float = quantity(
        "N m", "the rigid (undeformed) wing's at the same alpha, deflections and roll rate"
    )
    lift: float = quantity("N", "lift of both halves (the symmetric equilibrium's)")
    right: Stations = quantity("", "right wing: deformation and internal loads at the stations")
    left: Stations = quantity(
        "", "left wing, mirrored frame: deformation and internal loads at the stations"
    )
    right_panels: Panels = quantity("", "right wing: aerodynamic loads on the strips")
    left_panels: Panels = quantity("", "left wing, mirrored frame: loads on the strips")
    hinge_moments: list[HingeMoment] = quantity("", "one per control surface")
    stability: RollStability = quantity("", "antisymmetric static stability")
    solver: SolveInfo = quantity("", "how the answer was obtained")
    validity: list[Finding] = quantity(
        "", "where this answer leaves the model's validity, on either wing", default_factory=list
    )


@dataclass(frozen=True)
class Reversal:
    """Where a control's elastic derivative vanishes: control reversal."""

    dynamic_pressure: float | None = quantity(
        "Pa", "the smallest positive dynamic pressure at which the elastic derivative is zero"
    )
    velocity: float | None = quantity("m/s", "its airspeed at this density, or null")
    reason: str | None = quantity("", "why the values are null, else null", default=None)


@dataclass(frozen=True, eq=False)
class ControlEffectiveness:
    """One control surface's rigid and elastic derivative at one flight condition.

    An aileron's derivative is of the rolling moment (`RollResponse`'s axis and sign), a
    flap's of the lift of both halves, per degree of deflection (trailing edge down, the left
    aileron's up), at this dynamic pressure."""

    name: str = quantity("", "the surface (wing.control_surfaces[].name)")
    kind: Literal["flap", "aileron"] = quantity("", "what it is (ControlSurface.kind)")
    measure: Literal["lift", "rolling_moment"] = quantity(
        "", "what the derivatives are of: a flap's lift, an aileron's rolling moment"
    )
    unit: Literal["N/deg", "N m/deg"] = quantity(
        "", "the unit of derivative and rigid_derivative: N/deg (lift) or N m/deg"
    )
    derivative: float = quantity(
        "",
        "elastic control derivative, in `unit`: d(measure)/d(deflection), the structure deforming",
    )
    rigid_derivative: float = quantity(
        "", "the same of the rigid (undeformed) wing at this alpha, in `unit`"
    )
    effectiveness: float | None = quantity(
        "-", "derivative / rigid_derivative (1 for a rigid wing, 0 at reversal), or null"
    )
    coefficient_derivative: float = quantity(
        "1/deg",
        "derivative over q S (flap: dCL/d deflection) or q S b (aileron: dCl/d deflection), "
        "S the jig planform area of both halves, b the span",
    )
    hinge_moment: float = quantity(
        "N m", "the right wing's hinge moment at this equilibrium, trailing edge down positive"
    )
    reversal: Reversal = quantity(
        "",
        "linear reversal: the generalised eigenvalue of the bordered Jacobian at the "
        "unloaded jig (alpha 0, the classical problem)",
    )
    local_reversal: Reversal = quantity(
        "",
        "the same eigenvalue linearised at this equilibrium (where the derivative at this "
        "state would vanish)",
    )
    divergence_pressure: float | None = quantity(
        "Pa",
        "linear divergence of the problem the surface acts in, at the unloaded jig: the "
        "symmetric one for a flap, the antisymmetric one for an aileron; null if none",
    )
    first: Literal["reversal", "divergence", "neither"] = quantity(
        "", "which of linear reversal and that divergence comes first as q rises"
    )


@dataclass(frozen=True, eq=False)
class ControlSweepPoint:
    """One airspeed of a control sweep."""

    velocity: float = quantity("m/s", "requested airspeed")
    status: Literal["equilibrium", "no_equilibrium", "not_converged"] = quantity(
        "", "as AirspeedPoint.status"
    )
    controls: list[ControlEffectiveness] = quantity(
        "", "one per control surface (empty without an equilibrium)"
    )
    no_equilibrium: PointFailure | None = quantity("", "why there is none")


@dataclass(frozen=True)
class ReversalSummary:
    """One surface's reversal, computed two ways, and what comes first."""

    name: str = quantity("", "the surface")
    kind: Literal["flap", "aileron"] = quantity("", "what it is")
    reversal: Reversal = quantity("", "linear reversal (eigenvalue at the unloaded jig)")
    crossing: Reversal = quantity(
        "",
        "where the sweep's elastic derivative changes sign, interpolated linearly in q "
        "between the two airspeeds around it (null if it does not change sign)",
    )
    divergence_pressure: float | None = quantity(
        "Pa", "linear divergence of the surface's problem (symmetric or antisymmetric)"
    )
    first: Literal["reversal", "divergence", "neither"] = quantity(
        "", "which comes first as the airspeed rises, reversal or divergence"
    )


@dataclass(frozen=True, eq=False)
class ControlSweep:
    """Control effectiveness against airspeed, with each surface's reversal."""

    points: list[ControlSweepPoint] = quantity("", "one per requested airspeed, in order")
    reversals: list[ReversalSummary] = quantity("", "one per control surface")
    symmetric_divergence: LinearDivergence = quantity(
        "", "linear (symmetric) divergence of the unloaded jig"
    )
    antisymmetric_divergence: LinearDivergence = quantity(
        "", "linear antisymmetric divergence of the unloaded jig"
    )
    solver: AirspeedSweepInfo = quantity("", "how the answer was obtained")
