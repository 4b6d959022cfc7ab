"""app.jobs.manager: a job is checked at submission, stored (up to FLEXWING_MAX_QUEUED_JOBS
waiting) before it is acknowledged, claimed by a replica under a lease and run through the
service, and kept with its result or problem; a queued job cancels unrun, a running one has its
work cancelled (here, or on the replica running it); a synchronous call past its wait is adopted
as a running job that its answer finishes; a stopping replica hands its jobs back, and a dead
one's are taken up by another when its leases expire, a batch from the items it had answered,
none recorded twice.

In process, with a stand-in for the service (`FakeService`: a call whose request is in `hold`
waits for the test to open `gate`) and operations of the test's own, so every step is the
test's to order. The tests about replicas run on SQLite and on a real PostgreSQL (`database`).
Nothing here is timed: `WAIT` only turns a hang into a failure.
"""

from __future__ import annotations

import asyncio
import contextlib
import json
from collections.abc import AsyncIterator, Awaitable, Callable
from types import SimpleNamespace
from typing import Any

import pytest
from pydantic import RootModel

from app.jobs.manager import JobManager
from app.jobs.operations import JobContext, JobKind
from app.metrics import Metrics
from app.problems import FieldError, Problem
from app.settings import Settings
from tests.app.jobs.conftest import Backend

WAIT = 30.0  # [s] a hang guard only


class Word(RootModel[str]):
    """A request of the test's operations: a word that says how its call ends."""


class Flags(RootModel[list[bool]]):
    """A batch of the test's: each item ok or a problem."""


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


class FakeService:
    """What a job's operation calls (`answer`) and what the manager reads (`pool`). A call
    whose request is in `hold` (every call, with `hold_all`) waits for `gate`; a request named
    in FAILURES raises that error, any other is answered back."""

    def __init__(self, *, hold_all: bool = True) -> None:
        self.pool = SimpleNamespace(capacity=2, parallelism=2, chunk_seconds=0.05)
        self.gate = asyncio.Event()
        self.hold_all = hold_all
        self.hold: set[Any] = set()
        self.calls: list[Any] = []
        self.cancelled: list[Any] = []

    async def answer(self, name: str, request: Any) -> dict[str, Any]:
        self.calls.append(request)
        try:
            if self.hold_all or request in self.hold:
                await self.gate.wait()
        except asyncio.CancelledError:
            self.cancelled.append(request)
            raise
        if request in FAILURES:
            raise FAILURES[request][0]
        return {"answer": request}


def _check(request: Word, settings: Settings) -> None:
    if request.root == "invalid":
        raise Problem.invalid([FieldError("wing.chord[2]", "must be positive")])


async def _run_echo(context: JobContext, request: Word) -> str:
    return json.dumps(await context.service.answer("echo", request.root))


async def _run_items(context: JobContext, request: Flags) -> None:
    """Answer each item (through the service, as `index`) in reverse order, but those answered
    before (as the batch operation does)."""
    for index in reversed(range(len(request.root))):
        if index in context.answered:
            continue
        await context.service.answer("item", index)
        ok = request.root[index]
        context.item_answered(index, ok, json.dumps({"index": index, "ok": ok}))


ECHO = JobKind(
    name="echo",
    summary="an echo through the service",
    request_model=Word,
    request_description="a word",
    units=lambda request: 1,
    check=_check,
    run=_run_echo,
    result=bytes.decode,
)
ITEMS = JobKind(
    name="items",
    summary="items answered in place",
    request_model=Flags,
    request_description="a list of booleans",
    units=lambda request: len(request.root),
    check=lambda request, settings: None,
    run=_run_items,
    has_items=True,
)
JOB_KINDS = {"echo": ECHO, "items": ITEMS}


@pytest.fixture
def sqlite(tmp_path: Any) -> Backend:
    return Backend("sqlite", None, tmp_path / "jobs.sqlite3")


def _manager(settings: Settings, service: FakeService) -> JobManager:
    return JobManager(settings, service, Metrics(), JOB_KINDS)  # type: ignore[arg-type]


@contextlib.asynccontextmanager
async def _started(settings: Settings, service: FakeService) -> AsyncIterator[JobManager]:
    manager = _manager(settings, service)
    await manager.start()
    try:
        yield manager
    finally:
        await manager.close()


