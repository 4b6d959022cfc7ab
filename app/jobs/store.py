"""The store: jobs, their items, leases, rate-limit buckets and API keys, in SQLite (one
machine, the default) or PostgreSQL (FLEXWING_DATABASE_URL: replicas share it), behind one
interface. The SQL below is written once for both (`app.jobs.stores.dialects` says the little
that differs); the tables are described in `app.jobs.stores.schema`.

Running a job is leased, not locked by a process: a replica *claims* a queued job (or one whose
lease has expired: its replica died) and holds it for `lease` seconds, renewed by its heartbeat.
Everything a running job writes is fenced by its lease (`owner = ? AND status = 'running'`), so
a replica that lost its lease (it stalled, its database was away) can no longer record
anything; an item is recorded once (`ON CONFLICT DO NOTHING`), so no item is answered twice.
On PostgreSQL a claim passes rows another claim holds (SKIP LOCKED) and an item's fence holds
its job's row until the commit (FOR SHARE), so a claim never overtakes an item being written.

Ids are `new_job_id()`: 128 bits from `secrets`, so an id is as hard to guess as a key.
"""

from __future__ import annotations

import json
import secrets
from pathlib import Path
from typing import Any, TypeVar

from app.jobs.stores import Database, Dialect, PostgreSQL, Session, SQLite, migrate

__all__ = ["JOB_ID_BYTES", "Claim", "JobRow", "Store", "interrupted_problem", "new_job_id"]

T = TypeVar("T")
JobRow = dict[str, Any]
Claim = dict[str, Any]

JOB_ID_BYTES = 16  # 128 random bits
_JOB_COLUMNS = (
    "id, operation, status, owner, principal, created, started, finished, expires, done, total, "
    "problems, lease_expires, cancel_requested"
)
_FENCE = "id = ? AND owner = ? AND status = 'running'"


def new_job_id() -> str:
    """A new job's id: 128 random bits (`secrets`) as 22 URL-safe base64 characters."""
    return secrets.token_urlsafe(JOB_ID_BYTES)


def interrupted_problem(
    status: str, done: int, total: int, why: str | None = None
) -> dict[str, Any]:
    """The job-interrupted problem of a job that was `status` when its service stopped."""
    if status == "queued":
        what = "before this job started"
    else:
        what = f"while this job ran ({done} of {total} units done)"
    return {
        "type": "/problems/job-interrupted",
        "title": "Job interrupted",
        "status": 503,
        "detail": why or f"the service stopped {what}; submit it again",
        "done": done,
        "total": total,
    }


