"""Jobs: accepted at once, run in the background, kept in the jobs database.

A submitted job is checked (the same 422 problems as the synchronous endpoint), stored as
`queued` and put on an in-memory queue that `job_runners` runner tasks take from. Running, it is
an asyncio task calling the operation (`app.jobs.operations`) through the same `Service` as the
endpoints, so a job's answers are the endpoint's answers. Queued and running jobs live in memory
(`LiveJob`) and in the database (progress written at most every `_PROGRESS_INTERVAL` s, each batch
item as it is answered); finished ones only in the database, until their retention ends.

Cancelling (DELETE) a queued job finishes it at once; a running one has its task cancelled: no new
work starts, work already in a worker runs to its end unrecorded. Stopping the service fails
every queued and running job with /problems/job-interrupted; so does the next start for the jobs
of an instance that died without stopping (see `app.jobs.store`).
"""

from __future__ import annotations

import asyncio
import json
import logging
import secrets
import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

from app.jobs import store
from app.jobs.models import FINISHED_STATES, JOB_STATES
from app.jobs.operations import JOB_KINDS, JobKind
from app.jobs.signals import on_shutdown_signals
from app.jobs.store import JobRow, JobStore, OwnerLock
from app.metrics import Metrics
from app.problems import PROBLEM_TYPES, FieldError, Problem, ProblemType, problem_body
from app.service import Service
from app.settings import Settings

__all__ = ["JobManager", "LiveJob"]

log = logging.getLogger(__name__)

_PROGRESS_INTERVAL = 0.5  # [s] progress of a running job is written this often at most

PROBLEM_TYPES["job-interrupted"] = ProblemType(
    "job-interrupted",
    "Job interrupted",
    503,
    "The service stopped while this job was queued or running (`done` of `total` units were "
    "finished; a batch's answered items stay in items.ndjson). Submit it again.",
)
PROBLEM_TYPES["job-conflict"] = ProblemType(
    "job-conflict",
    "Job runs elsewhere",
    409,
    "The job runs in another service process that shares the jobs database; cancel it there.",
)


def _prefixed(problem: Problem, prefix: str) -> Problem:
    """An invalid-input problem about a request, its field paths from `prefix` (the body)."""
    if problem.type.slug != "invalid-input":
        return problem
    listed = problem.extensions.get("errors", [])
    errors = [FieldError(f"{prefix}.{e['field']}", e["reason"]) for e in listed]
    renamed = Problem.invalid(errors)
    renamed.extensions["error_count"] = problem.extensions.get("error_count", len(errors))
    return renamed


@dataclass(eq=False)
class LiveJob:
    """A queued or running job, in memory (`row()` is its database row)."""

    id: str
    operation: JobKind
    request: Any  # the validated request model; None once finished
    created: float  # [s since the epoch]
    total: int
    status: str = "queued"
    started: float | None = None
    finished: float | None = None
    expires: float | None = None
    done: int = 0
    problems: int = 0
    result: str | None = None  # JSON text
    problem: dict[str, Any] | None = None
    task: asyncio.Task[None] | None = None
    cancel_requested: bool = False
    principal: str = ""  # its API key (app.security.keys.ApiKey.principal); "" without keys
    answers: int = 0  # batch items answered: their order in the database
    progress_written: float = 0.0  # [s, monotonic]
    changed: asyncio.Event = field(default_factory=asyncio.Event)

    def row(self) -> JobRow:
        return {
            "id": self.id,
            "operation": self.operation.name,
            "status": self.status,
            "principal": self.principal,
            "created": self.created,
            "started": self.started,
            "finished": self.finished,
            "expires": self.expires,
            "done": self.done,
            "total": self.total,
            "problems": self.problems,
            "problem": self.problem,
        }

    def notify(self) -> None:
        """Wake whoever waits for a change (event streams)."""
        self.changed.set()
        self.changed = asyncio.Event()


@dataclass
class _Context:
    """An operation's `operations.JobContext`: the service, how many items to keep in flight,
    and a place to record batch items."""

    manager: JobManager
    job: LiveJob

    @property
    def service(self) -> Service:
        return self.manager.service

    @property
    def lanes(self) -> int:
        return self.manager.service.pool.capacity

    @property
    def parallelism(self) -> int:
        return self.manager.service.pool.parallelism

    @property
    def chunk_seconds(self) -> float:
        return self.manager.service.pool.chunk_seconds

    def item_answered(self, index: int, ok: bool, line: str) -> None:
        self.manager.item_answered(self.job, index, ok, line)

    def progress(self, done: int, total: int) -> None:
        self.manager.progressed(self.job, done)


