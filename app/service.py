"""Between the routes and the workers: one path for every operation.

request model -> `task` (the service's limits, then the solver input it describes: the
request's one change of form) -> result cache -> the pool runs `app.execution.worker.run` ->
result cache -> the response's payload, or the problem its error maps to (`app.problems`).

The service keeps no solver state between requests: every solve starts from the wing itself, so
the answer to a request never depends on the requests before it.
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from typing import Any

from pydantic import BaseModel

from app.cache import ResultCache
from app.execution import worker
from app.execution.pool import (
    BudgetExceeded,
    NotReady,
    Overloaded,
    Progress,
    WorkerLost,
    WorkerPool,
)
from app.metrics import Metrics
from app.problems import FieldError, Problem, problem_of
from app.schemas.derive import RequestModel
from app.schemas.limits import panel_errors, station_and_point_errors
from app.settings import Settings
from solver import InvalidInput, SolverError

__all__ = ["OPERATIONS", "Operation", "Service", "task_of"]

Payload = dict[str, Any]


@dataclass(frozen=True)
class Operation:
    """A synchronous operation: the setting that holds its time budget, and the label its
    successes carry in the solves metric."""

    name: str
    budget: str
    answered: str


OPERATIONS = {
    "solve": Operation("solve", "solve_timeout", "equilibrium"),
    "sweep": Operation("sweep", "sweep_timeout", "completed"),
    "optimize": Operation("optimize", "optimize_timeout", "optimum"),
    "flutter": Operation("flutter", "flutter_timeout", "analysed"),
}


def _cached(payload: Payload) -> Payload:
    """A payload answered from the result cache says so, where it has a `solver` block."""
    if "solver" not in payload:
        return payload
    return payload | {"solver": payload["solver"] | {"cached": True, "seconds": 0.0}}


def _label(error: SolverError | InvalidInput) -> str:
    """The solves metric's outcome of a failure: its problem type (no_equilibrium, ...)."""
    return problem_of(error).type.slug.replace("-", "_")


def task_of(request: BaseModel, settings: Settings) -> Any:
    """The solver input a validated request describes, within the service's limits; raises
    the invalid-input problem naming every bad field (from the request's root)."""
    errors = station_and_point_errors(request, settings)
    if errors:
        raise Problem.invalid(errors)
    assert isinstance(request, RequestModel)
    try:
        task = request.to_solver()
    except InvalidInput as error:
        raise Problem.invalid([FieldError(error.field or "body", error.reason)]) from None
    errors = panel_errors(task, settings)
    if errors:
        raise Problem.invalid(errors)
    return task


class Service:
    def __init__(self, settings: Settings, pool: WorkerPool, metrics: Metrics) -> None:
        self.settings = settings
        self.pool = pool
        self.metrics = metrics
        self.results: ResultCache[Payload | SolverError | InvalidInput] = ResultCache(
            settings.result_cache_bytes
        )

    def task(self, request: BaseModel) -> Any:
        """The solver input of a validated request (`task_of`)."""
        return task_of(request, self.settings)

    async def answer(
        self, operation: str, request: BaseModel, progress: Progress | None = None
    ) -> Payload:
        """The response payload of `request` to `operation` (a key of `OPERATIONS`), or the
        problem that says why there is none; `progress(done, total)` as its parts are done."""
        return await self.run(operation, self.task(request), progress)

    async def run(self, operation: str, task: Any, progress: Progress | None = None) -> Payload:
        """The payload of a solver input's answer: from the result cache (marked so) or from
        a worker (and then cached)."""
        key = (operation, task.key)
        hit = self.results.get(key)
        self.metrics.cache.labels("result", "miss" if hit is None else "hit").inc()
        if isinstance(hit, SolverError | InvalidInput):
            raise problem_of(hit)
        if hit is not None:
            return _cached(hit)
        kind = OPERATIONS[operation]
        budget = getattr(self.settings, kind.budget)
        outcome = await self._in_a_worker(task, budget, operation, progress)
        if outcome.error is not None:
            self.metrics.solves.labels(operation, _label(outcome.error)).inc()
            self.results.put(key, outcome.error)
            raise problem_of(outcome.error)
        assert outcome.payload is not None
        self.metrics.solves.labels(operation, kind.answered).inc()
        self.results.put(key, outcome.payload)
        return outcome.payload

    async def _in_a_worker(
        self, task: Any, budget: float, operation: str, progress: Progress | None
    ) -> worker.Outcome:
        """Run a task in the pool; the pool's failures become 503/504 problems."""
        started = time.perf_counter()
        retry_after = {"Retry-After": str(self.settings.retry_after)}
        try:
            outcome = await self.pool.run(
                worker.run, task, timeout=budget, kind=operation, progress=progress
            )
        except Overloaded as error:
            raise Problem("overloaded", str(error), headers=retry_after) from None
        except NotReady as error:
            raise Problem("not-ready", str(error), headers=retry_after) from None
        except WorkerLost as error:
            raise Problem("worker-lost", str(error), headers=retry_after) from None
        except BudgetExceeded as error:
            spent = {"timeout": error.timeout}
            raise Problem("solve-timeout", str(error), extensions=spent) from None
        self.metrics.solve_seconds.labels(operation).observe(time.perf_counter() - started)
        return outcome  # type: ignore[no-any-return]
