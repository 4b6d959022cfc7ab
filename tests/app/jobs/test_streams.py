"""app.jobs.streams: the wire formats a job streams in.

- `events`: server-sent events (text/event-stream): a `retry:` line, then numbered events, each
  `id`, `event` (progress while the job is queued or running, end with its final state) and
  one `data` line of the job's view, each ended by a blank line.
- `item_lines`: a batch's NDJSON, one line per answered item in the order they were answered,
  each ended by a newline, until the job ends; `result_items`: the lines in request order.

The manager is a minimal stand-in: the operations registry, the live job (or none), a wait for
its change, a pause between polls, and a store of lists (its queries are tests/app/jobs/
test_store.py's). A job that is not live here (another replica runs it) is read from the store
at each poll."""

from __future__ import annotations

import asyncio
import json
from collections.abc import AsyncIterator
from typing import Any

import pytest

from app.jobs import streams
from app.jobs.operations import JOB_KINDS
from app.jobs.views import job_view

WAIT = 10.0  # [s] a hang guard only

FINISHED: dict[str, Any] = {
    "id": "job-1",
    "operation": "batch",
    "status": "succeeded",
    "principal": "",
    "created": 1_700_000_000.0,
    "started": 1_700_000_001.0,
    "finished": 1_700_000_002.0,
    "expires": 1_700_086_402.0,
    "done": 3,
    "total": 3,
    "problems": 1,
    "problem": None,
}


class ListStore:
    """The store's reads that streams make, on lists: `rows` are what successive reads of the
    job find (the last one again once they run out)."""

    def __init__(self) -> None:
        self.items: list[tuple[int, int, str]] = []  # (index, seq, line)
        self.rows: list[dict[str, Any]] = [FINISHED]
        self.reads = 0

    async def get_job(self, job_id: str, with_result: bool = False) -> dict[str, Any]:
        self.reads += 1
        return self.rows.pop(0) if len(self.rows) > 1 else self.rows[0]

    async def items_by_answer(self, job_id: str, after: int, limit: int) -> list[Any]:
        found = sorted((seq, line) for _, seq, line in self.items if seq > after)
        return found[:limit]

    async def items_by_index(self, job_id: str, after: int, limit: int) -> list[Any]:
        found = sorted((index, line) for index, _, line in self.items if index > after)
        return found[:limit]


class LiveStandIn:
    """A queued or running job: its row as it is now (what `Manager` changes make it)."""

    def __init__(self, row: dict[str, Any]) -> None:
        self.current = row

    def row(self) -> dict[str, Any]:
        return self.current


class Manager:
    """What the streams read of a `JobManager`."""

    def __init__(self, live: LiveStandIn | None = None, changes: list[Any] | None = None) -> None:
        self.operations = JOB_KINDS
        self.store = ListStore()
        self.stopping = False
        self.poll_interval = 0.5
        self.pauses: list[Any] = []  # what happens at each poll
        self._live = live
        self._changes = list(changes or [])
        self.waits = 0

    def live(self, job_id: str) -> LiveStandIn | None:
        return self._live

    async def wait_for_change(self, job: Any, timeout: float) -> bool:
        self.waits += 1
        if not self._changes:
            self._live = None  # nothing more happens: the job has ended
            return True
        change = self._changes.pop(0)
        change(self)
        return True

    async def pause(self, seconds: float) -> bool:
        if self.pauses:
            self.pauses.pop(0)(self)
        return not self.stopping

    def answer(self, index: int, seq: int, line: str) -> None:
        self.store.items.append((index, seq, line))


async def _collect(stream: AsyncIterator[str]) -> list[str]:
    async def drain() -> list[str]:
        return [chunk async for chunk in stream]

    return await asyncio.wait_for(drain(), WAIT)


def _events(text: str) -> list[dict[str, str]]:
    """Parse an event stream (the SSE format: blank-line separated fields)."""
    assert text.endswith("\n\n")
    parsed = []
    for block in text.split("\n\n")[:-1]:
        fields: dict[str, str] = {}
        for line in block.split("\n"):
            name, _, value = line.partition(": ")
            assert name not in fields, block  # one data line per event: its JSON has no newline
            fields[name] = value
        parsed.append(fields)
    return parsed


@pytest.fixture(autouse=True)
def no_pause(monkeypatch: pytest.MonkeyPatch) -> None:
    """The events' pause between sends (0.2 s) changes what is sent only by coalescing."""
    monkeypatch.setattr(streams, "_EVENT_INTERVAL", 0.0)


def test_a_finished_jobs_events_are_the_retry_time_and_one_end_event() -> None:
    chunks = asyncio.run(_collect(streams.events(Manager(), "job-1", FINISHED)))  # type: ignore[arg-type]
    assert chunks[0] == "retry: 15000\n\n"  # the keep-alive interval, in milliseconds
    assert chunks[1:] == [
        f"id: 1\nevent: end\ndata: {json.dumps(job_view(FINISHED, JOB_KINDS))}\n\n"
    ]
    (retry, end) = _events("".join(chunks))
    assert retry == {"retry": "15000"}
    assert (end["id"], end["event"]) == ("1", "end")
    assert json.loads(end["data"])["progress"] == {"done": 3, "total": 3, "problems": 1}


