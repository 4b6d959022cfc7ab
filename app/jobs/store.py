"""Jobs in an embedded SQLite database (stdlib sqlite3), written from one thread.

One thread owns the connection; the event loop hands it small operations through a queue
(`write`: fire and forget, in order; `read`: awaitable) and never waits on the disk. The thread
runs what is queued, then commits once: many item writes of a busy batch share one commit. A read
sees every write queued before it, and its answer is handed back only after that commit: what a
client has read survives even a SIGKILL of the service.

Tables:

    jobs   one row per job: id, operation, status, owner (the service instance running it),
           principal (the API key that submitted it, `app.security.keys.ApiKey.principal`;
           "" without keys: only that key sees the job), times [s since the epoch], progress
           (done, total, problems), result and problem as JSON text;
    items  one row per answered batch item: (job, idx) -> its NDJSON line; seq is the order in
           which items were answered (what items.ndjson streams by).

Ids are `new_job_id()`: 128 bits from `secrets`, so an id is as hard to guess as a key, with
or without API keys.

Owners: each service instance holds an exclusive lock (`fcntl.flock`) on a file of its own beside
the database for as long as it lives, released by the kernel however it ends. A job still queued
or running under an owner whose lock is free was interrupted: `interrupt_orphans` marks it
failed. So a restart reports the jobs it lost, and several instances may share one database
without failing each other's jobs.
"""

from __future__ import annotations

import asyncio
import concurrent.futures
import contextlib
import fcntl
import functools
import json
import logging
import os
import queue
import secrets
import sqlite3
import threading
from collections.abc import Callable
from pathlib import Path
from typing import Any, TypeVar

from app.problems import Problem

__all__ = ["JOB_ID_BYTES", "JobRow", "JobStore", "OwnerLock", "new_job_id"]

log = logging.getLogger(__name__)

T = TypeVar("T")
JobRow = dict[str, Any]

_SCHEMA = """
CREATE TABLE IF NOT EXISTS jobs (
    id TEXT PRIMARY KEY,
    operation TEXT NOT NULL,
    status TEXT NOT NULL,
    owner TEXT NOT NULL,
    principal TEXT NOT NULL DEFAULT '',
    created REAL NOT NULL,
    started REAL,
    finished REAL,
    expires REAL,
    done INTEGER NOT NULL DEFAULT 0,
    total INTEGER NOT NULL,
    problems INTEGER NOT NULL DEFAULT 0,
    result TEXT,
    problem TEXT
);
CREATE INDEX IF NOT EXISTS jobs_by_creation ON jobs (created DESC, id DESC);
CREATE INDEX IF NOT EXISTS jobs_by_expiry ON jobs (expires);
CREATE INDEX IF NOT EXISTS jobs_by_owner ON jobs (owner, status);
CREATE TABLE IF NOT EXISTS items (
    job TEXT NOT NULL,
    idx INTEGER NOT NULL,
    seq INTEGER NOT NULL,
    ok INTEGER NOT NULL,
    line TEXT NOT NULL,
    PRIMARY KEY (job, idx)
);
CREATE INDEX IF NOT EXISTS items_by_answer ON items (job, seq);
"""
_UNFINISHED = ("queued", "running")
_JOB_COLUMNS = (
    "id, operation, status, owner, principal, created, started, finished, expires, done, total, "
    "problems"
)
JOB_ID_BYTES = 16  # 128 random bits


def new_job_id() -> str:
    """A new job's id: 128 random bits (`secrets`) as 22 URL-safe base64 characters."""
    return secrets.token_urlsafe(JOB_ID_BYTES)


_BATCH_LIMIT = 512  # queued operations run under one commit at most
_STOP = object()


class OwnerLock:
    """This instance's lock file `<db>.owners/<owner>.lock`, held (flock) while it lives."""

    def __init__(self, db: Path, owner: str) -> None:
        self.directory = db.with_name(db.name + ".owners")
        self.owner = owner
        self._fd: int | None = None

    def acquire(self) -> None:
        self.directory.mkdir(parents=True, exist_ok=True)
        self._fd = os.open(self.directory / f"{self.owner}.lock", os.O_RDWR | os.O_CREAT, 0o600)
        fcntl.flock(self._fd, fcntl.LOCK_EX | fcntl.LOCK_NB)

    def release(self) -> None:
        if self._fd is None:
            return
        with contextlib.suppress(OSError):
            (self.directory / f"{self.owner}.lock").unlink()
        os.close(self._fd)
        self._fd = None

    def is_alive(self, owner: str) -> bool:
        """Whether the instance `owner` still holds its lock."""
        path = self.directory / f"{owner}.lock"
        try:
            fd = os.open(path, os.O_RDWR)
        except FileNotFoundError:
            return False
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            return True
        finally:
            os.close(fd)
        with contextlib.suppress(OSError):
            path.unlink()
        return False


