"""The worker pool: solves run in other processes, never on the event loop.

Work goes through the `concurrent.futures.Executor` interface only, so the local
`ProcessPoolExecutor` can be swapped by configuration (`FLEXWING_EXECUTOR=module:factory`) for
any executor, e.g. a Dask ``Client(...).get_executor()``. On top of it this module adds:

- warm-up: every worker compiles or loads the solver functions of the common mesh sizes before
  the pool is ready (the pool initializer, plus one `worker.warm` job per worker);
- bounded concurrency: at most `jobs_per_worker` jobs per worker are handed to the executor at
  once (one running, the next queued behind it, so a worker never idles between jobs); at most
  `max_pending` jobs run or wait, beyond that the request is shed (`Overloaded`);
- worker death: a dead process breaks a `ProcessPoolExecutor`; the pool is rebuilt, the jobs it
  carried are retried once (setting) or fail with `WorkerLost`;
- time budget: a job running longer than its budget fails with `SolveTimeout` and its pool is
  recycled (its processes killed), since a running job cannot be cancelled otherwise. Local
  workers write each job's start time into shared memory, so the budget counts the run, not the
  wait behind another job; with another executor it counts from dispatch.
"""

from __future__ import annotations

import asyncio
import contextlib
import importlib
import logging
import multiprocessing
import os
import signal
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
        self._slots = asyncio.Semaphore(settings.workers * settings.jobs_per_worker)
        # Shared with local workers, by dispatch slot: when its job started (time.monotonic(),
        # 0 while queued) and in which process.
        self._free_slots = list(range(settings.workers * settings.jobs_per_worker))
        self._starts: Any = None
        self._pids: Any = None
        self._pending = 0
        self._warming: asyncio.Task[None] | None = None
        self._watchdog: asyncio.Task[None] | None = None
        self.detail = "not started"
        metrics.running.set_function(self.running)

    # ------------------------------------------------------------------------- lifecycle

    @property
    def ready(self) -> bool:
        return self._ready.is_set() and not self._closing

    def running(self) -> int:
        """Jobs running in local workers now (started, not yet collected)."""
        if self._starts is None:
            return 0
        return sum(1 for start in self._starts if start > 0.0)

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
            processes = self._dispose(self._executor)
            self._executor = None
            await asyncio.to_thread(lambda: [p.join(timeout=5) for p in processes])
        self.metrics.ready.set(0)
        self.detail = "closed"

    def _make_executor(self) -> Executor:
        if self.settings.executor != "process":
            return _load_factory(self.settings.executor)(self.settings)
        context = multiprocessing.get_context(self.settings.start_method)
        if self.settings.start_method == "forkserver":
            # New workers fork from a server that has already imported solver and casadi.
            context.set_forkserver_preload(["app.worker"])
        if self._starts is None:
            self._starts = context.RawArray("d", len(self._free_slots))
            self._pids = context.RawArray("q", len(self._free_slots))
        return ProcessPoolExecutor(
            max_workers=self.settings.workers,
            mp_context=context,
            initializer=worker.initialize,
            initargs=(self.warm_stations, self.settings.warmup_timeout, self._starts, self._pids),
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

    def _recycle(self, generation: int, reason: str, victim: int | None = None) -> None:
        """Replace the executor of `generation` (once: later calls for it do nothing).

        `victim`: the pid of a worker to kill (SIGKILL); the others are terminated (SIGTERM), so
        the jobs they carried can tell they were only collateral (see `_collateral`).
        """
        if generation != self._generation or self._closing or self._executor is None:
            return
        old = self._executor
        replaced = len(self.pids()) if reason == "timeout" else self.settings.workers
        log.warning("replacing the worker pool (%s)", reason)
        self.metrics.worker_restarts.labels(reason).inc(replaced)
        self._replace_executor()
        self._dispose(old, victim)

    @staticmethod
    def _dispose(executor: Executor, victim: int | None = None) -> list[Any]:
        """Stop an executor without waiting (never blocks): end its local processes.

        Its jobs are not cancelled: they fail with BrokenProcessPool as their processes end, and
        `_run` resubmits those that never ran or whose worker was only collateral.
        """
        processes = list((getattr(executor, "_processes", None) or {}).values())
        for process in processes:
            with contextlib.suppress(Exception):
                if process.pid == victim:
                    process.kill()
                else:
                    process.terminate()
        executor.shutdown(wait=False)
        return processes

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
                if self._closing:
                    raise NotReady("the service is shutting down")
                executor, generation = self._executor, self._generation
                assert executor is not None
                slot = self._free_slots.pop()
                try:
                    local = isinstance(executor, ProcessPoolExecutor)
                    if local:
                        self._starts[slot] = 0.0
                    try:
                        future: Future[T] = executor.submit(
                            worker.run_timed, slot if local else None, fn, job
                        )
                        # Kept for `_collateral`: shutting a broken pool down drops them.
                        processes = getattr(executor, "_processes", None) or {}
                        manager = getattr(executor, "_executor_manager_thread", None)
                    except (BrokenProcessPool, RuntimeError) as error:
                        # The pool broke while idle: this job never ran, so no attempt is spent.
                        refused += 1
                        if refused > 4:
                            raise WorkerLost(f"the executor refuses jobs: {error}") from None
                        self._recycle(generation, "died")
                        continue
                    try:
                        return await self._result(future, slot if local else None, timeout)
                    except TimeoutError:
                        self.metrics.solves.labels(kind, "timeout").inc()
                        if not future.cancel() and local:
                            # A running job cannot be cancelled: kill its process (and pool).
                            self._recycle(generation, "timeout", victim=int(self._pids[slot]))
                        raise SolveTimeout(timeout) from None
                    except BrokenProcessPool:
                        # A job that was queued, or running in a worker that did not die itself
                        # but was ended with its pool, is resubmitted without spending an
                        # attempt (a few times at most).
                        started = local and self._starts[slot] > 0.0
                        if local:
                            self._starts[slot] = 0.0  # not running any more
                        self._recycle(generation, "died")
                        collateral = local and (
                            not started or await self._collateral(processes, manager, slot)
                        )
                        if collateral and refused < 4:
                            refused += 1
                            continue
                        attempt += 1
                        if attempt >= attempts:
                            self.metrics.solves.labels(kind, "worker_lost").inc()
                            raise WorkerLost(
                                "the worker process running this request died"
                                + (" twice" if attempts > 1 else "")
                            ) from None
                        log.warning("retrying a %s whose worker died", kind)
                finally:
                    if local:
                        self._starts[slot] = 0.0
                    self._free_slots.append(slot)

    async def _collateral(self, processes: dict[int, Any], manager: Any, slot: int) -> bool:
        """Whether the job that ran in `slot` of a broken pool was not the one whose worker died:
        its worker was terminated (SIGTERM) by the pool as it broke."""
        if manager is not None:
            # The pool's manager thread ends its processes; their exit codes are final after.
            await asyncio.to_thread(manager.join, 5.0)
        process = processes.get(int(self._pids[slot]))
        return process is not None and process.exitcode == -signal.SIGTERM

    async def _result(self, future: Future[T], slot: int | None, timeout: float) -> T:
        """The job's result, or TimeoutError once it has run `timeout` seconds.

        The clock starts when a local worker starts the job (its shared start time), or at
        dispatch for other executors. A job still queued behind another waits on: the job ahead
        has a budget of its own.
        """
        loop = asyncio.get_running_loop()
        waiting = asyncio.wrap_future(future)
        deadline = loop.time() + timeout
        while True:
            try:
                return await asyncio.wait_for(asyncio.shield(waiting), deadline - loop.time())
            except asyncio.CancelledError:
                task = asyncio.current_task()
                if future.cancelled() and not (task is not None and task.cancelling()):
                    # The executor dropped the job (e.g. a remote one shutting down).
                    raise BrokenProcessPool("the executor cancelled the job") from None
                raise
            except TimeoutError:
                if slot is None:
                    raise
                started = float(self._starts[slot])  # time.monotonic() in the worker
                deadline = (started if started > 0 else loop.time()) + timeout
                if deadline <= loop.time():
                    waiting.cancel()
                    raise
