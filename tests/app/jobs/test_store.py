"""app.jobs.store: one interface, the same specification on SQLite and on a real PostgreSQL
(`database`, tests/app/jobs/conftest.py). What a read hands back has been committed; the schema
is versioned and migrated once; a job is claimed by one replica at a time, under a lease that
expires; what a replica writes after losing its lease changes nothing; an item is recorded
once; a token bucket is shared by every store on the database; API keys are kept by name.

Times are passed in (`now`), so leases and buckets are tested without waiting. Nothing here is
timed: `WAIT` only turns a hang into a failure."""

from __future__ import annotations

import asyncio
import contextlib
import sqlite3
import threading
from collections.abc import Awaitable, Callable
from pathlib import Path
from typing import Any

import httpx
import psycopg
import pytest

from app.jobs.store import Store, interrupted_problem, new_job_id
from app.jobs.stores import SCHEMA_VERSION, Session
from app.problems import Problem
from tests.app.jobs.conftest import Backend

WAIT = 10.0  # [s] guards a hang only
NOW = 1_700_000_000.0  # [s since the epoch] the tests' clock
LEASE = 10.0  # [s]


def _run(scenario: Callable[[], Awaitable[None]]) -> None:
    async def guarded() -> None:
        await asyncio.wait_for(scenario(), 60)

    asyncio.run(guarded())


@contextlib.asynccontextmanager
async def _opened(store: Store) -> Any:
    await store.open()
    try:
        yield store
    finally:
        await store.close()


def _job(created: float = NOW, **fields: Any) -> dict[str, Any]:
    return {
        "id": new_job_id(),
        "operation": "batch",
        "status": "queued",
        "owner": "",
        "principal": "",
        "created": created,
        "total": 3,
        "request": '{"items": []}',
    } | fields


def _committed(database: Backend, sql: str) -> list[Any]:
    """What another connection sees: only what was committed."""
    if database.url is None:
        with contextlib.closing(sqlite3.connect(database.path)) as other:
            return other.execute(sql).fetchall()
    with psycopg.connect(database.url) as connection:
        return connection.execute(sql).fetchall()


# --------------------------------------------------------------------- reads and commits


def test_a_read_answers_only_after_the_writes_before_it_are_committed(database: Backend):
    """One batch of the writer thread holds an item write, a read and a write that blocks: the
    read's answer must wait for the batch's commit, and by then the item is committed."""

    async def scenario() -> None:
        async with _opened(database.store()) as jobs:
            job = _job(status="running", owner="me")
            assert await jobs.submit(job, 10)
            busy, blocker, holding = threading.Event(), threading.Event(), threading.Event()

            def hold(session: Session) -> None:
                holding.set()
                busy.wait(WAIT)

            # Keep the thread busy (and wait until it is) so that the next three operations
            # are queued behind it and drained as one batch.
            jobs.database.write(hold)
            assert await asyncio.to_thread(holding.wait, WAIT)
            jobs.insert_item(job["id"], "me", 0, 1, True, '{"index": 0}')
            answer = asyncio.ensure_future(jobs.items_by_answer(job["id"], 0, 10))
            await asyncio.sleep(0)  # let the read queue itself
            reached = threading.Event()

            def blocking_write(session: Session) -> None:
                reached.set()
                blocker.wait(WAIT)

            jobs.database.write(blocking_write)
            busy.set()
            # The batch has run up to the blocking write: the read is behind it, uncommitted.
            assert await asyncio.to_thread(reached.wait, WAIT)
            await asyncio.sleep(0)  # an answer already sent would be delivered by now
            assert not answer.done(), "a read answered before its batch was committed"
            lines = "SELECT line FROM items ORDER BY seq"
            assert await asyncio.to_thread(_committed, database, lines) == []
            blocker.set()
            assert await asyncio.wait_for(answer, WAIT) == [(1, '{"index": 0}')]
            assert await asyncio.to_thread(_committed, database, lines) == [('{"index": 0}',)]

    _run(scenario)


