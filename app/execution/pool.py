"""The worker pool: solves run in other processes (or on other machines), never on the event loop.

`WorkerPool` is what the service talks to. It admits work (at most `max_pending` tasks running or
waiting, beyond that `Overloaded`), retries a task whose worker died under it (once, setting
`retry_on_worker_loss`; a task that was only collateral damage of another worker's death is
resubmitted without spending that retry), and reports readiness. Where tasks run is a backend,
chosen by `FLEXWING_EXECUTOR`:

- ``process`` (default): `app.execution.processes.LocalWorkers`, worker processes this service
  starts and owns (multiprocessing processes with a pipe each way): warm-up before ready, at
  most `tasks_per_worker` tasks handed to a worker at once, a time budget counted from the
  task's start in its worker (past it: `BudgetExceeded` and the worker is killed), a dead worker
  detected at once.
- ``dask``: `app.execution.dask_cluster.DaskWorkers`, a dask.distributed cluster at
  `FLEXWING_DASK_SCHEDULER`.
- ``module:callable``: `app.execution.executor.ExecutorWorkers` over any
  `concurrent.futures.Executor` the callable returns (given the Settings).

Backends raise `WorkerDied` for a task whose worker died while running it and `Collateral` for a
task that never ran or was stopped because another worker died; only this module turns them
into retries or `WorkerLost`.
"""

from __future__ import annotations

import asyncio
import contextlib
import dataclasses
import importlib
import logging
from collections import deque
from collections.abc import AsyncIterator, Callable
from concurrent.futures import Executor
from dataclasses import dataclass
from typing import Any, Protocol, TypeVar

from app.metrics import Metrics
from app.settings import Settings

__all__ = [
    "affinity_of",
    "Backend",
    "BackendState",
    "Progress",
    "Capacity",
    "ClusterWorkerInfo",
    "Collateral",
    "NotReady",
    "Overloaded",
    "PoolError",
    "BudgetExceeded",
    "WorkerDied",
    "WorkerLost",
    "WorkerPool",
]

log = logging.getLogger(__name__)

T = TypeVar("T")

# What a task reports as it goes, on the event loop: progress(done, total).
Progress = Callable[[int, int], None]

# Threads of numerical libraries per worker: the pool is the parallelism.
THREAD_VARIABLES = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")
# Free resubmissions of a task that was only collateral damage, before it counts as lost.
_FREE_RESUBMISSIONS = 4


class PoolError(Exception):
    """A task could not be run; the subclasses say why."""


class Overloaded(PoolError):
    pass


class NotReady(PoolError):
    pass


class WorkerLost(PoolError):
    pass


class BudgetExceeded(PoolError):
    def __init__(self, timeout: float) -> None:
        super().__init__(f"the task ran longer than its budget of {timeout:g} s")
        self.timeout = timeout


class WorkerDied(PoolError):
    """Backend to pool: the worker running this task died while running it."""


class Collateral(PoolError):
    """Backend to pool: the task never ran, or was stopped because another worker died."""


@dataclass(frozen=True)
class ClusterWorkerInfo:
    """One worker of a remote cluster, as /readyz reports it."""

    address: str
    name: str
    threads: int
    warm: bool
    pid: int | None


class Capacity:
    """A counting limit whose size may change (a cluster grows or shrinks): at most `size`
    holders at once, the others wait in arrival order."""

    def __init__(self, size: int) -> None:
        self.size = size
        self.held = 0
        self._waiters: deque[asyncio.Future[None]] = deque()

    @contextlib.asynccontextmanager
    async def slot(self) -> AsyncIterator[None]:
        await self._acquire()
        try:
            yield
        finally:
            self.release()

    async def _acquire(self) -> None:
        if self.held < self.size and not self._waiters:
            self.held += 1
            return
        waiter = asyncio.get_running_loop().create_future()
        self._waiters.append(waiter)
        try:
            await waiter
        except asyncio.CancelledError:
            if waiter.done() and not waiter.cancelled():
                self.release()  # it was handed a slot just before the cancellation
            else:
                with contextlib.suppress(ValueError):
                    self._waiters.remove(waiter)
            raise

    def release(self) -> None:
        self.held -= 1
        self._wake()

    def resize(self, size: int) -> None:
        self.size = size
        self._wake()

    def _wake(self) -> None:
        while self._waiters and self.held < self.size:
            waiter = self._waiters.popleft()
            if not waiter.done():
                self.held += 1
                waiter.set_result(None)


