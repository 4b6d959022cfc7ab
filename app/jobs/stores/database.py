"""One connection to the store's database, owned by one thread, and what happens when the
database goes away.

The event loop hands the thread small operations through a queue (`write`: fire and forget, in
order; `read`: awaitable) and never waits on the disk or the network. The thread runs what is
queued, then commits once: many item writes of a busy batch share one commit. A read sees every
write queued before it, and its answer is handed back only after that commit: what a client has
read survives even a SIGKILL of the service.

An operation is `operation(session, *args)`; `session.execute` takes SQL with ``?`` placeholders
in either dialect (`app.jobs.stores.dialects`).

When the database cannot be reached (at the start, or lost mid-run: the connection breaks) the
store is *unavailable*: reads are refused at once with 503 /problems/database-unavailable
(Retry-After), writes are kept in memory, in order, and the thread connects again with a growing
pause (0.1 s to 2 s). Once it is back, the kept writes run first, then everything else: every
write is idempotent (an insert of a row that is there already does nothing, an update sets
values), so a batch whose commit may or may not have reached the database before the connection
broke is safely run again. An operation that fails for another reason (a bug, a constraint)
fails alone: its batch is rolled back and run again one operation per transaction.
"""

from __future__ import annotations

import asyncio
import concurrent.futures
import logging
import queue
import threading
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any, TypeVar

from app.jobs.stores.dialects import Dialect
from app.problems import PROBLEM_TYPES, Problem, ProblemType

__all__ = ["Database", "Session", "Unavailable", "unavailable"]

log = logging.getLogger(__name__)

T = TypeVar("T")

PROBLEM_TYPES["database-unavailable"] = ProblemType(
    "database-unavailable",
    "Jobs database unavailable",
    503,
    "The jobs database (FLEXWING_DATABASE_URL, or the SQLite file FLEXWING_JOBS_DB) cannot be "
    "reached just now: job operations wait for it, synchronous endpoints (/solve, ...) answer as "
    "usual. Retry after the Retry-After header's seconds; nothing accepted before is lost.",
)

_BATCH_LIMIT = 512  # queued operations run under one commit at most
_FIRST_RETRY, _LAST_RETRY = 0.1, 2.0  # [s] pauses between connection attempts
_STOP = object()


class Unavailable(Exception):
    """The database could not be reached for this operation (its connection broke)."""


def unavailable(name: str, reason: str | None, retry_after: int) -> Problem:
    """503 database-unavailable naming the database (never its password) and why."""
    return Problem(
        "database-unavailable",
        f"the jobs database {name} is unavailable ({reason or 'connecting'}); retry shortly",
        headers={"Retry-After": str(max(1, retry_after))},
    )


class Session:
    """What an operation gets: `execute(sql, args)` with ``?`` placeholders, and the dialect
    for what differs (`session.dialect.least`, `.skip_locked`, ...)."""

    def __init__(self, connection: Any, dialect: Dialect) -> None:
        self.connection = connection
        self.dialect = dialect

    def execute(self, sql: str, args: Sequence[Any] = ()) -> Any:
        return self.connection.execute(self.dialect.sql(sql), tuple(args))


@dataclass
class _Task:
    operation: Callable[..., Any]
    args: tuple[Any, ...]
    future: concurrent.futures.Future[Any] | None  # None: a write
    outcome: tuple[bool, Any] | None = field(default=None)  # (ok, value or error)


