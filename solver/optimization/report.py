"""How a design's constraints are reported at the optimum (each with its value at the station
closest to its limit, and whether it shapes the optimum), how far a design breaks them, and the
span efficiency of a drag, and the optimal design's answer: shared by the single-point and the
multipoint problem."""

from __future__ import annotations

import math
from collections.abc import Iterable

import numpy as np

from solver.inputs.design import DesignProblem
from solver.inputs.wing import Wing
from solver.results.design import (
    ConstraintValue,
    DesignCaseResult,
    OptimalDesign,
    OptimizerInfo,
    RigidOptimum,
)
from solver.results.equilibrium import Equilibrium
from solver.statics.trefftz import trefftz_drag

__all__ = [
    "ACTIVE",
    "Entry",
    "constraint_value",
    "efficiency",
    "optimal_design",
    "stability_value",
    "worst_violation",
]

ACTIVE = 1e-6  # relative distance to a limit at which a constraint counts as active

UNITS = {
    "lift": "N",
    "root_twist_slope": "deg",
    "jig_twist": "deg",
    "tip_heave": "m",
    "von_mises": "Pa",
}

# A constraint as the optimiser holds it: (name, scale, lower, upper) in the function's units.
Entry = tuple[str, float, np.ndarray, np.ndarray]


def _station_of(name: str, index: int, y: np.ndarray) -> float | None:
    """[m] where a constraint binds: its station, the tip for the tip heave, None for totals."""
    if name == "tip_heave":
        return float(y[-1])
    if name in ("jig_twist", "von_mises"):
        return float(y[index])
    return None


def constraint_value(
    entry: Entry,
    values: np.ndarray,
    y: np.ndarray,
    equilibrium: Equilibrium,
    safety_factor: float,
    case: str | None = None,
) -> ConstraintValue:
    """One constraint at the optimum, from its `values` (m,) there; the von Mises stress's is
    the equilibrium's largest against the allowable yield_stress / `safety_factor`."""
    name, scale, lower, upper = entry
    # The station closest to a limit.
    gaps = np.minimum(values - lower, upper - values)
    worst = int(np.argmin(gaps))
    active = bool(gaps[worst] <= ACTIVE * scale) if np.isfinite(gaps[worst]) else False
    value, low, high = float(values[worst]), lower[worst], upper[worst]
    if name == "von_mises":
        tube = equilibrium.wing.spar
        assert tube is not None
        allowable = tube.material.yield_stress / safety_factor
        stresses = equilibrium.stations.von_mises_stress
        assert stresses is not None
        worst = int(np.argmax(stresses))
        value, low, high = float(stresses[worst]), -np.inf, allowable
        active = bool(high - value <= ACTIVE * allowable)
    return ConstraintValue(
        name=name,  # type: ignore[arg-type]
        value=value,
        lower=None if not np.isfinite(low) else float(low),
        upper=None if not np.isfinite(high) else float(high),
        unit=UNITS[name],
        active=active,
        y=_station_of(name, worst, y),
        case=case,
    )


def stability_value(
    equilibrium: Equilibrium, limit: float, case: str | None = None
) -> ConstraintValue:
    """q / local divergence pressure at the optimum against its `limit` (checked there)."""
    margin = equilibrium.stability.margin
    return ConstraintValue(
        name="stability_margin",
        value=margin,
        lower=None,
        upper=limit,
        unit="-",
        active=bool(limit - margin <= ACTIVE),
        case=case,
    )


def worst_violation(judged: Iterable[tuple[Entry, np.ndarray]]) -> tuple[int, float]:
    """(index, violation) of the most violated constraint among (entry, values) pairs, in units
    of its scale; (-1, 0.0) when none is violated."""
    worst, excess = -1, 0.0
    for index, ((_, scale, lower, upper), values) in enumerate(judged):
        value = values / scale
        violation = float(np.max(np.maximum(lower / scale - value, value - upper / scale)))
        if violation > excess:
            worst, excess = index, violation
    return worst, excess


def efficiency(lift: float, dynamic_pressure: float, semispan: float, drag: float) -> float:
    """e = L^2 / (q pi b^2 D)."""
    span = 2 * semispan
    return lift**2 / (dynamic_pressure * math.pi * span**2 * drag)


def optimal_design(
    problem: DesignProblem,
    optimal_wing: Wing,
    control_points: np.ndarray | None,
    jig_twist: np.ndarray,
    wall_thickness: np.ndarray | None,
    equilibrium: Equilibrium,
    penalty: float,
    constraints: list[ConstraintValue],
    rigid: RigidOptimum | None,
    optimizer: OptimizerInfo,
    cases: list[DesignCaseResult] | None = None,
) -> OptimalDesign:
    """The answer at the optimum: the objective's value (its penalty [the objective's unit]
    included), both drags [N] and their span efficiencies, of the design flight's
    `equilibrium`."""
    lift = equilibrium.totals.lift
    near, far = equilibrium.totals.induced_drag, trefftz_drag(equilibrium)
    objective = {
        "induced_drag": near,
        "trefftz_drag": far,
        "spar_mass": equilibrium.totals.spar_mass or 0.0,
    }[problem.objective] + penalty
    q, semispan = problem.dynamic_pressure, optimal_wing.semispan
    return OptimalDesign(
        wing=optimal_wing,
        jig_twist=jig_twist,
        control_points=control_points,
        wall_thickness=wall_thickness,
        objective=problem.objective,
        objective_value=objective,
        induced_drag=near,
        trefftz_drag=far,
        span_efficiency=efficiency(lift, q, semispan, near),
        trefftz_span_efficiency=efficiency(lift, q, semispan, far),
        spar_mass=equilibrium.totals.spar_mass,
        constraints=constraints,
        equilibrium=equilibrium,
        rigid=rigid,
        optimizer=optimizer,
        cases=cases,
    )