def test_an_operation_that_fails_fails_alone_and_the_rest_of_its_batch_is_kept(
    database: Backend,
):
    """A write that breaks a constraint (PostgreSQL aborts the whole transaction then) costs
    only itself: the batch is run again one operation at a time."""

    async def scenario() -> None:
        async with _opened(database.store()) as jobs:
            first, second = _job(), _job()

            def broken(session: Session) -> None:
                session.execute("INSERT INTO jobs (id) VALUES (?)", ("no-operation",))

            jobs.insert_job(first)
            jobs.database.write(broken)
            jobs.insert_job(second)
            assert await jobs.get_job(first["id"]) is not None
            assert await jobs.get_job(second["id"]) is not None
            assert await jobs.get_job("no-operation") is None

    _run(scenario)


def test_a_read_of_a_store_that_is_not_open_is_refused_not_left_waiting(database: Backend):
    """An app without its lifespan (or after it) has no writer thread: a read would wait for
    ever; it is 503 not-ready instead."""
    closed = database.store()
    with pytest.raises(Problem) as refused:
        asyncio.run(asyncio.wait_for(closed.count_by_status(0.0), 10))
    assert refused.value.type.slug == "not-ready"


def test_a_jobs_request_to_an_app_without_its_lifespan_is_503(in_process: httpx.Client):
    assert in_process.get("/jobs", timeout=10).status_code == 503


# ---------------------------------------------------------------------------- the schema


def test_replicas_that_open_a_new_database_together_migrate_it_once(database: Backend):
    async def scenario() -> None:
        stores = [database.store() for _ in range(3)]
        await asyncio.gather(*(store.open() for store in stores))
        try:
            assert all(store.available for store in stores)
        finally:
            await asyncio.gather(*(store.close() for store in stores))
        versions = _committed(database, "SELECT version FROM schema_version ORDER BY version")
        assert versions == [(n,) for n in range(1, SCHEMA_VERSION + 1)]

    _run(scenario)


def test_an_sqlite_file_of_issue_13_is_migrated_in_place_keeping_its_jobs(tmp_path: Path):
    """The schema before versions (and before API keys: no principal column)."""
    path = tmp_path / "jobs.sqlite3"
    with contextlib.closing(sqlite3.connect(path)) as old:
        old.executescript(
            "CREATE TABLE jobs (id TEXT PRIMARY KEY, operation TEXT NOT NULL, status TEXT NOT "
            "NULL, owner TEXT NOT NULL, created REAL NOT NULL, started REAL, finished REAL, "
            "expires REAL, done INTEGER NOT NULL DEFAULT 0, total INTEGER NOT NULL, problems "
            "INTEGER NOT NULL DEFAULT 0, result TEXT, problem TEXT);"
            "INSERT INTO jobs (id, operation, status, owner, created, finished, done, total, "
            "result) VALUES ('old', 'solve', 'succeeded', 'x', 1.0, 2.0, 1, 1, '{}');"
        )
        old.commit()

    async def scenario() -> None:
        async with _opened(Store.of(None, path)) as jobs:
            row = await jobs.get_job("old", with_result=True)
            assert row is not None
            assert (row["status"], row["principal"], row["result"]) == ("succeeded", "", "{}")

    _run(scenario)


# ---------------------------------------------------------------- submission and claims


def test_a_submission_is_stored_unless_max_queued_jobs_wait(database: Backend):
    async def scenario() -> None:
        async with _opened(database.store()) as jobs:
            assert await jobs.submit(_job(), 2)
            assert await jobs.submit(_job(), 2)
            refused = _job()
            assert not await jobs.submit(refused, 2)
            assert await jobs.get_job(refused["id"]) is None
            assert await jobs.count_by_status(NOW) == {"queued": 2}

    _run(scenario)


def test_replicas_claiming_at_once_take_each_job_once_the_oldest_first(database: Backend):
    """Three stores (replicas) claim six queued jobs concurrently, two each at most: every job
    is claimed by exactly one, oldest first, and a seventh claim finds nothing."""

    async def scenario() -> None:
        replicas = [database.store() for _ in range(3)]
        await asyncio.gather(*(replica.open() for replica in replicas))
        try:
            submitted = [_job(created=NOW + n) for n in range(6)]
            for job in submitted:
                assert await replicas[0].submit(job, 100)
            claims = await asyncio.gather(
                *(
                    replica.claim(f"replica-{n}", NOW + 10, LEASE)
                    for n, replica in enumerate(replicas)
                    for _ in range(2)
                )
            )
            ids = [claim["id"] for claim in claims if claim is not None]
            assert sorted(ids) == sorted(job["id"] for job in submitted)
            assert await replicas[1].claim("replica-1", NOW + 10, LEASE) is None
            first = await replicas[0].claim("late", NOW + 10, LEASE)
            assert first is None
            (row,) = [c for c in claims if c is not None and c["id"] == submitted[0]["id"]]
            assert (row["status"], row["attempts"], row["started"]) == ("running", 1, NOW + 10)
            assert row["request"] == '{"items": []}'
            counts = await replicas[2].count_by_status(NOW)
            assert counts == {"running": 6}
        finally:
            await asyncio.gather(*(replica.close() for replica in replicas))

    _run(scenario)


