"""app.jobs.manager: a job is checked at submission, queued (up to FLEXWING_MAX_QUEUED_JOBS),
run through the service, and kept with its result or problem; a queued job cancels unrun, a
running one has its work cancelled; a synchronous call past its wait is adopted as a running job
that its answer finishes; stopping the service fails what was unfinished as interrupted.

In process, on a temporary jobs database, with a stand-in for the service (`FakeService`: its
calls wait for the test to open a gate) and operations of the test's own, so every step is the
test's to order. Nothing here is timed: `WAIT` only turns a hang into a failure.
"""

from __future__ import annotations

import asyncio
import contextlib
import json
from collections.abc import AsyncIterator, Awaitable, Callable
from pathlib import Path
from types import SimpleNamespace
from typing import Any

import pytest

from app.jobs import store
from app.jobs.manager import JobManager, LiveJob
from app.jobs.operations import JobContext, JobKind
from app.metrics import Metrics
from app.problems import FieldError, Problem
from app.settings import Settings

WAIT = 10.0  # [s] a hang guard only


class FakeService:
    """What a job's operation calls (`answer`) and what the manager reads (`pool.capacity`).
    Each call waits for `gate`; the request says how it ends: a dict is answered back, an
    exception is raised."""

    def __init__(self) -> None:
        self.pool = SimpleNamespace(capacity=2)
        self.gate = asyncio.Event()
        self.calls: list[Any] = []
        self.cancelled: list[Any] = []

    async def answer(self, name: str, request: Any) -> dict[str, Any]:
        self.calls.append(request)
        try:
            await self.gate.wait()
        except asyncio.CancelledError:
            self.cancelled.append(request)
            raise
        if isinstance(request, BaseException):
            raise request
        return {"answer": request}


def _check(request: Any, settings: Settings) -> None:
    if request == "invalid":
        raise Problem.invalid([FieldError("wing.chord[2]", "must be positive")])


async def _run_echo(context: JobContext, request: Any) -> str:
    return json.dumps(await context.service.answer("echo", request))


async def _run_items(context: JobContext, request: Any) -> None:
    """Answer each item of `request` (a list of booleans: ok or a problem) in reverse order."""
    for index in reversed(range(len(request))):
        ok = request[index]
        context.item_answered(index, ok, json.dumps({"index": index, "ok": ok}))


# Requests are plain values here: the manager never validates them (the routes do).
ECHO = JobKind(
    name="echo",
    summary="an echo through the service",
    request_model=object,  # type: ignore[arg-type]
    request_description="anything",
    units=lambda request: 1,
    check=_check,
    run=_run_echo,
    result=json.dumps,
)
ITEMS = JobKind(
    name="items",
    summary="items answered in place",
    request_model=object,  # type: ignore[arg-type]
    request_description="a list of booleans",
    units=len,
    check=lambda request, settings: None,
    run=_run_items,
    has_items=True,
)
JOB_KINDS = {"echo": ECHO, "items": ITEMS}


def _settings(tmp_path: Path, **changes: Any) -> Settings:
    defaults: dict[str, Any] = {"workers": 1, "jobs_db": tmp_path / "jobs.sqlite3"}
    return Settings(**(defaults | changes))


@contextlib.asynccontextmanager
async def _started(settings: Settings, service: FakeService) -> AsyncIterator[JobManager]:
    manager = JobManager(settings, service, Metrics(), JOB_KINDS)  # type: ignore[arg-type]
    await manager.start()
    try:
        yield manager
    finally:
        await manager.close()


async def _until(condition: Callable[[], bool]) -> None:
    while not condition():
        await asyncio.sleep(0.001)


def _run(scenario: Callable[[], Awaitable[None]]) -> None:
    async def guarded() -> None:
        await asyncio.wait_for(scenario(), WAIT)

    asyncio.run(guarded())


def _stored(settings: Settings, job_id: str) -> dict[str, Any]:
    """A job's row as the database holds it (after the manager has closed it)."""

    async def read() -> dict[str, Any]:
        jobs = store.JobStore(settings.jobs_db)
        await jobs.open()
        try:
            row = await jobs.read(store.get_job, job_id, True)
        finally:
            await jobs.close()
        assert row is not None
        return row

    return asyncio.run(read())