class JobStore:
    """The jobs database behind its writer thread (see the module docstring)."""

    def __init__(self, path: Path) -> None:
        self.path = path
        self._tasks: queue.SimpleQueue[Any] = queue.SimpleQueue()
        self._thread: threading.Thread | None = None

    # --------------------------------------------------------------------- thread plumbing

    async def open(self) -> None:
        self.path.parent.mkdir(parents=True, exist_ok=True)
        self._thread = threading.Thread(target=self._serve, name="flexwing-jobs-db", daemon=True)
        self._thread.start()
        await self.read(_create_schema)

    async def close(self) -> None:
        if self._thread is None:
            return
        self._tasks.put(_STOP)
        await asyncio.to_thread(self._thread.join, 30)
        self._thread = None

    def write(self, operation: Callable[..., Any], *args: Any) -> None:
        """Queue `operation(connection, *args)`; failures are logged."""
        self._tasks.put((operation, args, None))

    async def read(self, operation: Callable[..., T], *args: Any) -> T:
        """Run `operation(connection, *args)` after everything queued before it; 503
        not-ready while the database is not open (an app without its lifespan, a closed one),
        where a read would wait for ever."""
        if self._thread is None:
            raise Problem("not-ready", "the jobs database is not open")
        future: concurrent.futures.Future[T] = concurrent.futures.Future()
        self._tasks.put((operation, args, future))
        return await asyncio.wrap_future(future)

    def _serve(self) -> None:
        connection = sqlite3.connect(self.path, isolation_level="DEFERRED")
        connection.execute("PRAGMA journal_mode=WAL")
        connection.execute("PRAGMA synchronous=NORMAL")
        stop = False
        while not stop:
            batch = [self._tasks.get()]
            while len(batch) < _BATCH_LIMIT:
                try:
                    batch.append(self._tasks.get_nowait())
                except queue.Empty:
                    break
            answers = []
            for task in batch:
                if task is _STOP:
                    stop = True
                else:
                    answers.append(self._run(connection, *task))
            connection.commit()
            for answer in answers:
                if answer is not None:
                    answer()
        connection.close()

    @staticmethod
    def _run(
        connection: sqlite3.Connection,
        operation: Callable[..., Any],
        args: tuple[Any, ...],
        future: concurrent.futures.Future[Any] | None,
    ) -> Callable[[], None] | None:
        """Run one operation; for a read, what hands its outcome back (after the commit)."""
        try:
            value = operation(connection, *args)
        except Exception as error:
            if future is None:
                log.exception("jobs database: %s failed", operation.__name__)
                return None
            return functools.partial(future.set_exception, error)
        return None if future is None else functools.partial(future.set_result, value)


# --------------------------------------------------------- operations (run in the thread)


def _create_schema(connection: sqlite3.Connection) -> None:
    connection.executescript(_SCHEMA)
    columns = {row[1] for row in connection.execute("PRAGMA table_info(jobs)")}
    if "principal" not in columns:  # a database from before API keys: its jobs are keyless
        with contextlib.suppress(sqlite3.OperationalError):  # another process added it first
            connection.execute("ALTER TABLE jobs ADD COLUMN principal TEXT NOT NULL DEFAULT ''")
    connection.execute(
        "CREATE INDEX IF NOT EXISTS jobs_by_principal ON jobs (principal, created DESC, id DESC)"
    )


def insert_job(connection: sqlite3.Connection, row: JobRow) -> None:
    columns = ", ".join(row)
    marks = ", ".join("?" for _ in row)
    connection.execute(f"INSERT INTO jobs ({columns}) VALUES ({marks})", tuple(row.values()))


def update_job(connection: sqlite3.Connection, job_id: str, fields: JobRow) -> None:
    assignments = ", ".join(f"{name} = ?" for name in fields)
    connection.execute(f"UPDATE jobs SET {assignments} WHERE id = ?", (*fields.values(), job_id))


def insert_item(
    connection: sqlite3.Connection, job_id: str, index: int, seq: int, ok: bool, line: str
) -> None:
    connection.execute(
        "INSERT OR REPLACE INTO items (job, idx, seq, ok, line) VALUES (?, ?, ?, ?, ?)",
        (job_id, index, seq, ok, line),
    )


def _as_row(cursor: sqlite3.Cursor, values: tuple[Any, ...]) -> JobRow:
    return {column[0]: value for column, value in zip(cursor.description, values, strict=True)}


def get_job(connection: sqlite3.Connection, job_id: str, with_result: bool) -> JobRow | None:
    columns = _JOB_COLUMNS + (", result, problem" if with_result else ", problem")
    cursor = connection.execute(f"SELECT {columns} FROM jobs WHERE id = ?", (job_id,))
    values = cursor.fetchone()
    return None if values is None else _as_row(cursor, values)


