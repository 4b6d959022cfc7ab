"""Jobs: POST /jobs, GET /jobs, GET and DELETE /jobs/{id}, its events and a batch's items.

Also `respond_async`, the dependency that turns a /sweep call with ``Prefer: respond-async``
(RFC 7240) into a job: 202 with Location, as POST /jobs answers.
"""

import email.message
import json
from collections.abc import AsyncIterator, Awaitable, Callable, Mapping
from typing import Annotated, Any, Literal

from fastapi import APIRouter, Body, Depends, FastAPI, Header, Path, Query, Request
from fastapi.exceptions import RequestValidationError
from fastapi.responses import JSONResponse, Response, StreamingResponse
from pydantic import TypeAdapter, ValidationError

from app.jobs import streams
from app.jobs.manager import JobManager
from app.jobs.models import STUDY_BATCH, JobList, JobStatus
from app.jobs.operations import JobKind, submission_type
from app.jobs.views import job_view
from app.problems import Problem, ProblemDetails
from app.schemas import SOLVE_EXAMPLES, SWEEP_EXAMPLES
from app.security import owner as owner_of
from app.security import principal

__all__ = ["ACCEPTED", "install", "make_router", "respond_async"]

JobId = Annotated[
    str,
    Path(
        min_length=1,
        max_length=64,
        pattern=r"^[A-Za-z0-9_-]+$",
        description="The job id POST /jobs answered (22 URL-safe base64 characters).",
    ),
]
# Whose jobs a request sees and creates: its API key's (app.security); "" without keys.
Principal = Annotated[str, Depends(principal)]
_LOCATION: dict[str, Any] = {
    "Location": {"description": "/jobs/{id}", "schema": {"type": "string"}}
}
# OpenAPI links from an accepted job to what can be asked of it: clients, generators and
# stateful fuzzers follow them from the 202's `id`.
_JOB_LINKS: dict[str, Any] = {
    name: {
        "operationId": operation,
        "parameters": {"job_id": "$response.body#/id"},
        "description": description,
    }
    for name, operation, description in (
        ("GetJob", "get_job", "The job's state, progress, and result or problem."),
        ("CancelJob", "cancel_job", "Cancel the job."),
        ("JobEvents", "job_events", "The job's progress as Server-Sent Events."),
        ("JobItems", "job_items", "A batch job's answered items as NDJSON."),
    )
}
ACCEPTED: dict[int | str, dict[str, Any]] = {
    202: {
        "links": _JOB_LINKS,
        "model": JobStatus,
        "description": (
            "Accepted as a job: with Prefer: respond-async, or when the answer was not ready "
            "within FLEXWING_SYNC_WAIT (default 10 s; Prefer: wait=<seconds> asks for longer, up "
            "to the operation's time budget). Poll Location (GET /jobs/{id}) or its events."
        ),
        "headers": _LOCATION,
    }
}


def _problem(description: str) -> dict[str, Any]:
    return {"model": ProblemDetails, "description": description}


Responses = dict[int | str, dict[str, Any]]
_UNAVAILABLE: Responses = {
    503: _problem(
        "The jobs database cannot be reached just now (/problems/database-unavailable): retry "
        "after Retry-After."
    ),
}
_NOT_FOUND: Responses = {
    404: _problem(
        "No such job, it has expired, or another API key created it (/problems/not-found)."
    ),
    422: _problem("A job id that is not one (/problems/invalid-input, field `path.job_id`)."),
    **_UNAVAILABLE,
}
_LIST_RESPONSES: Responses = {
    422: _problem("A bad `limit`, `cursor` or `status`."),
    **_UNAVAILABLE,
}
_CANCEL_RESPONSES: Responses = {
    **_NOT_FOUND,
    409: _problem(
        "The job runs on another replica, which did not confirm the cancel in time; it has "
        "been asked to (/problems/job-conflict)."
    ),
}
_SUBMIT_RESPONSES: Responses = {
    202: {"headers": _LOCATION, "links": _JOB_LINKS},
    413: _problem("Body larger than FLEXWING_MAX_JOB_BODY_BYTES (/problems/body-too-large)."),
    422: _problem(
        "Invalid body (/problems/invalid-input): `errors` names each bad field from the body's "
        "root (`request.items[3].wing.chord[2]`; `operation` for an unknown operation)."
    ),
    503: _problem(
        "FLEXWING_MAX_QUEUED_JOBS jobs wait already (/problems/overloaded), or the jobs "
        "database cannot be reached just now (/problems/database-unavailable); retry after "
        "Retry-After."
    ),
}


