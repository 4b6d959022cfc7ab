"""What an answer is when the path to the requested airspeed does not end in a stable
equilibrium: the branch from the jig shape decides.

Natural-parameter steps stall approaching a fold, and Newton from a poor start can wander off or
land on another, statically unstable branch (for the study's wing and rect_public: a nose-down,
negative-lift branch that never joins the jig's). Neither may reach the user as a plain answer.
The branch from the jig (pseudo-arclength continuation, `solver.statics.branch`) decides:

- beyond its fold: `NoEquilibrium` naming the fold speed;
- below the fold: Newton from the branch's own (interpolated) state at this q; a stable
  equilibrium is the answer; an unstable one is `NoEquilibrium` (the branch has no stable
  equilibrium here), a failure `ConvergenceError`;
- where the branch could not be followed that far: `ConvergenceError` saying why.

Every outcome depends on the wing, alpha and q only: the branch is canonical.
"""

from __future__ import annotations

import time

from solver.errors import ConvergenceError, NoEquilibrium
from solver.inputs.flight import OperatingPoint, dynamic_pressure, velocity_for
from solver.inputs.options import SolverOptions
from solver.numerics.newton import newton
from solver.results.equilibrium import Equilibrium
from solver.statics.branch import branch, fold, search_velocity_limit
from solver.statics.system import CoupledSystem
from solver.statics.verdict import judge

__all__ = ["from_branch", "settle"]


def settle(
    system: CoupledSystem,
    flight: OperatingPoint,
    options: SolverOptions,
    prior_iterations: int,
    started: float,
) -> Equilibrium:
    """The answer at `flight` from the branch from the jig (the path did not give one)."""
    limit = search_velocity_limit(system, flight.density, flight.velocity)
    found = fold(system, flight.density, limit)
    if found.velocity is not None and flight.velocity > found.velocity:
        raise NoEquilibrium(flight.velocity, found.velocity)
    return from_branch(system, flight, options, prior_iterations, started, limit)


def from_branch(
    system: CoupledSystem,
    flight: OperatingPoint,
    options: SolverOptions,
    prior_iterations: int,
    started: float | None = None,
    velocity_limit: float | None = None,
) -> Equilibrium:
    """Newton at `flight`'s q from the branch's state there (cubic Hermite in arclength, O(ds^4)
    from the equilibrium, so one or two iterations); below the fold only."""
    started = time.perf_counter() if started is None else started
    q = flight.dynamic_pressure
    if velocity_limit is None:
        velocity_limit = search_velocity_limit(system, flight.density, flight.velocity)
    traced = branch(system, dynamic_pressure(flight.density, velocity_limit))
    fold_point = traced.fold
    if fold_point is not None and q > fold_point.dynamic_pressure:
        fold_velocity = velocity_for(fold_point.dynamic_pressure, flight.density)
        raise NoEquilibrium(flight.velocity, fold_velocity)
    if traced.reached_pressure < q:
        reached = velocity_for(traced.reached_pressure, flight.density)
        why = traced.reason or "it ended"
        raise ConvergenceError(
            flight.velocity,
            prior_iterations,
            float("nan"),
            f"the branch from the jig could be followed only to {reached:.6g} m/s ({why})",
        )
    result = newton(
        system.evaluate,
        system.residual,
        traced.start_for(q),
        q,
        options.tolerance,
        options.max_iterations,
    )
    iterations = prior_iterations + result.iterations
    if not result.converged:
        raise ConvergenceError(flight.velocity, iterations, result.residual_norm, result.reason)
    equilibrium = judge(
        system,
        flight,
        options,
        result.x,
        result.evaluation,
        iterations=iterations,
        residual_norm=result.residual_norm,
        warm_start=False,  # started from the canonical branch, not from a caller's state
        started=started,
    )
    if not equilibrium.stability.stable:
        local = equilibrium.stability.local_divergence_pressure
        raise NoEquilibrium(
            flight.velocity,
            None,
            "the equilibrium on the branch from the jig is statically unstable here: its local "
            f"divergence pressure {local:.6g} Pa is below q = {q:.6g} Pa",
        )
    return equilibrium
