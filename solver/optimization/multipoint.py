"""The multipoint design: one jig twist (and one spar) for the design flight and every load case
of a problem, in one IPOPT problem on exact gradients (as OpenAeroStruct's multipoint
optimisation carries a 2.5 g point beside the cruise: Jasa et al., "Open-source coupled
aerostructural optimization using Python", Struct. Multidisc. Optim. 57, 2018, section 6).

The design vector is v = (twist d, walls t, alpha_1 .. alpha_C): the design flight flies at its
fixed jig alpha (the twist trims it, as in the single-point problem: one fixed alpha removes the
freedom of turning the whole twist and every alpha by one angle), each load case at its own
alpha, a variable of the problem with its lift as an equality constraint (trimmed). Each case's
equilibrium, and its functions' exact gradients, are its `CaseSpace`'s.

Constraints, each named by its case in the answer: in the design flight the lift, the jig
twist's bounds (and with every station free, the total twist's root slope), the tip heave and
the spar's stress at every station; in every load case its lift, tip heave and stress at every
station (no aggregation: (von Mises / allowable)^2 - 1 <= 0 at each station of each case, the
form of the single-point problem). The objective is the design flight's (its drag, or the spar's
mass, which no case changes). The wing's own mass (`wing.mass`) weighs n g in every case.

IPOPT's answer is judged as the single-point one's, except that an iteration limit, or a stop at
a design that meets every constraint, is `OptimizerNotConverged` (not-converged): only a design
IPOPT found infeasible, or stopped at while violating a constraint, is `InfeasibleDesign`, and
it names the case.
"""

from __future__ import annotations

import numpy as np

from solver.errors import (
    InfeasibleDesign,
    OptimizerNotConverged,
    SolverError,
    numerical_failures_as,
)
from solver.inputs.design import DESIGN_FLIGHT_CASE, DesignProblem
from solver.inputs.flight import FlightCondition
from solver.inputs.options import SolverOptions
from solver.inputs.wing import Wing
from solver.optimization.case_space import CaseFlight, CaseSpace
from solver.optimization.design_space import DesignPoint
from solver.optimization.nlp import run_ipopt, stopped_by_a_limit, succeeded
from solver.optimization.report import (
    ACTIVE,
    Entry,
    constraint_value,
    optimal_design,
    stability_value,
    worst_violation,
)
from solver.results.design import (
    ConstraintValue,
    DesignCaseResult,
    OptimalDesign,
    OptimizerInfo,
    RigidOptimum,
)
from solver.results.equilibrium import Equilibrium
from solver.statics.solve import solve
from solver.statics.trim import MAX_TRIM_ALPHA

__all__ = ["optimize_cases"]


class _Cases:
    """The multipoint problem's objective and constraints over its cases' spaces, scaled, with
    their bounds (`solver.optimization.nlp.Problem`)."""

    def __init__(self, spaces: list[CaseSpace], problem: DesignProblem) -> None:
        self.spaces, self.problem = spaces, problem
        first = spaces[0]
        n = first.wing.n_stations
        # (case index, constraint) in the order IPOPT sees them.
        self.entries: list[tuple[int, Entry]] = []
        for c, space in enumerate(spaces):
            lift = space.flight.lift
            self.entries.append((c, ("lift", abs(lift), np.array([lift]), np.array([lift]))))
            if c == 0:
                if problem.control_points is None:
                    self.entries.append((c, ("root_twist_slope", 1.0, np.zeros(1), np.zeros(1))))
                lower, upper = problem.twist_bounds
                self.entries.append((c, ("jig_twist", 1.0, np.full(n, lower), np.full(n, upper))))
            if problem.max_tip_heave is not None:
                limit = problem.max_tip_heave
                heave = ("tip_heave", limit, np.array([-limit]), np.array([limit]))
                self.entries.append((c, heave))
            if space.spar is not None:
                stress = ("von_mises", 1.0, np.full(n - 1, -np.inf), np.zeros(n - 1))
                self.entries.append((c, stress))
        self.size = sum(entry[2].size for _, entry in self.entries)
        self.failure: tuple[str, SolverError] | None = None
        # IPOPT's variables: twist and alphas in degrees, walls in millimetres (all of order one).
        self.variable_scale = np.ones(first.n_design)
        self.variable_scale[first.walls] = 1e-3

    def point(self, scaled: np.ndarray) -> list[DesignPoint] | None:
        v = scaled * self.variable_scale
        points = []
        for space in self.spaces:
            try:
                with numerical_failures_as(space.velocity):
                    points.append(space.at(v))
            except SolverError as error:  # IPOPT shortens its step on NaN
                self.failure = (space.flight.name, error)
                return None
        return points

    def objective(self, points: list[DesignPoint]) -> float:
        name = self.problem.objective
        return float(points[0].values[name][0] + points[0].values["penalty"][0])

    def objective_gradient(self, points: list[DesignPoint]) -> np.ndarray:
        name = self.problem.objective
        gradient = points[0].gradients[name][0] + points[0].gradients["penalty"][0]
        return gradient * self.variable_scale

    def values(self, points: list[DesignPoint]) -> np.ndarray:
        return np.concatenate([points[c].values[entry[0]] / entry[1] for c, entry in self.entries])

    def jacobian(self, points: list[DesignPoint]) -> np.ndarray:
        rows = [points[c].gradients[entry[0]] / entry[1] for c, entry in self.entries]
        return np.vstack(rows) * self.variable_scale

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        return (
            np.concatenate([entry[2] / entry[1] for _, entry in self.entries]),
            np.concatenate([entry[3] / entry[1] for _, entry in self.entries]),
        )

    def case_of(self, index: int) -> str | None:
        """The case an entry holds in (None for the jig twist's bounds: every case's)."""
        c, entry = self.entries[index]
        return None if entry[0] == "jig_twist" else self.spaces[c].flight.name


