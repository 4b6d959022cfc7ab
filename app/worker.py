"""What runs inside a worker process. Everything crossing the process boundary is plain data.

Jobs carry validated solver inputs (`Wing` and `FlightCondition` are dataclasses of numpy arrays
and floats); outcomes carry JSON-ready payloads of the solver's results (`app.results`). No CasADi
object ever leaves the worker: each process builds (or loads from the disk cache) the compiled
functions of a mesh size once and keeps them in the solver's cache.
"""

from __future__ import annotations

import logging
import math
import os
from dataclasses import dataclass
from typing import Any, Literal

import numpy as np

from app.results import payload
from solver import (
    ConvergenceError,
    DesignProblem,
    FlightCondition,
    InfeasibleDesign,
    InvalidInput,
    NoEquilibrium,
    SolverError,
    SolverOptions,
    TrimCondition,
    Wing,
    optimize,
    solve,
    sweep,
    trim,
    trim_sweep,
    warm_up,
)

__all__ = [
    "Failure",
    "SolveJob",
    "SolveOutcome",
    "SweepJob",
    "SweepOutcome",
    "WarmReport",
    "OptimizeJob",
    "run_optimize",
    "run_solve",
    "run_sweep",
    "warm",
]

Payload = dict[str, Any]

log = logging.getLogger(__name__)


@dataclass(frozen=True)
class SolveJob:
    wing: Wing
    flight: FlightCondition | TrimCondition  # trimmed: alpha is solved for
    options: SolverOptions
    initial_guess: np.ndarray | None = None  # (n,) the caller's own starting state


@dataclass(frozen=True)
class SweepJob:
    """At `alpha` [deg], or trimmed to `lift` [N] when it is not None."""

    wing: Wing
    velocities: tuple[float, ...]
    alpha: float | None
    density: float
    options: SolverOptions
    lift: float | None = None


@dataclass(frozen=True)
class OptimizeJob:
    wing: Wing
    problem: DesignProblem
    options: SolverOptions


@dataclass(frozen=True)
class Failure:
    """A solve that ended without an equilibrium, as data (solver exceptions do not pickle).
    invalid_input: the solver refused an input the service's validation let through (a defect
    of that validation, still answered as the input's 422)."""

    kind: Literal["no_equilibrium", "not_converged", "infeasible_design", "invalid_input"]
    message: str
    velocity: float
    fold_velocity: float | None = None
    iterations: int | None = None
    residual_norm: float | None = None
    reason: str | None = None
    constraint: str | None = None  # infeasible_design: which one
    field: str | None = None  # invalid_input: which input


@dataclass(frozen=True)
class SolveOutcome:
    payload: Payload | None  # a SolveResponse as a dict
    failure: Failure | None


@dataclass(frozen=True)
class SweepOutcome:
    payload: Payload | None  # a SweepResponse as a dict
    failure: Failure | None = None  # only invalid_input: a sweep answers failures per point


@dataclass(frozen=True)
class WarmReport:
    pid: int
    compiled: dict[int, bool]


# ------------------------------------------------------------------------- process lifetime


def warm(warm_stations: tuple[int, ...], timeout: float) -> WarmReport:
    """Compile or load the solver functions of the common mesh sizes in this worker (each one
    waits up to `timeout` seconds) and report which are served compiled.

    Never raises: a worker whose compilation failed still serves from CasADi's virtual machine.
    """
    compiled = {}
    for n in warm_stations:
        try:
            compiled[n] = warm_up(n, timeout)
        except Exception:
            log.exception("warming N=%d failed; this worker uses CasADi's VM for it", n)
            compiled[n] = False
    return WarmReport(os.getpid(), compiled)


# --------------------------------------------------------------------------------- the jobs


def _finite_or_none(value: float | None) -> float | None:
    return None if value is None or not math.isfinite(value) else float(value)


def _failure(error: SolverError | InvalidInput, velocity: float) -> Failure:
    if isinstance(error, InvalidInput):
        return Failure("invalid_input", error.reason, velocity, field=error.field)
    if isinstance(error, InfeasibleDesign):
        return Failure("infeasible_design", str(error), velocity, constraint=error.constraint)
    if isinstance(error, NoEquilibrium):
        return Failure("no_equilibrium", str(error), velocity, fold_velocity=error.fold_velocity)
    if isinstance(error, ConvergenceError):
        return Failure(
            "not_converged",
            str(error),
            velocity,
            iterations=error.iterations,
            residual_norm=_finite_or_none(error.residual_norm),
            reason=error.reason,
        )
    return Failure("not_converged", str(error), velocity)


def run_solve(job: SolveJob) -> SolveOutcome:
    """One equilibrium, or the reason there is none."""
    try:
        if isinstance(job.flight, TrimCondition):
            equilibrium = trim(job.wing, job.flight, job.options)
        else:
            equilibrium = solve(job.wing, job.flight, job.initial_guess, job.options)
    except (SolverError, InvalidInput) as error:
        return SolveOutcome(None, _failure(error, job.flight.velocity))
    return SolveOutcome(payload(equilibrium), None)


def run_sweep(job: SweepJob) -> SweepOutcome:
    """Every point's equilibrium or its failure (in the payload), or the input refused."""
    try:
        if job.lift is not None:
            result = trim_sweep(job.wing, list(job.velocities), job.lift, job.density, job.options)
        else:
            assert job.alpha is not None
            result = sweep(job.wing, list(job.velocities), job.alpha, job.density, job.options)
    except InvalidInput as error:
        return SweepOutcome(None, _failure(error, max(job.velocities, default=0.0)))
    return SweepOutcome(payload(result))


def run_optimize(job: OptimizeJob) -> SolveOutcome:
    """One optimal design (an OptimizeResponse as a dict), or the reason there is none."""
    try:
        design = optimize(job.wing, job.problem, job.options)
    except (SolverError, InvalidInput) as error:
        return SolveOutcome(None, _failure(error, job.problem.velocity))
    return SolveOutcome(payload(design), None)
