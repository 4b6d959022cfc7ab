"""Tasks on a dask.distributed cluster (FLEXWING_EXECUTOR=dask, FLEXWING_DASK_SCHEDULER=tcp://...).

The service is a Dask client (asynchronous, on its own event loop). Every task (a solve, a
sweep, a design) is one Dask task running the same worker function as the local pool
(`app.execution.worker.run`), so a request gets the same answer wherever it runs. Dask workers
need flexwing installed (they import `app.execution.worker` and `solver`); each builds or loads
the solver model of a mesh size on first use and keeps it, and compiled libraries are shared
through FLEXWING_CACHE_DIR when every worker sees the same directory (the first worker
compiles, the others load its library).

The cluster is watched every `_WATCH_INTERVAL` s: a worker that joins gets a warm-up task pinned to
it (`worker.warm`, the warm mesh sizes), one that leaves is forgotten. Dask batches its messages
(the client every 10 ms, the scheduler and workers every few ms), so one task's round trip takes
~20 ms however short the task: tasks in flight are limited to the cluster's threads x
FLEXWING_DASK_TASKS_PER_THREAD, enough to keep every thread busy. The service is ready once a
worker is warm; /readyz lists every worker and whether it is warm.

Faults: Dask itself reruns the tasks of a worker that dies on another worker (a task that kills
`distributed.scheduler.allowed-failures` workers fails with KilledWorker, here `WorkerDied`). The
time budget counts from submission (Dask does not tell when a task starts); past it the request
gets 504 and the worker running it is restarted when it has a nanny (`dask worker` starts one
unless --no-nanny), since a running task cannot be stopped otherwise.
"""

from __future__ import annotations

import asyncio
import contextlib
import hashlib
import logging
import secrets
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, TypeVar

import distributed
from distributed import Client, KilledWorker
from distributed.client import FutureCancelledError

from app.execution import worker
from app.execution.pool import (
    BackendState,
    BudgetExceeded,
    ClusterWorkerInfo,
    NotReady,
    Progress,
    WorkerDied,
)
from app.metrics import Metrics
from app.settings import Settings

__all__ = ["DaskWorkers"]

log = logging.getLogger(__name__)

T = TypeVar("T")

_WATCH_INTERVAL = 1.0  # [s] how often the cluster's workers are listed
_CONNECT_TIMEOUT = 10.0  # [s] to reach the scheduler


@dataclass
class _DaskWorker:
    address: str
    name: str
    threads: int
    warm: bool = False
    pid: int | None = None
    warming: Any = None  # the warm-up task's Dask future


