"""The static aeroelastic equilibrium of one wing at one flight condition: the policy.

The answer is the equilibrium on the branch from the jig shape at the requested dynamic
pressure, if that equilibrium exists and is statically stable; otherwise a typed error. It is
found by following the branch in q from the rigid jig (`solver.numerics.path`), or from a `hint` (an
earlier answer for the same wing and alpha) when one is given, and when that path does not end in
a stable equilibrium the branch's pseudo-arclength continuation decides (`solver.statics.recovery`).

Without a hint or an initial guess, every step is a deterministic function of the wing, the
flight condition and the options: the same request gives the same bits in a fresh process and
after any number of other requests. A hint only shortens the path: the answer agrees with the
cold one to the residual tolerance times the problem's conditioning (~1e-9 relative on the
study's wing). A caller's `initial_guess` may reach another equilibrium than the jig branch's;
it is then returned with `stability.branch == "other"`.
"""

from __future__ import annotations

import dataclasses
import time

import numpy as np

from solver.errors import InvalidInput, SolverError, numerical_failures_as
from solver.fields import prefixed
from solver.inputs.flight import FlightCondition, OperatingPoint
from solver.inputs.options import InitialGuess, SolverOptions
from solver.inputs.wing import Wing
from solver.numerics.branch_points import scaled_norm
from solver.numerics.newton import newton
from solver.numerics.path import PathSettings, follow
from solver.results.equilibrium import Equilibrium
from solver.statics.branch import fold, pressure_scale, search_velocity_limit
from solver.statics.jig import jig
from solver.statics.recovery import settle
from solver.statics.system import CoupledSystem
from solver.statics.trim import trim
from solver.statics.verdict import judge

__all__ = ["SAME_EQUILIBRIUM", "solve"]

# Two converged states closer than this (scaled coordinates, `solver.numerics.continuation`) are the
# same equilibrium: the residual tolerance times the conditioning is far below it, and distinct
# equilibria of a wing lie far above it.
SAME_EQUILIBRIUM = 1e-6


def solve(
    wing: Wing,
    flight: FlightCondition | OperatingPoint,
    initial_guess: np.ndarray | InitialGuess | None = None,
    options: SolverOptions | None = None,
    *,
    hint: Equilibrium | None = None,
) -> Equilibrium:
    """The static aeroelastic equilibrium of `wing` at `flight`: at its angle of attack, or
    trimmed to its lift (`solver.trim`: alpha solved for).

    initial_guess: (n,) a state to start Newton from (unknowns as in `solver.model.layout`), or an
        `InitialGuess` deformation (flight at a given alpha only). If Newton
        converges from it to an equilibrium other than the jig branch's, that equilibrium is
        returned, flagged `stability.branch == "other"` (and `stable` says whether it is); if it
        reaches the jig branch's, or fails, the answer is the one without a guess.
    hint: an earlier answer for the same wing and alpha; it may only save time. Ignored unless it
        lies on the jig's branch and is stable.
    Raises `NoEquilibrium` beyond the fold of the branch (or where its equilibrium is unstable),
    `ConvergenceError` when no answer could be reached, `InvalidInput` for a guess that is not a
    finite state of this wing's mesh, or a guess and a hint together.
    """
    started = time.perf_counter()
    options = options or SolverOptions()
    if isinstance(flight, OperatingPoint):  # an answer's own point: solved at its alpha
        flight = FlightCondition(
            flight.velocity, flight.alpha, flight.density, load_factor=flight.load_factor
        )
    if flight.velocity is None:
        raise InvalidInput("velocity", "is required: the airspeed to solve at")
    if isinstance(initial_guess, InitialGuess):
        with prefixed("initial_guess"):
            initial_guess = initial_guess.state(wing.n_stations, options.chordwise_panels)
            if options.structure == "geometrically_exact":  # its slope unknown: the rotation
                n = wing.n_stations
                slope = initial_guess[n : 2 * n]
                initial_guess[n : 2 * n] = np.arcsin(np.clip(slope, -1.0, 1.0))
                if wing.in_plane_bending_stiffness is not None:  # lag: v, psi start at zero
                    initial_guess = np.insert(initial_guess, 3 * n, np.zeros(2 * n))
    if flight.alpha is None:
        if initial_guess is not None:
            raise InvalidInput(
                "initial_guess",
                "a starting deformation is for flight at a given alpha; a trimmed solve starts "
                "from the rigid jig trimmed to the same lift",
            )
        return trim(wing, flight, options)
    if hint is not None and initial_guess is not None:
        raise InvalidInput("initial_guess", "give an initial_guess or a hint, not both")
    point = flight.at_alpha(flight.alpha)
    system = CoupledSystem.of(wing, point.alpha, options).with_inertia(
        flight.inertial_load_factor, point.dynamic_pressure
    )
    with numerical_failures_as(point.velocity):
        if initial_guess is not None:
            equilibrium = _from_initial_guess(system, point, initial_guess, options, started)
        else:
            equilibrium = _on_branch(system, point, options, started, _usable(system, hint))
        if options.find_fold:
            # The branch of the wing at this alpha under its lift alone: its own divergence.
            unloaded = system.unloaded
            limit = search_velocity_limit(unloaded, point.density, point.velocity)
            equilibrium = dataclasses.replace(
                equilibrium, fold=fold(unloaded, point.density, limit)
            )
    return equilibrium