async def _until(condition: Callable[[], bool]) -> None:
    while not condition():
        await asyncio.sleep(0.005)


async def _status(manager: JobManager, job_id: str, wanted: str) -> dict[str, Any]:
    """The job's row once it is `wanted`."""
    while True:
        row = await manager.find(job_id, principal="", with_result=True)
        if row is not None and row["status"] == wanted:
            return row
        await asyncio.sleep(0.005)


def _run(scenario: Callable[[], Awaitable[None]]) -> None:
    async def guarded() -> None:
        await asyncio.wait_for(scenario(), WAIT)

    asyncio.run(guarded())


def _sample(metrics: Metrics, name: str, **labels: str) -> float:
    value = metrics.registry.get_sample_value(name, labels)
    return 0.0 if value is None else value


# ------------------------------------------------------------------------ submit and run


def test_a_submitted_job_is_stored_then_runs_and_its_result_is_kept(sqlite: Backend) -> None:
    settings = sqlite.settings(job_retention=600.0)
    service = FakeService()

    async def scenario() -> None:
        async with _started(settings, service) as manager:
            job = await manager.submit("echo", Word("10 m/s"), principal="")
            assert (job["status"], job["total"], job["done"]) == ("queued", 1, 0)
            stored = await manager.store.get_job(job["id"])  # committed before it was answered
            assert stored is not None and stored["status"] in ("queued", "running")
            seen = await _status(manager, job["id"], "running")
            assert seen["result"] is None and seen["started"] >= seen["created"]
            service.gate.set()
            row = await _status(manager, job["id"], "succeeded")
            assert json.loads(row["result"]) == {"answer": "10 m/s"}
            assert (row["done"], row["total"], row["problem"]) == (1, 1, None)
            assert row["created"] <= row["started"] <= row["finished"]
            assert row["expires"] == pytest.approx(row["finished"] + 600.0)
            assert manager.live(job["id"]) is None  # finished: in the store only
            metrics = manager.metrics
            assert _sample(metrics, "flexwing_jobs_submitted_total", operation="echo") == 1
            assert _sample(metrics, "flexwing_jobs", state="succeeded") == 1
            assert _sample(metrics, "flexwing_jobs", state="queued") == 0

    _run(scenario)


def test_beyond_max_queued_jobs_a_submission_is_503_overloaded_and_not_stored(
    sqlite: Backend,
) -> None:
    settings = sqlite.settings(job_runners=1, max_queued_jobs=1, retry_after=7)
    service = FakeService()

    async def scenario() -> None:
        async with _started(settings, service) as manager:
            running = await manager.submit("echo", Word("A"), principal="")
            await _until(lambda: service.calls == ["A"])
            waiting = await manager.submit("echo", Word("B"), principal="")
            assert manager.queued() == 1
            with pytest.raises(Problem) as refused:
                await manager.submit("echo", Word("C"), principal="")
            assert refused.value.type.slug == "overloaded" and refused.value.status == 503
            assert refused.value.headers == {"Retry-After": "7"}
            assert _sample(manager.metrics, "flexwing_requests_shed_total") == 1
            listed = await manager.page(10, None, None, principal="")
            assert sorted(row["id"] for row in listed) == sorted([running["id"], waiting["id"]])
            service.gate.set()

    _run(scenario)


def test_a_queued_job_cancelled_finishes_at_once_and_never_runs(sqlite: Backend) -> None:
    settings = sqlite.settings(job_runners=1, max_queued_jobs=1)
    service = FakeService()

    async def scenario() -> None:
        async with _started(settings, service) as manager:
            await manager.submit("echo", Word("A"), principal="")
            await _until(lambda: service.calls == ["A"])
            queued = await manager.submit("echo", Word("B"), principal="")
            row = await manager.cancel(queued["id"], principal="")
            assert row is not None and row["status"] == "cancelled"
            assert manager.queued() == 0  # its place in the queue is free again
            last = await manager.submit("echo", Word("D"), principal="")
            service.gate.set()
            await _status(manager, last["id"], "succeeded")
            assert service.calls == ["A", "D"]
            stored = await manager.find(queued["id"], principal="")
            assert stored is not None
            assert (stored["status"], stored["done"], stored["started"]) == ("cancelled", 0, None)

    _run(scenario)


