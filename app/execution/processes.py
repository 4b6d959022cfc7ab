"""Worker processes this service starts and owns (FLEXWING_EXECUTOR=process), on public APIs only.

Each worker is a `multiprocessing` process with two channels: an inbox (a `multiprocessing.Queue`,
whose feeder thread keeps the event loop from ever blocking on a full pipe) and an outbox (a
one-way `Pipe`). A reader thread per worker waits on the outbox and on the process's sentinel
(`multiprocessing.connection.wait`) and hands every message to the event loop. A worker says

    ("warm", WarmReport)         once, after compiling or loading the warm mesh sizes;
    ("started", seq)             when it begins task `seq` (its time budget starts here);
    ("progress", seq, done, total)  as a task that reports its progress goes;
    ("done", seq, ok, value)     with the task's result, or the exception it raised.

When its outbox ends (EOF) and the process has exited, the worker is gone: its tasks fail with
`WorkerDied` (the one it was running, if it died on its own) or `Collateral` (queued ones, and
those of workers this pool ended itself), and the pool is replaced as a whole: a new generation
of workers is started and warmed, the survivors of the old one are ended with SIGTERM. A task past
its budget gets `BudgetExceeded` and its worker is killed (SIGKILL), which replaces the generation
the same way (its other tasks are collateral, resubmitted for free by `app.execution.pool`).
"""

from __future__ import annotations

import asyncio
import contextlib
import logging
import multiprocessing
import os
import pickle
import signal
import threading
from collections.abc import Callable
from dataclasses import dataclass, field
from multiprocessing.connection import Connection, wait
from multiprocessing.process import BaseProcess
from multiprocessing.queues import Queue
from typing import Any, TypeVar

from app.execution import worker
from app.execution.pool import (
    THREAD_VARIABLES,
    BudgetExceeded,
    Capacity,
    ClusterWorkerInfo,
    Collateral,
    NotReady,
    Progress,
    WorkerDied,
)
from app.metrics import Metrics
from app.settings import Settings

__all__ = ["LocalWorkers", "serve"]

log = logging.getLogger(__name__)

T = TypeVar("T")

_STOP_GRACE = 5.0  # [s] a worker told to stop has this long to finish before SIGTERM
_RESPAWN_DELAY = 1.0  # [s] before replacing a generation that never became warm (no hot loop)


# ------------------------------------------------------------------- inside a worker process


def serve(
    inbox: Queue[bytes | None],
    outbox: Connection,
    warm_stations: tuple[int, ...],
    warmup_timeout: float,
) -> None:
    """A worker's life: warm up, then run tasks from the inbox until told to stop (None)."""
    # Ctrl-C in a terminal reaches the whole process group: the service decides when we stop.
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    outbox.send(("warm", worker.warm(warm_stations, warmup_timeout)))
    while (message := inbox.get()) is not None:
        seq, fn, task, reports = pickle.loads(message)
        outbox.send(("started", seq))
        outbox.send_bytes(_outcome(seq, fn, task, outbox if reports else None))


def _outcome(seq: int, fn: Callable[..., Any], task: Any, outbox: Connection | None) -> bytes:
    """The pickled ("done", seq, ok, value) message of one task; an unpicklable error as text.
    With an `outbox`, the task reports its progress there as it goes."""

    def progress(done: int, total: int) -> None:
        assert outbox is not None
        outbox.send(("progress", seq, done, total))

    try:
        value, ok = (fn(task) if outbox is None else fn(task, progress)), True
    except Exception as error:
        value, ok = error, False
    try:
        return pickle.dumps(("done", seq, ok, value))
    except Exception as error:
        failure = RuntimeError(f"{type(value).__name__}: {value} ({error})")
        return pickle.dumps(("done", seq, False, failure))


# ------------------------------------------------------------------------ in the service