def _usable(system: CoupledSystem, hint: Equilibrium | None) -> Equilibrium | None:
    """The hint if it is a stable jig-branch answer of this wing at this alpha, else None."""
    if hint is None:
        return None
    hinted = CoupledSystem.of(hint.wing, hint.flight.alpha, hint.options)
    same = hinted.key == system.key
    on_branch = hint.stability.branch == "jig" and hint.stability.stable
    return hint if same and on_branch else None


def _path_settings(options: SolverOptions) -> PathSettings:
    return PathSettings(max_corrector_iterations=min(options.max_iterations, 8))


def _on_branch(
    system: CoupledSystem,
    flight: OperatingPoint,
    options: SolverOptions,
    started: float,
    hint: Equilibrium | None,
) -> Equilibrium:
    """Follow the branch from the jig (or the hint) to q; the branch decides if that fails."""
    q = flight.dynamic_pressure
    if hint is not None:
        start, start_q, start_evaluation = hint.state, hint.dynamic_pressure, hint.evaluation
    else:
        rigid = jig(system)
        start, start_q, start_evaluation = rigid.state, 0.0, rigid.evaluation
    path = follow(
        system.evaluate,
        system.residual,
        start,
        start_q,
        start_evaluation,
        q,
        system.scale(pressure_scale(system)),
        options.tolerance,
        _path_settings(options),
    )
    if path.reached:
        equilibrium = judge(
            system,
            flight,
            options,
            path.x,
            path.evaluation,
            iterations=path.iterations,
            residual_norm=path.residual_norm,
            warm_start=hint is not None,
            started=started,
        )
        if equilibrium.stability.stable:
            return equilibrium
    return settle(system, flight, options, path.iterations, started)


def _from_initial_guess(
    system: CoupledSystem,
    flight: OperatingPoint,
    initial_guess: np.ndarray,
    options: SolverOptions,
    started: float,
) -> Equilibrium:
    """Newton from the caller's state; the jig branch's answer unless it reached another."""
    n = system.layout.n_unknowns
    guess = np.asarray(initial_guess, dtype=float)
    if guess.shape != (n,) or not np.all(np.isfinite(guess)):
        raise InvalidInput("initial_guess", f"must be a finite state of shape ({n},)")
    q = flight.dynamic_pressure
    result = newton(
        system.evaluate,
        system.residual,
        guess,
        q,
        options.tolerance,
        options.max_iterations,
    )
    try:
        on_branch: Equilibrium | None = _on_branch(system, flight, options, started, None)
    except SolverError:
        if not result.converged:
            raise
        on_branch = None
    if not result.converged:
        assert on_branch is not None
        return on_branch
    scale = system.scale(pressure_scale(system))
    if on_branch is not None and scaled_norm(result.x - on_branch.state, scale) <= SAME_EQUILIBRIUM:
        return on_branch
    return judge(
        system,
        flight,
        options,
        result.x,
        result.evaluation,
        iterations=result.iterations,
        residual_norm=result.residual_norm,
        warm_start=True,
        started=started,
        branch="other",
    )