def test_a_running_job_cancelled_has_its_work_cancelled_and_ends_cancelled(
    sqlite: Backend,
) -> None:
    settings = sqlite.settings()
    service = FakeService()

    async def scenario() -> None:
        async with _started(settings, service) as manager:
            job = await manager.submit("echo", Word("A"), principal="")
            await _until(lambda: service.calls == ["A"])
            row = await manager.cancel(job["id"], principal="")
            assert row is not None and row["status"] == "cancelled"
            assert service.cancelled == ["A"]
            stored = await manager.find(job["id"], principal="", with_result=True)
            assert stored is not None
            assert (stored["status"], stored["done"], stored["result"], stored["problem"]) == (
                "cancelled",
                0,
                None,
                None,
            )
            again = await manager.cancel(job["id"], principal="")  # finished: stays as it is
            assert again is not None and again["status"] == "cancelled"

    _run(scenario)


@pytest.mark.parametrize("failure", list(FAILURES), ids=list(FAILURES))
def test_a_job_whose_work_fails_ends_failed_with_the_problem_the_endpoint_would_answer(
    sqlite: Backend, failure: str
) -> None:
    settings = sqlite.settings()
    service = FakeService(hold_all=False)
    expected = FAILURES[failure][1]

    async def scenario() -> None:
        async with _started(settings, service) as manager:
            job = await manager.submit("echo", Word(failure), principal="")
            row = await _status(manager, job["id"], "failed")
            assert row["result"] is None
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
    sqlite: Backend, prefix: str | None, field: str
) -> None:
    settings = sqlite.settings()

    async def scenario() -> None:
        async with _started(settings, FakeService()) as manager:
            with pytest.raises(Problem) as refused:
                await manager.submit("echo", Word("invalid"), principal="", prefix=prefix)
            assert refused.value.type.slug == "invalid-input"
            assert refused.value.extensions["errors"] == [
                {"field": field, "reason": "must be positive"}
            ]
            assert refused.value.extensions["error_count"] == 1
            assert manager.queued() == 0
            assert await manager.page(10, None, None, principal="") == []

    _run(scenario)


def test_batch_items_are_recorded_as_answered_and_counted(sqlite: Backend) -> None:
    settings = sqlite.settings()
    service = FakeService(hold_all=False)

    async def scenario() -> None:
        async with _started(settings, service) as manager:
            job = await manager.submit("items", Flags([True, False, True]), principal="")
            assert job["total"] == 3
            row = await _status(manager, job["id"], "succeeded")
            assert (row["done"], row["problems"], row["result"]) == (3, 1, None)
            by_answer = await manager.store.items_by_answer(job["id"], 0, 10)
            assert [json.loads(line)["index"] for _, line in by_answer] == [2, 1, 0]
            by_index = await manager.store.items_by_index(job["id"], -1, 10)
            assert [json.loads(line)["ok"] for _, line in by_index] == [True, False, True]
            assert _sample(manager.metrics, "flexwing_batch_items_total", outcome="ok") == 2
            assert _sample(manager.metrics, "flexwing_batch_items_total", outcome="problem") == 1

    _run(scenario)


def test_another_principals_job_is_no_job_at_all(sqlite: Backend) -> None:
    settings = sqlite.settings()
    service = FakeService()

    async def scenario() -> None:
        async with _started(settings, service) as manager:
            job = await manager.submit("echo", Word("A"), principal="alice")
            assert await manager.find(job["id"], principal="bob") is None
            assert await manager.cancel(job["id"], principal="bob") is None
            assert await manager.page(10, None, None, principal="bob") == []
            service.gate.set()
            while (row := await manager.find(job["id"], principal="alice")) is None or row[
                "status"
            ] != "succeeded":
                await asyncio.sleep(0.005)
            assert await manager.find(job["id"], principal="bob") is None

    _run(scenario)


# ----------------------------------------------------------------------------- adopt


async def _adopted_outcome(
    manager: JobManager, job_id: str, answer: asyncio.Future[bytes], how: str
) -> None:
    if how == "succeeded":
        answer.set_result(b'{"lift": 304.1}')
    elif how == "failed":
        answer.set_exception(Problem("solve-timeout", "over", extensions={"timeout": 20.0}))
    else:
        await asyncio.sleep(0)  # a DELETE comes in a later request: the job has begun waiting
        row = await manager.cancel(job_id, principal="")
        assert row is not None and row["status"] == "cancelled"
        assert answer.cancelled()  # the service call itself is cancelled
    await _until(lambda: manager.live(job_id) is None)