class Store:
    """The store of one service process: its `Database` connection and what it asks of it."""

    def __init__(self, dialect: Dialect, *, retry_after: int = 1) -> None:
        self.dialect = dialect
        self.database = Database(dialect, migrate, retry_after=retry_after)
        # Claims and rate-limit buckets on a connection of their own: never queued behind a
        # batch's item writes, and their commits do not wait for the disk. Losing one with the
        # database server's last moments costs a retry, never a job: a claim not kept leaves
        # the job claimable again (everything a job writes is fenced by its claim), a token
        # not kept a request's worth of limit.
        self.coordination = Database(dialect, migrate, retry_after=retry_after, durable=False)

    @classmethod
    def of(cls, database_url: str | None, jobs_db: Path, retry_after: int = 1) -> Store:
        """PostgreSQL at `database_url` when set, else the SQLite file `jobs_db`."""
        dialect: Dialect = PostgreSQL(database_url) if database_url else SQLite(jobs_db)
        return cls(dialect, retry_after=retry_after)

    @property
    def name(self) -> str:
        """The database, as /readyz names it (no password)."""
        return self.dialect.name

    @property
    def shared(self) -> bool:
        """Whether replicas on other machines share it (PostgreSQL)."""
        return self.dialect.shared

    @property
    def available(self) -> bool:
        return self.database.available

    @property
    def reason(self) -> str | None:
        """Why it is not available, or None."""
        return self.database.reason

    async def open(self) -> None:
        await self.database.open()
        await self.coordination.open()

    async def close(self) -> None:
        await self.coordination.close()
        await self.database.close()

    @property
    def is_open(self) -> bool:
        return self.database.is_open

    # --------------------------------------------------------------------------- jobs

    async def submit(self, row: JobRow, max_queued: int) -> bool:
        """Store a queued job unless `max_queued` jobs wait already (False then). Answered
        after its commit: an accepted job is never lost."""
        return await self.database.read(_submit, row, max_queued)

    def insert_job(self, row: JobRow) -> None:
        """Store a job (queued behind the writes before it): a synchronous call adopted."""
        self.database.write(_insert_job, row)

    def update_job(self, job_id: str, owner: str, fields: JobRow) -> None:
        """Set `fields` of a job `owner` runs (nothing if its lease has passed to another)."""
        self.database.write(_update_job, job_id, owner, fields)

    def insert_item(
        self, job_id: str, owner: str, index: int, seq: int, ok: bool, line: str
    ) -> None:
        """Record a batch item's line, once, while `owner` runs the job."""
        self.database.write(_insert_item, job_id, owner, index, seq, ok, line)

    def release(self, job_id: str, owner: str, done: int, problems: int) -> None:
        """Hand a running job back to the queue (its replica is stopping): another replica, or
        this one's next start, takes it up where it was (a batch's answered items stay)."""
        self.database.write(_release, job_id, owner, done, problems)

    async def get_job(self, job_id: str, with_result: bool = False) -> JobRow | None:
        return await self.database.read(_get_job, job_id, with_result)

    async def list_jobs(
        self,
        limit: int,
        before: tuple[float, str] | None,
        status: str | None,
        now: float,
        principal: str,
    ) -> list[JobRow]:
        """`principal`'s jobs, newest first, `limit` at most, created before the cursor
        `before` (created, id)."""
        return await self.database.read(_list_jobs, limit, before, status, now, principal)

    async def items_by_answer(self, job_id: str, after_seq: int, limit: int) -> list[Any]:
        """(seq, line) of the items answered after `after_seq`, in the order answered."""
        return await self.database.read(_items_by, "seq", job_id, after_seq, limit)

    async def items_by_index(self, job_id: str, after_index: int, limit: int) -> list[Any]:
        """(index, line) of the items after `after_index`, in request order."""
        return await self.database.read(_items_by, "idx", job_id, after_index, limit)

    async def count_by_status(self, now: float) -> dict[str, int]:
        return await self.database.read(_count_by_status, now)

    async def delete_expired(self, now: float) -> dict[str, int]:
        """Delete the jobs (and items) whose retention has ended; how many, by status."""
        return await self.database.read(_delete_expired, now)

    async def claim(self, owner: str, now: float, lease: float) -> Claim | None:
        """The oldest job that is queued, or running under an expired lease, now `owner`'s
        until `now + lease`, with its request and (a batch's) items answered so far; None."""
        return await self.coordination.read(_claim, owner, now, lease)

    async def renew(self, owner: str, until: float, job_ids: list[str]) -> dict[str, bool]:
        """Extend `owner`'s leases of `job_ids` (the jobs it runs) to `until`: {job id: cancel
        asked for} of those it still holds."""
        # On the jobs' own connection: after every job this replica stored (an adopted call's
        # insert is queued there), so a renewal never misses one of its jobs.
        return await self.database.read(_renew, owner, until, job_ids)

    async def cancel_queued(self, job_id: str, principal: str, now: float, expires: float) -> bool:
        """Cancel a job of `principal` that no replica runs (queued, or its lease expired)."""
        return await self.database.read(_cancel_queued, job_id, principal, now, expires)

    async def ask_cancel(self, job_id: str, principal: str) -> None:
        """Ask the replica running a job of `principal` to cancel it (at its next heartbeat)."""
        await self.database.read(_ask_cancel, job_id, principal)

    # ------------------------------------------------------------------ rate-limit buckets

    async def take_token(self, client: str, rate: float, burst: int, now: float) -> float:
        """One request of `client` from its token bucket (`burst` at most, refilled at `rate`
        [1/s]): 0.0 if it may go ahead, else [s] until its next token."""
        return await self.coordination.read(_take_token, client, rate, burst, now)

    async def forget_buckets(self, before: float) -> None:
        """Drop buckets untouched since `before` (full again by then: as new ones)."""
        await self.coordination.read(_forget_buckets, before)

    # ------------------------------------------------------------------------- API keys

    async def api_keys(self) -> list[tuple[str, str]]:
        """(name, SHA-256 digest in hex) of every key kept here."""
        return await self.database.read(_api_keys)

    async def add_api_key(self, name: str, digest: str, now: float) -> bool:
        """Keep a key's digest under `name`; False if the name or the key is there already."""
        return await self.database.read(_add_api_key, name, digest, now)

    async def revoke_api_key(self, name: str) -> bool:
        return await self.database.read(_revoke_api_key, name)