class DaskWorkers(BackendState):
    # A task's round trip through the scheduler is ~10 ms and costs the scheduler, the worker
    # and the client CPU of their own (benchmarks/batch_benchmark.py): a chunk of batch items
    # takes about 50 round trips' time (0.25 s: 219 items/s on 2 workers, 0.5 s: 237).
    CHUNK_SECONDS = 0.5

    def __init__(self, settings: Settings, metrics: Metrics) -> None:
        if not settings.dask_scheduler:
            raise ValueError("FLEXWING_EXECUTOR=dask needs FLEXWING_DASK_SCHEDULER=tcp://host:port")
        # No slots until the cluster's threads are known: they grow and shrink with it.
        detail = f"connecting to the Dask scheduler at {settings.dask_scheduler}"
        super().__init__(settings, 0, detail)
        self.metrics = metrics
        self.address = settings.dask_scheduler
        self._workers: dict[str, _DaskWorker] = {}
        self._client: Any = None
        self._watching: asyncio.Task[None] | None = None
        self._background: set[asyncio.Task[Any]] = set()

    # -------------------------------------------------------------------- what it reports

    @property
    def parallelism(self) -> int:
        return max(1, sum(w.threads for w in self._workers.values()))

    def pids(self) -> list[int]:
        return []  # remote processes: see `cluster`

    def running(self) -> int:
        return min(self._slots.held, sum(w.threads for w in self._workers.values()))

    def cluster(self) -> list[ClusterWorkerInfo] | None:
        return [
            ClusterWorkerInfo(w.address, w.name, w.threads, w.warm, w.pid)
            for w in sorted(self._workers.values(), key=lambda w: w.address)
        ]

    # ------------------------------------------------------------------------- lifecycle

    async def start(self) -> None:
        log.info("Dask %s client of %s", distributed.__version__, self.address)
        self._watching = asyncio.create_task(self._watch(), name="flexwing-dask-watch")

    async def close(self) -> None:
        self._closing = True
        self._ready.set()  # wakes tasks waiting for a worker: they see `_closing`
        self._slots.resize(1 << 30)
        for task in (self._watching, *self._background):
            if task is not None:
                task.cancel()
        if self._client is not None:
            with contextlib.suppress(Exception):
                await self._client.close()
        self.metrics.ready.set(0)
        self._detail = "closed"

    async def _watch(self) -> None:
        while not self._closing:
            try:
                if self._client is None:
                    self._client = await self._connect()
                await self._refresh()
            except asyncio.CancelledError:
                raise
            except Exception as error:
                self._detail = f"cannot reach the Dask scheduler at {self.address}: {error}"
                log.warning("%s", self._detail)
            await asyncio.sleep(_WATCH_INTERVAL)

    async def _connect(self) -> Any:
        return await Client(
            self.address,
            asynchronous=True,
            timeout=_CONNECT_TIMEOUT,
            set_as_default=False,
            name="flexwing-service",
        )

    async def _refresh(self) -> None:
        """Follow the cluster's workers: warm the new ones, forget the gone ones."""
        identity = await self._client.scheduler.identity()
        present: dict[str, Any] = identity.get("workers", {})
        for address in set(self._workers) - set(present):
            gone = self._workers.pop(address)
            log.warning("Dask worker %s (%s) left the cluster", gone.name, address)
            self.metrics.worker_restarts.labels("died").inc()
            if gone.warming is not None:
                self._spawn(gone.warming.cancel())
        for address, info in present.items():
            if address not in self._workers:
                name, threads = str(info.get("name", address)), int(info.get("nthreads", 1))
                self._workers[address] = _DaskWorker(address, name, threads)
                self._spawn(self._warm(self._workers[address]))
        threads = sum(w.threads for w in self._workers.values())
        self._slots.resize(threads * self.settings.dask_tasks_per_thread)
        self._report()

    async def _warm(self, target: _DaskWorker) -> None:
        """A warm-up task pinned to `target` (it compiles or loads the warm mesh sizes)."""
        target.warming = self._client.submit(
            worker.warm,
            self.warm_stations,
            self.settings.warmup_timeout,
            key=f"flexwing-warm-{secrets.token_hex(8)}",
            workers=[target.address],
            allow_other_workers=False,
            pure=False,
        )
        report: worker.WarmReport = await target.warming.result()
        target.warm, target.pid, target.warming = True, report.pid, None
        self._report()

    def _report(self) -> None:
        warm = sum(w.warm for w in self._workers.values())
        total = len(self._workers)
        if warm:
            self._started = True
            self._ready.set()
            self.metrics.ready.set(1)
            self._detail = f"ready: {warm} of {total} Dask worker(s) warm at {self.address}"
        else:
            self._ready.clear()
            self.metrics.ready.set(0)
            self._detail = f"waiting for a warm Dask worker ({total} connected) at {self.address}"

    def _spawn(self, coroutine: Any) -> None:
        task = asyncio.ensure_future(coroutine)
        self._background.add(task)
        task.add_done_callback(self._background.discard)
        task.add_done_callback(_log_failure)

    # --------------------------------------------------------------------------- running

    async def attempt(
        self,
        fn: Callable[..., T],
        task: Any,
        timeout: float,
        progress: Progress | None = None,
        affinity: bytes | None = None,
    ) -> T:
        """(`progress` is not reported from here: a task's progress arrives with its end.) A
        task with an `affinity` prefers one worker, the same for the same wing while the
        cluster keeps its workers (rendezvous hashing), which the scheduler may pass over."""
        async with self._slots.slot():
            await self._ready.wait()
            if self._closing or self._client is None:
                raise NotReady("the service is shutting down")
            preferred = _rendezvous(affinity, [a for a, w in self._workers.items() if w.warm])
            placement: dict[str, Any] = {}
            if preferred is not None:
                placement = {"workers": [preferred], "allow_other_workers": True}
            future = self._client.submit(fn, task, pure=False, **placement)
            return await self._outcome(future, timeout)

    async def _outcome(self, future: Any, timeout: float) -> Any:
        try:
            return await asyncio.wait_for(future.result(), timeout)
        except TimeoutError:
            self._spawn(self._restart_worker_of(future.key))
            self._spawn(future.cancel())
            raise BudgetExceeded(timeout) from None
        except (KilledWorker, FutureCancelledError, OSError) as error:
            raise WorkerDied(f"{type(error).__name__}: {error}") from None

    async def _restart_worker_of(self, key: str) -> None:
        """Restart the worker running task `key` (possible when it has a nanny)."""
        processing: dict[str, list[str]] = await self._client.processing()
        for address, keys in processing.items():
            if key in keys:
                self.metrics.worker_restarts.labels("timeout").inc()
                await self._client.restart_workers([address], raise_for_error=False)


def _rendezvous(affinity: bytes | None, addresses: list[str]) -> str | None:
    """The worker a wing prefers: the address with the highest hash of (wing, address), so a
    worker that joins or leaves moves only its own share of the wings."""
    if affinity is None or not addresses:
        return None
    return max(addresses, key=lambda a: hashlib.blake2b(affinity + a.encode()).digest())


def _log_failure(task: asyncio.Future[Any]) -> None:
    if not task.cancelled() and task.exception() is not None:
        log.warning("Dask background task failed: %r", task.exception())