def _manager(request: Request) -> JobManager:
    manager: JobManager = request.app.state.jobs
    return manager


def _accepted(manager: JobManager, job_row: Mapping[str, Any]) -> JSONResponse:
    view = job_view(job_row, manager.operations)
    return JSONResponse(view, status_code=202, headers={"Location": view["links"]["self"]})


async def _job_or_404(
    manager: JobManager, job_id: str, owner: str, **kwargs: Any
) -> dict[str, Any]:
    """The job `owner` created (a job of another key is answered as no job at all)."""
    row = await manager.find(job_id, principal=owner, **kwargs)
    if row is None:
        raise Problem("not-found", f"no job {job_id!r} (never submitted, or expired)")
    return row


# ------------------------------------------------------------------------ pagination cursor


# A page's end as `created~id`: the creation time [s since the epoch] as its shortest exact
# decimal and the job's id, so every string of this pattern is a cursor (the document says
# exactly what is accepted; an old base64 cursor is refused, and its client starts again).
CURSOR_PATTERN = r"^[0-9]{1,12}(\.[0-9]{1,17})?~[A-Za-z0-9_-]{1,64}$"


def _cursor(row: Mapping[str, Any]) -> str:
    return f"{float(row['created'])!r}~{row['id']}"


def _parse_cursor(cursor: str) -> tuple[float, str]:
    created, _, job_id = cursor.partition("~")
    return float(created), job_id


# --------------------------------------------------------------------------- the router


def make_router(operations: Mapping[str, JobKind]) -> APIRouter:
    """The jobs routes; POST /jobs takes any operation of `operations`."""
    submission = submission_type(operations)
    router = APIRouter(tags=["jobs"])
    examples = _examples(operations)

    @router.post(
        "/jobs",
        operation_id="submit_job",
        status_code=202,
        response_model=JobStatus,
        responses=_SUBMIT_RESPONSES,
        summary="Run a solve, a sweep, an optimisation or a batch of solves as a job",
    )
    async def submit_job(
        body: Annotated[submission, Body(openapi_examples=examples)],  # type: ignore[valid-type]
        request: Request,
        owner: Principal,
    ) -> Any:
        """Accepted at once: 202 with the job's id and `Location: /jobs/{id}`.

        `request` is what that endpoint takes (a batch: `{items: [a /solve body, ...]}`); a body
        the endpoint would refuse gets its 422 here. Jobs run in the background,
        FLEXWING_JOB_RUNNERS at once, each spread over every worker.
        """
        manager = _manager(request)
        job = await manager.submit(
            body.operation,  # type: ignore[attr-defined]
            body.request,  # type: ignore[attr-defined]
            principal=owner,
        )
        return _accepted(manager, job)

    _add_list_route(router)
    _add_job_routes(router)
    _add_streaming_routes(router)
    return router


def _examples(operations: Mapping[str, JobKind]) -> dict[str, Any]:
    found = {
        "batch": ("Three speeds of the study's wing as one batch", STUDY_BATCH),
        "solve": ("The study's wing at 10 m/s", SOLVE_EXAMPLES["study"]["value"]),
        "sweep": ("The study's sweep", SWEEP_EXAMPLES["study"]["value"]),
    }
    return {
        name: {"summary": summary, "value": {"operation": name, "request": value}}
        for name, (summary, value) in found.items()
        if name in operations
    }