def _flights(problem: DesignProblem, n_variables: int) -> list[CaseFlight]:
    """The design flight (fixed alpha) and every load case (its alpha the variable after the
    `n_variables` twist and wall variables), as the spaces fly them."""
    design = problem.flight
    flights = [
        CaseFlight(
            DESIGN_FLIGHT_CASE,
            design.velocity,
            design.density,
            problem.lift,
            design.load_factor,
            problem.alpha,
            None,
        )
    ]
    for c, case in enumerate(problem.load_cases):
        flight = case.flight
        assert flight.velocity is not None and flight.required_lift is not None
        flights.append(
            CaseFlight(
                case.name,
                flight.velocity,
                flight.density,
                flight.required_lift,
                case.inertial_load_factor,
                0.0,  # where it starts: the start design's trim (`_start`)
                n_variables + c,
            )
        )
    return flights


def _start(
    spaces: list[CaseSpace], problem: DesignProblem, start: np.ndarray, options: SolverOptions
) -> None:
    """Each load case's alpha and state at the start design, from its trimmed solve (the
    warm start of its Newton iterations); raises `InfeasibleDesign` naming a case the start
    design cannot fly."""
    wing = spaces[0].design_wing(start)
    for space, case in zip(spaces[1:], problem.load_cases, strict=True):
        try:
            equilibrium = solve(wing, case.flight, options=options)
        except SolverError as error:
            raise InfeasibleDesign(
                "lift",
                f"the starting design (the rigid optimum's twist, the wing's own walls) cannot "
                f"fly this case, so the search has nowhere to start: {error}",
                case=case.name,
            ) from error
        index = space.flight.alpha_index
        assert index is not None
        start[index] = equilibrium.totals.alpha
        space.x = np.array(equilibrium.state)


def optimize_cases(
    wing: Wing,
    problem: DesignProblem,
    options: SolverOptions,
    rigid: RigidOptimum | None,
    start_twist: np.ndarray | None,
    tolerance: float,
) -> OptimalDesign:
    """The multipoint optimum of `problem` (module docstring), started from `start_twist` (the
    rigid optimum's twist variables, or None: zero) and the wing's own walls, with the rigid
    optimum `rigid` reported beside it. Raises `InfeasibleDesign` naming the constraint and the
    case, `OptimizerNotConverged` when IPOPT stops at its limit."""
    probe = CaseSpace(wing, problem, options, _flights(problem, 0)[0], 0)
    n_variables = probe.n_twist + probe.n_wall
    flights = _flights(problem, n_variables)
    spaces = [CaseSpace(wing, problem, options, flight, len(flights) - 1) for flight in flights]
    first = spaces[0]
    start = np.zeros(first.n_design)
    if start_twist is not None:
        start[: first.n_twist] = start_twist
    if first.n_wall:
        assert wing.spar is not None
        start[first.walls] = wing.spar.wall_thickness
    lower_v, upper_v = first.variable_bounds()
    lower_v[n_variables:], upper_v[n_variables:] = -MAX_TRIM_ALPHA, MAX_TRIM_ALPHA
    _start(spaces, problem, start, options)
    cases = _Cases(spaces, problem)
    history = 6 if first.n_wall else min(20, first.n_design)  # as the single-point problem's

    def evaluations() -> int:
        return sum(space.evaluations for space in spaces)

    bounds, limits = (lower_v, upper_v), cases.bounds()
    v, info = run_ipopt(cases, start, bounds, limits, tolerance, history, evaluations)
    if stopped_by_a_limit(info):
        # L-BFGS can creep along the curved boundary of the stresses' constraints, its steps
        # shrinking (2 of the benchmark's 96 problems): SR1, whose approximation may be
        # indefinite as the Lagrangian's is, goes on from where it stopped.
        v, more = run_ipopt(cases, v, bounds, limits, tolerance, history, evaluations, "sr1")
        info = OptimizerInfo(
            iterations=info.iterations + more.iterations,
            evaluations=more.evaluations,
            status=more.status,
            seconds=info.seconds + more.seconds,
        )
    if not succeeded(info):
        raise _failure(cases, v, info)
    return _report(wing, problem, options, cases, v, info, rigid)


