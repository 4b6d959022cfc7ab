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

__all__ = ["ConstraintValue", "OptimalDesign", "OptimizerInfo", "RigidOptimum"]


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
