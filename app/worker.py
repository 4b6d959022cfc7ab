"""What runs inside a worker process. Everything crossing the process boundary is plain data.

Jobs carry validated solver inputs (`Wing` and `FlightCondition` are dataclasses of numpy arrays
and floats); outcomes carry JSON-ready dicts shaped like the response models in `app.schemas`,
plus the solver state vectors that the service keeps for warm starts. No CasADi object ever
leaves the worker: each process builds (or loads from the disk cache) the compiled functions of a
mesh size once and keeps them for its lifetime.
"""

from __future__ import annotations

import dataclasses
import logging
import math
import os
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any, Literal, TypeVar

import numpy as np

from solver import (
    ConvergenceError,
    DivergenceSummary,
    Equilibrium,
    FlightCondition,
    NoEquilibrium,
    SolverError,
    SolverOptions,
    Wing,
    solve,
    sweep,
)
from solver.compiled import compile_now, model_for

__all__ = [
    "Failure",
    "SolveJob",
    "SolveOutcome",
    "SweepJob",
    "SweepOutcome",
    "WarmReport",
    "initialize",
    "run_solve",
    "run_sweep",
    "run_timed",
    "warm",
]

Payload = dict[str, Any]
T = TypeVar("T")

log = logging.getLogger(__name__)


@dataclass(frozen=True)
class SolveJob:
    wing: Wing
    flight: FlightCondition
    options: SolverOptions
    initial_guess: np.ndarray | None = None  # (4N - 1,) solver state
    # True when the service chose the guess (a stored stable equilibrium): a hint that must not
    # change the answer, unlike a guess the user supplied.
    hint: bool = False


@dataclass(frozen=True)
class SweepJob:
    wing: Wing
    velocities: tuple[float, ...]
    alpha: float
    density: float
    options: SolverOptions


@dataclass(frozen=True)
class Failure:
    """A solve that ended without an equilibrium, as data (solver exceptions do not pickle)."""

    kind: Literal["no_equilibrium", "not_converged"]
    message: str
    velocity: float
    fold_velocity: float | None = None
    iterations: int | None = None
    residual_norm: float | None = None
    reason: str | None = None


@dataclass(frozen=True)
class SolveOutcome:
    payload: Payload | None  # a SolveResponse as a dict
    failure: Failure | None
    state: np.ndarray | None = None  # converged solver state, for warm starts
    stable: bool = False


@dataclass(frozen=True)
class SweepOutcome:
    payload: Payload  # a SweepResponse as a dict
    # (dynamic pressure [Pa], state) of every stable equilibrium, for warm starts
    states: list[tuple[float, np.ndarray]] = field(default_factory=list)


@dataclass(frozen=True)
class WarmReport:
    pid: int
    compiled: dict[int, bool]


# ------------------------------------------------------------------------- process lifetime


# The local pool's shared arrays, by dispatch slot: job start time (time.monotonic()) and pid.
_starts: Any = None
_pids: Any = None


def initialize(
    warm_stations: tuple[int, ...], timeout: float, starts: Any = None, pids: Any = None
) -> None:
    """Pool initializer: compile or load the solver functions of the common mesh sizes.

    Never raises: a worker whose compilation failed still serves from CasADi's virtual machine.
    """
    global _starts, _pids
    if starts is not None:
        _starts, _pids = starts, pids
    for n in warm_stations:
        try:
            compile_now(n, timeout)
        except Exception:
            log.exception("warming N=%d failed; this worker uses CasADi's VM for it", n)


def warm(warm_stations: tuple[int, ...], timeout: float) -> WarmReport:
    """Warm this worker (a no-op after the initializer) and report what it serves compiled.

    Executors without an initializer (e.g. Dask's) are warmed by this job alone.
    """
    initialize(warm_stations, timeout)
    return WarmReport(os.getpid(), {n: model_for(n).compiled for n in warm_stations})


def run_timed(slot: int | None, fn: Callable[[Any], T], job: Any) -> T:
    """Run `fn(job)`, first noting its start in the pool's shared clock (its time budget)."""
    if slot is not None and _starts is not None:
        _pids[slot] = os.getpid()
        _starts[slot] = time.monotonic()
    return fn(job)


# ------------------------------------------------------------------------------- conversion


def _finite_or_none(value: float | None) -> float | None:
    return None if value is None or not math.isfinite(value) else float(value)