def _failure(cases: _Cases, v: np.ndarray, info: OptimizerInfo) -> SolverError:
    """Why IPOPT stopped without an optimum (module docstring)."""
    design = cases.spaces[0].flight
    points = cases.point(v / cases.variable_scale)
    if points is None:
        assert cases.failure is not None
        name, error = cases.failure
        return InfeasibleDesign("lift", f"no equilibrium near the last design: {error}", case=name)
    judged = [(entry, points[c].values[entry[0]]) for c, entry in cases.entries]
    index, excess = worst_violation(judged)
    # Within what the answer calls a constraint at its limit (`report.ACTIVE`): no violation
    # to name.
    feasible = index < 0 or excess <= ACTIVE
    if stopped_by_a_limit(info) or (feasible and "Infeasible" not in info.status):
        return OptimizerNotConverged(
            design.velocity,
            info.iterations,
            excess,
            f"IPOPT stopped with {info.status} before its optimality test held",
        )
    if index < 0:
        return InfeasibleDesign(
            "optimizer", f"IPOPT stopped with {info.status} after {info.iterations} iterations"
        )
    return InfeasibleDesign(
        cases.entries[index][1][0],
        f"IPOPT stopped with {info.status} after {info.iterations} iterations; violated by "
        f"{excess:.3g} of its scale",
        violation=excess,
        case=cases.case_of(index),
    )


def _equilibria(
    optimal_wing: Wing, problem: DesignProblem, options: SolverOptions
) -> list[Equilibrium]:
    """The optimal wing's equilibrium in the design flight (at its alpha, its mass under its
    load factor) and in every load case (trimmed), as /solve answers each flight."""
    design = problem.flight
    load_factor = design.load_factor if optimal_wing.mass is not None else None
    flight = FlightCondition(
        design.velocity, problem.alpha, design.density, load_factor=load_factor
    )
    out = [solve(optimal_wing, flight, options=options)]
    for case in problem.load_cases:
        out.append(solve(optimal_wing, case.flight, options=options))
    return out


def _report(
    wing: Wing,
    problem: DesignProblem,
    options: SolverOptions,
    cases: _Cases,
    v: np.ndarray,
    info: OptimizerInfo,
    rigid: RigidOptimum | None,
) -> OptimalDesign:
    """The optimum as the single-point one is answered, with every case's equilibrium."""
    first = cases.spaces[0]
    optimal_wing = first.design_wing(v)
    equilibria = _equilibria(optimal_wing, problem, options)
    points = cases.point(v / cases.variable_scale)
    assert points is not None  # IPOPT's last design, evaluated before
    values: list[ConstraintValue] = []
    for index, (c, entry) in enumerate(cases.entries):
        values.append(
            constraint_value(
                entry,
                points[c].values[entry[0]],
                wing.y,
                equilibria[c],
                options.safety_factor,
                case=cases.case_of(index),
            )
        )
    limit = problem.max_stability_margin
    for space, equilibrium in zip(cases.spaces, equilibria, strict=True):
        value = stability_value(equilibrium, limit, case=space.flight.name)
        values.append(value)
        if value.value > limit:
            raise InfeasibleDesign(
                "stability_margin",
                f"the optimum's q / local divergence pressure is {value.value:.4g}, above the "
                f"allowed {limit:.4g}",
                case=space.flight.name,
            )
    equilibrium = equilibria[0]
    jig, wall = first.split(v)
    return optimal_design(
        problem,
        optimal_wing,
        None if problem.control_points is None else v[: first.n_twist].copy(),
        jig,
        None if wall is None else wall.copy(),
        equilibrium,
        float(points[0].values["penalty"][0]),
        values,
        rigid,
        info,
        cases=[
            _case_result(space.flight, found)
            for space, found in zip(cases.spaces, equilibria, strict=True)
        ],
    )


def _case_result(flight: CaseFlight, equilibrium: Equilibrium) -> DesignCaseResult:
    return DesignCaseResult(
        name=flight.name,
        velocity=flight.velocity,
        density=flight.density,
        load_factor=flight.load_factor,
        lift=flight.lift,
        alpha=equilibrium.totals.alpha,
        max_von_mises_stress=equilibrium.totals.max_von_mises_stress,
        equilibrium=equilibrium,
    )
