"""A design's answer: the jig twist (and spar walls), the drag and span efficiency of the optimum
and of the rigid wing's, every constraint with its activity, what the optimizer did.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

import numpy as np

from solver.inputs.wing import Wing
from solver.results.equilibrium import Equilibrium
from solver.results.quantities import internal, quantity

__all__ = ["ConstraintValue", "DesignCaseResult", "OptimalDesign", "OptimizerInfo", "RigidOptimum"]


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
    case: str | None = quantity(
        "",
        "with load cases, the case it holds in ('flight': the design flight, else a load "
        "case's name; null for the jig twist's bounds, which hold for all); null without",
        default=None,
    )


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
class DesignCaseResult:
    """One case of a multipoint design at the optimum, with the optimal wing's equilibrium.

    Its flight as flown: the airspeed, the air, the load factor and lift, the angle of attack."""

    name: str = quantity("", "'flight' (the design flight), or the load case's name")
    velocity: float = quantity("m/s", "true airspeed")
    density: float = quantity("kg/m^3", "the air's density")
    load_factor: float = quantity("-", "n: the lift carried over the weight; 1 for a lift given")
    lift: float = quantity("N", "the lift required (load_factor * weight, or the lift given)")
    alpha: float = quantity(
        "deg",
        "the angle of attack: the design flight's fixed one (the twist trims it), a load "
        "case's trimmed one",
    )
    max_von_mises_stress: float | None = quantity(
        "Pa", "the spar's largest von Mises stress in this case, or null without spar"
    )
    equilibrium: Equilibrium = quantity(
        "", "the optimal wing's equilibrium in this case, as /solve answers its flight"
    )


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
    cases: list[DesignCaseResult] | None = quantity(
        "",
        "with load cases: the design flight ('flight', first: the objective, drags and "
        "efficiencies above are its) and every load case, each with the optimal wing's "
        "equilibrium; null without",
        default=None,
    )