def affinity_of(task: Any) -> bytes | None:
    """The wing a task asks about (its `Wing.key`), or None (a batch's chunk of many wings).

    A worker's solver cache keeps what a wing's answers share and rebuild bit for bit (its
    jig, its branch from the jig, its trimmed divergence limit, its compiled mesh): the same
    wing asked again, at other airspeeds, answers sooner on the worker that answered it
    before. Only where a task runs depends on it, never its answer."""
    wing = getattr(task, "wing", None)
    key = getattr(wing, "key", None)
    return key if isinstance(key, bytes) else None


class BackendState:
    """What every backend keeps and reports alike: its readiness, whether it has been ready,
    what it is doing (`detail`), and the slots of the tasks it runs or holds."""

    def __init__(self, settings: Settings, slots: int, detail: str = "not started") -> None:
        self.settings = settings
        self.warm_stations = tuple(settings.warm_stations)
        self._slots = Capacity(slots)
        self._ready = asyncio.Event()
        self._started = False
        self._closing = False
        self._detail = detail

    @property
    def ready(self) -> bool:
        return self._ready.is_set() and not self._closing

    @property
    def started(self) -> bool:
        """Has been ready at least once (until then a task is refused with `NotReady`)."""
        return self._started

    @property
    def detail(self) -> str:
        return self._detail

    @property
    def capacity(self) -> int:
        """Tasks it runs or holds at once."""
        return self._slots.size

    async def wait_ready(self) -> None:
        await self._ready.wait()


class Backend(Protocol):
    """Where tasks run. `attempt` runs one task once (see the module docstring for its errors)."""

    @property
    def ready(self) -> bool: ...

    @property
    def started(self) -> bool:
        """Has been ready at least once (until then a task is refused with `NotReady`)."""
        ...

    @property
    def detail(self) -> str: ...

    @property
    def capacity(self) -> int:
        """Tasks it runs or holds at once (workers x tasks_per_worker)."""
        ...

    @property
    def parallelism(self) -> int:
        """Tasks it runs at the same time (the local workers; a Dask cluster's threads)."""
        ...

    async def start(self) -> None: ...

    async def wait_ready(self) -> None: ...

    async def attempt(
        self,
        fn: Callable[..., T],
        task: Any,
        timeout: float,
        progress: Progress | None = None,
        affinity: bytes | None = None,
    ) -> T:
        """Run `fn(task)` once (`fn(task, progress)` with `progress`, which the backend calls
        on the event loop as the worker reports, where it can); `affinity`: the task's wing,
        whose worker to prefer, where the solver's cache may already hold its jig, branches
        and limits (`affinity_of`)."""
        ...

    async def close(self) -> None: ...

    def pids(self) -> list[int]: ...

    def running(self) -> int: ...

    def cluster(self) -> list[ClusterWorkerInfo] | None: ...


def _load(path: str) -> Any:
    """The object `module:name` names."""
    module, _, name = path.partition(":")
    return getattr(importlib.import_module(module), name)


def _load_factory(path: str) -> Callable[[Settings], Executor]:
    module, _, name = path.partition(":")
    if not module or not name:
        raise ValueError(
            f"FLEXWING_EXECUTOR must be 'process', 'dask' or 'module:callable', not {path!r}"
        )
    factory: Callable[[Settings], Executor] = _load(path)
    return factory


# FLEXWING_EXECUTOR names -> backend classes, loaded by name: each pulls in its own libraries
# (Dask's only when it is used), and each imports this module (its errors), not the reverse.
BACKENDS = {
    "process": "app.execution.processes:LocalWorkers",
    "dask": "app.execution.dask_cluster:DaskWorkers",
}
EXECUTOR_BACKEND = "app.execution.executor:ExecutorWorkers"  # for FLEXWING_EXECUTOR=module:callable


def make_backend(settings: Settings, metrics: Metrics) -> Backend:
    """The backend `settings.executor` names."""
    if settings.executor not in BACKENDS:
        factory = _load_factory(settings.executor)
        return _load(EXECUTOR_BACKEND)(settings, factory)  # type: ignore[no-any-return]
    try:
        backend = _load(BACKENDS[settings.executor])
    except ImportError as error:
        raise ValueError(
            f"FLEXWING_EXECUTOR={settings.executor} needs {error.name}: "
            "pip install 'flexwing[dask]'"
        ) from error
    return backend(settings, metrics)  # type: ignore[no-any-return]