def test_a_job_whose_lease_expired_is_claimed_again_with_its_items_and_the_old_owner_is_fenced(
    database: Backend,
):
    """Replica A claims a batch, answers two items and stalls past its lease; replica B claims
    it with those two items; A's late writes (an item, its progress, its result) change
    nothing; B's are recorded, and an item B answers again is not recorded twice."""

    async def scenario() -> None:
        async with _opened(database.store()) as a, _opened(database.store()) as b:
            job = _job()
            assert await a.submit(job, 10)
            claim = await a.claim("A", NOW, LEASE)
            assert claim is not None and claim["answered"] == {}
            a.insert_item(job["id"], "A", 2, 1, True, '{"index": 2, "by": "A"}')
            a.insert_item(job["id"], "A", 0, 2, False, '{"index": 0, "by": "A"}')
            assert await a.renew("A", NOW + LEASE, [job["id"]]) == {job["id"]: False}
            assert await b.claim("B", NOW + LEASE / 2, LEASE) is None  # the lease holds
            taken = await b.claim("B", NOW + 2 * LEASE, LEASE)
            assert taken is not None and taken["id"] == job["id"]
            assert (taken["answered"], taken["answers"], taken["attempts"]) == (
                {2: True, 0: False},
                2,
                2,
            )
            assert await a.renew("A", NOW + 3 * LEASE, [job["id"]]) == {}  # A lost the lease
            a.insert_item(job["id"], "A", 1, 3, True, '{"index": 1, "by": "A"}')
            a.update_job(job["id"], "A", {"status": "succeeded", "result": "A's"})
            b.insert_item(job["id"], "B", 0, 3, True, '{"index": 0, "by": "B"}')
            b.insert_item(job["id"], "B", 1, 3, True, '{"index": 1, "by": "B"}')
            b.update_job(job["id"], "B", {"status": "succeeded", "done": 3, "problems": 1})
            row = await b.get_job(job["id"], with_result=True)
            assert row is not None and (row["status"], row["done"], row["result"]) == (
                "succeeded",
                3,
                None,
            )
            lines = await b.items_by_index(job["id"], -1, 10)
            assert [line for _, line in lines] == [
                '{"index": 0, "by": "A"}',
                '{"index": 1, "by": "B"}',
                '{"index": 2, "by": "A"}',
            ]
            by_answer = await b.items_by_answer(job["id"], 0, 10)
            assert [seq for seq, _ in by_answer] == [1, 2, 3]

    _run(scenario)


def test_a_released_job_is_queued_again_and_keeps_its_items_and_attempts(database: Backend):
    async def scenario() -> None:
        async with _opened(database.store()) as jobs:
            job = _job()
            assert await jobs.submit(job, 10)
            assert await jobs.claim("A", NOW, LEASE) is not None
            jobs.insert_item(job["id"], "A", 1, 1, True, "{}")
            jobs.release(job["id"], "A", 1, 0)
            row = await jobs.get_job(job["id"])
            assert row is not None and (row["status"], row["done"]) == ("queued", 1)
            again = await jobs.claim("B", NOW + 1, LEASE)
            assert again is not None
            assert (again["attempts"], again["answered"]) == (1, {1: True})

    _run(scenario)


