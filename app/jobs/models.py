"""Request and response models of the jobs API (POST /jobs, GET /jobs/{id}, ...).

The submission body is `{"operation": <name>, "request": <what that endpoint takes>}`; its model is
built from the operations registry (`app.jobs.operations.submission_type`).
"""

from __future__ import annotations

from datetime import datetime
from typing import Annotated, Any, Literal

from pydantic import BaseModel, ConfigDict, Field

from app.problems import ProblemDetails
from app.schemas import SolveRequest, SolveResponse, study_wing
from app.settings import MAX_BATCH_ITEMS
from solver import ISA_SEA_LEVEL_DENSITY

__all__ = [
    "JOB_STATES",
    "STUDY_BATCH",
    "BatchItem",
    "BatchRequest",
    "BatchResult",
    "JobLinks",
    "JobList",
    "JobProgress",
    "JobState",
    "JobStatus",
    "Request",
]

JobState = Literal["queued", "running", "succeeded", "failed", "cancelled"]
JOB_STATES: tuple[str, ...] = ("queued", "running", "succeeded", "failed", "cancelled")
FINISHED_STATES = frozenset({"succeeded", "failed", "cancelled"})


class Request(BaseModel):
    # As app.schemas: a value of another JSON type than documented is invalid, not converted.
    model_config = ConfigDict(extra="forbid", strict=True)


STUDY_BATCH: dict[str, Any] = {
    "items": [
        {
            "wing": study_wing(),
            "flight": {"velocity": v, "alpha": 5.0, "density": ISA_SEA_LEVEL_DENSITY},
        }
        for v in (8.0, 10.0, 12.0)
    ]
}


class BatchRequest(Request):
    """Independent solves (any wings, any flight conditions), answered in the same order."""

    model_config = ConfigDict(
        extra="forbid", strict=True, json_schema_extra={"examples": [STUDY_BATCH]}
    )

    items: Annotated[list[SolveRequest], Field(min_length=1, max_length=MAX_BATCH_ITEMS)] = Field(
        description=(
            "[-] 1 to FLEXWING_MAX_BATCH_ITEMS (default and at most 10,000) /solve request "
            "bodies. One whose solve fails (no equilibrium, not converged, an invalid wing that "
            "the schema cannot tell, a lost worker) is answered with its problem in place."
        ),
        json_schema_extra={"x-flexwing-limit": "max_batch_items"},
    )


class BatchItem(BaseModel):
    """The answer to one batch item: the /solve response, or the problem /solve would return."""

    index: int = Field(description="[-] position of the item in `request.items`, from 0.")
    status: Literal["ok", "problem"] = Field(description="ok: `result`; problem: `problem`.")
    result: SolveResponse | None = Field(  # type: ignore[valid-type]
        default=None, description="The /solve response."
    )
    problem: ProblemDetails | None = Field(
        default=None, description="The problem+json body /solve would have answered."
    )


class BatchResult(BaseModel):
    """Every item's answer, in request order."""

    items: list[BatchItem]


class JobProgress(BaseModel):
    done: int = Field(
        description=(
            "[-] units finished: batch items answered (ok or problem), sweep points, 1 for a solve."
        )
    )
    total: int = Field(description="[-] units in the job.")
    problems: int = Field(description="[-] batch items answered with a problem (part of done).")


class JobLinks(BaseModel):
    self: str = Field(description="This job: GET for its state and result, DELETE to cancel.")
    events: str = Field(description="Server-sent events of its progress and final state.")
    items: str | None = Field(
        description="A batch's items as NDJSON, streamed as they are answered; null otherwise."
    )


class JobStatus(BaseModel):
    """A job's state; `result` or `problem` once it has finished."""

    id: str = Field(description="Unguessable job id (128 random bits, URL-safe base64).")
    operation: str = Field(description="What the job runs: solve, sweep, optimize or batch.")
    status: JobState = Field(
        description=(
            "queued (waiting for a runner), running, succeeded (`result`), failed (`problem`), "
            "cancelled (DELETE; `progress` says what was done)."
        )
    )
    progress: JobProgress
    created_at: datetime = Field(description="[UTC, RFC 3339] when it was submitted.")
    started_at: datetime | None = Field(description="[UTC, RFC 3339] when it started running.")
    finished_at: datetime | None = Field(description="[UTC, RFC 3339] when it finished.")
    expires_at: datetime | None = Field(
        description="[UTC, RFC 3339] when a finished job is deleted (FLEXWING_JOB_RETENTION)."
    )
    result: dict[str, Any] | None = Field(
        default=None,
        description=(
            "Succeeded jobs, in GET /jobs/{id} only: what the synchronous endpoint answers "
            "(a SolveResponse for solve, a SweepResponse for sweep) or, for batch, a BatchResult."
        ),
    )
    problem: ProblemDetails | None = Field(
        description=(
            "Failed jobs: the problem the synchronous endpoint would have answered, or "
            "/problems/job-interrupted when the service stopped while it was queued or running."
        )
    )
    links: JobLinks


class JobList(BaseModel):
    """Jobs, newest first, without their results."""

    jobs: list[JobStatus]
    next: str | None = Field(description="The next page (a relative URL), or null at the end.")