def _sample(metrics: Metrics, name: str, **labels: str) -> float:
    value = metrics.registry.get_sample_value(name, labels)
    return 0.0 if value is None else value


# ------------------------------------------------------------------------ submit and run


def test_a_submitted_job_is_queued_then_runs_and_its_result_is_kept(tmp_path: Path) -> None:
    settings = _settings(tmp_path, job_retention=600.0)
    service = FakeService()

    async def scenario() -> None:
        async with _started(settings, service) as manager:
            job = manager.submit("echo", {"v": 10.0}, principal="")
            assert (job.status, job.total, job.done) == ("queued", 1, 0)
            await _until(lambda: job.status == "running")
            seen = await manager.find(job.id, principal="")
            assert seen is not None and seen["status"] == "running" and seen["result"] is None
            service.gate.set()
            await _until(lambda: job.status == "succeeded")
            row = await manager.find(job.id, principal="", with_result=True)
            assert row is not None
            assert json.loads(row["result"]) == {"answer": {"v": 10.0}}
            assert (row["status"], row["done"], row["total"], row["problem"]) == (
                "succeeded",
                1,
                1,
                None,
            )
            assert row["created"] <= row["started"] <= row["finished"]
            assert row["expires"] == pytest.approx(row["finished"] + 600.0)
            assert manager.live(job.id) is None  # finished: in the database only
            metrics = manager.metrics
            assert _sample(metrics, "flexwing_jobs_submitted_total", operation="echo") == 1
            assert _sample(metrics, "flexwing_jobs", state="succeeded") == 1
            assert _sample(metrics, "flexwing_jobs", state="queued") == 0

    _run(scenario)


def test_beyond_max_queued_jobs_a_submission_is_503_overloaded_and_not_stored(
    tmp_path: Path,
) -> None:
    settings = _settings(tmp_path, job_runners=1, max_queued_jobs=1, retry_after=7)
    service = FakeService()

    async def scenario() -> None:
        async with _started(settings, service) as manager:
            running = manager.submit("echo", "A", principal="")
            await _until(lambda: running.status == "running")
            waiting = manager.submit("echo", "B", principal="")
            assert waiting.status == "queued" and manager.queued() == 1
            with pytest.raises(Problem) as refused:
                manager.submit("echo", "C", principal="")
            assert refused.value.type.slug == "overloaded" and refused.value.status == 503
            assert refused.value.headers == {"Retry-After": "7"}
            assert _sample(manager.metrics, "flexwing_requests_shed_total") == 1
            listed = await manager.page(10, None, None, principal="")
            assert sorted(row["id"] for row in listed) == sorted([running.id, waiting.id])
            service.gate.set()

    _run(scenario)


def test_a_queued_job_cancelled_finishes_at_once_and_never_runs(tmp_path: Path) -> None:
    settings = _settings(tmp_path, job_runners=1, max_queued_jobs=1)
    service = FakeService()

    async def scenario() -> None:
        async with _started(settings, service) as manager:
            first = manager.submit("echo", "A", principal="")
            await _until(lambda: first.status == "running")
            queued = manager.submit("echo", "B", principal="")
            row = await manager.cancel(queued.id, principal="")
            assert row is not None and row["status"] == "cancelled"
            assert manager.queued() == 0  # its place in the queue is free again
            # A job submitted after it runs after the first: by then the runner has taken the
            # cancelled one from the queue, and passed it over.
            last = manager.submit("echo", "D", principal="")
            service.gate.set()
            await _until(lambda: last.status == "succeeded")
            assert service.calls == ["A", "D"]
            stored = await manager.find(queued.id, principal="")
            assert stored is not None
            assert (stored["status"], stored["done"], stored["started"]) == ("cancelled", 0, None)

    _run(scenario)