def test_a_queued_job_cancels_at_once_a_running_one_is_asked_to(database: Backend):
    async def scenario() -> None:
        async with _opened(database.store()) as jobs:
            queued, running = _job(principal="alice"), _job(principal="alice", created=NOW - 1)
            for job in (running, queued):
                assert await jobs.submit(job, 10)
            claim = await jobs.claim("A", NOW, LEASE)
            assert claim is not None and claim["id"] == running["id"]
            assert not await jobs.cancel_queued(queued["id"], "bob", NOW, NOW + 60)
            assert await jobs.cancel_queued(queued["id"], "alice", NOW, NOW + 60)
            row = await jobs.get_job(queued["id"])
            assert row is not None and (row["status"], row["finished"]) == ("cancelled", NOW)
            assert not await jobs.cancel_queued(running["id"], "alice", NOW + 1, NOW + 60)
            await jobs.ask_cancel(running["id"], "alice")
            assert await jobs.renew("A", NOW + LEASE, [running["id"]]) == {running["id"]: True}
            assert await jobs.renew("A", NOW + LEASE, []) == {}
            # Its replica died before it could: once the lease has expired, it cancels here.
            assert await jobs.cancel_queued(running["id"], "alice", NOW + 3 * LEASE, NOW + 60)

    _run(scenario)


def test_expired_jobs_are_deleted_with_their_items(database: Backend):
    async def scenario() -> None:
        async with _opened(database.store()) as jobs:
            old, kept = _job(status="running", owner="A"), _job(status="running", owner="A")
            for job in (old, kept):
                assert await jobs.submit(job, 10)
                jobs.insert_item(job["id"], "A", 0, 1, True, "{}")
            jobs.update_job(old["id"], "A", {"status": "succeeded", "expires": NOW})
            jobs.update_job(kept["id"], "A", {"status": "succeeded", "expires": NOW + 60})
            assert await jobs.delete_expired(NOW) == {"succeeded": 1}
            assert await jobs.get_job(old["id"]) is None
            assert await jobs.items_by_index(old["id"], -1, 10) == []
            assert len(await jobs.items_by_index(kept["id"], -1, 10)) == 1

    _run(scenario)


def test_the_interrupted_problem_says_what_was_done() -> None:
    problem = interrupted_problem("running", 2, 5)
    assert (problem["status"], problem["done"], problem["total"]) == (503, 2, 5)
    assert "2 of 5 units done" in problem["detail"]
    assert "before this job started" in interrupted_problem("queued", 0, 1)["detail"]


# ------------------------------------------------------------------ rate-limit buckets

RATE, BURST = 2.0, 3  # [1/s], [requests]


def test_a_token_bucket_allows_its_burst_then_its_rate_across_replicas(database: Backend):
    """Two stores share one client's bucket: 3 at once between them, then one token every
    0.5 s; another client is not affected."""

    async def scenario() -> None:
        async with _opened(database.store()) as a, _opened(database.store()) as b:
            replicas = (a, b, a)
            waits = [await r.take_token("key:x", RATE, BURST, NOW) for r in replicas]
            assert waits == [0.0, 0.0, 0.0]
            assert await b.take_token("key:x", RATE, BURST, NOW) == pytest.approx(1 / RATE)
            assert await a.take_token("key:y", RATE, BURST, NOW) == 0.0
            # A quarter of a token later: still refused, the wait shorter by that time.
            assert await a.take_token("key:x", RATE, BURST, NOW + 0.125) == pytest.approx(0.375)
            assert await b.take_token("key:x", RATE, BURST, NOW + 0.5) == 0.0
            # Long idle: full again, never more than the burst.
            later = NOW + 3600
            waits = [await r.take_token("key:x", RATE, BURST, later) for r in (a, b, a, b)]
            assert waits[:3] == [0.0, 0.0, 0.0] and waits[3] > 0
            await a.forget_buckets(later)
            assert _committed(database, "SELECT client FROM buckets") == [("key:x",)]
            await a.forget_buckets(later + 1)
            assert _committed(database, "SELECT client FROM buckets") == []

    _run(scenario)


# ------------------------------------------------------------------------------ API keys


def test_api_keys_are_kept_by_name_once_and_revoked(database: Backend):
    async def scenario() -> None:
        async with _opened(database.store()) as keys:
            assert await keys.add_api_key("alice", "ab" * 32, NOW)
            assert not await keys.add_api_key("alice", "cd" * 32, NOW)  # the name is taken
            assert not await keys.add_api_key("bob", "ab" * 32, NOW)  # the key is alice's
            assert await keys.add_api_key("bob", "ef" * 32, NOW)
            assert await keys.api_keys() == [("alice", "ab" * 32), ("bob", "ef" * 32)]
            assert await keys.revoke_api_key("alice")
            assert not await keys.revoke_api_key("alice")
            assert await keys.api_keys() == [("bob", "ef" * 32)]

    _run(scenario)