ADOPTED = {
    "succeeded": ('{"lift": 304.1}', None),
    "failed": (None, {"type": "/problems/solve-timeout", "status": 504, "timeout": 20.0}),
    "cancelled": (None, None),
}


@pytest.mark.parametrize("how", list(ADOPTED), ids=list(ADOPTED))
def test_an_adopted_service_call_runs_at_once_and_its_answer_finishes_the_job(
    sqlite: Backend, how: str
) -> None:
    settings = sqlite.settings(max_queued_jobs=1)
    result, problem = ADOPTED[how]

    async def scenario() -> None:
        async with _started(settings, FakeService()) as manager:
            answer: asyncio.Future[bytes] = asyncio.get_running_loop().create_future()
            job = manager.adopt("echo", answer, 6, principal="")
            assert (job.status, job.total, job.started) == ("running", 6, job.created)
            assert manager.queued() == 0  # it never waits in the queue
            await _adopted_outcome(manager, job.id, answer, how)
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
    sqlite: Backend,
) -> None:
    settings = sqlite.settings()

    async def scenario() -> None:
        async with _started(settings, FakeService()) as manager:
            answer: asyncio.Future[bytes] = asyncio.get_running_loop().create_future()
            job = manager.adopt("echo", answer, 1, principal="")
            await manager.cancel(job.id, principal="")
            assert job.status == "cancelled"
            assert answer.cancelled()

    _run(scenario)


# ------------------------------------------------------------------------------ stopping


def test_a_stopping_replica_hands_its_jobs_back_and_the_next_start_runs_them(
    sqlite: Backend,
) -> None:
    """Stopped while a batch runs (two of its three items answered) and a solve waits: both
    are queued again; the next start runs them, the batch from its third item (the first two
    are not asked again). An adopted call cannot be run again: it fails as interrupted."""
    settings = sqlite.settings(job_runners=1)
    first = FakeService(hold_all=False)
    first.hold = {0}  # the batch answers items 2 and 1, then waits on item 0

    async def scenario() -> None:
        async with _started(settings, first) as manager:
            batch = await manager.submit("items", Flags([True, True, False]), principal="")
            await _until(lambda: first.calls == [2, 1, 0])
            waiting = await manager.submit("echo", Word("B"), principal="")
            answer: asyncio.Future[bytes] = asyncio.get_running_loop().create_future()
            adopted = manager.adopt("echo", answer, 1, principal="")
        assert first.cancelled == [0] and answer.cancelled()
        second = FakeService(hold_all=False)
        async with _started(settings, second) as manager:
            stopped = await manager.find(adopted.id, principal="", with_result=True)
            assert stopped is not None and stopped["status"] == "failed"
            assert json.loads(stopped["problem"])["type"] == "/problems/job-interrupted"
            row = await _status(manager, batch["id"], "succeeded")
            assert (row["done"], row["problems"]) == (3, 1)
            await _status(manager, waiting["id"], "succeeded")
            assert second.calls == [0, "B"]  # the oldest first; items 2 and 1 not again
            lines = await manager.store.items_by_answer(batch["id"], 0, 10)
            assert [json.loads(line)["index"] for _, line in lines] == [2, 1, 0]

    _run(scenario)


# ------------------------------------------------------------------------------ replicas


