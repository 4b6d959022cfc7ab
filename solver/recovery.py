"""What `solve` does when Newton fails or lands on a statically unstable equilibrium.

Newton from a poor start near or past the fold either wanders off or converges to another,
unstable branch (for the study's wing and rect_public: a nose-down, negative-lift branch that
never joins the jig's). Neither may reach the user as a plain answer. The branch from the jig
shape decides:

- beyond its fold: `NoEquilibrium` naming the fold speed; except that an unstable equilibrium
  reached from a start the caller chose (a raw state, or an unstable equilibrium) is returned,
  flagged by its `stability`.
- below the fold: Newton again, from the branch state at this q (Hermite-interpolated from the
  continuation); if that fails too, the original `ConvergenceError`; if it finds only unstable
  equilibria, `NoEquilibrium` (an unstable state from the solver's own start is never an answer).
"""

from __future__ import annotations

import dataclasses

import numpy as np

from solver.compiled import model_for
from solver.divergence import Fold, equilibrium_branch, find_fold, search_velocity_limit
from solver.equilibrium import Equilibrium, SolverOptions, equilibrium_from_state
from solver.errors import ConvergenceError, NoEquilibrium
from solver.newton import newton
from solver.wing import FlightCondition, Wing

__all__ = ["settle"]


def settle(
    wing: Wing,
    flight: FlightCondition,
    initial_guess: Equilibrium | np.ndarray | None,
    equilibrium: Equilibrium | None,
    failure: ConvergenceError | None,
    options: SolverOptions,
    started: float,
) -> Equilibrium:
    """The answer of `solve` given Newton's outcome: `equilibrium` if it converged, else `failure`.

    Stable equilibria pass through (with the fold attached if `options.find_fold`); every
    other answer carries the fold it was judged by.
    """
    fold: Fold | None = None
    if options.find_fold:
        fold = _fold(wing, flight)
    if equilibrium is not None and equilibrium.stability.stable:
        return _with_fold(equilibrium, fold)
    fold = fold or _fold(wing, flight)
    callers_start = initial_guess is not None and not (
        isinstance(initial_guess, Equilibrium) and initial_guess.stability.stable
    )
    if equilibrium is not None and callers_start:
        return _with_fold(equilibrium, fold)  # the caller's own start: flagged, not replaced
    if fold.velocity is not None and flight.velocity > fold.velocity:
        raise NoEquilibrium(flight.velocity, fold.velocity)
    attempt = equilibrium if equilibrium is not None else failure
    assert attempt is not None  # Newton either converged or failed
    first_attempt = attempt.iterations
    retried = _from_branch(wing, flight, options, started, first_attempt)
    if retried is not None and retried.stability.stable:
        return _with_fold(retried, fold)
    if equilibrium is not None or retried is not None:
        # Only statically unstable equilibria, from the solver's own starts: not an answer.
        raise NoEquilibrium(
            flight.velocity, fold.velocity, "only statically unstable equilibria were found"
        )
    assert failure is not None
    raise failure


def _fold(wing: Wing, flight: FlightCondition) -> Fold:
    limit = search_velocity_limit(wing, flight.density, flight.velocity)
    return find_fold(wing, flight.alpha, flight.density, limit)


def _with_fold(equilibrium: Equilibrium, fold: Fold | None) -> Equilibrium:
    return equilibrium if fold is None else dataclasses.replace(equilibrium, fold=fold)


def _from_branch(
    wing: Wing,
    flight: FlightCondition,
    options: SolverOptions,
    started: float,
    prior_iterations: int,
) -> Equilibrium | None:
    """Newton from the continuation's state nearest in q, or None if it does not converge.

    The equilibrium reports the Newton iterations of both attempts; it is a warm start (from a
    traced branch state), whatever the caller's first start was.
    """
    q = flight.dynamic_pressure
    limit = search_velocity_limit(wing, flight.density, flight.velocity)
    branch = equilibrium_branch(wing, flight.alpha, 0.5 * flight.density * limit**2)
    model = model_for(wing.n_stations)
    p = wing.parameters(flight.alpha)
    result = newton(
        lambda x: model.evaluate(x, p),
        lambda x: model.residual(x, p),
        branch.start_for(q),
        q,
        options.tolerance,
        options.max_iterations,
    )
    if not result.converged:
        return None
    return equilibrium_from_state(
        wing,
        flight,
        result.x,
        result.evaluation,
        iterations=prior_iterations + result.iterations,
        residual_norm=result.residual_norm,
        warm_start=True,
        started=started,
    )