def list_jobs(
    connection: sqlite3.Connection,
    limit: int,
    before: tuple[float, str] | None,
    status: str | None,
    now: float,
    principal: str,
) -> list[JobRow]:
    """`principal`'s jobs, newest first, `limit` at most, created before the cursor `before`
    (created, id)."""
    where = ["principal = ?", "(expires IS NULL OR expires > ?)"]
    args: list[Any] = [principal, now]
    if before is not None:
        where.append("(created < ? OR (created = ? AND id < ?))")
        args += [before[0], before[0], before[1]]
    if status is not None:
        where.append("status = ?")
        args.append(status)
    cursor = connection.execute(
        f"SELECT {_JOB_COLUMNS}, problem FROM jobs WHERE {' AND '.join(where)} "
        "ORDER BY created DESC, id DESC LIMIT ?",
        (*args, limit),
    )
    return [_as_row(cursor, values) for values in cursor.fetchall()]


def item_lines_by_answer(
    connection: sqlite3.Connection, job_id: str, after_seq: int, limit: int
) -> list[tuple[int, str]]:
    """(seq, line) of the items answered after `after_seq`, in the order they were answered."""
    cursor = connection.execute(
        "SELECT seq, line FROM items WHERE job = ? AND seq > ? ORDER BY seq LIMIT ?",
        (job_id, after_seq, limit),
    )
    return list(cursor.fetchall())


def item_lines_by_index(
    connection: sqlite3.Connection, job_id: str, after_index: int, limit: int
) -> list[tuple[int, str]]:
    """(index, line) of the items after `after_index`, in request order."""
    cursor = connection.execute(
        "SELECT idx, line FROM items WHERE job = ? AND idx > ? ORDER BY idx LIMIT ?",
        (job_id, after_index, limit),
    )
    return list(cursor.fetchall())


def count_by_status(connection: sqlite3.Connection, now: float) -> dict[str, int]:
    cursor = connection.execute(
        "SELECT status, COUNT(*) FROM jobs WHERE expires IS NULL OR expires > ? GROUP BY status",
        (now,),
    )
    return dict(cursor.fetchall())


def delete_expired(connection: sqlite3.Connection, now: float) -> dict[str, int]:
    """Delete the jobs (and items) whose retention has ended; how many, by status."""
    cursor = connection.execute("SELECT id, status FROM jobs WHERE expires <= ?", (now,))
    expired = cursor.fetchall()
    counts: dict[str, int] = {}
    for job_id, status in expired:
        connection.execute("DELETE FROM items WHERE job = ?", (job_id,))
        connection.execute("DELETE FROM jobs WHERE id = ?", (job_id,))
        counts[status] = counts.get(status, 0) + 1
    return counts


def unfinished_owners(connection: sqlite3.Connection) -> list[str]:
    cursor = connection.execute(
        "SELECT DISTINCT owner FROM jobs WHERE status IN (?, ?)", _UNFINISHED
    )
    return [owner for (owner,) in cursor.fetchall()]


def interrupt_jobs_of(
    connection: sqlite3.Connection, owner: str, now: float, retention: float
) -> int:
    """Mark every queued or running job of `owner` failed with a job-interrupted problem."""
    cursor = connection.execute(
        "SELECT id, status, done, total FROM jobs WHERE owner = ? AND status IN (?, ?)",
        (owner, *_UNFINISHED),
    )
    rows = cursor.fetchall()
    for job_id, status, done, total in rows:
        # A batch's answered items are all here; its progress column may lag (written every
        # half second).
        answered, problems = connection.execute(
            "SELECT COUNT(*), COUNT(*) - COALESCE(SUM(ok), 0) FROM items WHERE job = ?", (job_id,)
        ).fetchone()
        done = max(done, answered)
        problem = interrupted_problem(status, done, total)
        connection.execute(
            "UPDATE jobs SET status = 'failed', finished = ?, expires = ?, problem = ?, "
            "done = ?, problems = MAX(problems, ?) WHERE id = ?",
            (now, now + retention, json.dumps(problem), done, problems, job_id),
        )
    return len(rows)


def interrupted_problem(status: str, done: int, total: int) -> dict[str, Any]:
    """The job-interrupted problem of a job that was `status` when its service stopped."""
    if status == "queued":
        what = "before this job started"
    else:
        what = f"while this job ran ({done} of {total} units done)"
    return {
        "type": "/problems/job-interrupted",
        "title": "Job interrupted",
        "status": 503,
        "detail": f"the service stopped {what}; submit it again",
        "done": done,
        "total": total,
    }


def owner_of(connection: sqlite3.Connection, job_id: str) -> str | None:
    """The instance that holds a job (its lock's owner), or None for an unknown job."""
    found = connection.execute("SELECT owner FROM jobs WHERE id = ?", (job_id,)).fetchone()
    return None if found is None else str(found[0])
