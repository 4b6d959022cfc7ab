"""Request and response models of the jobs API (POST /jobs, GET /jobs/{id}, ...).

The submission body is `{"operation": <name>, "request": <what that endpoint takes>}`; its model is
built from the operations registry (`submission_type`), so a new operation adds itself. Validation
errors name fields from the body's root (`request.items[3].wing.chord[2]`): the union's tags start
with "@", which `app.problems` leaves out of field paths. An operation that does not exist is an
error on `operation`.
"""

from __future__ import annotations

from collections.abc import Mapping
from datetime import datetime
from typing import TYPE_CHECKING, Annotated, Any, Literal, Union

from pydantic import BaseModel, ConfigDict, Discriminator, Field, Tag, create_model
from pydantic.json_schema import SkipJsonSchema

from app.problems import ProblemDetails
from app.schemas import SolveRequest, SolveResponse, study_wing
from app.settings import MAX_BATCH_ITEMS
from solver.wing import ISA_SEA_LEVEL_DENSITY

if TYPE_CHECKING:
    from app.jobs.operations import Operation

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
    "submission_type",
]

JobState = Literal["queued", "running", "succeeded", "failed", "cancelled"]
JOB_STATES: tuple[str, ...] = ("queued", "running", "succeeded", "failed", "cancelled")
FINISHED_STATES = frozenset({"succeeded", "failed", "cancelled"})


class _Request(BaseModel):
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


class BatchRequest(_Request):
    """Independent solves (any wings, any flight conditions), answered in the same order."""

    model_config = ConfigDict(
        extra="forbid", strict=True, json_schema_extra={"examples": [STUDY_BATCH]}
    )

    items: Annotated[list[SolveRequest], Field(min_length=1, max_length=MAX_BATCH_ITEMS)] = Field(
        description=(
            "[-] 1 to FLEXWING_MAX_BATCH_ITEMS (default and at most 10,000) /solve request "
            "bodies. One whose solve fails (no equilibrium, not converged, an invalid wing that "
            "the schema cannot tell, a lost worker) is answered with its problem in place."
        )
    )


class BatchItem(BaseModel):
    """The answer to one batch item: the /solve response, or the problem /solve would return."""

    index: int = Field(description="[-] position of the item in `request.items`, from 0.")
    status: Literal["ok", "problem"] = Field(description="ok: `result`; problem: `problem`.")
    result: SolveResponse | None = Field(default=None, description="The /solve response.")
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
    operation: str = Field(description="What the job runs: solve, sweep or batch.")
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


def submission_type(operations: Mapping[str, Operation]) -> Any:
    """The POST /jobs body: one model per operation, told apart by `operation`."""
    names = tuple(operations)

    def tag(value: Any) -> str:
        name = value.get("operation") if isinstance(value, dict) else None
        return f"@{name}" if isinstance(name, str) and name in operations else "@unknown"

    members: list[Any] = [
        Annotated[_submission_model(op), Tag(f"@{name}")] for name, op in operations.items()
    ]
    unknown = create_model(
        "UnknownJobSubmission",
        __base__=_Request,
        operation=(Literal[names], Field(description="The operation to run.")),  # type: ignore[valid-type,arg-type]
        request=(Any, None),
    )
    members.append(Annotated[unknown, Tag("@unknown"), SkipJsonSchema()])
    return Annotated[Union[tuple(members)], Discriminator(tag)]  # noqa: UP007


def _submission_model(operation: Operation) -> type[BaseModel]:
    name = operation.name
    model: type[BaseModel] = create_model(
        f"{name.capitalize()}JobSubmission",
        __base__=_Request,
        __doc__=f"Run {operation.summary} as a job.",
        operation=(Literal[name], Field(description="The operation to run.")),  # type: ignore[valid-type,arg-type]
        request=(operation.request_model, Field(description=operation.request_description)),
    )
    return model