def test_any_replica_answers_for_a_job_another_runs_and_cancels_it(database: Backend) -> None:
    """Replica A has one runner, busy; a job submitted to A is run by replica B (it polls the
    store); A reads its state and result, and cancels B's running job through the store."""
    # Leases of 4 s: renewed every second, with room for a loaded machine's pauses (a lease
    # that expired under A's running job would hand it to B, which is another test's).
    settings = database.settings(job_runners=1, job_poll_interval=0.05, job_lease=4.0)
    a_service, b_service = FakeService(), FakeService(hold_all=False)
    b_service.hold = {"slow"}

    async def scenario() -> None:
        async with _started(settings, a_service) as a:
            busy = await a.submit("echo", Word("A busy"), principal="")
            await _until(lambda: a_service.calls == ["A busy"])
            async with _started(settings, b_service):  # replica B
                quick = await a.submit("echo", Word("quick"), principal="")
                row = await _status(a, quick["id"], "succeeded")
                assert json.loads(row["result"]) == {"answer": "quick"}
                assert b_service.calls == ["quick"] and a_service.calls == ["A busy"]
                slow = await a.submit("echo", Word("slow"), principal="")
                await _until(lambda: "slow" in b_service.calls)
                cancelled = await a.cancel(slow["id"], principal="")
                assert cancelled is not None and cancelled["status"] == "cancelled"
                assert b_service.cancelled == ["slow"]
            a_service.gate.set()
            await _status(a, busy["id"], "succeeded")

    _run(scenario)


def test_a_dead_replicas_batch_is_finished_by_another_each_item_recorded_once(
    database: Backend,
) -> None:
    """Replica A answers two of a batch's four items and stops renewing its lease (as if it
    hung or died) while its work goes on. Replica B takes the batch up once the lease expires
    and answers the rest; what A answers after that is fenced out: each item is recorded
    once, and the job is answered once, by B."""
    settings = database.settings(job_lease=1.0, job_poll_interval=0.05)
    a_service, b_service = FakeService(hold_all=False), FakeService(hold_all=False)
    a_service.hold = {1}  # A answers items 3 and 2, then waits on item 1

    async def scenario() -> None:
        a = _manager(settings, a_service)
        await a.start()
        try:
            batch = await a.submit("items", Flags([True, False, True, True]), principal="")
            await _until(lambda: a_service.calls == [3, 2, 1])
            while len(await a.store.items_by_answer(batch["id"], 0, 10)) < 2:
                await asyncio.sleep(0.005)  # items 3 and 2 committed (a loaded machine is slow)
            a._tasks[1].cancel()  # its heartbeat stops: the lease is no longer renewed
            a._tasks[0].cancel()  # and it claims nothing more
            async with _started(settings, b_service) as b:
                row = await _status(b, batch["id"], "succeeded")
                assert (row["done"], row["problems"]) == (4, 1)
                assert b_service.calls == [1, 0]  # B asks only what A had not answered
                a_service.gate.set()  # A's late answers come now: items 1 and 0, again
                await _until(lambda: a._live == {})
                assert a_service.calls == [3, 2, 1, 0]
                stored = await b.store.items_by_answer(batch["id"], 0, 10)
                indices = [json.loads(line)["index"] for _, line in stored]
                assert indices == [3, 2, 1, 0]  # each once: A's two, then B's two
                final = await b.find(batch["id"], principal="", with_result=True)
                assert final == row  # A's finish changed nothing
        finally:
            await a.close()

    _run(scenario)


def test_a_job_claimed_while_the_leases_are_renewed_is_not_taken_for_lost(
    sqlite: Backend,
) -> None:
    """The heartbeat's renewal of job A is in flight when job B is claimed: its answer does
    not name B (B was not asked about), and B runs on; only what was asked is judged."""
    settings = sqlite.settings(job_lease=1.0)
    service = FakeService()

    async def scenario() -> None:
        async with _started(settings, service) as manager:
            renew = manager.store.renew
            asked, go = asyncio.Event(), asyncio.Event()
            renewals: list[list[str]] = []

            async def held_back(owner: str, until: float, job_ids: list[str]) -> Any:
                renewals.append(list(job_ids))
                asked.set()
                await go.wait()
                return await renew(owner, until, job_ids)

            manager.store.renew = held_back  # type: ignore[method-assign]
            first = await manager.submit("echo", Word("A"), principal="")
            await asked.wait()  # a renewal of A alone is in flight
            second = await manager.submit("echo", Word("B"), principal="")
            await _until(lambda: service.calls == ["A", "B"])
            go.set()
            await _until(lambda: len(renewals) >= 3)  # two more heartbeats, B renewed in them
            assert renewals[0] == [first["id"]]
            assert sorted(renewals[-1]) == sorted([first["id"], second["id"]])
            job = manager.live(second["id"])
            assert job is not None and not job.lease_lost
            service.gate.set()
            await _status(manager, second["id"], "succeeded")

    _run(scenario)
