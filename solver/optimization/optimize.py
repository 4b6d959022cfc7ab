"""Design: the jig twist (and the spar's wall) of the wing that flies, by IPOPT on exact gradients
(the reduced functions and their gradients: `solver.optimization.design_space`).

The study's closing sketch: make the jig twist a design variable, require the lift, minimise the
drag of the deformed wing. Solved here in the reduced (nested) space: the design vector v holds
the jig-twist variables d (k control points, or every station) and, when the spar is sized, the
wall thickness t (N); each design's equilibrium x(v) comes from Newton (warm-started from the
previous design's, in IPOPT's deterministic order), and every function's gradient from one
forward sensitivity at the equilibrium,

    dx/dv = -J^{-1} dr/dv,    dF/dv = F_x dx/dv + F_v,

with J the coupled Jacobian the solver already has. Design derivatives come for free from the
model's structure: the jig twist enters the lattice only through the streamwise twist
phi cos(sweep) - u' sin(sweep) + jig, so dr/d(jig) is the aerodynamic part of dr/dphi over
cos(sweep); EI and GJ enter only the beam's trapezoid rows, differentiated by hand. IPOPT runs
with a limited-memory Hessian.

Why nested: the simultaneous form (the equilibrium equations as IPOPT constraints, as the study
and the AeroSandbox reference solve it) needs the Hessian of the lattice's residual; CasADi takes
100-160 s to build it for N = 30 (measured), where one reduced gradient costs one evaluation.

Well-posed by construction: the vortex lattice's near-field drag over free station twists runs
away (a zigzag between stations costs nothing). Control points (a cubic spline with zero slope
at the root) are the default; with every station free, the total twist's slope at the root is
held at zero (tw[0] = tw[1], as the reference) and a smoothness penalty
w sum (tw[i+1] - 2 tw[i] + tw[i-1])^2 [N, w in N/deg^2] is offered. The far-field (Trefftz
plane) drag of the planar wake, which such zigzags cannot lower, is reported and offered as the
objective.
"""

from __future__ import annotations

import numpy as np

from solver.errors import (
    InfeasibleDesign,
    InvalidInput,
    OptimizerNotConverged,
    SolverError,
    numerical_failures_as,
)
from solver.inputs.design import DesignProblem
from solver.inputs.flight import FlightCondition
from solver.inputs.options import SolverOptions, check_lag
from solver.inputs.wing import Wing
from solver.optimization.design_space import DesignPoint, DesignSpace
from solver.optimization.multipoint import optimize_cases
from solver.optimization.nlp import run_ipopt, stopped_by_a_limit, succeeded
from solver.optimization.report import (
    ACTIVE,
    Entry,
    constraint_value,
    efficiency,
    optimal_design,
    stability_value,
    worst_violation,
)
from solver.results.design import ConstraintValue, OptimalDesign, OptimizerInfo, RigidOptimum
from solver.results.equilibrium import Equilibrium
from solver.statics.solve import solve

__all__ = ["optimize"]


