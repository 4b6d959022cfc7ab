"""Worker processes this service starts and owns (FLEXWING_EXECUTOR=process), on public APIs only.

Each worker is a `multiprocessing` process with a one-way pipe each way, both driven by the
service's event loop itself (asyncio pipe transports: no thread between the loop and a worker,
and a write never blocks the loop, it is buffered until the pipe takes it). Messages are framed
as `multiprocessing.connection.Connection` frames them (a 4-byte big-endian length, then the
bytes), so the worker reads and writes its ends as plain Connections. The service sends a task
as the pickled (seq, fn, task, reports) and an empty message to stop; a worker says

    ("warm", WarmReport)         once, after compiling or loading the warm mesh sizes;
    ("started", seq)             when it begins task `seq` (its time budget starts here);
    ("progress", seq, done, total)  as a task that reports its progress goes;
    ("done", seq, ok, value, seconds)  with the task's result, or the exception it raised,
                                 and the time it ran in the worker [s]
                                 (flexwing_worker_task_duration_seconds).

When the process has exited (its sentinel) and its outbox has ended (EOF; at most
`_EOF_GRACE` s later, should another process hold the pipe open), the worker is gone: its tasks
fail with `WorkerDied` (the one it was running, if it died on its own) or `Collateral` (queued
ones, and those of workers this pool ended itself), and the pool is replaced as a whole: a new
generation of workers is started and warmed, the survivors of the old one are ended with
SIGTERM. A task past its budget gets `BudgetExceeded` and its worker is killed (SIGKILL), which
replaces the generation the same way (its other tasks are collateral, resubmitted for free by
`app.execution.pool`). A worker whose inbox ends (the service is gone) exits.
"""

from __future__ import annotations

import asyncio
import contextlib
import logging
import multiprocessing
import os
import pickle
import signal
import struct
import time
from collections import OrderedDict
from collections.abc import Callable
from dataclasses import dataclass, field
from multiprocessing.connection import Connection
from multiprocessing.process import BaseProcess
from typing import Any, TypeVar