# --------------------------------------------------------- operations (run in the thread)


def _as_row(cursor: Any, values: Any) -> JobRow:
    return {column[0]: value for column, value in zip(cursor.description, values, strict=True)}


def _insert_job(session: Session, row: JobRow) -> None:
    columns = ", ".join(row)
    marks = ", ".join("?" for _ in row)
    session.execute(
        f"INSERT INTO jobs ({columns}) VALUES ({marks}) ON CONFLICT (id) DO NOTHING",
        tuple(row.values()),
    )


def _submit(session: Session, row: JobRow, max_queued: int) -> bool:
    (queued,) = session.execute("SELECT COUNT(*) FROM jobs WHERE status = 'queued'").fetchone()
    if queued >= max_queued:
        return False
    _insert_job(session, row)
    return True


def _update_job(session: Session, job_id: str, owner: str, fields: JobRow) -> None:
    assignments = ", ".join(f"{name} = ?" for name in fields)
    session.execute(
        f"UPDATE jobs SET {assignments} WHERE {_FENCE}", (*fields.values(), job_id, owner)
    )


def _insert_item(
    session: Session, job_id: str, owner: str, index: int, seq: int, ok: bool, line: str
) -> None:
    session.execute(
        "INSERT INTO items (job, idx, seq, ok, line) SELECT ?, ?, ?, ?, ? "
        f"WHERE EXISTS (SELECT 1 FROM jobs WHERE {_FENCE}{session.dialect.share_lock}) "
        "ON CONFLICT (job, idx) DO NOTHING",
        (job_id, index, seq, int(ok), line, job_id, owner),
    )


def _release(session: Session, job_id: str, owner: str, done: int, problems: int) -> None:
    session.execute(
        "UPDATE jobs SET status = 'queued', owner = '', lease_expires = NULL, "
        f"attempts = attempts - 1, done = ?, problems = ? WHERE {_FENCE}",
        (done, problems, job_id, owner),
    )


def _get_job(session: Session, job_id: str, with_result: bool) -> JobRow | None:
    columns = _JOB_COLUMNS + (", result, problem" if with_result else ", problem")
    cursor = session.execute(f"SELECT {columns} FROM jobs WHERE id = ?", (job_id,))
    values = cursor.fetchone()
    return None if values is None else _as_row(cursor, values)


def _list_jobs(
    session: Session,
    limit: int,
    before: tuple[float, str] | None,
    status: str | None,
    now: float,
    principal: str,
) -> list[JobRow]:
    where = ["principal = ?", "(expires IS NULL OR expires > ?)"]
    args: list[Any] = [principal, now]
    if before is not None:
        where.append("(created < ? OR (created = ? AND id < ?))")
        args += [before[0], before[0], before[1]]
    if status is not None:
        where.append("status = ?")
        args.append(status)
    cursor = session.execute(
        f"SELECT {_JOB_COLUMNS}, problem FROM jobs WHERE {' AND '.join(where)} "
        "ORDER BY created DESC, id DESC LIMIT ?",
        (*args, limit),
    )
    return [_as_row(cursor, values) for values in cursor.fetchall()]


def _items_by(session: Session, order: str, job_id: str, after: int, limit: int) -> list[Any]:
    cursor = session.execute(
        f"SELECT {order}, line FROM items WHERE job = ? AND {order} > ? ORDER BY {order} LIMIT ?",
        (job_id, after, limit),
    )
    return [tuple(row) for row in cursor.fetchall()]


def _count_by_status(session: Session, now: float) -> dict[str, int]:
    cursor = session.execute(
        "SELECT status, COUNT(*) FROM jobs WHERE expires IS NULL OR expires > ? GROUP BY status",
        (now,),
    )
    return {status: int(count) for status, count in cursor.fetchall()}


def _delete_expired(session: Session, now: float) -> dict[str, int]:
    expired = session.execute("SELECT id, status FROM jobs WHERE expires <= ?", (now,)).fetchall()
    counts: dict[str, int] = {}
    for job_id, status in expired:
        session.execute("DELETE FROM items WHERE job = ?", (job_id,))
        session.execute("DELETE FROM jobs WHERE id = ?", (job_id,))
        counts[status] = counts.get(status, 0) + 1
    return counts


