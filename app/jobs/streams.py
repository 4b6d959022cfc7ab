"""The wire formats a job streams in: server-sent events of its progress and final state
(`events`), and a batch's answers as NDJSON, as they are answered (`item_lines`) or in request
order (`result_items`).

A job this replica runs wakes its streams as it changes; one that another replica runs (or that
waits in the queue) is read from the store every `manager.poll_interval` (0.5 s, as often as a
running job's progress is written there): see docs/deployment.md for why polling and not
PostgreSQL's LISTEN/NOTIFY."""

from __future__ import annotations

import asyncio
import json
from collections.abc import AsyncIterator

from app.jobs.manager import JobManager
from app.jobs.models import FINISHED_STATES
from app.jobs.store import JobRow
from app.jobs.views import job_view

__all__ = ["events", "item_lines", "result_items"]

_EVENT_INTERVAL = 0.2  # [s] an event stream sends progress this often at most
_KEEPALIVE = 15.0  # [s] an idle event stream sends a comment this often
_STREAM_CHUNK = 500  # items read from the database at once when streaming


async def _finished(manager: JobManager, job_id: str) -> bool:
    """Whether a job that is not live here has ended (or is gone)."""
    row = await manager.store.get_job(job_id)
    return row is None or row["status"] in FINISHED_STATES


async def item_lines(manager: JobManager, job_id: str) -> AsyncIterator[str]:
    """A batch's NDJSON lines in the order they are answered, until the job ends."""
    after = 0
    while True:
        # Before reading: once a job is seen finished, its items are all in.
        live = manager.live(job_id)
        ended = live is None and await _finished(manager, job_id)
        rows = await manager.store.items_by_answer(job_id, after, _STREAM_CHUNK)
        for seq, line in rows:
            yield line + "\n"
            after = seq
        if rows:
            continue
        if ended:
            return
        if live is not None:
            if not await manager.wait_for_change(live, _KEEPALIVE) and manager.stopping:
                return
        elif not await manager.pause(manager.poll_interval):
            return


async def result_items(manager: JobManager, job_id: str) -> AsyncIterator[str]:
    """A finished batch's item lines in request order."""
    after = -1
    while rows := await manager.store.items_by_index(job_id, after, _STREAM_CHUNK):
        for index, line in rows:
            yield line
            after = index


async def events(manager: JobManager, job_id: str, first: JobRow) -> AsyncIterator[str]:
    """Server-sent events: `progress` while the job is queued or running, then `end` with
    its final state (no result: GET /jobs/{id} has it)."""
    yield f"retry: {int(_KEEPALIVE * 1000)}\n\n"
    row: JobRow | None = first
    last, number, quiet = None, 0, 0.0
    while row is not None:
        view = job_view(row, manager.operations)
        final = view["status"] in FINISHED_STATES
        if view != last:
            number += 1
            kind = "end" if final else "progress"
            yield f"id: {number}\nevent: {kind}\ndata: {json.dumps(view)}\n\n"
            last, quiet = view, 0.0
        if final or manager.stopping:
            return
        live = manager.live(job_id)
        if live is not None:
            if not await manager.wait_for_change(live, _KEEPALIVE) and not manager.stopping:
                yield ": keep-alive\n\n"
            await asyncio.sleep(_EVENT_INTERVAL)
            row = live.row()
            if manager.live(job_id) is not live and row["status"] not in FINISHED_STATES:
                row = await manager.store.get_job(job_id)  # handed back, or taken over
            continue
        # Queued, or running on another replica: its row in the store, every poll interval.
        if not await manager.pause(manager.poll_interval):
            return
        quiet += manager.poll_interval
        if quiet >= _KEEPALIVE:
            yield ": keep-alive\n\n"
            quiet = 0.0
        row = await manager.store.get_job(job_id)
