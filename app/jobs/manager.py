"""Jobs: accepted at once, run in the background by whichever replica is free, kept in the store.

A submitted job is checked (the same 422 problems as the synchronous endpoint) and stored as
`queued` with its request; the 202 is sent once that is committed, so an accepted job is never
lost. Each replica's dispatcher claims queued jobs from the store (`app.jobs.store`), up to
`job_runners` at once: a *lease* of `job_lease` seconds that its heartbeat renews every
`_heartbeat` seconds. A job it runs is an asyncio task calling the operation
(`app.jobs.operations`) through the same `Service` as the endpoints, so a job's answers are the
endpoint's answers; it lives in memory (`LiveJob`) and in the store (progress written at most
every `_PROGRESS_INTERVAL` s, each batch item as it is answered). A replica that dies stops
renewing: once its leases expire another replica claims the jobs and finishes them, a batch
from the items already answered (each item is recorded once). What a replica writes for a job
is fenced by its lease, so a job is answered once even if two replicas ran it.

Cancelling (DELETE) a queued job finishes it at once; a running one here has its task
cancelled (no new work starts, work already in a worker runs to its end unrecorded); one
running on another replica is flagged, and that replica cancels it at its next heartbeat.
Stopping a replica hands its running jobs back to the queue (another replica, or this one's
next start, takes them up); a synchronous call past its wait (`adopt`) has no stored request
and is failed with /problems/job-interrupted instead, as is a job whose replicas stopped
`job_attempts` times while it ran.
"""

from __future__ import annotations

import asyncio
import contextlib
import json
import logging
import secrets
import time
from collections.abc import Awaitable, Callable, Mapping
from typing import Any

from app.jobs.live import LiveJob, RunContext
from app.jobs.models import FINISHED_STATES, JOB_STATES
from app.jobs.operations import JOB_KINDS, JobKind
from app.jobs.signals import on_shutdown_signals
from app.jobs.store import Claim, JobRow, Store, interrupted_problem, new_job_id, request_json
from app.metrics import Metrics
from app.problems import PROBLEM_TYPES, FieldError, Problem, ProblemType, problem_body
from app.service import Service
from app.settings import Settings

__all__ = ["JobManager", "LiveJob"]  # LiveJob: app.jobs.live

log = logging.getLogger(__name__)

_PROGRESS_INTERVAL = 0.5  # [s] progress of a running job is written this often at most
_CANCEL_WAIT = 5.0  # [s] longest a DELETE waits for another replica to cancel its job