def _dataclass_payload(obj: Any) -> Payload:
    """A flat dataclass of numbers and strings as a dict, non-finite numbers as None."""
    return {
        k: (_finite_or_none(v) if isinstance(v, float) else v)
        for k, v in dataclasses.asdict(obj).items()
    }


def equilibrium_payload(eq: Equilibrium) -> Payload:
    """An equilibrium as a SolveResponse dict."""
    stability = eq.stability
    payload: Payload = {
        "stations": {
            "y": eq.y.tolist(),
            "heave": eq.heave.tolist(),
            "slope": eq.slope.tolist(),
            "twist": eq.twist.tolist(),
            "shear": eq.shear.tolist(),
            "bending_moment": eq.bending_moment.tolist(),
            "torque": eq.torque.tolist(),
        },
        "panels": {
            "y": eq.panel_y.tolist(),
            "lift": eq.panel_lift.tolist(),
            "lift_per_span": eq.panel_lift_per_span.tolist(),
            "torque": eq.panel_torque.tolist(),
        },
        "totals": {
            "lift": eq.lift,
            "induced_drag": eq.induced_drag,
            "CL": eq.CL,
            "CDi": eq.CDi,
            "CL_deformed_area": eq.CL * eq.reference_area / eq.deformed_area,
            "reference_area": eq.reference_area,
            "deformed_area": eq.deformed_area,
            "rigid_lift": eq.rigid_lift,
            "lift_amplification": _finite_or_none(eq.lift_amplification),
            "tip_heave": eq.tip_heave,
            "tip_twist": eq.tip_twist,
            "root_bending_moment": eq.root_bending_moment,
            "root_torque": eq.root_torque,
        },
        "stability": {
            "stable": stability.stable,
            "margin": stability.margin,
            "local_divergence_pressure": stability.local_divergence_pressure,
            "divergence_dynamic_pressure": stability.divergence_dynamic_pressure,
            "divergence_velocity": stability.divergence_velocity,
        },
        "solver": {
            "iterations": eq.iterations,
            "residual_norm": eq.residual_norm,
            "warm_start": eq.warm_start,
            "seconds": eq.seconds,
            "cached": False,
        },
    }
    if eq.fold is not None:
        payload["fold"] = _dataclass_payload(eq.fold)
    return payload


def _failure(error: SolverError, velocity: float) -> Failure:
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


# --------------------------------------------------------------------------------- the jobs


def _solve(job: SolveJob) -> Equilibrium:
    if job.hint:
        # A stored state is only the service's hint: it may save time, never change the answer.
        return solve(job.wing, job.flight, options=job.options, hint=job.initial_guess)
    return solve(job.wing, job.flight, job.initial_guess, job.options)


def run_solve(job: SolveJob) -> SolveOutcome:
    """One equilibrium, or the reason there is none."""
    try:
        eq = _solve(job)
    except SolverError as error:
        return SolveOutcome(None, _failure(error, job.flight.velocity))
    return SolveOutcome(equilibrium_payload(eq), None, eq.state, eq.stability.stable)


def _divergence_payload(summary: DivergenceSummary) -> Payload:
    return {
        "linear": _dataclass_payload(summary.linear),
        "fit": _dataclass_payload(summary.fit),
        "fold": _dataclass_payload(summary.fold),
    }


def run_sweep(job: SweepJob) -> SweepOutcome:
    started = time.perf_counter()
    result = sweep(job.wing, list(job.velocities), job.alpha, job.density, job.options)
    points: list[Payload] = []
    states: list[tuple[float, np.ndarray]] = []
    for point in result.points:
        eq = point.equilibrium
        if eq is not None:
            points.append(
                {
                    "velocity": point.velocity,
                    "status": "equilibrium",
                    "equilibrium": equilibrium_payload(eq),
                    "no_equilibrium": None,
                }
            )
            if eq.stability.stable:
                states.append((eq.dynamic_pressure, eq.state))
            continue
        error = point.error if point.error is not None else SolverError("no result")
        failure = _failure(error, point.velocity)
        points.append(
            {
                "velocity": point.velocity,
                "status": failure.kind,
                "equilibrium": None,
                "no_equilibrium": {
                    "reason": failure.message,
                    "fold_velocity": failure.fold_velocity,
                },
            }
        )
    payload = {
        "points": points,
        "divergence": _divergence_payload(result.divergence),
        "solver": {"seconds": time.perf_counter() - started, "cached": False},
    }
    return SweepOutcome(payload, states)
