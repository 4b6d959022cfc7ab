"""Control surfaces' answers: the ailerons' roll response (both wings, the rolling moment, the
hinge moments, the free-roll rate), and control effectiveness and reversal against airspeed.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

import numpy as np

from solver.inputs.flight import OperatingPoint
from solver.inputs.options import SolverOptions
from solver.inputs.wing import Wing
from solver.results.equilibrium import Equilibrium, Panels, SolveInfo, Stations
from solver.results.findings import Finding
from solver.results.quantities import internal, quantity
from solver.results.sweep import AirspeedSweepInfo, LinearDivergence, PointFailure

__all__ = [
    "ControlEffectiveness",
    "ControlSweep",
    "ControlSweepPoint",
    "HingeMoment",
    "Reversal",
    "ReversalSummary",
    "RollResponse",
    "RollStability",
]


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
