"""Between the routes and the workers: one path for every operation.

request model -> `task` (the service's limits, then the solver input it describes: the
request's one change of form) -> result cache -> the pool runs `app.execution.worker.run` ->
result cache -> the response body the worker serialised (`app.schemas.Answer`), or the problem
its error maps to (`app.problems`).

The service keeps no solver state between requests: every solve starts from the wing itself, so
the answer to a request never depends on the requests before it.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence
from typing import Any, TypeVar

from pydantic import BaseModel

import solver
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
from app.schemas.responses import Answer
from app.settings import Settings
from solver import InvalidInput, SolverError

__all__ = ["Service", "budget_of", "parts_of", "task_of"]

T = TypeVar("T")


# Operation name -> its row of the solver's table: its time budget and metric label.
_TABLE: dict[str, solver.Operation] = {
    operation.name: operation for operation in solver.OPERATION_TABLE
}


def parts_of(operation: str, task: Any) -> int:
    """[-] how many parts the solver input `task` of `operation` reports progress in."""
    return _TABLE[operation].count_parts(task)


def budget_of(operation: str, settings: Settings) -> float:
    """[s] the time budget of one answer of `operation` (FLEXWING_<BUDGET>_TIMEOUT)."""
    seconds: float = getattr(settings, f"{_TABLE[operation].budget}_timeout")
    return seconds


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
        self.results: ResultCache[Answer | SolverError | InvalidInput] = ResultCache(
            settings.result_cache_bytes
        )

    def task(self, request: BaseModel) -> Any:
        """The solver input of a validated request (`task_of`)."""
        return task_of(request, self.settings)

    async def answer(
        self, operation: str, request: BaseModel, progress: Progress | None = None
    ) -> bytes:
        """The response body of `request` to `operation` (a name of `solver.OPERATION_TABLE`),
        or the problem that says why there is none; `progress(done, total)` as its parts are
        done."""
        return await self.run(operation, self.task(request), progress)

    async def run(self, operation: str, task: Any, progress: Progress | None = None) -> bytes:
        """The response body of a solver input's answer: from the result cache (marked so) or
        from a worker (and then cached)."""
        key = (operation, task.key)
        hit = self._cached(key)
        if hit is not None:
            return hit
        budget = budget_of(operation, self.settings)
        outcome = await self._in_a_worker(worker.run, task, budget, operation, progress)
        return self._recorded(operation, key, outcome)

    async def run_each(self, operation: str, tasks: Sequence[Any]) -> list[bytes | Problem]:
        """The answers of many inputs of one operation (a batch's chunk), each its response
        body or its problem: cached ones from the cache, the others as one worker task (one
        round trip, one Dask task, for all of them) whose budget is theirs together.

        Raises the pool's problem when the chunk could not be answered as a whole (the pool
        full or not ready, its worker lost, its budget spent): the caller decides whether to
        wait, or to ask again one input at a time.
        """
        keys = [(operation, task.key) for task in tasks]
        answers: list[bytes | Problem | None] = []
        for key in keys:
            try:
                answers.append(self._cached(key))
            except Problem as problem:
                answers.append(problem)
        missing = [i for i, answer in enumerate(answers) if answer is None]
        if missing:
            budget = budget_of(operation, self.settings) * len(missing)
            chunk = tuple(tasks[i] for i in missing)
            outcomes = await self._in_a_worker(worker.run_each, chunk, budget, operation, None)
            for i, outcome in zip(missing, outcomes, strict=True):
                try:
                    answers[i] = self._recorded(operation, keys[i], outcome)
                except Problem as problem:
                    answers[i] = problem
        return [answer for answer in answers if answer is not None]

    def _cached(self, key: tuple[str, bytes]) -> bytes | None:
        """The cached answer's body (marked as cached), its problem raised, or None."""
        hit = self.results.get(key)
        self.metrics.cache.labels("result", "miss" if hit is None else "hit").inc()
        if isinstance(hit, SolverError | InvalidInput):
            raise problem_of(hit)
        return None if hit is None else hit.body(cached=True)

    def _recorded(self, operation: str, key: tuple[str, bytes], outcome: worker.Outcome) -> bytes:
        """A worker's outcome counted and cached: its body, or its problem raised."""
        if outcome.error is not None:
            self.metrics.solves.labels(operation, _label(outcome.error)).inc()
            self.results.put(key, outcome.error)
            raise problem_of(outcome.error)
        answer = outcome.answer
        assert answer is not None
        self.metrics.solves.labels(operation, _TABLE[operation].answered).inc()
        self.results.put(key, answer, answer.nbytes)
        return answer.body()

    async def _in_a_worker(
        self,
        fn: Callable[..., T],
        task: Any,
        budget: float,
        operation: str,
        progress: Progress | None,
    ) -> T:
        """Run `fn(task)` in the pool; the pool's failures become 503/504 problems."""
        started = time.perf_counter()
        retry_after = {"Retry-After": str(self.settings.retry_after)}
        try:
            outcome = await self.pool.run(
                fn, task, timeout=budget, kind=operation, progress=progress
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
        if fn is worker.run:  # a chunk's time is not one answer's
            self.metrics.solve_seconds.labels(operation).observe(time.perf_counter() - started)
        return outcome