def _claim(session: Session, owner: str, now: float, lease: float) -> Claim | None:
    cursor = session.execute(
        "UPDATE jobs SET status = 'running', owner = ?, lease_expires = ?, "
        "attempts = attempts + 1, started = COALESCE(started, ?) "
        "WHERE id = (SELECT id FROM jobs WHERE status = 'queued' OR (status = 'running' AND "
        "(lease_expires IS NULL OR lease_expires < ?)) "
        f"ORDER BY created, id LIMIT 1{session.dialect.skip_locked}) "
        f"RETURNING {_JOB_COLUMNS}, request, attempts",
        (owner, now + lease, now, now),
    )
    values = cursor.fetchone()
    if values is None:
        return None
    claim = _as_row(cursor, values)
    answered = session.execute(
        "SELECT idx, seq, ok FROM items WHERE job = ?", (claim["id"],)
    ).fetchall()
    claim["answered"] = {int(index): bool(ok) for index, _, ok in answered}
    claim["answers"] = max((int(seq) for _, seq, _ in answered), default=0)
    return claim


def _renew(session: Session, owner: str, until: float, job_ids: list[str]) -> dict[str, bool]:
    if not job_ids:
        return {}
    marks = ", ".join("?" for _ in job_ids)
    cursor = session.execute(
        "UPDATE jobs SET lease_expires = ? WHERE owner = ? AND status = 'running' "
        f"AND id IN ({marks}) RETURNING id, cancel_requested",
        (until, owner, *job_ids),
    )
    return {job_id: bool(asked) for job_id, asked in cursor.fetchall()}


def _cancel_queued(
    session: Session, job_id: str, principal: str, now: float, expires: float
) -> bool:
    cursor = session.execute(
        "UPDATE jobs SET status = 'cancelled', finished = ?, expires = ?, owner = '', "
        "lease_expires = NULL, request = NULL WHERE id = ? AND principal = ? AND "
        "(status = 'queued' OR (status = 'running' AND "
        "(lease_expires IS NULL OR lease_expires < ?)))",
        (now, expires, job_id, principal, now),
    )
    return int(cursor.rowcount) == 1


def _ask_cancel(session: Session, job_id: str, principal: str) -> None:
    session.execute(
        "UPDATE jobs SET cancel_requested = 1 WHERE id = ? AND principal = ? "
        "AND status = 'running'",
        (job_id, principal),
    )


def _take_token(session: Session, client: str, rate: float, burst: int, now: float) -> float:
    least, greatest = session.dialect.least, session.dialect.greatest
    refilled = f"{least}(?, buckets.tokens + {greatest}(0, ? - buckets.updated) * ?)"
    args = (float(burst), now, rate)
    tokens, granted = session.execute(
        "INSERT INTO buckets (client, tokens, updated, granted) VALUES (?, ?, ?, 1) "
        "ON CONFLICT (client) DO UPDATE SET "
        f"tokens = CASE WHEN {refilled} >= 1 THEN {refilled} - 1 ELSE {refilled} END, "
        f"granted = CASE WHEN {refilled} >= 1 THEN 1 ELSE 0 END, "
        f"updated = {greatest}(buckets.updated, ?) RETURNING tokens, granted",
        (client, float(burst) - 1.0, now, *(args * 4), now),
    ).fetchone()
    return 0.0 if granted else (1.0 - float(tokens)) / rate


def _forget_buckets(session: Session, before: float) -> None:
    session.execute("DELETE FROM buckets WHERE updated < ?", (before,))


def _api_keys(session: Session) -> list[tuple[str, str]]:
    rows = session.execute("SELECT name, digest FROM api_keys ORDER BY name").fetchall()
    return [(str(name), str(digest)) for name, digest in rows]


def _add_api_key(session: Session, name: str, digest: str, now: float) -> bool:
    cursor = session.execute(
        "INSERT INTO api_keys (name, digest, created) VALUES (?, ?, ?) ON CONFLICT DO NOTHING",
        (name, digest, now),
    )
    return int(cursor.rowcount) == 1


def _revoke_api_key(session: Session, name: str) -> bool:
    cursor = session.execute("DELETE FROM api_keys WHERE name = ?", (name,))
    return int(cursor.rowcount) == 1


def request_json(request: Any) -> str:
    """A request model as the JSON text the store keeps (what another replica runs)."""
    dump = getattr(request, "model_dump_json", None)
    return dump() if callable(dump) else json.dumps(request)