def test_a_running_job_cancelled_has_its_work_cancelled_and_ends_cancelled(
    tmp_path: Path,
) -> None:
    settings = _settings(tmp_path)
    service = FakeService()

    async def scenario() -> None:
        async with _started(settings, service) as manager:
            job = manager.submit("echo", "A", principal="")
            await _until(lambda: service.calls == ["A"])
            row = await manager.cancel(job.id, principal="")
            assert row is not None and row["status"] == "cancelled"
            assert service.cancelled == ["A"]
            stored = await manager.find(job.id, principal="", with_result=True)
            assert stored is not None
            assert (stored["status"], stored["done"], stored["result"], stored["problem"]) == (
                "cancelled",
                0,
                None,
                None,
            )
            again = await manager.cancel(job.id, principal="")  # finished: stays as it is
            assert again is not None and again["status"] == "cancelled"

    _run(scenario)


FAILURES = {
    "a problem": (
        Problem("no-equilibrium", "beyond the fold", extensions={"fold_velocity": 21.44}),
        {"type": "/problems/no-equilibrium", "status": 422, "fold_velocity": 21.44},
    ),
    "a defect": (
        RuntimeError("a secret from deep inside"),
        {"type": "/problems/internal-error", "status": 500, "detail": "unexpected RuntimeError"},
    ),
}


@pytest.mark.parametrize(("error", "expected"), list(FAILURES.values()), ids=list(FAILURES))
def test_a_job_whose_work_fails_ends_failed_with_the_problem_the_endpoint_would_answer(
    tmp_path: Path, error: BaseException, expected: dict[str, Any]
) -> None:
    settings = _settings(tmp_path)
    service = FakeService()
    service.gate.set()

    async def scenario() -> None:
        async with _started(settings, service) as manager:
            job = manager.submit("echo", error, principal="")
            await _until(lambda: job.status == "failed")
            row = await manager.find(job.id, principal="", with_result=True)
            assert row is not None and row["result"] is None
            problem = json.loads(row["problem"])
            assert expected.items() <= problem.items()
            assert "secret" not in row["problem"]
            assert (row["done"], row["total"]) == (1, 1)  # its one unit was answered

    _run(scenario)


@pytest.mark.parametrize(
    ("prefix", "field"),
    [("request", "request.wing.chord[2]"), (None, "wing.chord[2]")],
    ids=["from-the-body", "as-checked"],
)
def test_an_invalid_request_is_refused_at_submission_naming_its_field(
    tmp_path: Path, prefix: str | None, field: str
) -> None:
    settings = _settings(tmp_path)
    service = FakeService()

    async def scenario() -> None:
        async with _started(settings, service) as manager:
            with pytest.raises(Problem) as refused:
                manager.submit("echo", "invalid", principal="", prefix=prefix)
            assert refused.value.type.slug == "invalid-input"
            assert refused.value.extensions["errors"] == [
                {"field": field, "reason": "must be positive"}
            ]
            assert refused.value.extensions["error_count"] == 1
            assert manager.queued() == 0
            assert await manager.page(10, None, None, principal="") == []

    _run(scenario)


def test_batch_items_are_recorded_as_answered_and_counted(tmp_path: Path) -> None:
    settings = _settings(tmp_path)
    service = FakeService()

    async def scenario() -> None:
        async with _started(settings, service) as manager:
            job = manager.submit("items", [True, False, True], principal="")
            assert job.total == 3
            await _until(lambda: job.status == "succeeded")
            row = await manager.find(job.id, principal="", with_result=True)
            assert row is not None
            assert (row["done"], row["problems"], row["result"]) == (3, 1, None)
            by_answer = await manager.store.read(store.item_lines_by_answer, job.id, 0, 10)
            assert [json.loads(line)["index"] for _, line in by_answer] == [2, 1, 0]
            by_index = await manager.store.read(store.item_lines_by_index, job.id, -1, 10)
            assert [json.loads(line)["ok"] for _, line in by_index] == [True, False, True]
            assert _sample(manager.metrics, "flexwing_batch_items_total", outcome="ok") == 2
            assert _sample(manager.metrics, "flexwing_batch_items_total", outcome="problem") == 1

    _run(scenario)


