"""Tasks on any `concurrent.futures.Executor` (FLEXWING_EXECUTOR=module:callable).

The callable takes the Settings and returns the executor. Warm-up is one `worker.warm` task per
configured worker. The executor owns its workers, so this backend cannot see their start times nor
kill them: a task's time budget counts from its submission, and a task past it gets `BudgetExceeded`
while it runs on to its end. An executor that breaks (`BrokenExecutor`) or drops a task fails that
task with `WorkerDied`.
"""

from __future__ import annotations

import asyncio
import logging
from collections.abc import Callable
from concurrent.futures import BrokenExecutor, Executor, Future
from typing import Any, TypeVar

from app.execution import worker
from app.execution.pool import (
    BackendState,
    BudgetExceeded,
    ClusterWorkerInfo,
    NotReady,
    Progress,
    WorkerDied,
)
from app.settings import Settings

__all__ = ["ExecutorWorkers"]

log = logging.getLogger(__name__)

T = TypeVar("T")


class ExecutorWorkers(BackendState):
    def __init__(self, settings: Settings, factory: Callable[[Settings], Executor]) -> None:
        super().__init__(settings, settings.workers * settings.tasks_per_worker)
        self.factory = factory
        self._executor: Executor | None = None
        self._in_flight: set[Future[Any]] = set()
        self._warming: asyncio.Task[None] | None = None

    @property
    def parallelism(self) -> int:
        return self.settings.workers

    def pids(self) -> list[int]:
        return []

    def running(self) -> int:
        return sum(1 for future in self._in_flight if future.running())

    def cluster(self) -> list[ClusterWorkerInfo] | None:
        return None

    async def start(self) -> None:
        self._executor = self.factory(self.settings)
        self._warming = asyncio.create_task(self._warm(self._executor), name="flexwing-warm")

    async def _warm(self, executor: Executor) -> None:
        """One warm task per configured worker."""
        self._detail = f"warming {self.settings.workers} worker(s) for N = {self.warm_stations}"
        timeout = self.settings.warmup_timeout
        futures = [
            asyncio.wrap_future(executor.submit(worker.warm, self.warm_stations, timeout))
            for _ in range(self.settings.workers)
        ]
        try:
            reports = await asyncio.gather(*futures)
        except Exception as error:  # e.g. a remote executor that cannot run the task
            log.exception("warming the workers failed")
            self._detail = f"warm-up failed: {type(error).__name__}: {error}"
            return
        compiled = all(all(r.compiled.values()) for r in reports)
        self._detail = "ready" + ("" if compiled else " (some mesh sizes on CasADi's VM)")
        self._started = True
        self._ready.set()

    async def close(self) -> None:
        self._closing = True
        self._ready.set()
        if self._warming is not None:
            self._warming.cancel()
        if self._executor is not None:
            self._executor.shutdown(wait=False, cancel_futures=True)
        self._detail = "closed"

    async def attempt(
        self,
        fn: Callable[..., T],
        task: Any,
        timeout: float,
        progress: Progress | None = None,
        affinity: bytes | None = None,
    ) -> T:
        """(`progress` is not reported from here: a task's progress arrives with its end; an
        executor chooses its own worker, whatever the `affinity`.)"""
        async with self._slots.slot():
            await self._ready.wait()
            if self._closing or self._executor is None:
                raise NotReady("the service is shutting down")
            try:
                future = self._executor.submit(fn, task)
            except (BrokenExecutor, RuntimeError) as error:
                raise WorkerDied(f"the executor refuses tasks: {error}") from None
            self._in_flight.add(future)
            future.add_done_callback(self._in_flight.discard)
            return await self._outcome(future, timeout)

    @staticmethod
    async def _outcome(future: Future[T], timeout: float) -> T:
        try:
            return await asyncio.wait_for(asyncio.wrap_future(future), timeout)
        except TimeoutError:
            raise BudgetExceeded(timeout) from None
        except BrokenExecutor as error:
            raise WorkerDied(str(error)) from None
        except asyncio.CancelledError:
            task = asyncio.current_task()
            if future.cancelled() and not (task is not None and task.cancelling()):
                raise WorkerDied("the executor dropped the task") from None
            raise