class JobManager:
    def __init__(
        self,
        settings: Settings,
        service: Service,
        metrics: Metrics,
        operations: Mapping[str, JobKind] = JOB_KINDS,
    ) -> None:
        self.settings = settings
        self.service = service
        self.metrics = metrics
        self.operations = operations
        self.owner = secrets.token_hex(8)
        self.store = JobStore(settings.jobs_db)
        self._lock = OwnerLock(settings.jobs_db, self.owner)
        self._live: dict[str, LiveJob] = {}
        self._queue: asyncio.Queue[LiveJob] = asyncio.Queue()
        self._counts: dict[str, int] = dict.fromkeys(JOB_STATES, 0)
        self._tasks: list[asyncio.Task[None]] = []
        self._stopping = asyncio.Event()
        self._restore_signals: Callable[[], None] = lambda: None
        self._started = False
        metrics.job_queue.set_function(self.queued)

    # ------------------------------------------------------------------------- lifecycle

    async def start(self) -> None:
        self._stopping = asyncio.Event()
        self._lock.acquire()
        await self.store.open()
        self._started = True
        await self._interrupt_orphans()
        await self._recount()
        self._tasks = [
            asyncio.create_task(self._runner(), name=f"flexwing-job-runner-{n}")
            for n in range(self.settings.job_runners)
        ]
        self._tasks.append(asyncio.create_task(self._janitor(), name="flexwing-job-janitor"))
        self._restore_signals = on_shutdown_signals(asyncio.get_running_loop(), self._stopping.set)

    async def close(self) -> None:
        """Fail the jobs still queued or running (interrupted), then close the database."""
        self._stopping.set()
        self._restore_signals()
        for task in self._tasks:
            task.cancel()
        running = [job.task for job in self._live.values() if job.task is not None]
        for job in list(self._live.values()):
            if job.task is not None:
                job.task.cancel()
            if job.status == "queued":
                self._finish(job, "failed", problem=self._interrupted(job))
        await asyncio.gather(*self._tasks, *running, return_exceptions=True)
        if self._started:
            await self.store.close()
        self._lock.release()

    def queued(self) -> int:
        return sum(1 for job in self._live.values() if job.status == "queued")

    # ------------------------------------------------------------------------ submission

    def submit(
        self, name: str, request: Any, *, principal: str, prefix: str | None = "request"
    ) -> LiveJob:
        """Check and queue a job of `principal` (its API key's; "" without keys); raises the
        endpoint's 422 problem (paths from `prefix`) or 503 overloaded when `max_queued_jobs`
        are waiting."""
        operation = self.operations[name]
        try:
            operation.check(request, self.settings)
        except Problem as problem:
            raise _prefixed(problem, prefix) if prefix else problem from None
        if self._stopping.is_set() or self.queued() >= self.settings.max_queued_jobs:
            self.metrics.shed.inc()
            raise Problem(
                "overloaded",
                f"{self.queued()} jobs are waiting to start (FLEXWING_MAX_QUEUED_JOBS)",
                headers={"Retry-After": str(self.settings.retry_after)},
            )
        job = LiveJob(
            store.new_job_id(),
            operation,
            request,
            time.time(),
            operation.units(request),
            principal=principal,
        )
        self._live[job.id] = job
        self.store.write(store.insert_job, job.row() | {"owner": self.owner, "problem": None})
        self._count(None, "queued")
        self.metrics.jobs_submitted.labels(name).inc()
        self._queue.put_nowait(job)
        return job

    def adopt(
        self, name: str, answer: asyncio.Future[bytes], total: int, *, principal: str
    ) -> LiveJob:
        """A synchronous request past its wait, as a running job of `principal`: `answer` (its
        service call, already running) finishes it, recorded as the job's result or problem.
        It never waits in the queue: it runs already."""
        operation = self.operations[name]
        assert operation.result is not None, f"{name} answers no body"
        started = time.time()
        job = LiveJob(
            store.new_job_id(),
            operation,
            None,
            started,
            total,
            status="running",
            started=started,
            principal=principal,
        )
        self._live[job.id] = job
        self.store.write(store.insert_job, job.row() | {"owner": self.owner, "problem": None})
        self._count(None, "running")
        self.metrics.jobs_submitted.labels(name).inc()
        job.task = asyncio.create_task(self._finish_adopted(job, answer, operation.result))
        job.task.add_done_callback(lambda task: self._cancelled_before_it_began(job, answer, task))
        return job

    def _cancelled_before_it_began(
        self, job: LiveJob, answer: asyncio.Future[bytes], task: asyncio.Task[None]
    ) -> None:
        """An adopted job's task cancelled before its first step never reached
        `_finish_adopted`: end the job and its call here."""
        if not task.cancelled() or job.status in FINISHED_STATES:
            return
        answer.cancel()
        if job.cancel_requested:
            self._finish(job, "cancelled")
        else:
            self._finish(job, "failed", problem=self._interrupted(job))

    async def _finish_adopted(
        self,
        job: LiveJob,
        answer: asyncio.Future[bytes],
        result: Callable[[bytes], str],
    ) -> None:
        try:
            body = await answer
        except asyncio.CancelledError:
            answer.cancel()
            if job.cancel_requested:
                self._finish(job, "cancelled")
            else:
                self._finish(job, "failed", problem=self._interrupted(job))
        except Problem as problem:
            self._finish(job, "failed", problem=problem_body(problem))
        except Exception as error:
            log.exception("job %s (%s) failed", job.id, job.operation.name)
            internal = Problem("internal-error", f"unexpected {type(error).__name__}")
            self._finish(job, "failed", problem=problem_body(internal))
        else:
            self._finish(job, "succeeded", result=result(body))

    # --------------------------------------------------------------------------- running

    async def _runner(self) -> None:
        while True:
            job = await self._queue.get()
            if job.status != "queued":
                continue  # cancelled while it waited
            job.task = asyncio.create_task(self._execute(job), name=f"flexwing-job-{job.id}")
            await asyncio.wait([job.task])

    async def _execute(self, job: LiveJob) -> None:
        if job.status != "queued":
            return  # cancelled between being taken from the queue and starting
        job.status, job.started = "running", time.time()
        self.store.write(store.update_job, job.id, {"status": "running", "started": job.started})
        self._count("queued", "running")
        job.notify()
        try:
            result = await job.operation.run(_Context(self, job), job.request)
        except asyncio.CancelledError:
            if job.cancel_requested:
                self._finish(job, "cancelled")
            else:
                self._finish(job, "failed", problem=self._interrupted(job))
        except Problem as problem:
            self._finish(job, "failed", problem=problem_body(problem))
        except Exception as error:
            log.exception("job %s (%s) failed", job.id, job.operation.name)
            internal = Problem("internal-error", f"unexpected {type(error).__name__}")
            self._finish(job, "failed", problem=problem_body(internal))
        else:
            self._finish(job, "succeeded", result=result)

    def item_answered(self, job: LiveJob, index: int, ok: bool, line: str) -> None:
        job.done += 1
        job.problems += not ok
        job.answers += 1
        self.store.write(store.insert_item, job.id, index, job.answers, ok, line)
        self.metrics.batch_items.labels("ok" if ok else "problem").inc()
        now = time.monotonic()
        if now - job.progress_written >= _PROGRESS_INTERVAL:
            job.progress_written = now
            progress = {"done": job.done, "problems": job.problems}
            self.store.write(store.update_job, job.id, progress)
        job.notify()

    def progressed(self, job: LiveJob, done: int) -> None:
        """`done` of the job's units are done (its answer still to come): shown at once, written
        at most every _PROGRESS_INTERVAL s."""
        if job.status != "running" or done <= job.done:
            return
        job.done = min(done, job.total)
        now = time.monotonic()
        if now - job.progress_written >= _PROGRESS_INTERVAL:
            job.progress_written = now
            self.store.write(store.update_job, job.id, {"done": job.done})
        job.notify()

    def _finish(
        self,
        job: LiveJob,
        status: str,
        *,
        result: str | None = None,
        problem: dict[str, Any] | None = None,
    ) -> None:
        """Record the final state (the database write is queued before anyone can read)."""
        interrupted = problem is not None and problem["type"] == "/problems/job-interrupted"
        if not job.operation.has_items and status in ("succeeded", "failed") and not interrupted:
            job.done = job.total  # its one unit was answered, with a result or a problem
        previous = job.status
        job.status, job.finished = status, time.time()
        job.expires = job.finished + self.settings.job_retention
        job.result, job.problem, job.request = result, problem, None
        fields = job.row() | {"result": result, "problem": json.dumps(problem) if problem else None}
        self.store.write(store.update_job, job.id, fields)
        self._count(previous, status)
        del self._live[job.id]
        job.notify()

    def _interrupted(self, job: LiveJob) -> dict[str, Any]:
        return store.interrupted_problem(job.status, job.done, job.total)

    # ------------------------------------------------------------------- reading and cancel

    async def find(
        self, job_id: str, *, principal: str, with_result: bool = False
    ) -> JobRow | None:
        """A job's row (a live one from memory), None if unknown, expired or `principal`'s
        not (another key's job is no job, as far as this key can tell)."""
        live = self._live.get(job_id)
        if live is not None:
            return live.row() | {"result": None} if live.principal == principal else None
        row = await self.store.read(store.get_job, job_id, with_result)
        if row is None or (row["expires"] is not None and row["expires"] <= time.time()):
            return None
        return row if row["principal"] == principal else None

    async def page(
        self, limit: int, before: tuple[float, str] | None, status: str | None, *, principal: str
    ) -> list[JobRow]:
        """`principal`'s jobs, newest first (see `store.list_jobs`)."""
        rows = await self.store.read(store.list_jobs, limit, before, status, time.time(), principal)
        return [self._live[r["id"]].row() if r["id"] in self._live else r for r in rows]

    async def cancel(self, job_id: str, *, principal: str) -> JobRow | None:
        """Cancel a queued or running job of `principal`; a finished one stays as it is. None
        when `principal` has no such job."""
        job = self._live.get(job_id)
        if job is not None and job.principal != principal:
            return None
        if job is None:
            return await self._cancel_elsewhere(job_id, principal)
        job.cancel_requested = True
        if job.status == "queued":  # (its task, if any, has not begun: it never will)
            self._finish(job, "cancelled")
            if job.task is not None:
                job.task.cancel()
        elif job.task is not None:
            job.task.cancel()
            await asyncio.wait([job.task])
        return job.row()

    async def _cancel_elsewhere(self, job_id: str, principal: str) -> JobRow | None:
        row = await self.find(job_id, principal=principal)
        if row is None or row["status"] in FINISHED_STATES:
            return row
        owner = await self.store.read(store.owner_of, job_id)
        if owner is not None and self._lock.is_alive(owner):
            raise Problem("job-conflict", f"job {job_id} runs in another service process")
        await self._interrupt_orphans()
        return await self.find(job_id, principal=principal)

    # ------------------------------------------------------------ what streams read

    def live(self, job_id: str) -> LiveJob | None:
        return self._live.get(job_id)

    async def wait_for_change(self, job: LiveJob, timeout: float) -> bool:
        """Until `job` changes (True), the service stops or `timeout` [s] passes (False)."""
        waits = [
            asyncio.create_task(job.changed.wait()),
            asyncio.create_task(self._stopping.wait()),
        ]
        done, pending = await asyncio.wait(
            waits, timeout=timeout, return_when=asyncio.FIRST_COMPLETED
        )
        for task in pending:
            task.cancel()
        return bool(done) and not self._stopping.is_set()

    @property
    def stopping(self) -> bool:
        return self._stopping.is_set()

    # -------------------------------------------------------------- housekeeping, metrics

    async def _janitor(self) -> None:
        """Delete expired jobs, fail those of dead instances, refresh the job counts."""
        interval = max(0.2, min(5.0, self.settings.job_retention / 2))
        while True:
            await asyncio.sleep(interval)
            try:
                await self.store.read(store.delete_expired, time.time())
                await self._interrupt_orphans()
                await self._recount()
            except Exception:
                log.exception("jobs housekeeping failed")

    async def _interrupt_orphans(self) -> None:
        owners = await self.store.read(store.unfinished_owners)
        for owner in owners:
            if owner != self.owner and not self._lock.is_alive(owner):
                count = await self.store.read(
                    store.interrupt_jobs_of, owner, time.time(), self.settings.job_retention
                )
                log.warning("%d job(s) of a stopped service instance marked interrupted", count)

    async def _recount(self) -> None:
        counts = await self.store.read(store.count_by_status, time.time())
        self._counts = {state: counts.get(state, 0) for state in JOB_STATES}
        for state, count in self._counts.items():
            self.metrics.jobs.labels(state).set(count)

    def _count(self, previous: str | None, status: str) -> None:
        for state, change in ((previous, -1), (status, 1)):
            if state is not None:
                self._counts[state] = self._counts.get(state, 0) + change
                self.metrics.jobs.labels(state).set(self._counts[state])
