"""A job running in this replica: its state in memory (`LiveJob`) and what its operation gets
to work with (`RunContext`, an `app.jobs.operations.JobContext`)."""

from __future__ import annotations

import asyncio
from dataclasses import dataclass, field
from typing import Any, Protocol

from app.jobs.operations import JobKind
from app.jobs.store import Claim, JobRow
from app.service import Service

__all__ = ["LiveJob", "Recorder", "RunContext", "unknown_operation"]


class Recorder(Protocol):
    """What a running job reports to (the `JobManager`)."""

    service: Service

    def item_answered(self, job: LiveJob, index: int, ok: bool, line: str) -> None: ...

    def progressed(self, job: LiveJob, done: int) -> None: ...


@dataclass(eq=False)
class LiveJob:
    """A job running in this replica, in memory (`row()` is its store row)."""

    id: str
    operation: JobKind
    request: Any  # the validated request model; None once finished, or adopted
    created: float  # [s since the epoch]
    total: int
    status: str = "running"
    started: float | None = None
    finished: float | None = None
    expires: float | None = None
    done: int = 0
    problems: int = 0
    result: str | None = None  # JSON text
    problem: dict[str, Any] | None = None
    task: asyncio.Task[None] | None = None
    cancel_requested: bool = False
    releasing: bool = False  # the replica stops: back to the queue
    lease_lost: bool = False  # another replica holds it now: record nothing more
    principal: str = ""  # its API key (app.security.keys.ApiKey.principal); "" without keys
    answers: int = 0  # batch items answered: their order in the store
    answered: frozenset[int] = frozenset()  # items answered before this replica took it up
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

    @classmethod
    def claimed(cls, claim: Claim, operation: JobKind | None, request: Any) -> LiveJob:
        """The job of a claim (`Store.claim`) as it is taken up here: `request` if this replica
        still holds it (it accepted the job), else read from the claim later; a batch's
        progress is the items answered so far."""
        job = cls(
            claim["id"],
            operation or unknown_operation(claim["operation"]),
            request,
            claim["created"],
            claim["total"],
            started=claim["started"],
            done=claim["done"],
            problems=claim["problems"],
            principal=claim["principal"],
            answers=claim["answers"],
            answered=frozenset(claim["answered"]),
            cancel_requested=bool(claim["cancel_requested"]),
        )
        if job.answered:
            job.done = len(job.answered)
            job.problems = sum(not ok for ok in claim["answered"].values())
        return job


@dataclass
class RunContext:
    """An operation's `operations.JobContext`: the service, how many items to keep in flight,
    and a place to record batch items."""

    manager: Recorder
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

    @property
    def answered(self) -> frozenset[int]:
        return self.job.answered

    def progress(self, done: int, total: int) -> None:
        self.manager.progressed(self.job, done)


def unknown_operation(name: str) -> JobKind:
    """A stand-in for an operation this replica does not know (a newer replica's job): the
    job is failed, never run."""

    async def run(context: Any, request: Any) -> None:
        return None

    return JobKind(
        name=name,
        summary="unknown",
        request_model=object,  # type: ignore[arg-type]
        request_description="",
        units=lambda request: 1,
        check=lambda request, settings: None,
        run=run,
    )
