"""Between the routes and the pool: the result cache, and failures as problems.

request model -> `app.inputs` -> result cache -> `app.pool` runs `app.worker` -> result cache
-> response dict (validated against the response model by FastAPI)

The service keeps no solver state between requests: every solve starts from the wing itself, so
the answer to a request never depends on the requests before it.
"""

from __future__ import annotations

import dataclasses
import time
from collections.abc import Callable
from typing import Any, TypeVar

from app import worker
from app.cache import ResultCache
from app.inputs import optimize_input, solve_input, sweep_input
from app.metrics import Metrics
from app.pool import NotReady, Overloaded, SolveTimeout, WorkerLost, WorkerPool
from app.problems import FieldError, Problem
from app.schemas import OptimizeRequest, SolveRequest, SweepRequest
from app.settings import Settings

__all__ = ["Service"]

T = TypeVar("T")
Payload = dict[str, Any]


def _failure_problem(failure: worker.Failure) -> Problem:
    if failure.kind == "invalid_input":
        return Problem.invalid([FieldError(failure.field or "body", failure.message)])
    if failure.kind == "infeasible_design":
        return Problem(
            "infeasible-design", failure.message, extensions={"constraint": failure.constraint}
        )
    if failure.kind == "no_equilibrium":
        return Problem(
            "no-equilibrium",
            failure.message,
            extensions={"velocity": failure.velocity, "fold_velocity": failure.fold_velocity},
        )
    return Problem(
        "not-converged",
        failure.message,
        extensions={
            "velocity": failure.velocity,
            "iterations": failure.iterations,
            "residual_norm": failure.residual_norm,
            "reason": failure.reason,
        },
    )


def _cached(payload: Payload) -> Payload:
    return payload | {"solver": payload["solver"] | {"cached": True, "seconds": 0.0}}


class Service:
    def __init__(self, settings: Settings, pool: WorkerPool, metrics: Metrics) -> None:
        self.settings = settings
        self.pool = pool
        self.metrics = metrics
        self.results: ResultCache[Payload | worker.Failure] = ResultCache(
            settings.result_cache_bytes
        )

    async def _run(self, fn: Callable[[Any], T], job: Any, timeout: float, kind: str) -> T:
        """Run a job in the pool; pool failures become 503/504 problems."""
        started = time.perf_counter()
        retry_after = {"Retry-After": str(self.settings.retry_after)}
        try:
            result = await self.pool.run(fn, job, timeout=timeout, kind=kind)
        except Overloaded as error:
            raise Problem("overloaded", str(error), headers=retry_after) from None
        except NotReady as error:
            raise Problem("not-ready", str(error), headers=retry_after) from None
        except WorkerLost as error:
            raise Problem("worker-lost", str(error), headers=retry_after) from None
        except SolveTimeout as error:
            budget = {"timeout": error.timeout}
            raise Problem("solve-timeout", str(error), extensions=budget) from None
        self.metrics.solve_seconds.labels(kind).observe(time.perf_counter() - started)
        return result

    def _lookup(self, key: tuple[Any, ...]) -> Payload | worker.Failure | None:
        hit = self.results.get(key)
        self.metrics.cache.labels("result", "miss" if hit is None else "hit").inc()
        return hit

    async def _answer(
        self,
        kind: str,
        key: tuple[Any, ...],
        run: Callable[[Any], worker.SolveOutcome],
        job: Any,
        timeout: float,
        answered: str,
        from_cache: Callable[[Payload], Payload] = _cached,
    ) -> Payload:
        """One answer or its problem, from the result cache (`from_cache` marks it so) or the
        pool (and then cached); `answered` labels the solves metric of a success."""
        hit = self._lookup(key)
        if isinstance(hit, worker.Failure):
            raise _failure_problem(hit)
        if hit is not None:
            return from_cache(hit)
        outcome = await self._run(run, job, timeout, kind)
        if outcome.failure is not None:
            self.metrics.solves.labels(kind, outcome.failure.kind).inc()
            self.results.put(key, outcome.failure)
            raise _failure_problem(outcome.failure)
        assert outcome.payload is not None
        self.metrics.solves.labels(kind, answered).inc()
        self.results.put(key, outcome.payload)
        return outcome.payload

    async def solve(self, request: SolveRequest) -> Payload:
        inputs = solve_input(request, self.settings)
        flight = inputs.flight
        key = (
            "solve",
            inputs.wing.key,
            type(flight).__name__,
            dataclasses.astuple(flight),
            dataclasses.astuple(inputs.options),
            None if inputs.initial_guess is None else inputs.initial_guess.tobytes(),
        )
        job = worker.SolveJob(inputs.wing, flight, inputs.options, inputs.initial_guess)
        return await self._answer(
            "solve", key, worker.run_solve, job, self.settings.solve_timeout, "equilibrium"
        )

    async def sweep(self, request: SweepRequest) -> Payload:
        inputs = sweep_input(request, self.settings)
        key = (
            "sweep",
            inputs.wing.key,
            inputs.velocities,
            inputs.alpha,
            inputs.lift,
            inputs.density,
            dataclasses.astuple(inputs.options),
        )
        hit = self._lookup(key)
        if isinstance(hit, dict):
            return _cached(hit)
        job = worker.SweepJob(
            inputs.wing,
            inputs.velocities,
            inputs.alpha,
            inputs.density,
            inputs.options,
            inputs.lift,
        )
        outcome = await self._run(worker.run_sweep, job, self.settings.sweep_timeout, "sweep")
        if outcome.failure is not None:
            self.metrics.solves.labels("sweep", outcome.failure.kind).inc()
            raise _failure_problem(outcome.failure)
        assert outcome.payload is not None
        self.metrics.solves.labels("sweep", "completed").inc()
        self.results.put(key, outcome.payload)
        return outcome.payload

    async def optimize(self, request: OptimizeRequest) -> Payload:
        inputs = optimize_input(request, self.settings)
        key = (
            "optimize",
            inputs.wing.key,
            dataclasses.astuple(inputs.problem),
            dataclasses.astuple(inputs.options),
        )
        job = worker.OptimizeJob(inputs.wing, inputs.problem, inputs.options)
        timeout = self.settings.optimize_timeout
        # An optimum has no `solver` block to say it came from the cache: it is returned as is.
        return await self._answer(
            "optimize", key, worker.run_optimize, job, timeout, "optimum", lambda hit: hit
        )