PROBLEM_TYPES["job-interrupted"] = ProblemType(
    "job-interrupted",
    "Job interrupted",
    503,
    "The job could not be finished: a synchronous request past its wait whose replica stopped "
    "(its request is not kept), or a job whose replicas stopped FLEXWING_JOB_ATTEMPTS times "
    "while it ran (`done` of `total` units were finished; a batch's answered items stay in "
    "items.ndjson). Submit it again.",
)
PROBLEM_TYPES["job-conflict"] = ProblemType(
    "job-conflict",
    "Job runs elsewhere",
    409,
    "The job runs on another replica sharing the jobs database, which did not confirm the "
    "cancel in time: it has been asked to cancel it at its next heartbeat. GET the job to see.",
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


class JobManager:
    def __init__(
        self,
        settings: Settings,
        service: Service,
        metrics: Metrics,
        operations: Mapping[str, JobKind] = JOB_KINDS,
        store: Store | None = None,
    ) -> None:
        self.settings = settings
        self.service = service
        self.metrics = metrics
        self.operations = operations
        self.owner = secrets.token_hex(8)  # this replica, as the store's leases name it
        self.store = store or Store.of(
            settings.database_url, settings.jobs_db, settings.retry_after
        )
        self._live: dict[str, LiveJob] = {}
        self._submitted: dict[str, Any] = {}  # requests accepted here, not yet claimed
        self._runners: set[asyncio.Task[None]] = set()
        self._counts: dict[str, int] = dict.fromkeys(JOB_STATES, 0)
        self._tasks: list[asyncio.Task[None]] = []
        self._stopping = asyncio.Event()
        self._wake = asyncio.Event()
        self._restore_signals: Callable[[], None] = lambda: None
        self._heartbeat = min(1.0, settings.job_lease / 4)  # [s] leases renewed this often
        metrics.job_queue.set_function(self.queued)

    # ------------------------------------------------------------------------- lifecycle

    async def start(self) -> None:
        """Open the store (an unreachable database is retried in the background: /readyz
        says so) and start claiming jobs."""
        self._stopping = asyncio.Event()
        self._wake = asyncio.Event()
        await self.store.open()
        with contextlib.suppress(Problem):
            await self._recount()
        self._tasks = [
            asyncio.create_task(self._dispatch(), name="flexwing-job-dispatcher"),
            asyncio.create_task(self._keep_leases(), name="flexwing-job-leases"),
            asyncio.create_task(self._janitor(), name="flexwing-job-janitor"),
        ]
        self._restore_signals = on_shutdown_signals(asyncio.get_running_loop(), self._stopping.set)

    async def close(self) -> None:
        """Hand the running jobs back to the queue (adopted calls fail as interrupted), then
        close the store once that is written."""
        self._stopping.set()
        self._restore_signals()
        for task in self._tasks:
            task.cancel()
        running = [job.task for job in self._live.values() if job.task is not None]
        for job in self._live.values():
            job.releasing = True
            if job.task is not None:
                job.task.cancel()
        await asyncio.gather(*self._tasks, *running, return_exceptions=True)
        await self.store.close()

    def queued(self) -> int:
        """Jobs waiting in the store (every replica's; as last counted here)."""
        return self._counts.get("queued", 0)

    @property
    def ready(self) -> bool:
        """The store is reachable: jobs can be accepted and read."""
        return self.store.available

    # ------------------------------------------------------------------------ submission

    def _overloaded(self, detail: str) -> Problem:
        self.metrics.shed.inc()
        return Problem(
            "overloaded", detail, headers={"Retry-After": str(self.settings.retry_after)}
        )

    async def submit(
        self, name: str, request: Any, *, principal: str, prefix: str | None = "request"
    ) -> JobRow:
        """Check and store a job of `principal` (its API key's; "" without keys); its row once
        committed. Raises the endpoint's 422 problem (paths from `prefix`), 503 overloaded when
        `max_queued_jobs` are waiting, 503 database-unavailable without the store."""
        operation = self.operations[name]
        try:
            operation.check(request, self.settings)
        except Problem as problem:
            raise _prefixed(problem, prefix) if prefix else problem from None
        if self._stopping.is_set():
            raise self._overloaded("this replica is stopping")
        row: JobRow = {
            "id": new_job_id(),
            "operation": name,
            "status": "queued",
            "owner": self.owner,
            "principal": principal,
            "created": time.time(),
            "total": operation.units(request),
            "request": request_json(request),
        }
        limit = self.settings.max_queued_jobs
        if not await self.store.submit(row, limit):
            raise self._overloaded(f"{limit} jobs are waiting to start (FLEXWING_MAX_QUEUED_JOBS)")
        self._submitted[row["id"]] = request
        self._count(None, "queued")
        self.metrics.jobs_submitted.labels(name).inc()
        self._wake.set()
        del row["request"], row["owner"]
        unset = dict.fromkeys(("started", "finished", "expires", "problem"))
        return row | unset | {"done": 0, "problems": 0}

    def adopt(
        self, name: str, answer: asyncio.Future[bytes], total: int, *, principal: str
    ) -> LiveJob:
        """A synchronous request past its wait, as a running job of `principal`: `answer` (its
        service call, already running) finishes it, recorded as the job's result or problem.
        It never waits in the queue: it runs already, here (its request is not stored: if this
        replica stops first, it fails as interrupted)."""
        operation = self.operations[name]
        result = operation.result
        assert result is not None, f"{name} answers no body"
        started = time.time()
        job = LiveJob(
            new_job_id(), operation, None, started, total, started=started, principal=principal
        )
        self._live[job.id] = job
        lease = started + self.settings.job_lease
        self.store.insert_job(
            job.row() | {"owner": self.owner, "problem": None, "lease_expires": lease}
        )
        self._count(None, "running")
        self.metrics.jobs_submitted.labels(name).inc()

        async def body() -> str:
            return result(await answer)

        job.task = asyncio.create_task(self._settle(job, body, answer.cancel))
        job.task.add_done_callback(lambda task: self._cancelled_before_it_began(job, answer, task))
        return job

    def _cancelled_before_it_began(
        self, job: LiveJob, answer: asyncio.Future[bytes], task: asyncio.Task[None]
    ) -> None:
        """An adopted job's task cancelled before its first step never reached `_settle`: end
        the job and its call here."""
        if task.cancelled() and job.id in self._live:
            answer.cancel()
            self._stopped(job)

    # --------------------------------------------------------------------------- running

    async def _dispatch(self) -> None:
        """Claim jobs while runners are free; between claims that find nothing, wait for a
        submission here or `job_poll_interval` (a job submitted to another replica)."""
        while True:
            if len(self._runners) >= self.settings.job_runners:
                await asyncio.wait(set(self._runners), return_when=asyncio.FIRST_COMPLETED)
                continue
            claim = None
            if self.store.available:
                try:
                    claim = await self.store.claim(self.owner, time.time(), self.settings.job_lease)
                except Problem:
                    claim = None  # the database went away: wait for it
                except Exception:
                    log.exception("claiming a job failed")
                    claim = None
            if claim is None:
                with contextlib.suppress(TimeoutError):
                    await asyncio.wait_for(self._wake.wait(), self.settings.job_poll_interval)
                self._wake.clear()
                continue
            self._take_up(claim)

    def _take_up(self, claim: Claim) -> None:
        """Run a claimed job here (or settle it at once: cancelled, unknown, not resumable)."""
        job_id = claim["id"]
        was = "queued" if claim["done"] == 0 and claim["attempts"] == 1 else "running"
        self._count("queued" if claim["attempts"] == 1 else None, "running")
        operation = self.operations.get(claim["operation"])
        request = self._submitted.pop(job_id, None)
        job = LiveJob.claimed(claim, operation, request)
        self._live[job_id] = job
        why = None
        if operation is None:
            why = f"this replica does not know the operation {claim['operation']!r}"
        elif request is None and claim["request"] is None:
            why = "the replica answering this synchronous request stopped; submit it again"
        elif claim["attempts"] > self.settings.job_attempts:
            why = (
                f"the replicas running it stopped {claim['attempts'] - 1} times "
                "(FLEXWING_JOB_ATTEMPTS); submit it again"
            )
        if job.cancel_requested:
            self._finish(job, "cancelled")
        elif why is not None:
            self._finish(job, "failed", problem=interrupted_problem(was, job.done, job.total, why))
        else:
            if job.request is None:
                assert operation is not None
                job.request = operation.request_model.model_validate_json(claim["request"])
            job.task = asyncio.create_task(self._run(job), name=f"flexwing-job-{job_id}")
            self._runners.add(job.task)
            job.task.add_done_callback(self._runners.discard)
        job.notify()

    async def _run(self, job: LiveJob) -> None:
        context = RunContext(self, job)
        await self._settle(job, lambda: job.operation.run(context, job.request))

    async def _settle(
        self,
        job: LiveJob,
        work: Callable[[], Awaitable[str | None]],
        cancel: Callable[[], Any] = lambda: None,
    ) -> None:
        """Await a job's work and finish it with its result, its problem or its stop."""
        try:
            result = await work()
        except asyncio.CancelledError:
            cancel()
            self._stopped(job)
        except Problem as problem:
            self._finish(job, "failed", problem=problem_body(problem))
        except Exception as error:
            log.exception("job %s (%s) failed", job.id, job.operation.name)
            internal = Problem("internal-error", f"unexpected {type(error).__name__}")
            self._finish(job, "failed", problem=problem_body(internal))
        else:
            self._finish(job, "succeeded", result=result)

    def _stopped(self, job: LiveJob) -> None:
        """A job whose work was cancelled: as asked, handed back, lost to another replica, or
        interrupted."""
        if job.cancel_requested:
            self._finish(job, "cancelled")
        elif job.lease_lost:
            self._forget(job, None)
        elif job.releasing and job.request is not None:
            self.store.release(job.id, self.owner, job.done, job.problems)
            self._forget(job, "queued")
        else:
            self._finish(job, "failed", problem=self._interrupted(job))

    def item_answered(self, job: LiveJob, index: int, ok: bool, line: str) -> None:
        if index in job.answered:
            return  # answered before this replica took the job up (recorded once)
        job.done += 1
        job.problems += not ok
        job.answers += 1
        self.store.insert_item(job.id, self.owner, index, job.answers, ok, line)
        self.metrics.batch_items.labels("ok" if ok else "problem").inc()
        now = time.monotonic()
        if now - job.progress_written >= _PROGRESS_INTERVAL:
            job.progress_written = now
            progress = {"done": job.done, "problems": job.problems}
            self.store.update_job(job.id, self.owner, progress)
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
            self.store.update_job(job.id, self.owner, {"done": job.done})
        job.notify()

    def _finish(
        self,
        job: LiveJob,
        status: str,
        *,
        result: str | None = None,
        problem: dict[str, Any] | None = None,
    ) -> None:
        """Record the final state (the write is queued before anyone can read, and fenced by
        this replica's lease)."""
        interrupted = problem is not None and problem["type"] == "/problems/job-interrupted"
        if not job.operation.has_items and status in ("succeeded", "failed") and not interrupted:
            job.done = job.total  # its one unit was answered, with a result or a problem
        job.status, job.finished = status, time.time()
        job.expires = job.finished + self.settings.job_retention
        job.result, job.problem, job.request = result, problem, None
        fields = job.row() | {"result": result, "lease_expires": None, "request": None}
        fields["problem"] = None if problem is None else json.dumps(problem)
        for name in ("id", "operation", "principal", "created", "total"):
            del fields[name]
        self.store.update_job(job.id, self.owner, fields)
        self._forget(job, status)

    def _forget(self, job: LiveJob, status: str | None) -> None:
        """This replica is done with `job` (now `status` in the counts; None: not its to say)."""
        self._live.pop(job.id, None)
        if status is not None:
            self._count("running", status)
        job.notify()

    def _interrupted(self, job: LiveJob) -> dict[str, Any]:
        return interrupted_problem(job.status, job.done, job.total)

    # ------------------------------------------------------------------- reading and cancel

    async def find(
        self, job_id: str, *, principal: str, with_result: bool = False
    ) -> JobRow | None:
        """A job's row (a live one from memory), None if unknown, expired or `principal`'s
        not (another key's job is no job, as far as this key can tell)."""
        live = self._live.get(job_id)
        if live is not None:
            return live.row() | {"result": None} if live.principal == principal else None
        row = await self.store.get_job(job_id, with_result)
        if row is None or (row["expires"] is not None and row["expires"] <= time.time()):
            return None
        return row if row["principal"] == principal else None

    async def page(
        self, limit: int, before: tuple[float, str] | None, status: str | None, *, principal: str
    ) -> list[JobRow]:
        """`principal`'s jobs, newest first (see `Store.list_jobs`)."""
        rows = await self.store.list_jobs(limit, before, status, time.time(), principal)
        return [self._live[r["id"]].row() if r["id"] in self._live else r for r in rows]

    async def cancel(self, job_id: str, *, principal: str) -> JobRow | None:
        """Cancel a queued or running job of `principal`; a finished one stays as it is. None
        when `principal` has no such job."""
        job = self._live.get(job_id)
        if job is not None:
            return await self._cancel_here(job, principal)
        row = await self.find(job_id, principal=principal)
        if row is None or row["status"] in FINISHED_STATES:
            return row
        now = time.time()
        expires = now + self.settings.job_retention
        if await self.store.cancel_queued(job_id, principal, now, expires):
            self._count(row["status"], "cancelled")
            self._submitted.pop(job_id, None)
            return await self.find(job_id, principal=principal)
        # Running on another replica (or just claimed by this one): ask, then wait for it.
        await self.store.ask_cancel(job_id, principal)
        deadline = time.monotonic() + _CANCEL_WAIT
        while time.monotonic() < deadline:
            job = self._live.get(job_id)
            if job is not None:
                return await self._cancel_here(job, principal)
            row = await self.find(job_id, principal=principal)
            if row is None or row["status"] in FINISHED_STATES:
                return row
            await asyncio.sleep(self._heartbeat / 4)
        raise Problem(
            "job-conflict",
            f"job {job_id} runs on another replica, asked to cancel it at its next heartbeat",
        )

    async def _cancel_here(self, job: LiveJob, principal: str) -> JobRow | None:
        if job.principal != principal:
            return None
        job.cancel_requested = True
        if job.task is not None:
            job.task.cancel()
            await asyncio.wait([job.task])
        return job.row()

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

    async def pause(self, seconds: float) -> bool:
        """Sleep `seconds` [s] (a stream polling a job another replica runs); False when the
        service stops first."""
        with contextlib.suppress(TimeoutError):
            await asyncio.wait_for(self._stopping.wait(), seconds)
        return not self._stopping.is_set()

    @property
    def poll_interval(self) -> float:
        """[s] how often a stream reads a job that another replica runs (its progress is
        written every 0.5 s)."""
        return _PROGRESS_INTERVAL

    @property
    def stopping(self) -> bool:
        return self._stopping.is_set()

    # -------------------------------------------------------------- housekeeping, metrics

    async def _keep_leases(self) -> None:
        """Renew the leases of the jobs this replica runs every `_heartbeat` s; cancel here what
        was asked to be cancelled elsewhere, and stop (unrecorded) what another replica has
        taken over. Only the jobs running before the renewal was asked are judged by it (a job
        claimed meanwhile is not in its answer), and only those are renewed (a job given up
        here is left to expire)."""
        while True:
            await asyncio.sleep(self._heartbeat)
            running = [
                job_id
                for job_id, job in self._live.items()
                if job.task is not None and not job.task.done()
            ]
            if not running or not self.store.available:
                continue
            until = time.time() + self.settings.job_lease
            try:
                held = await self.store.renew(self.owner, until, running)
            except Problem:
                continue  # unreachable from here: past the lease, the fences keep us out
            except Exception:
                log.exception("renewing the leases failed")
                continue
            for job_id in running:
                job = self._live.get(job_id)
                if job is None or job.task is None or job.task.done():
                    continue
                if job_id not in held:
                    log.warning("job %s: its lease passed to another replica", job_id)
                    job.lease_lost = True
                    job.task.cancel()
                elif held[job_id] and not job.cancel_requested:
                    job.cancel_requested = True
                    job.task.cancel()

    async def _janitor(self) -> None:
        """Delete expired jobs and idle rate-limit buckets, refresh the job counts."""
        interval = max(0.2, min(5.0, self.settings.job_retention / 2))
        while True:
            await asyncio.sleep(interval)
            if not self.store.available:
                continue
            try:
                now = time.time()
                await self.store.delete_expired(now)
                if self.settings.client_rate_limit > 0:
                    idle = self.settings.rate_burst / self.settings.client_rate_limit
                    await self.store.forget_buckets(now - idle - 60.0)
                await self._recount()
            except Problem:
                continue  # the database went away: next time
            except Exception:
                log.exception("jobs housekeeping failed")

    async def _recount(self) -> None:
        counts = await self.store.count_by_status(time.time())
        self._counts = {state: counts.get(state, 0) for state in JOB_STATES}
        for state, count in self._counts.items():
            self.metrics.jobs.labels(state).set(count)
        if len(self._submitted) > self._counts["queued"]:  # claimed by other replicas
            self._submitted.clear()

    def _count(self, previous: str | None, status: str) -> None:
        for state, change in ((previous, -1), (status, 1)):
            if state is not None:
                self._counts[state] = max(0, self._counts.get(state, 0) + change)
                self.metrics.jobs.labels(state).set(self._counts[state])