class Database:
    """The store's connection behind its thread (see the module docstring)."""

    def __init__(
        self,
        dialect: Dialect,
        prepare: Callable[[Session], None],
        *,
        retry_after: int = 1,
        durable: bool = True,
    ) -> None:
        self.dialect = dialect
        self.durable = durable  # False: commits need not wait for the database's disk
        self.name = dialect.name
        self._prepare = prepare
        self.retry_after = retry_after
        self._tasks: queue.SimpleQueue[Any] = queue.SimpleQueue()
        self._thread: threading.Thread | None = None
        self._tried = threading.Event()  # the first connection attempt has ended
        self.available = False
        self.reason: str | None = "not open"  # why not available

    # ------------------------------------------------------------------- the event loop's side

    async def open(self) -> None:
        """Start the thread and wait for its first connection attempt (not for success: an
        unreachable database is retried in the background, and reads are refused meanwhile)."""
        self.reason = "connecting"
        self._thread = threading.Thread(target=self._serve, name="flexwing-store", daemon=True)
        self._thread.start()
        await asyncio.to_thread(self._tried.wait)

    async def close(self) -> None:
        if self._thread is None:
            return
        self._tasks.put(_STOP)
        await asyncio.to_thread(self._thread.join, 30)
        self._thread = None
        self.available, self.reason = False, "closed"

    @property
    def is_open(self) -> bool:
        return self._thread is not None

    def write(self, operation: Callable[..., Any], *args: Any) -> None:
        """Queue `operation(session, *args)`; kept while the database is away; failures are
        logged."""
        self._tasks.put(_Task(operation, args, None))

    async def read(self, operation: Callable[..., T], *args: Any) -> T:
        """Run `operation(session, *args)` after everything queued before it and commit; 503
        not-ready when the store is not open (an app without its lifespan), 503
        database-unavailable when the database cannot be reached."""
        if self._thread is None:
            raise Problem("not-ready", "the jobs database is not open")
        if not self.available:
            raise unavailable(self.name, self.reason, self.retry_after)
        future: concurrent.futures.Future[T] = concurrent.futures.Future()
        self._tasks.put(_Task(operation, args, future))
        try:
            return await asyncio.wrap_future(future)
        except Unavailable:
            raise unavailable(self.name, self.reason, self.retry_after) from None

    # ------------------------------------------------------------------------- the thread

    def _serve(self) -> None:
        connection: Any = None
        held: list[_Task] = []  # writes kept while the database is away, in order
        pause = _FIRST_RETRY
        while True:
            if connection is None:
                connection = self._connect()
                self._tried.set()
                if connection is None:
                    if self._wait_away(held, pause):
                        break
                    pause = min(2 * pause, _LAST_RETRY)
                    continue
                pause = _FIRST_RETRY
            batch, stop = self._take(block=not held)
            batch, held = held + batch, []
            if self._run_batch(connection, batch):
                held = [task for task in batch if task.future is None]
                self.dialect.close(connection)
                connection = None
                if stop:
                    break
                continue
            if stop:
                break
        if held:
            log.error("jobs database: %d writes not made (stopped while it was away)", len(held))
        if connection is not None:
            self.dialect.close(connection)

    def _connect(self) -> Any:
        try:
            connection = self.dialect.connect()
        except Exception as error:
            self._set_away(self.dialect.describe(error))
            return None
        try:
            session = Session(connection, self.dialect)
            self._prepare(session)
            self.dialect.commit(connection)
            if not self.durable:
                self.dialect.relax_commit(session)
        except Exception as error:
            log.exception("jobs database %s: preparing the schema failed", self.name)
            self.dialect.close(connection)
            self._set_away(self.dialect.describe(error))
            return None
        if not self.available:
            log.warning("jobs database %s: connected", self.name)
        self.available, self.reason = True, None
        return connection

    def _set_away(self, reason: str) -> None:
        if self.available or self.reason != reason:
            log.error("jobs database %s unavailable: %s", self.name, reason)
        self.available, self.reason = False, reason

    def _wait_away(self, held: list[_Task], pause: float) -> bool:
        """While the database is away: for `pause` [s], refuse reads, keep writes. True when
        the store is being closed."""
        deadline = time.monotonic() + pause
        while (left := deadline - time.monotonic()) > 0:
            try:
                task = self._tasks.get(timeout=left)
            except queue.Empty:
                return False
            if task is _STOP:
                return True
            if task.future is None:
                held.append(task)
            else:
                task.future.set_exception(Unavailable())
        return False

    def _take(self, block: bool) -> tuple[list[_Task], bool]:
        """What is queued (waiting for a first task when `block`), and whether to stop after."""
        batch: list[_Task] = []
        try:
            first = self._tasks.get() if block else self._tasks.get_nowait()
        except queue.Empty:
            return batch, False
        stop = first is _STOP
        if not stop:
            batch.append(first)
        while len(batch) < _BATCH_LIMIT and not stop:
            try:
                task = self._tasks.get_nowait()
            except queue.Empty:
                break
            if task is _STOP:
                stop = True
            else:
                batch.append(task)
        return batch, stop

    def _run_batch(self, connection: Any, batch: list[_Task]) -> bool:
        """Run and commit `batch`, then hand reads their answers. True when the connection
        broke (the batch's reads are refused, its writes to be run again)."""
        session = Session(connection, self.dialect)
        try:
            if self._run_together(session, batch):
                for task in batch:
                    _hand_back(task)
                return False
            # One operation failed (not the connection): each alone, in its own transaction.
            self.dialect.rollback(connection)
            for task in batch:
                self.dialect.begin(connection, 2)
                if self._run(session, task, quiet=False):
                    try:
                        self.dialect.commit(connection)
                    except Exception as error:
                        if self.dialect.broken(connection, error):
                            raise
                        self.dialect.rollback(connection)
                        task.outcome = (False, error)
                else:
                    self.dialect.rollback(connection)
                _hand_back(task)
        except Exception as error:
            if not self.dialect.broken(connection, error):
                log.exception("jobs database %s: a batch failed", self.name)
            self._set_away(f"the connection was lost: {self.dialect.describe(error)}")
            for task in batch:
                if task.future is not None and not task.future.done():
                    task.future.set_exception(Unavailable())
            return True
        return False

    def _run_together(self, session: Session, batch: list[_Task]) -> bool:
        """Every operation of `batch` in one transaction, committed; False (nothing committed)
        when one of them failed."""
        try:
            self.dialect.begin(session.connection, len(batch))
            for task in batch:
                if not self._run(session, task, quiet=True):
                    return False
            self.dialect.commit(session.connection)
        except Exception as error:
            if self.dialect.broken(session.connection, error):
                raise
            return False
        return True

    def _run(self, session: Session, task: _Task, *, quiet: bool) -> bool:
        """Run one operation; whether it succeeded (a failed write is logged unless `quiet`).
        A broken connection propagates."""
        try:
            task.outcome = (True, task.operation(session, *task.args))
        except Exception as error:
            if self.dialect.broken(session.connection, error):
                raise
            task.outcome = (False, error)
            if task.future is None and not quiet:
                log.error("jobs database: %s failed: %s", task.operation.__name__, error)
            return False
        return True


def _hand_back(task: _Task) -> None:
    """A read's answer (after its commit); a write's nothing."""
    if task.future is None or task.outcome is None or task.future.done():
        return
    ok, value = task.outcome
    if ok:
        task.future.set_result(value)
    else:
        task.future.set_exception(value)