class _Constraints:
    """Which functions are IPOPT's objective and constraints, scaled, with their bounds."""

    def __init__(self, space: DesignSpace, problem: DesignProblem) -> None:
        self.space, self.problem = space, problem
        n = space.wing.n_stations
        weight = problem.lift
        # name -> (scale, lower, upper) in the function's own units
        self.entries: list[Entry] = [("lift", weight, np.array([weight]), np.array([weight]))]
        if problem.control_points is None:
            self.entries.append(("root_twist_slope", 1.0, np.zeros(1), np.zeros(1)))
        lower, upper = problem.twist_bounds
        self.entries.append(("jig_twist", 1.0, np.full(n, lower), np.full(n, upper)))
        if problem.max_tip_heave is not None and not space.rigid:
            limit = problem.max_tip_heave
            self.entries.append(("tip_heave", limit, np.array([-limit]), np.array([limit])))
        if space.spar is not None:
            self.entries.append(("von_mises", 1.0, np.full(n - 1, -np.inf), np.zeros(n - 1)))
        self.size = sum(lo.size for _, _, lo, _ in self.entries)
        self.failure: SolverError | None = None
        # IPOPT's variables: twist in degrees, walls in millimetres (both of order one).
        self.variable_scale = np.ones(space.n_design)
        self.variable_scale[space.n_twist :] = 1e-3

    def point(self, scaled: np.ndarray) -> DesignPoint | None:
        try:
            with numerical_failures_as(self.problem.velocity):
                return self.space.at(scaled * self.variable_scale)
        except SolverError as error:  # IPOPT shortens its step on NaN
            self.failure = error
            return None

    def objective(self, point: DesignPoint) -> float:
        name = self.problem.objective
        return float(point.values[name][0] + point.values["penalty"][0])

    def objective_gradient(self, point: DesignPoint) -> np.ndarray:
        name = self.problem.objective
        return (point.gradients[name][0] + point.gradients["penalty"][0]) * self.variable_scale

    def values(self, point: DesignPoint) -> np.ndarray:
        return np.concatenate([point.values[name] / scale for name, scale, _, _ in self.entries])

    def jacobian(self, point: DesignPoint) -> np.ndarray:
        rows = [point.gradients[name] / scale for name, scale, _, _ in self.entries]
        return np.vstack(rows) * self.variable_scale

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        return (
            np.concatenate([lo / scale for _, scale, lo, _ in self.entries]),
            np.concatenate([hi / scale for _, scale, _, hi in self.entries]),
        )


def _run_ipopt(
    space: DesignSpace, problem: DesignProblem, start: np.ndarray, tolerance: float
) -> tuple[np.ndarray, OptimizerInfo, _Constraints]:
    constraints = _Constraints(space, problem)
    bounds = space.variable_bounds()
    # Twist alone is nearly quadratic: a history as long as the design vector (up to 20)
    # takes 46 iterations on 30 stations where IPOPT's 6 takes 66. With the spar's walls
    # the long history overshoots into designs without equilibrium: IPOPT's 6 there.
    history = 6 if space.n_wall else min(20, space.n_design)
    limits = constraints.bounds()
    v, info = run_ipopt(
        constraints, start, bounds, limits, tolerance, history, lambda: space.evaluations
    )
    if stopped_by_a_limit(info):
        # As in the multipoint problem: L-BFGS can creep along a curved boundary of the
        # stresses, its steps shrinking; SR1 goes on from where it stopped.
        v, more = run_ipopt(
            constraints, v, bounds, limits, tolerance, history, lambda: space.evaluations, "sr1"
        )
        info = OptimizerInfo(
            iterations=info.iterations + more.iterations,
            evaluations=more.evaluations,
            status=more.status,
            seconds=info.seconds + more.seconds,
        )
    return v, info, constraints


def optimize(
    wing: Wing, problem: DesignProblem, options: SolverOptions | None = None
) -> OptimalDesign:
    """The jig twist (and spar wall) that minimises `problem.objective` while the flexible wing
    carries `problem.lift`, with the equilibrium of the optimal wing as `solve` answers it and
    the rigid wing's optimum beside it. Raises `InfeasibleDesign` naming the constraint that
    could not be met, `InvalidInput` for a problem the wing cannot pose (sizing without a spar).
    """
    options = options or SolverOptions()
    check_lag(wing.in_plane_bending_stiffness, options, "the optimiser")
    if problem.size_spar and wing.spar is None:
        raise InvalidInput("design.wall_thickness", "the wing has no spar to size")
    tolerance = 1e-10
    rigid, rigid_twist = None, None
    if problem.objective != "spar_mass":
        rigid, rigid_twist = _rigid_optimum(wing, problem, options, tolerance)
    if problem.multipoint:
        return optimize_cases(wing, problem, options, rigid, rigid_twist, tolerance)
    space = DesignSpace(wing, problem, options, rigid=False)
    start = np.zeros(space.n_design)
    if rigid_twist is not None:
        start[: space.n_twist] = rigid_twist  # the flying shape the flexible wing aims at
    if space.n_wall:
        assert wing.spar is not None
        start[space.n_twist :] = wing.spar.wall_thickness
    v, info, constraints = _run_ipopt(space, problem, start, tolerance)
    if not succeeded(info):
        raise _infeasible(space, constraints, v, info)
    optimal_wing = space.design_wing(v)
    flight = FlightCondition(problem.velocity, problem.alpha, problem.density)
    equilibrium = solve(optimal_wing, flight, options=options)
    point = space.at(v)
    values = _constraint_values(space, constraints, point, equilibrium)
    for value in values:
        if (
            value.name == "stability_margin"
            and value.upper is not None
            and value.value > value.upper
        ):
            raise InfeasibleDesign(
                "stability_margin",
                f"the optimum's q / local divergence pressure is {value.value:.4g}, above the "
                f"allowed {value.upper:.4g}",
            )
    jig, wall = space.split(v)
    return optimal_design(
        problem,
        optimal_wing,
        None if problem.control_points is None else v[: space.n_twist].copy(),
        jig,
        None if wall is None else wall.copy(),
        equilibrium,
        float(point.values["penalty"][0]),
        values,
        rigid,
        info,
    )