def test_another_principals_job_is_no_job_at_all(tmp_path: Path) -> None:
    settings = _settings(tmp_path)
    service = FakeService()

    async def scenario() -> None:
        async with _started(settings, service) as manager:
            job = manager.submit("echo", "A", principal="alice")
            assert await manager.find(job.id, principal="bob") is None
            assert await manager.cancel(job.id, principal="bob") is None
            assert await manager.page(10, None, None, principal="bob") == []
            assert job.status in ("queued", "running") and not job.cancel_requested
            service.gate.set()
            await _until(lambda: job.status == "succeeded")
            assert await manager.find(job.id, principal="bob") is None
            mine = await manager.find(job.id, principal="alice")
            assert mine is not None and mine["status"] == "succeeded"

    _run(scenario)


# ----------------------------------------------------------------------------- adopt


async def _adopted_outcome(
    manager: JobManager, job: LiveJob, answer: asyncio.Future[dict[str, Any]], how: str
) -> None:
    if how == "succeeded":
        answer.set_result({"lift": 304.1})
    elif how == "failed":
        answer.set_exception(Problem("solve-timeout", "over", extensions={"timeout": 20.0}))
    else:
        await asyncio.sleep(0)  # a DELETE comes in a later request: the job has begun waiting
        row = await manager.cancel(job.id, principal="")
        assert row is not None and row["status"] == "cancelled"
        assert answer.cancelled()  # the service call itself is cancelled
    await _until(lambda: job.status != "running")


ADOPTED = {
    "succeeded": ('{"lift": 304.1}', None),
    "failed": (None, {"type": "/problems/solve-timeout", "status": 504, "timeout": 20.0}),
    "cancelled": (None, None),
}


@pytest.mark.parametrize("how", list(ADOPTED), ids=list(ADOPTED))
def test_an_adopted_service_call_runs_at_once_and_its_answer_finishes_the_job(
    tmp_path: Path, how: str
) -> None:
    settings = _settings(tmp_path, max_queued_jobs=1)
    result, problem = ADOPTED[how]

    async def scenario() -> None:
        async with _started(settings, FakeService()) as manager:
            answer: asyncio.Future[dict[str, Any]] = asyncio.get_running_loop().create_future()
            job = manager.adopt("echo", answer, 6, principal="")
            assert (job.status, job.total, job.started) == ("running", 6, job.created)
            assert manager.queued() == 0  # it never waits in the queue
            await _adopted_outcome(manager, job, answer, how)
            row = await manager.find(job.id, principal="", with_result=True)
            assert row is not None and row["status"] == how
            assert row["result"] == result
            if problem is None:
                assert row["problem"] is None
            else:
                assert problem.items() <= json.loads(row["problem"]).items()
            assert row["done"] == (0 if how == "cancelled" else 6)

    _run(scenario)


def test_an_adopted_call_cancelled_before_the_loop_turns_still_ends_cancelled(
    tmp_path: Path,
) -> None:
    settings = _settings(tmp_path)

    async def scenario() -> None:
        async with _started(settings, FakeService()) as manager:
            answer: asyncio.Future[bytes] = asyncio.get_running_loop().create_future()
            job = manager.adopt("echo", answer, 1, principal="")
            await manager.cancel(job.id, principal="")
            assert job.status == "cancelled"
            assert answer.cancelled()

    _run(scenario)


# ------------------------------------------------------------------------------ stopping


def test_stopping_the_service_fails_its_queued_and_running_jobs_as_interrupted(
    tmp_path: Path,
) -> None:
    settings = _settings(tmp_path, job_runners=1)
    service = FakeService()
    ids: dict[str, str] = {}

    async def scenario() -> None:
        async with _started(settings, service) as manager:
            running = manager.submit("echo", "A", principal="")
            await _until(lambda: service.calls == ["A"])
            queued = manager.submit("echo", "B", principal="")
            ids.update(running=running.id, queued=queued.id)
        assert service.cancelled == ["A"]

    _run(scenario)
    running, queued = _stored(settings, ids["running"]), _stored(settings, ids["queued"])
    for row in (running, queued):
        assert row["status"] == "failed"
        problem = json.loads(row["problem"])
        assert (problem["type"], problem["status"]) == ("/problems/job-interrupted", 503)
        assert (problem["done"], problem["total"]) == (0, 1)
    assert "while this job ran (0 of 1 units done)" in json.loads(running["problem"])["detail"]
    assert "before this job started" in json.loads(queued["problem"])["detail"]
