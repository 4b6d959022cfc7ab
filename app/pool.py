"""The worker pool: solves run in other processes, never on the event loop.

Work goes through the `concurrent.futures.Executor` interface only, so the local
`ProcessPoolExecutor` can be swapped by configuration (`FLEXWING_EXECUTOR=module:factory`) for
any executor, e.g. a Dask ``Client(...).get_executor()``. On top of it this module adds:

- warm-up: every worker compiles or loads the solver functions of the common mesh sizes before
  the pool is ready (the pool initializer, plus one `worker.warm` job per worker);
- bounded concurrency: at most `workers` jobs are handed to the executor at once, so a job's time
  budget counts its run, not its wait; at most `max_pending` jobs run or wait, beyond that the
  request is shed (`Overloaded`);
- worker death: a dead process breaks a `ProcessPoolExecutor`; the pool is rebuilt, the jobs it
  carried are retried once (setting) or fail with `WorkerLost`;
- time budget: a job past its budget fails with `SolveTimeout` and its pool is recycled (its
  processes killed), since a running job cannot be cancelled otherwise.
"""

from __future__ import annotations

import asyncio
import contextlib
import importlib
import logging
import multiprocessing
import os
from collections.abc import Callable
from concurrent.futures import Executor, Future, ProcessPoolExecutor
from concurrent.futures.process import BrokenProcessPool
from typing import Any, TypeVar

from app import worker
from app.metrics import Metrics
from app.settings import Settings

__all__ = ["NotReady", "Overloaded", "PoolError", "SolveTimeout", "WorkerLost", "WorkerPool"]

log = logging.getLogger(__name__)

T = TypeVar("T")

# Threads of numerical libraries per worker: the pool is the parallelism.
_THREAD_VARIABLES = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")
_WATCH_INTERVAL = 0.5  # [s] how often an idle pool is checked for dead workers


class PoolError(Exception):
    """A job could not be run; the subclasses say why."""


class Overloaded(PoolError):
    pass


class NotReady(PoolError):
    pass


class WorkerLost(PoolError):
    pass


class SolveTimeout(PoolError):
    def __init__(self, timeout: float) -> None:
        super().__init__(f"the job ran longer than its budget of {timeout:g} s")
        self.timeout = timeout


def _load_factory(path: str) -> Callable[[Settings], Executor]:
    module, _, name = path.partition(":")
    if not module or not name:
        raise ValueError(f"FLEXWING_EXECUTOR must be 'process' or 'module:callable', not {path!r}")
    factory: Callable[[Settings], Executor] = getattr(importlib.import_module(module), name)
    return factory


