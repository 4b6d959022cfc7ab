"""app.jobs.store: what a read hands back has been committed, so a client never sees an item
that a SIGKILL of the service could still lose."""

from __future__ import annotations

import asyncio
import contextlib
import sqlite3
import threading
from pathlib import Path

import httpx
import pytest

from app.jobs import store
from app.problems import Problem

WAIT = 10.0  # [s] guards a hang only; nothing here is timed


def _items_on_disk(path: Path) -> list[str]:
    """The item lines another connection sees: only what was committed."""
    with contextlib.closing(sqlite3.connect(path)) as other:
        return [line for (line,) in other.execute("SELECT line FROM items ORDER BY seq")]


def test_a_read_answers_only_after_the_writes_before_it_are_committed(tmp_path: Path):
    """One batch of the writer thread holds an item write, a read and a write that blocks: the
    read's answer must wait for the batch's commit, and by then the item is on disk."""

    async def scenario() -> None:
        jobs = store.JobStore(tmp_path / "jobs.sqlite")
        await jobs.open()
        busy, blocker, holding = threading.Event(), threading.Event(), threading.Event()

        def hold(connection: object) -> None:
            holding.set()
            busy.wait(WAIT)

        # Keep the thread busy (and wait until it is) so that the next three operations are
        # queued behind it and drained as one batch.
        jobs.write(hold)
        assert await asyncio.to_thread(holding.wait, WAIT)
        jobs.write(store.insert_item, "job", 0, 1, True, '{"index": 0}')
        answer = asyncio.ensure_future(jobs.read(store.item_lines_by_answer, "job", 0, 10))
        await asyncio.sleep(0)  # let the read queue itself
        reached = threading.Event()

        def blocking_write(connection: object) -> None:
            reached.set()
            blocker.wait(WAIT)

        jobs.write(blocking_write)
        busy.set()
        # The batch has run up to the blocking write: the read is behind it, uncommitted.
        assert await asyncio.to_thread(reached.wait, WAIT)
        await asyncio.sleep(0)  # an answer already sent would be delivered by now
        assert not answer.done(), "a read answered before its batch was committed"
        assert _items_on_disk(tmp_path / "jobs.sqlite") == []
        blocker.set()
        assert await asyncio.wait_for(answer, WAIT) == [(1, '{"index": 0}')]
        assert _items_on_disk(tmp_path / "jobs.sqlite") == ['{"index": 0}']
        await jobs.close()

    asyncio.run(scenario())


def test_a_read_of_a_database_that_is_not_open_is_refused_not_left_waiting(tmp_path: Path):
    """An app without its lifespan (or after it) has no writer thread: a read would wait for
    ever; it is 503 not-ready instead."""
    closed = store.JobStore(tmp_path / "jobs.sqlite3")
    with pytest.raises(Problem) as refused:
        asyncio.run(asyncio.wait_for(closed.read(store.count_by_status, 0.0), 10))
    assert refused.value.type.slug == "not-ready"


def test_a_jobs_request_to_an_app_without_its_lifespan_is_503(in_process: httpx.Client):
    assert in_process.get("/jobs", timeout=10).status_code == 503