from app.execution import worker
from app.execution.pool import (
    THREAD_VARIABLES,
    BackendState,
    BudgetExceeded,
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
# Wings a worker remembers having run: as many as the service keeps built (`Wing.__kept__`).
_REMEMBERED_WINGS = 64

T = TypeVar("T")

_STOP_GRACE = 5.0  # [s] a worker told to stop has this long to finish before SIGTERM
_RESPAWN_DELAY = 1.0  # [s] before replacing a generation that never became warm (no hot loop)
_EOF_GRACE = 1.0  # [s] after its exit, a worker's outbox has this long to end before it is gone
_STOP = b""  # the message that tells a worker to stop


# ------------------------------------------------------------------- inside a worker process


def serve(
    inbox: Connection,
    outbox: Connection,
    warm_stations: tuple[int, ...],
    warmup_timeout: float,
) -> None:
    """A worker's life: warm up, then run tasks from the inbox until told to stop (an empty
    message) or the inbox ends (the service is gone)."""
    # Ctrl-C in a terminal reaches the whole process group: the service decides when we stop.
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    outbox.send(("warm", worker.warm(warm_stations, warmup_timeout)))
    while True:
        try:
            message = inbox.recv_bytes()
        except (EOFError, OSError):
            return
        if message == _STOP:
            return
        seq, fn, task, reports = pickle.loads(message)
        outbox.send(("started", seq))
        outbox.send_bytes(_outcome(seq, fn, task, outbox if reports else None))


def _outcome(seq: int, fn: Callable[..., Any], task: Any, outbox: Connection | None) -> bytes:
    """The pickled ("done", seq, ok, value, seconds) message of one task; an unpicklable
    error as text. With an `outbox`, the task reports its progress there as it goes."""

    def progress(done: int, total: int) -> None:
        assert outbox is not None
        outbox.send(("progress", seq, done, total))

    started = time.perf_counter()
    try:
        value, ok = (fn(task) if outbox is None else fn(task, progress)), True
    except Exception as error:
        value, ok = error, False
    seconds = time.perf_counter() - started
    try:
        return pickle.dumps(("done", seq, ok, value, seconds))
    except Exception as error:
        failure = RuntimeError(f"{type(value).__name__}: {value} ({error})")
        return pickle.dumps(("done", seq, False, failure, seconds))


# ------------------------------------------------------------------------ in the service


def _frame(payload: bytes) -> bytes:
    """`payload` framed as `Connection.send_bytes` frames it."""
    if len(payload) > 0x7FFFFFFF:
        return struct.pack("!iQ", -1, len(payload)) + payload
    return struct.pack("!i", len(payload)) + payload


def _owned(end: Connection) -> int:
    """A pipe end's file descriptor, taken from its Connection (closed) for the event loop."""
    fd = os.dup(end.fileno())
    end.close()
    return fd


class _Frames(asyncio.Protocol):
    """The outbox's bytes as messages: each complete frame unpickled and handed to
    `on_message`, the pipe's end to `on_end`."""

    def __init__(
        self, on_message: Callable[[tuple[Any, ...]], None], on_end: Callable[[], None]
    ) -> None:
        self.on_message = on_message
        self.on_end = on_end
        self.buffer = bytearray()

    def data_received(self, data: bytes) -> None:
        self.buffer += data
        while (frame := self._next_frame()) is not None:
            try:
                message = pickle.loads(frame)
            except Exception as error:  # a result that does not unpickle here
                log.exception("unreadable message from a worker")
                message = ("unreadable", repr(error))
            self.on_message(message)

    def _next_frame(self) -> bytes | None:
        buffer = self.buffer
        if len(buffer) < 4:
            return None
        (size,) = struct.unpack_from("!i", buffer)
        start = 4
        if size == -1:
            if len(buffer) < 12:
                return None
            (size,) = struct.unpack_from("!Q", buffer, 4)
            start = 12
        if len(buffer) < start + size:
            return None
        frame = bytes(buffer[start : start + size])
        del buffer[: start + size]
        return frame

    def eof_received(self) -> bool | None:
        return None  # let the transport close: connection_lost follows

    def connection_lost(self, exc: Exception | None) -> None:
        self.on_end()


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
    inbox: asyncio.WriteTransport | None = None
    outbox: asyncio.ReadTransport | None = None
    assigned: dict[int, _Dispatch] = field(default_factory=dict)  # by seq, in hand-over order
    report: worker.WarmReport | None = None
    ended_by_pool: bool = False  # the pool sent it SIGTERM or SIGKILL
    exited: bool = False
    outbox_ended: bool = False
    exitcode: int | None = None
    process_ended: bool = False
    gone: asyncio.Event = field(default_factory=asyncio.Event)
    # The wings it ran last (`app.execution.pool.affinity_of`), least recent first.
    wings: OrderedDict[bytes, None] = field(default_factory=OrderedDict)

    @property
    def pid(self) -> int:
        return int(self.process.pid or 0)

    def recency(self, wing: bytes | None) -> int:
        """How recently it ran `wing`: its place among the wings it remembers (1 the
        oldest), 0 if it does not remember it."""
        if wing is None or wing not in self.wings:
            return 0
        return list(self.wings).index(wing) + 1

    def ran(self, wing: bytes | None) -> None:
        if wing is None:
            return
        self.wings[wing] = None
        self.wings.move_to_end(wing)
        while len(self.wings) > _REMEMBERED_WINGS:
            self.wings.popitem(last=False)


class LocalWorkers(BackendState):
    """`FLEXWING_WORKERS` local worker processes, replaced as a whole when one is lost."""

    def __init__(self, settings: Settings, metrics: Metrics) -> None:
        super().__init__(settings, settings.workers * settings.tasks_per_worker)
        self.metrics = metrics
        self._workers: list[_Worker] = []
        self._generation = 0
        self._seq = 0
        self._loop: asyncio.AbstractEventLoop | None = None
        self._context: Any = None
        self._connecting: set[asyncio.Task[None]] = set()

    # -------------------------------------------------------------------- what it reports

    @property
    def parallelism(self) -> int:
        return self.settings.workers

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
        assert self._loop is not None
        inbox_end, inbox = self._context.Pipe(duplex=False)
        outbox, outbox_end = self._context.Pipe(duplex=False)
        process = self._context.Process(
            target=serve,
            args=(inbox_end, outbox_end, self.warm_stations, self.settings.warmup_timeout),
            name=f"flexwing-worker-{generation}",
            daemon=True,
        )
        process.start()
        # The worker holds the only other ends: its death is our EOF (and EPIPE).
        inbox_end.close()
        outbox_end.close()
        new = _Worker(generation, process)
        self._loop.add_reader(process.sentinel, self._on_sentinel, new)
        connecting = self._loop.create_task(self._connect(new, _owned(inbox), _owned(outbox)))
        self._connecting.add(connecting)
        connecting.add_done_callback(lambda task: self._connected(new, task))
        return new

    def _connected(self, w: _Worker, task: asyncio.Task[None]) -> None:
        """A worker the loop could not connect to is ended: its exit replaces the pool."""
        self._connecting.discard(task)
        error = None if task.cancelled() else task.exception()
        if error is not None:
            log.error("no pipe to worker %d: %r", w.pid, error)
            with contextlib.suppress(Exception):
                w.process.kill()

    async def _connect(self, w: _Worker, inbox: int, outbox: int) -> None:
        """The event loop's transports on a new worker's pipe ends (file descriptors this
        pool owns from here)."""
        assert self._loop is not None
        reading = open(outbox, "rb", buffering=0)  # noqa: SIM115 (the transport closes it)
        writing = open(inbox, "wb", buffering=0)  # noqa: SIM115
        frames = _Frames(lambda message: self._on_message(w, message), lambda: self._on_end(w))
        # The inbox first: a worker's first message (warm) may make it take tasks at once.
        w.inbox, _ = await self._loop.connect_write_pipe(asyncio.BaseProtocol, writing)
        w.outbox, _ = await self._loop.connect_read_pipe(lambda: frames, reading)
        if w.exited:
            self._discard(w)

    async def close(self) -> None:
        """Let every worker finish what it holds (a few seconds at most), then end it."""
        self._closing = True
        self._ready.set()  # wakes tasks waiting for a warm pool: they see `_closing`
        if self._connecting:
            await asyncio.wait(set(self._connecting))
        workers = self._workers
        for w in workers:
            if w.inbox is not None and not w.inbox.is_closing():
                w.inbox.write(_frame(_STOP))
        await self._gone(workers, _STOP_GRACE)
        for w in workers:
            if not w.exited:
                w.ended_by_pool = True
                with contextlib.suppress(Exception):
                    w.process.terminate()
        await self._gone(workers, _STOP_GRACE)
        for w in workers:
            self._discard(w)
        self._workers = []
        workers.clear()
        self.metrics.ready.set(0)
        self._detail = "closed"

    @staticmethod
    async def _gone(workers: list[_Worker], timeout: float) -> None:
        waiting = [asyncio.ensure_future(w.gone.wait()) for w in workers if not w.exited]
        if waiting:
            _, pending = await asyncio.wait(waiting, timeout=timeout)
            for task in pending:
                task.cancel()

    def _discard(self, w: _Worker) -> None:
        """Let go of a worker's pipes and sentinel."""
        assert self._loop is not None
        with contextlib.suppress(Exception):
            self._loop.remove_reader(w.process.sentinel)
        for transport in (w.inbox, w.outbox):
            if transport is not None:
                transport.close()

    # ----------------------------------------------------------- messages from the workers

    def _on_sentinel(self, w: _Worker) -> None:
        """The process has exited: it is gone once its outbox has ended too (or a grace
        later, should another process still hold the pipe)."""
        assert self._loop is not None
        self._loop.remove_reader(w.process.sentinel)
        w.process.join(0)  # reaps it: the exit code is known from here
        w.exitcode = w.process.exitcode
        w.process_ended = True
        if w.outbox_ended:
            self._on_exit(w)
        else:
            self._loop.call_later(_EOF_GRACE, self._on_exit, w)

    def _on_end(self, w: _Worker) -> None:
        w.outbox_ended = True
        if w.process_ended:
            self._on_exit(w)

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

    def _on_done(self, w: _Worker, seq: int, ok: bool, value: Any, seconds: float) -> None:
        self.metrics.worker_seconds.observe(seconds)
        dispatch = w.assigned.pop(seq, None)
        if dispatch is None or dispatch.future.done():
            return  # its caller gave up (a timeout, a cancelled task)
        if ok:
            dispatch.future.set_result(value)
        else:
            dispatch.future.set_exception(value)

    def _on_exit(self, w: _Worker) -> None:
        if w.exited:
            return
        w.exited = True
        exitcode = w.exitcode
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
        w.gone.set()
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
        self,
        fn: Callable[..., T],
        task: Any,
        timeout: float,
        progress: Progress | None = None,
        affinity: bytes | None = None,
    ) -> T:
        """Run `fn(task)` once in the least busy worker (of those, the one that last ran
        `affinity`'s wing), within `timeout` s of its start (`fn(task, report)` with
        `progress`, called here as the worker reports)."""
        async with self._slots.slot():
            await self._ready.wait()
            if self._closing:
                raise NotReady("the service is shutting down")
            w = self._least_busy(affinity)
            dispatch = self._hand_over(w, fn, task, progress)
            return await self._outcome(w, dispatch, timeout)  # type: ignore[no-any-return]

    def _least_busy(self, affinity: bytes | None = None) -> _Worker:
        """The worker with the fewest tasks; of those, the one that ran `affinity`'s wing
        most recently (a busier worker is never chosen for its cache)."""
        alive = [w for w in self._workers if not w.exited and w.generation == self._generation]
        if not alive:
            raise Collateral("the worker pool is being replaced")
        fewest = min(len(w.assigned) for w in alive)
        idle = [w for w in alive if len(w.assigned) == fewest]
        chosen = max(idle, key=lambda w: w.recency(affinity))
        chosen.ran(affinity)
        return chosen

    def _hand_over(
        self, w: _Worker, fn: Callable[..., Any], task: Any, progress: Progress | None
    ) -> _Dispatch:
        assert self._loop is not None
        self._seq += 1
        # Pickled here: a task that does not pickle fails its own request.
        message = pickle.dumps((self._seq, fn, task, progress is not None))
        if w.inbox is None or w.inbox.is_closing():  # the worker is gone
            raise Collateral("the worker is gone")
        dispatch = _Dispatch(self._seq, self._loop.create_future(), progress=progress)
        # Its caller may be gone when it fails (a timeout, a cancelled task): nobody must care.
        dispatch.future.add_done_callback(lambda f: f.cancelled() or f.exception())
        w.assigned[self._seq] = dispatch
        # Buffered by the transport when the pipe is full: the loop never blocks here. A
        # worker that dies before reading it fails the task as collateral (`_on_exit`).
        w.inbox.write(_frame(message))
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
            # Waiting never cancels the task: a caller that gives up leaves it to its end.
            await asyncio.wait((dispatch.future,), timeout=max(0.0, deadline - loop.time()))
            if dispatch.future.done():
                return dispatch.future.result()
            started = dispatch.started
            deadline = (loop.time() if started is None else started) + timeout
            if deadline > loop.time():
                continue
            dispatch.future.cancel()
            if w.generation == self._generation and not w.exited:
                self._replace("timeout", victim=w)
            raise BudgetExceeded(timeout)