class WorkerPool:
    def __init__(self, settings: Settings, metrics: Metrics) -> None:
        self.settings = settings
        self.metrics = metrics
        self.warm_stations = tuple(settings.warm_stations)
        self._executor: Executor | None = None
        self._generation = 0
        self._ready = asyncio.Event()  # the current executor is warm
        self._started = False  # the first executor has been warm once
        self._closing = False
        self._slots = asyncio.Semaphore(settings.workers)
        self._pending = 0
        self._warming: asyncio.Task[None] | None = None
        self._watchdog: asyncio.Task[None] | None = None
        self.detail = "not started"

    # ------------------------------------------------------------------------- lifecycle

    @property
    def ready(self) -> bool:
        return self._ready.is_set() and not self._closing

    def pids(self) -> list[int]:
        if isinstance(self._executor, ProcessPoolExecutor):
            processes = getattr(self._executor, "_processes", None) or {}
            return sorted(pid for pid, p in processes.items() if p.is_alive())
        return []

    async def start(self) -> None:
        """Create the executor and begin warming it; returns at once (see `ready`)."""
        for variable in _THREAD_VARIABLES:
            os.environ.setdefault(variable, "1")
        self._replace_executor()
        self._watchdog = asyncio.create_task(self._watch(), name="flexwing-pool-watchdog")

    async def wait_ready(self, timeout: float | None = None) -> bool:
        with contextlib.suppress(TimeoutError):
            await asyncio.wait_for(self._ready.wait(), timeout)
        return self.ready

    async def close(self) -> None:
        self._closing = True
        self._ready.clear()
        for task in (self._watchdog, self._warming):
            if task is not None:
                task.cancel()
                with contextlib.suppress(asyncio.CancelledError, Exception):
                    await task
        if self._executor is not None:
            await asyncio.to_thread(self._dispose, self._executor)
            self._executor = None
        self.metrics.ready.set(0)
        self.detail = "closed"

    def _make_executor(self) -> Executor:
        if self.settings.executor != "process":
            return _load_factory(self.settings.executor)(self.settings)
        context = multiprocessing.get_context(self.settings.start_method)
        if self.settings.start_method == "forkserver":
            # New workers fork from a server that has already imported solver and casadi.
            context.set_forkserver_preload(["app.worker"])
        return ProcessPoolExecutor(
            max_workers=self.settings.workers,
            mp_context=context,
            initializer=worker.initialize,
            initargs=(self.warm_stations, self.settings.warmup_timeout),
        )

    def _replace_executor(self) -> None:
        self._generation += 1
        self._ready.clear()
        self.metrics.ready.set(0)
        self._executor = self._make_executor()
        if self._warming is not None:
            self._warming.cancel()
        self._warming = asyncio.create_task(
            self._warm(self._executor, self._generation), name="flexwing-pool-warm"
        )

    async def _warm(self, executor: Executor, generation: int) -> None:
        """One warm job per worker; each worker's initializer compiles or loads first."""
        self.detail = f"warming {self.settings.workers} worker(s) for N = {self.warm_stations}"
        futures = [
            executor.submit(worker.warm, self.warm_stations, self.settings.warmup_timeout)
            for _ in range(self.settings.workers)
        ]
        try:
            reports = await asyncio.gather(*(asyncio.wrap_future(f) for f in futures))
        except BrokenProcessPool:
            if generation == self._generation and not self._closing:
                self._recycle(generation, "died")
            return
        except Exception as error:  # e.g. a remote executor that cannot run the job
            log.exception("warming the worker pool failed")
            self.detail = f"warm-up failed: {type(error).__name__}: {error}"
            return
        if generation != self._generation or self._closing:
            return
        compiled = all(all(r.compiled.values()) for r in reports)
        self.detail = "ready" + ("" if compiled else " (some mesh sizes on CasADi's VM)")
        self._started = True
        self._ready.set()
        self.metrics.ready.set(1)

    async def _watch(self) -> None:
        """Replace a process pool whose worker died while it was idle."""
        while not self._closing:
            await asyncio.sleep(_WATCH_INTERVAL)
            executor = self._executor
            if isinstance(executor, ProcessPoolExecutor) and getattr(executor, "_broken", False):
                self._recycle(self._generation, "died")

    def _recycle(self, generation: int, reason: str) -> None:
        """Replace the executor of `generation` (once: later calls for it do nothing)."""
        if generation != self._generation or self._closing or self._executor is None:
            return
        old = self._executor
        replaced = len(self.pids()) if reason == "timeout" else self.settings.workers
        log.warning("replacing the worker pool (%s)", reason)
        self.metrics.worker_restarts.labels(reason).inc(replaced)
        self._replace_executor()
        self._dispose(old)

    @staticmethod
    def _dispose(executor: Executor) -> None:
        """Stop an executor without waiting for its running jobs: kill local processes."""
        processes = list((getattr(executor, "_processes", None) or {}).values())
        for process in processes:
            with contextlib.suppress(Exception):
                process.kill()
        executor.shutdown(wait=False, cancel_futures=True)
        for process in processes:
            with contextlib.suppress(Exception):
                process.join(timeout=5)

    # --------------------------------------------------------------------------- running

    async def run(self, fn: Callable[[Any], T], job: Any, *, timeout: float, kind: str) -> T:
        """Run `fn(job)` in a worker within `timeout` seconds of its start."""
        if not self._started or self._closing:
            raise NotReady(self.detail)
        if self._pending >= self.settings.max_pending:
            self.metrics.shed.inc()
            raise Overloaded(f"{self._pending} jobs are already running or waiting")
        self._pending += 1
        self.metrics.pending.set(self._pending)
        try:
            return await self._run(fn, job, timeout, kind)
        finally:
            self._pending -= 1
            self.metrics.pending.set(self._pending)

    async def _run(self, fn: Callable[[Any], T], job: Any, timeout: float, kind: str) -> T:
        attempts = 2 if self.settings.retry_on_worker_loss else 1
        attempt = 0
        refused = 0
        while True:
            async with self._slots:
                await self._ready.wait()
                executor, generation = self._executor, self._generation
                assert executor is not None
                try:
                    future: Future[T] = executor.submit(fn, job)
                except (BrokenProcessPool, RuntimeError) as error:
                    # The pool broke while idle: this job never ran, so no attempt is spent.
                    refused += 1
                    if refused > 2:
                        raise WorkerLost(f"the executor refuses jobs: {error}") from None
                    self._recycle(generation, "died")
                    continue
                try:
                    return await asyncio.wait_for(asyncio.wrap_future(future), timeout)
                except TimeoutError:
                    self.metrics.solves.labels(kind, "timeout").inc()
                    if not future.cancel() and isinstance(executor, ProcessPoolExecutor):
                        # A running job cannot be cancelled: kill its process (and pool).
                        self._recycle(generation, "timeout")
                    raise SolveTimeout(timeout) from None
                except BrokenProcessPool:
                    self._recycle(generation, "died")
                    attempt += 1
                    if attempt >= attempts:
                        self.metrics.solves.labels(kind, "worker_lost").inc()
                        raise WorkerLost(
                            "the worker process running this request died"
                            + (" twice" if attempts > 1 else "")
                        ) from None
                    log.warning("retrying a %s whose worker died", kind)