@dataclass(eq=False)
class _Dispatch:
    """A task handed to a worker; `started` is the event loop's time when the worker began it."""

    seq: int
    future: asyncio.Future[Any]
    started: float | None = None
    progress: Progress | None = None


@dataclass(eq=False)
class _Worker:
    generation: int
    process: BaseProcess
    inbox: Queue[bytes | None]
    outbox: Connection
    assigned: dict[int, _Dispatch] = field(default_factory=dict)  # by seq, in hand-over order
    report: worker.WarmReport | None = None
    ended_by_pool: bool = False  # the pool sent it SIGTERM or SIGKILL
    exited: bool = False
    reader: threading.Thread | None = None

    @property
    def pid(self) -> int:
        return int(self.process.pid or 0)


class LocalWorkers:
    """`FLEXWING_WORKERS` local worker processes, replaced as a whole when one is lost."""

    def __init__(self, settings: Settings, metrics: Metrics) -> None:
        self.settings = settings
        self.metrics = metrics
        self.warm_stations = tuple(settings.warm_stations)
        self._slots = Capacity(settings.workers * settings.tasks_per_worker)
        self._workers: list[_Worker] = []
        self._generation = 0
        self._seq = 0
        self._ready = asyncio.Event()
        self._started = False
        self._closing = False
        self._detail = "not started"
        self._loop: asyncio.AbstractEventLoop | None = None
        self._context: Any = None

    # -------------------------------------------------------------------- what it reports

    @property
    def ready(self) -> bool:
        return self._ready.is_set() and not self._closing

    @property
    def started(self) -> bool:
        return self._started

    @property
    def detail(self) -> str:
        return self._detail

    @property
    def capacity(self) -> int:
        return self._slots.size

    def pids(self) -> list[int]:
        return [w.pid for w in self._workers if not w.exited]

    def running(self) -> int:
        return sum(
            1
            for w in self._workers
            for d in w.assigned.values()
            if d.started is not None and not d.future.done()
        )

    def cluster(self) -> list[ClusterWorkerInfo] | None:
        return None

    async def wait_ready(self) -> None:
        await self._ready.wait()

    # ------------------------------------------------------------------------- lifecycle

    async def start(self) -> None:
        for variable in THREAD_VARIABLES:
            os.environ.setdefault(variable, "1")
        self._loop = asyncio.get_running_loop()
        self._context = multiprocessing.get_context(self.settings.start_method)
        if self.settings.start_method == "forkserver":
            # New workers fork from a server that has already imported solver and casadi.
            self._context.set_forkserver_preload(["app.execution.processes"])
        self._spawn_generation()

    def _spawn_generation(self) -> None:
        if self._closing:
            return
        self._generation += 1
        self._workers = [self._spawn(self._generation) for _ in range(self.settings.workers)]
        workers, stations = self.settings.workers, self.warm_stations
        self._detail = f"warming {workers} worker(s) for N = {stations}"

    def _spawn(self, generation: int) -> _Worker:
        inbox: Queue[bytes | None] = self._context.Queue()
        outbox, outbox_end = self._context.Pipe(duplex=False)
        process = self._context.Process(
            target=serve,
            args=(inbox, outbox_end, self.warm_stations, self.settings.warmup_timeout),
            name=f"flexwing-worker-{generation}",
            daemon=True,
        )
        process.start()
        outbox_end.close()  # the worker holds the only writing end: its death is our EOF
        new = _Worker(generation, process, inbox, outbox)
        new.reader = threading.Thread(
            target=self._read, args=(new,), name=f"flexwing-reader-{process.pid}", daemon=True
        )
        new.reader.start()
        return new

    async def close(self) -> None:
        """Let every worker finish what it holds (a few seconds at most), then end it."""
        self._closing = True
        self._ready.set()  # wakes tasks waiting for a warm pool: they see `_closing`
        workers = self._workers
        for w in workers:
            with contextlib.suppress(Exception):
                w.inbox.put(None)
        await asyncio.to_thread(self._join, workers, _STOP_GRACE)
        for w in workers:
            if not w.exited:
                w.ended_by_pool = True
                with contextlib.suppress(Exception):
                    w.process.terminate()
        await asyncio.to_thread(self._join, workers, _STOP_GRACE)
        for w in workers:
            self._discard(w)
        # Dropped now, their queues' semaphores are released before the process exits (else the
        # resource tracker warns of "leaked semaphore objects").
        self._workers = []
        workers.clear()
        self.metrics.ready.set(0)
        self._detail = "closed"

    @staticmethod
    def _join(workers: list[_Worker], timeout: float) -> None:
        for w in workers:
            if w.reader is not None:
                w.reader.join(timeout)

    @staticmethod
    def _discard(w: _Worker) -> None:
        """Let go of a worker's inbox without waiting for its feeder thread."""
        w.inbox.close()
        w.inbox.cancel_join_thread()

    # ----------------------------------------------------------- messages from the workers

    def _read(self, w: _Worker) -> None:
        """Reader thread: every message of `w` to the event loop, then its exit."""
        sentinel = w.process.sentinel
        while True:
            ready = wait([w.outbox, sentinel])
            if w.outbox not in ready:
                break  # the process ended and nothing is left to read
            try:
                message = w.outbox.recv()
            except (EOFError, OSError):
                break
            except Exception as error:  # a result that does not unpickle here
                log.exception("unreadable message from worker %d", w.pid)
                message = ("unreadable", repr(error))
            self._post(self._on_message, w, message)
        w.process.join(_STOP_GRACE)
        self._post(self._on_exit, w, w.process.exitcode)

    def _post(self, callback: Callable[..., None], *args: Any) -> None:
        assert self._loop is not None
        with contextlib.suppress(RuntimeError):  # the loop has closed: nobody is waiting
            self._loop.call_soon_threadsafe(callback, *args)

    def _on_message(self, w: _Worker, message: tuple[Any, ...]) -> None:
        kind = message[0]
        if kind == "warm":
            self._on_warm(w, message[1])
        elif kind == "started":
            dispatch = w.assigned.get(message[1])
            if dispatch is not None:
                assert self._loop is not None
                dispatch.started = self._loop.time()
        elif kind == "progress":
            dispatch = w.assigned.get(message[1])
            if dispatch is not None and dispatch.progress is not None:
                dispatch.progress(message[2], message[3])
        elif kind == "done":
            self._on_done(w, *message[1:])

    def _on_warm(self, w: _Worker, report: worker.WarmReport) -> None:
        w.report = report
        current = [x for x in self._workers if x.generation == self._generation]
        if w.generation != self._generation or not all(x.report for x in current):
            return
        self._detail = "ready"
        self._started = True
        self._ready.set()
        self.metrics.ready.set(1)

    @staticmethod
    def _on_done(w: _Worker, seq: int, ok: bool, value: Any) -> None:
        dispatch = w.assigned.pop(seq, None)
        if dispatch is None or dispatch.future.done():
            return  # its caller gave up (a timeout, a cancelled task)
        if ok:
            dispatch.future.set_result(value)
        else:
            dispatch.future.set_exception(value)

    def _on_exit(self, w: _Worker, exitcode: int | None) -> None:
        w.exited = True
        # A task is collateral if it never started, or its worker was ended by the pool (SIGTERM)
        # because another one died; a worker killed from outside shows SIGKILL.
        ended_by_us = w.ended_by_pool and exitcode == -signal.SIGTERM
        for dispatch in w.assigned.values():
            if dispatch.future.done():
                continue
            collateral = dispatch.started is None or ended_by_us
            error = Collateral if collateral else WorkerDied
            dispatch.future.set_exception(error(f"worker {w.pid} exited ({exitcode})"))
        w.assigned.clear()
        self._discard(w)
        if w.generation == self._generation and not w.ended_by_pool and not self._closing:
            log.warning("worker %d exited unexpectedly (%s)", w.pid, exitcode)
            self._replace("died")

    # ------------------------------------------------------------------------ replacement

    def _replace(self, reason: str, victim: _Worker | None = None) -> None:
        """Start a new generation of workers and end the current one (`victim` with SIGKILL,
        the others with SIGTERM, so the tasks they were running count as collateral)."""
        if self._closing:
            return
        old = self._workers
        never_warm = not all(w.report for w in old)
        self.metrics.worker_restarts.labels(reason).inc(len(old))
        log.warning("replacing the worker pool (%s)", reason)
        self._ready.clear()
        self.metrics.ready.set(0)
        self._workers = []
        self._generation += 1  # tasks wait for the next generation from now on
        for w in old:
            self._end(w, kill=w is victim)
        if never_warm:
            assert self._loop is not None
            self._detail = f"workers died while warming; starting new ones in {_RESPAWN_DELAY} s"
            self._loop.call_later(_RESPAWN_DELAY, self._spawn_generation)
        else:
            self._spawn_generation()

    @staticmethod
    def _end(w: _Worker, *, kill: bool) -> None:
        if w.exited:
            return
        w.ended_by_pool = True
        with contextlib.suppress(Exception):
            if kill:
                w.process.kill()
            else:
                w.process.terminate()

    # --------------------------------------------------------------------------- running

    async def attempt(
        self, fn: Callable[..., T], task: Any, timeout: float, progress: Progress | None = None
    ) -> T:
        """Run `fn(task)` once in the least busy worker, within `timeout` s of its start
        (`fn(task, report)` with `progress`, called here as the worker reports)."""
        async with self._slots.slot():
            await self._ready.wait()
            if self._closing:
                raise NotReady("the service is shutting down")
            w = self._least_busy()
            dispatch = self._hand_over(w, fn, task, progress)
            return await self._outcome(w, dispatch, timeout)  # type: ignore[no-any-return]

    def _least_busy(self) -> _Worker:
        alive = [w for w in self._workers if not w.exited and w.generation == self._generation]
        if not alive:
            raise Collateral("the worker pool is being replaced")
        return min(alive, key=lambda w: len(w.assigned))

    def _hand_over(
        self, w: _Worker, fn: Callable[..., Any], task: Any, progress: Progress | None
    ) -> _Dispatch:
        assert self._loop is not None
        self._seq += 1
        # Pickled here: a task that does not pickle fails its own request.
        message = pickle.dumps((self._seq, fn, task, progress is not None))
        dispatch = _Dispatch(self._seq, self._loop.create_future(), progress=progress)
        # Its caller may be gone when it fails (a timeout, a cancelled task): nobody must care.
        dispatch.future.add_done_callback(lambda f: f.cancelled() or f.exception())
        w.assigned[self._seq] = dispatch
        try:
            w.inbox.put(message)
        except (ValueError, OSError):  # the inbox was closed: the worker is gone
            del w.assigned[self._seq]
            raise Collateral("the worker is gone") from None
        return dispatch

    async def _outcome(self, w: _Worker, dispatch: _Dispatch, timeout: float) -> Any:
        """The task's result, or BudgetExceeded once it has run `timeout` seconds.

        A task still queued behind another in its worker waits on: the task ahead has a budget of
        its own, and this one's starts when the worker begins it.
        """
        assert self._loop is not None
        loop = self._loop
        deadline = loop.time() + timeout
        while True:
            try:
                return await asyncio.wait_for(
                    asyncio.shield(dispatch.future), max(0.0, deadline - loop.time())
                )
            except TimeoutError:
                if dispatch.future.done():
                    continue
                started = dispatch.started
                deadline = (loop.time() if started is None else started) + timeout
                if deadline > loop.time():
                    continue
                dispatch.future.cancel()
                if w.generation == self._generation and not w.exited:
                    self._replace("timeout", victim=w)
                raise BudgetExceeded(timeout) from None