def _rigid_optimum(
    wing: Wing, problem: DesignProblem, options: SolverOptions, tolerance: float
) -> tuple[RigidOptimum, np.ndarray]:
    """The rigid wing's optimum, and its twist variables (where the flexible search starts)."""
    rigid_problem = problem.for_the_rigid_wing()
    space = DesignSpace(wing, rigid_problem, options, rigid=True)
    v, info, constraints = _run_ipopt(space, rigid_problem, np.zeros(space.n_design), tolerance)
    if not succeeded(info):
        raise _infeasible(space, constraints, v, info)
    point = space.at(v)
    lift = float(point.values["lift"][0])
    near = float(point.values["induced_drag"][0])
    far = float(point.values["trefftz_drag"][0])
    optimum = RigidOptimum(
        jig_twist=space.split(v)[0],
        induced_drag=near,
        trefftz_drag=far,
        span_efficiency=efficiency(lift, problem.dynamic_pressure, wing.semispan, near),
        trefftz_span_efficiency=efficiency(lift, problem.dynamic_pressure, wing.semispan, far),
        optimizer=info,
    )
    return optimum, v[: space.n_twist]


def _infeasible(
    space: DesignSpace, constraints: _Constraints, v: np.ndarray, info: OptimizerInfo
) -> SolverError:
    """Name the constraint the optimiser could not meet (the most violated at its last point),
    or, stopped by its iteration limit or at a design that meets every constraint, say it did
    not converge: a design not judged is no proof that none is feasible.

    v: (n_design,) the last design in physical units (twist [deg], walls [m])."""
    point = constraints.point(v / constraints.variable_scale)
    if point is None:
        return InfeasibleDesign(
            "lift", f"no equilibrium near the last design: {constraints.failure}"
        )
    index, excess = worst_violation(
        (entry, point.values[entry[0]]) for entry in constraints.entries
    )
    # At a design that meets every constraint (within what the answer calls a constraint at
    # its limit), a stop is the optimizer's, not the design's: as in the multipoint problem.
    feasible = index < 0 or excess <= ACTIVE
    if stopped_by_a_limit(info) or (feasible and "Infeasible" not in info.status):
        return OptimizerNotConverged(
            space.problem.velocity,
            info.iterations,
            excess,
            f"IPOPT stopped with {info.status} before its optimality test held",
        )
    worst = "optimizer" if index < 0 else constraints.entries[index][0]
    return InfeasibleDesign(
        worst,
        f"IPOPT stopped with {info.status} after {info.iterations} iterations"
        + (f"; violated by {excess:.3g} of its scale" if worst != "optimizer" else ""),
        violation=excess if worst != "optimizer" else None,
    )


def _constraint_values(
    space: DesignSpace, constraints: _Constraints, point: DesignPoint, equilibrium: Equilibrium
) -> list[ConstraintValue]:
    safety = space.options.safety_factor
    out = [
        constraint_value(entry, point.values[entry[0]], space.wing.y, equilibrium, safety)
        for entry in constraints.entries
    ]
    out.append(stability_value(equilibrium, space.problem.max_stability_margin))
    return out