def test_a_running_jobs_events_are_its_progress_then_its_end() -> None:
    queued = FINISHED | {"status": "queued", "started": None, "finished": None, "expires": None}
    queued |= {"done": 0, "problems": 0}
    live = LiveStandIn(queued)

    def progress(manager: Manager) -> None:
        live.current = queued | {"status": "running", "started": 1_700_000_001.0, "done": 1}

    def same(manager: Manager) -> None:
        pass  # woken without a change: nothing is sent

    def end(manager: Manager) -> None:
        live.current = FINISHED

    manager = Manager(live, [progress, same, end])
    text = "".join(asyncio.run(_collect(streams.events(manager, "job-1", queued))))  # type: ignore[arg-type]
    events = _events(text)[1:]
    assert [(e["id"], e["event"]) for e in events] == [
        ("1", "progress"),
        ("2", "progress"),
        ("3", "end"),
    ]
    views = [json.loads(e["data"]) for e in events]
    assert [v["status"] for v in views] == ["queued", "running", "succeeded"]
    assert [v["progress"]["done"] for v in views] == [0, 1, 3]


def test_an_idle_event_stream_sends_a_keep_alive_comment() -> None:
    running = FINISHED | {"status": "running", "finished": None, "expires": None}
    live = LiveStandIn(running)

    class Idle(Manager):
        async def wait_for_change(self, job: Any, timeout: float) -> bool:
            self.waits += 1
            if self.waits == 1:
                return False  # the keep-alive interval passed without a change
            live.current = FINISHED
            return True

    text = "".join(asyncio.run(_collect(streams.events(Idle(live), "job-1", running))))  # type: ignore[arg-type]
    assert ": keep-alive\n\n" in text
    assert text.index(": keep-alive") < text.index("event: end")


def test_a_stopping_service_ends_the_event_stream() -> None:
    running = FINISHED | {"status": "running", "finished": None, "expires": None}
    manager = Manager(LiveStandIn(running))
    manager.stopping = True
    text = "".join(asyncio.run(_collect(streams.events(manager, "job-1", running))))  # type: ignore[arg-type]
    assert [e.get("event") for e in _events(text)] == [None, "progress"]
    assert manager.waits == 0


def test_a_finished_batchs_items_stream_as_ndjson_in_the_order_answered() -> None:
    manager = Manager()
    for index, seq in ((2, 1), (0, 2), (1, 3)):
        manager.answer(index, seq, json.dumps({"index": index, "status": "ok"}))
    chunks = asyncio.run(_collect(streams.item_lines(manager, "job-1")))  # type: ignore[arg-type]
    assert all(chunk.endswith("\n") and chunk.count("\n") == 1 for chunk in chunks)
    assert [json.loads(chunk)["index"] for chunk in chunks] == [2, 0, 1]
    in_order = asyncio.run(_collect(streams.result_items(manager, "job-1")))  # type: ignore[arg-type]
    assert [json.loads(line)["index"] for line in in_order] == [0, 1, 2]


def test_a_running_batchs_items_stream_as_they_are_answered_until_it_ends() -> None:
    manager = Manager(LiveStandIn(FINISHED | {"status": "running"}))
    manager.answer(0, 1, '{"index": 0}')

    def answer_another(manager: Manager) -> None:
        manager.answer(1, 2, '{"index": 1}')

    manager._changes = [answer_another]
    chunks = asyncio.run(_collect(streams.item_lines(manager, "job-1")))  # type: ignore[arg-type]
    assert chunks == ['{"index": 0}\n', '{"index": 1}\n']
    assert manager.waits == 2  # once per new line, once more for the end


def test_a_long_batch_streams_past_one_chunk_of_reads(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(streams, "_STREAM_CHUNK", 2)
    manager = Manager()
    for index in range(5):
        manager.answer(index, index + 1, f'{{"index": {index}}}')
    chunks = asyncio.run(_collect(streams.item_lines(manager, "job-1")))  # type: ignore[arg-type]
    assert [json.loads(chunk)["index"] for chunk in chunks] == [0, 1, 2, 3, 4]
    in_order = asyncio.run(_collect(streams.result_items(manager, "job-1")))  # type: ignore[arg-type]
    assert len(in_order) == 5


# ------------------------------------------------------- a job another replica runs


def test_a_job_another_replica_runs_streams_its_progress_read_from_the_store() -> None:
    running = FINISHED | {"status": "running", "finished": None, "expires": None, "done": 1}
    manager = Manager()
    manager.store.rows = [running, running, running | {"done": 2}, FINISHED]
    text = "".join(asyncio.run(_collect(streams.events(manager, "job-1", running))))  # type: ignore[arg-type]
    views = [json.loads(e["data"]) for e in _events(text)[1:]]
    assert [(v["status"], v["progress"]["done"]) for v in views] == [
        ("running", 1),
        ("running", 2),
        ("succeeded", 3),
    ]
    assert manager.store.reads == 4  # one read per poll, an unchanged one sends nothing


def test_a_batch_another_replica_runs_streams_its_items_until_it_ends() -> None:
    running = FINISHED | {"status": "running", "finished": None}
    manager = Manager()
    manager.store.rows = [running, running, FINISHED]
    manager.answer(0, 1, '{"index": 0}')

    def answer_another(manager: Manager) -> None:
        manager.answer(1, 2, '{"index": 1}')

    manager.pauses = [answer_another]
    chunks = asyncio.run(_collect(streams.item_lines(manager, "job-1")))  # type: ignore[arg-type]
    assert chunks == ['{"index": 0}\n', '{"index": 1}\n']


def test_a_stopping_replica_ends_the_streams_of_jobs_it_polls() -> None:
    running = FINISHED | {"status": "running", "finished": None}
    manager = Manager()
    manager.store.rows = [running]

    def stop(manager: Manager) -> None:
        manager.stopping = True

    manager.pauses = [stop]
    chunks = asyncio.run(_collect(streams.item_lines(manager, "job-1")))  # type: ignore[arg-type]
    assert chunks == []
