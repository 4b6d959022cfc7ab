"""app.jobs.stores.database: when PostgreSQL is unreachable at the start, or lost mid-run, the
store says so (`available`, `reason`, naming the database without its password), refuses reads
with 503 database-unavailable and a Retry-After at once, keeps the writes queued meanwhile, and
makes them when the server is back: nothing written before or during the outage is lost.

A real server (tests/postgres.py) stopped with `pg_ctl -m immediate` (to its clients, a crash)
and started again on the same port. `WAIT` only turns a hang into a failure."""

from __future__ import annotations

import asyncio
import time
from collections.abc import Awaitable, Callable

import pytest

from app.jobs.store import Store, new_job_id
from app.jobs.stores import PostgreSQL, redacted
from app.problems import Problem
from tests.postgres import Cluster, free_port

pytestmark = pytest.mark.server

WAIT = 60.0  # [s] a hang guard only


def _run(scenario: Callable[[], Awaitable[None]]) -> None:
    async def guarded() -> None:
        await asyncio.wait_for(scenario(), WAIT)

    asyncio.run(guarded())


async def _until(condition: Callable[[], bool]) -> None:
    while not condition():
        await asyncio.sleep(0.05)


def _job() -> dict[str, object]:
    return {
        "id": new_job_id(),
        "operation": "solve",
        "status": "running",
        "owner": "A",
        "principal": "",
        "created": time.time(),
        "total": 1,
    }


def test_a_database_url_is_named_without_its_password() -> None:
    url = "postgresql://flexwing:s3cret@db.example.org:6543/jobs?sslmode=require"
    assert redacted(url) == "postgresql://flexwing@db.example.org:6543/jobs"
    assert "s3cret" not in PostgreSQL(url).name


def test_an_unreachable_database_at_the_start_is_unavailable_until_it_answers(
    postgres: Cluster,
) -> None:
    """Nothing listens on the port: `open` returns (no crash), the store is unavailable and
    says why; reads are 503 with Retry-After at once."""
    url = f"postgresql://flexwing:secret@127.0.0.1:{free_port()}/postgres"

    async def scenario() -> None:
        store = Store.of(url, postgres.directory, retry_after=3)
        await store.open()
        try:
            assert not store.available
            assert store.name == f"postgresql://flexwing@{url.split('@')[1]}"
            assert store.reason and "refused" in store.reason.lower()
            with pytest.raises(Problem) as refused:
                await store.get_job("any")
            assert refused.value.type.slug == "database-unavailable"
            assert refused.value.status == 503
            assert refused.value.headers == {"Retry-After": "3"}
            assert store.name in refused.value.detail and "secret" not in refused.value.detail
        finally:
            await store.close()

    _run(scenario)


def test_a_database_lost_mid_run_keeps_the_writes_and_makes_them_when_it_returns(
    postgres: Cluster,
) -> None:
    url = postgres.schema()

    async def scenario() -> None:
        store = Store.of(url, postgres.directory)
        await store.open()
        try:
            before, during = _job(), _job()
            assert await store.submit(before, 10)
            postgres.stop("immediate")
            try:
                # The next statement finds the connection broken.
                store.insert_item(str(before["id"]), "A", 0, 1, True, '{"index": 0}')
                with pytest.raises(Problem) as refused:
                    await store.get_job(str(before["id"]))
                assert refused.value.type.slug == "database-unavailable"
                assert not store.available and store.reason
                store.insert_job(during)  # kept while the database is away
                store.insert_item(str(before["id"]), "A", 1, 2, True, '{"index": 1}')
                with pytest.raises(Problem):  # refused at once, not queued
                    await store.count_by_status(0.0)
            finally:
                postgres.start()
            await _until(lambda: store.available)
            assert await store.get_job(str(during["id"])) is not None
            lines = await store.items_by_answer(str(before["id"]), 0, 10)
            assert lines == [(1, '{"index": 0}'), (2, '{"index": 1}')]
        finally:
            await store.close()

    _run(scenario)