class WorkerPool:
    """Admission, retries and readiness over a backend (see the module docstring)."""

    def __init__(self, settings: Settings, metrics: Metrics) -> None:
        self.settings = settings
        self.metrics = metrics
        self.warm_stations = tuple(settings.warm_stations)
        self.backend: Backend | None = None  # made in `start`: importing the app starts nothing
        self._pending = 0
        self._closing = False
        metrics.running.set_function(self.running)

    # ------------------------------------------------------------------------- lifecycle

    @property
    def ready(self) -> bool:
        return self.backend is not None and self.backend.ready and not self._closing

    @property
    def detail(self) -> str:
        if self._closing:
            return "closed"
        return "not started" if self.backend is None else self.backend.detail

    @property
    def capacity(self) -> int:
        """Tasks the workers run or hold at once: what keeps them all busy."""
        return max(1, self.backend.capacity if self.backend is not None else 1)

    @property
    def parallelism(self) -> int:
        """Tasks that run at the same time: `capacity` less those queued behind them."""
        return max(1, self.backend.parallelism if self.backend is not None else 1)

    @property
    def chunk_seconds(self) -> float:
        """[s] how long a task of several batch items should take on this backend: long
        enough that the round trip to a worker is a few per cent of it."""
        return getattr(self.backend, "CHUNK_SECONDS", 0.05)

    def running(self) -> int:
        """Tasks running in workers now (started, not yet collected)."""
        return 0 if self.backend is None else self.backend.running()

    def pids(self) -> list[int]:
        """Process ids of the local workers (empty for remote ones)."""
        return [] if self.backend is None else self.backend.pids()

    def cluster(self) -> list[dict[str, Any]] | None:
        """The workers of a remote cluster (as /readyz shows them), or None for local workers."""
        workers = None if self.backend is None else self.backend.cluster()
        return None if workers is None else [dataclasses.asdict(w) for w in workers]

    async def start(self) -> None:
        """Create the backend and begin warming it; returns at once (see `ready`)."""
        self.backend = make_backend(self.settings, self.metrics)
        await self.backend.start()

    async def wait_ready(self, timeout: float | None = None) -> bool:
        if self.backend is not None:
            with contextlib.suppress(TimeoutError):
                await asyncio.wait_for(self.backend.wait_ready(), timeout)
        return self.ready

    async def close(self) -> None:
        self._closing = True
        if self.backend is not None:
            await self.backend.close()
        self.metrics.ready.set(0)

    # --------------------------------------------------------------------------- running

    async def run(
        self,
        fn: Callable[..., T],
        task: Any,
        *,
        timeout: float,
        kind: str,
        progress: Progress | None = None,
    ) -> T:
        """Run `fn(task)` in a worker within `timeout` seconds of its start."""
        if self.backend is None or not self.backend.started or self._closing:
            raise NotReady(self.detail)
        if self._pending >= self.settings.max_pending:
            self.metrics.shed.inc()
            raise Overloaded(f"{self._pending} tasks are already running or waiting")
        self._pending += 1
        self.metrics.pending.set(self._pending)
        try:
            return await self._run_with_retries(self.backend, fn, task, timeout, kind, progress)
        finally:
            self._pending -= 1
            self.metrics.pending.set(self._pending)

    async def _run_with_retries(
        self,
        backend: Backend,
        fn: Callable[..., T],
        task: Any,
        timeout: float,
        kind: str,
        progress: Progress | None,
    ) -> T:
        """One attempt, one more if its worker died (setting), free ones for collateral."""
        attempts = 2 if self.settings.retry_on_worker_loss else 1
        free = _FREE_RESUBMISSIONS
        while True:
            if self._closing:
                raise NotReady("the service is shutting down")
            try:
                return await backend.attempt(fn, task, timeout, progress, affinity_of(task))
            except BudgetExceeded:
                self.metrics.solves.labels(kind, "timeout").inc()
                raise
            except Collateral:
                if free > 0:
                    free -= 1
                    continue
            except WorkerDied:
                pass
            attempts -= 1
            if attempts <= 0:
                self.metrics.solves.labels(kind, "worker_lost").inc()
                twice = " twice" if self.settings.retry_on_worker_loss else ""
                raise WorkerLost(f"the worker process running this request died{twice}")
            log.warning("retrying a %s whose worker died", kind)
