"""The wire formats a job streams in: server-sent events of its progress and final state
(`events`), and a batch's answers as NDJSON, as they are answered (`item_lines`) or in request
order (`result_items`)."""

from __future__ import annotations

import asyncio
import json
from collections.abc import AsyncIterator

from app.jobs import store
from app.jobs.manager import JobManager
from app.jobs.models import FINISHED_STATES
from app.jobs.store import JobRow
from app.jobs.views import job_view

__all__ = ["events", "item_lines", "result_items"]

_EVENT_INTERVAL = 0.2  # [s] an event stream sends progress this often at most
_KEEPALIVE = 15.0  # [s] an idle event stream sends a comment this often
_STREAM_CHUNK = 500  # items read from the database at once when streaming


async def item_lines(manager: JobManager, job_id: str) -> AsyncIterator[str]:
    """A batch's NDJSON lines in the order they are answered, until the job ends."""
    after = 0
    while True:
        live = manager.live(job_id)  # before reading: a finished job's items are all in
        rows = await manager.store.read(store.item_lines_by_answer, job_id, after, _STREAM_CHUNK)
        for seq, line in rows:
            yield line + "\n"
            after = seq
        if rows:
            continue
        if live is None:
            return
        if not await manager.wait_for_change(live, _KEEPALIVE) and manager.stopping:
            return


async def result_items(manager: JobManager, job_id: str) -> AsyncIterator[str]:
    """A finished batch's item lines in request order."""
    after = -1
    while rows := await manager.store.read(store.item_lines_by_index, job_id, after, _STREAM_CHUNK):
        for index, line in rows:
            yield line
            after = index


async def events(manager: JobManager, job_id: str, first: JobRow) -> AsyncIterator[str]:
    """Server-sent events: `progress` while the job is queued or running, then `end` with
    its final state (no result: GET /jobs/{id} has it)."""
    yield f"retry: {int(_KEEPALIVE * 1000)}\n\n"
    live, last, number = manager.live(job_id), None, 0
    while True:
        row = live.row() if live is not None else first
        view = job_view(row, manager.operations)
        final = view["status"] in FINISHED_STATES
        if view != last:
            number += 1
            kind = "end" if final else "progress"
            yield f"id: {number}\nevent: {kind}\ndata: {json.dumps(view)}\n\n"
            last = view
        if final or live is None or manager.stopping:
            return
        if not await manager.wait_for_change(live, _KEEPALIVE) and not manager.stopping:
            yield ": keep-alive\n\n"
        await asyncio.sleep(_EVENT_INTERVAL)