def _add_list_route(router: APIRouter) -> None:
    @router.get(
        "/jobs",
        operation_id="list_jobs",
        response_model=JobList,
        responses=_LIST_RESPONSES,
        summary="Jobs, newest first",
    )
    async def list_jobs(
        request: Request,
        owner: Principal,
        limit: Annotated[int, Query(ge=1, le=200, description="[-] jobs per page.")] = 50,
        cursor: Annotated[
            str | None,
            Query(
                max_length=100,
                pattern=CURSOR_PATTERN,
                description="`next` of the previous page (its creation time and id).",
            ),
        ] = None,
        status: Annotated[
            Literal["queued", "running", "succeeded", "failed", "cancelled"] | None,
            Query(description="Only jobs in this state."),
        ] = None,
    ) -> Any:
        """This API key's jobs (every job without keys), without results (GET /jobs/{id} has
        them); `next` is the following page."""
        manager = _manager(request)
        before = None if cursor is None else _parse_cursor(cursor)
        rows = await manager.page(limit + 1, before, status, principal=owner)
        page = rows[:limit]
        following = None
        if len(rows) > limit:
            query = f"limit={limit}&cursor={_cursor(page[-1])}"
            following = f"/jobs?{query}" + (f"&status={status}" if status else "")
        jobs = [job_view(row, manager.operations) for row in page]
        return JSONResponse({"jobs": jobs, "next": following})


def _add_job_routes(router: APIRouter) -> None:
    @router.get(
        "/jobs/{job_id}",
        operation_id="get_job",
        response_model=JobStatus,
        responses=_NOT_FOUND,
        summary="A job's state, progress, and result or problem",
    )
    async def get_job(job_id: JobId, request: Request, owner: Principal) -> Any:
        """`result` is what the synchronous endpoint answers (a batch's: every item in order)."""
        manager = _manager(request)
        row = await _job_or_404(manager, job_id, owner, with_result=True)
        return _job_response(manager, row)

    @router.delete(
        "/jobs/{job_id}",
        operation_id="cancel_job",
        response_model=JobStatus,
        responses=_CANCEL_RESPONSES,
        summary="Cancel a job",
    )
    async def cancel_job(job_id: JobId, request: Request, owner: Principal) -> Any:
        """Work not yet started is not run (`progress` says what was done; a batch's answered
        items stay in items.ndjson). A finished job is left as it is."""
        manager = _manager(request)
        row = await manager.cancel(job_id, principal=owner)
        if row is None:
            raise Problem("not-found", f"no job {job_id!r} (never submitted, or expired)")
        return JSONResponse(job_view(row, manager.operations))


def _job_response(manager: JobManager, row: Mapping[str, Any]) -> Response:
    """The job with its result: stored JSON spliced in, a batch's items streamed from the
    database (its result may be tens of megabytes)."""
    view = job_view(row, manager.operations)
    head = json.dumps(view)[:-1] + ', "result": '
    operation = manager.operations.get(row["operation"])
    if row["status"] == "succeeded" and operation is not None and operation.has_items:
        return StreamingResponse(
            _batch_body(manager, row["id"], head), media_type="application/json"
        )
    result = row.get("result")
    return Response(head + (result or "null") + "}", media_type="application/json")


async def _batch_body(manager: JobManager, job_id: str, head: str) -> AsyncIterator[str]:
    yield head + '{"items": ['
    separator = ""
    async for line in streams.result_items(manager, job_id):
        yield separator + line
        separator = ", "
    yield "]}}"


_EVENTS_RESPONSES: Responses = {
    200: {
        "description": (
            "text/event-stream: `progress` events (data: the job, as GET /jobs/{id} without "
            "result) while it is queued or running, then one `end` event with its final state, "
            "and the stream closes. Each event has `id` (its sequence number), `event` "
            "(progress or end) and `data` (one line of JSON); the stream opens with `retry`."
        ),
        # No schema: OpenAPI 3.1 can describe an event stream only as one string, which tools
        # that parse the events (schemathesis) then apply to each event and reject.
        "content": {"text/event-stream": {}},
    },
    **_NOT_FOUND,
}
_ITEMS_RESPONSES: Responses = {
    200: {
        "description": (
            "application/x-ndjson: one line per answered item, as they are answered "
            '(`{"index": 3, "status": "ok", "result": {...}}`, or status problem with `problem`); '
            "the stream ends when the job does."
        ),
        "content": {"application/x-ndjson": {"schema": {"type": "string"}}},
    },
    **_NOT_FOUND,
    404: _problem("No such batch job, or it has expired (/problems/not-found)."),
}


def _add_streaming_routes(router: APIRouter) -> None:
    @router.get(
        "/jobs/{job_id}/events",
        operation_id="job_events",
        response_class=StreamingResponse,
        responses=_EVENTS_RESPONSES,
        summary="Server-sent events of a job's progress and final state",
    )
    async def job_events(job_id: JobId, request: Request, owner: Principal) -> Any:
        manager = _manager(request)
        first = await _job_or_404(manager, job_id, owner)
        return StreamingResponse(
            streams.events(manager, job_id, first),
            media_type="text/event-stream",
            headers={"Cache-Control": "no-cache", "X-Accel-Buffering": "no"},
        )

    @router.get(
        "/jobs/{job_id}/items.ndjson",
        operation_id="job_items",
        response_class=StreamingResponse,
        responses=_ITEMS_RESPONSES,
        summary="A batch job's items, streamed as they are answered",
    )
    async def job_items(job_id: JobId, request: Request, owner: Principal) -> Any:
        manager = _manager(request)
        row = await _job_or_404(manager, job_id, owner)
        operation = manager.operations.get(row["operation"])
        if operation is None or not operation.has_items:
            raise Problem("not-found", f"job {job_id!r} is a {row['operation']}: it has no items")
        return StreamingResponse(
            streams.item_lines(manager, job_id), media_type="application/x-ndjson"
        )


# -------------------------------------------------------------- Prefer: respond-async


class JobAccepted(Exception):
    """Raised by `respond_async`: answer 202 for this job instead of running the endpoint."""

    def __init__(self, response: JSONResponse) -> None:
        self.response = response


def _prefers_async(prefer: str | None) -> bool:
    """RFC 7240: comma-separated preferences, each a token with optional parameters."""
    if not prefer:
        return False
    tokens = (part.split(";")[0].split("=")[0].strip().lower() for part in prefer.split(","))
    return "respond-async" in tokens


async def _json_body(request: Request) -> bool:
    """Whether the request has a body FastAPI reads as JSON: one of content type
    application/json or application/*+json (FastAPI's rule, with its default strict content
    type: any other body, or one without a content type, fails the endpoint's validation)."""
    content_type = request.headers.get("content-type")
    if not content_type or not await request.body():
        return False
    message = email.message.Message()
    message["content-type"] = content_type
    subtype = message.get_content_subtype()
    return message.get_content_maintype() == "application" and (
        subtype == "json" or subtype.endswith("+json")
    )


def respond_async(operation: str) -> Callable[..., Awaitable[None]]:
    """A dependency for the endpoint of `operation`: with ``Prefer: respond-async`` the body is
    validated as the endpoint would (same 422 problems) and run as a job (202 + Location)."""
    adapter: TypeAdapter[Any] | None = None

    async def prefer_respond_async(
        request: Request,
        prefer: Annotated[
            str | None,
            Header(
                description=(
                    "RFC 7240 preferences: `respond-async` runs this request as a job and answers "
                    "202 with `Location: /jobs/{id}` at once; `wait=<seconds>` waits that long "
                    "for the answer (default FLEXWING_SYNC_WAIT, at most the operation's time "
                    "budget) before it becomes a job (202)."
                )
            ),
        ] = None,
    ) -> None:
        nonlocal adapter
        if not _prefers_async(prefer) or not await _json_body(request):
            # Without a JSON body the endpoint's own validation answers (422, as without the
            # preference): FastAPI reads the body before its dependencies run.
            return
        manager = _manager(request)
        adapter = adapter or TypeAdapter(manager.operations[operation].request_model)
        try:
            body = adapter.validate_python(await request.json())
        except ValidationError as error:
            errors = [dict(e) | {"loc": ("body", *e["loc"])} for e in error.errors()]
            raise RequestValidationError(errors) from None
        # The owner read here, not as a dependency: every synchronous request passes this
        # dependency, and only these become jobs.
        job = await manager.submit(operation, body, principal=owner_of(request), prefix=None)
        response = _accepted(manager, job)
        response.headers["Preference-Applied"] = "respond-async"
        raise JobAccepted(response)

    return prefer_respond_async


def install(app: FastAPI, manager: JobManager) -> None:
    """The jobs routes and their exception handler on `app` (the manager in app.state.jobs)."""
    app.state.jobs = manager
    app.include_router(make_router(manager.operations))

    async def on_accepted(request: Request, exc: Exception) -> Response:
        assert isinstance(exc, JobAccepted)
        return exc.response

    app.add_exception_handler(JobAccepted, on_accepted)
