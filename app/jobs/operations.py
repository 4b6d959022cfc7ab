"""What a job can run: one `JobKind` per name. Every operation of `solver.OPERATION_TABLE` is
one, derived from its row (it answers what its endpoint answers, its progress counts the row's
parts); `batch` (many solves) is the one kind of its own. The POST /jobs body model is made from
this registry, before `app.main.create_app` builds the routes; `register` adds a kind.
"""

from __future__ import annotations

import asyncio
import json
from collections.abc import Awaitable, Callable, Collection, Mapping, Sequence
from dataclasses import dataclass
from typing import Annotated, Any, Literal, Protocol, TypeVar, Union

from pydantic import BaseModel, Discriminator, Field, Tag, create_model
from pydantic.json_schema import SkipJsonSchema

import solver
from app.jobs.models import BatchRequest, Request
from app.problems import FieldError, Problem, problem_body
from app.schemas import REQUESTS, SolveRequest
from app.schemas.limits import station_and_point_errors
from app.service import Service, parts_of, task_of
from app.settings import Settings

__all__ = ["JOB_KINDS", "JobContext", "JobKind", "register", "submission_type"]

T = TypeVar("T")

# Problems that mean "not now" for a batch item: it waits and tries again instead of failing.
_TRANSIENT = frozenset({"overloaded", "not-ready"})
_MAX_BACKOFF = 1.0  # [s]
# Batch items per worker task: at most _CHUNK, about the backend's `chunk_seconds` of work
# (`app.execution.pool`): one round trip for many solves of a few ms costs their share of the
# per-task overhead, and a chunk's lines still reach the store within that time.
_CHUNK = 64


class JobContext(Protocol):
    """What an operation's `run` gets from the job manager."""

    @property
    def service(self) -> Service:
        """The service the endpoints use (so a job answers what they answer)."""
        ...

    @property
    def lanes(self) -> int:
        """[-] items to keep in flight: enough to keep every worker busy."""
        ...

    @property
    def parallelism(self) -> int:
        """[-] worker tasks that run at the same time (the rest of the lanes queue)."""
        ...

    @property
    def chunk_seconds(self) -> float:
        """[s] about how long one worker task of batch items should take."""
        ...

    def item_answered(self, index: int, ok: bool, line: str) -> None:
        """Record batch item `index`'s NDJSON line (ok: a result, else a problem)."""
        ...

    @property
    def answered(self) -> Collection[int]:
        """Batch items answered already (a job taken up from a replica that stopped): not
        asked again."""
        ...

    def progress(self, done: int, total: int) -> None:
        """Record that `done` of the job's `total` units are done (a sweep's airspeeds)."""
        ...


@dataclass(frozen=True)
class JobKind:
    """One kind of job.

    `units`: its progress total for a request; `check`: settings-dependent validation at
    submission (raises an invalid-input Problem with paths relative to the request); `run`: does
    the work and returns the result as JSON text (None when it is assembled from batch items);
    `result`: an answer's response body as that JSON text (what a synchronous request past its
    wait becomes as a job records, `JobManager.adopt`).
    """

    name: str
    summary: str
    request_model: type[BaseModel]
    request_description: str
    units: Callable[[Any], int]
    check: Callable[[Any, Settings], None]
    run: Callable[[JobContext, Any], Awaitable[str | None]]
    has_items: bool = False
    result: Callable[[bytes], str] | None = None


JOB_KINDS: dict[str, JobKind] = {}


def register(kind: JobKind) -> None:
    JOB_KINDS[kind.name] = kind


# ---------------------------------------------------------------------------- solve, sweep


async def patiently(call: Callable[[], Awaitable[T]]) -> T:
    """`call()`, again after a pause while the pool is full or restarting (a job waits its turn
    where a synchronous request would get 503)."""
    backoff = 0.05
    while True:
        try:
            return await call()
        except Problem as problem:
            if problem.type.slug not in _TRANSIENT:
                raise
        await asyncio.sleep(backoff)
        backoff = min(2 * backoff, _MAX_BACKOFF)


def _text(body: bytes) -> str:
    """An answer's response body (JSON, UTF-8) as the job's result text."""
    return body.decode()


def _answering(name: str) -> Callable[[JobContext, Any], Awaitable[str]]:
    """A job that answers what the endpoint `name` answers."""

    async def run(context: JobContext, request: Any) -> str:
        answer = context.service.answer
        return _text(await patiently(lambda: answer(name, request, context.progress)))

    return run


def _check(request: Any, settings: Settings) -> None:
    task_of(request, settings)  # raises the endpoint's invalid-input problem


def _parts(name: str) -> Callable[[Any], int]:
    """The progress total of a request to the operation `name`: its solver input's parts."""

    def units(request: Any) -> int:
        return parts_of(name, request.to_solver())

    return units


# ----------------------------------------------------------------------------------- batch


def _check_batch(request: BatchRequest, settings: Settings) -> None:
    if len(request.items) > settings.max_batch_items:
        reason = (
            f"has {len(request.items)} items; at most {settings.max_batch_items} are allowed "
            "(FLEXWING_MAX_BATCH_ITEMS)"
        )
        raise Problem.invalid([FieldError("items", reason)])
    errors = [
        FieldError(f"items[{index}].{error.field}", error.reason)
        for index, item in enumerate(request.items)
        for error in station_and_point_errors(item, settings)
    ]
    if errors:
        raise Problem.invalid(errors)


def _ok_line(index: int, body: bytes) -> tuple[bool, str]:
    return True, f'{{"index": {index}, "status": "ok", "result": {_text(body)}}}'


def _problem_line(index: int, problem: Problem) -> tuple[bool, str]:
    body = json.dumps(problem_body(problem), allow_nan=False)
    return False, f'{{"index": {index}, "status": "problem", "problem": {body}}}'


async def answer_item(context: JobContext, index: int, request: SolveRequest) -> tuple[bool, str]:
    """(ok, NDJSON line) of one batch item: its /solve response or its problem."""
    try:
        result = await patiently(lambda: context.service.answer("solve", request))
    except Problem as problem:
        return _problem_line(index, problem)
    return _ok_line(index, result)


async def answer_chunk(
    context: JobContext, indices: Sequence[int], items: list[SolveRequest]
) -> list[tuple[bool, str]]:
    """(ok, NDJSON line) of consecutive batch items, answered as one worker task; a chunk the
    pool lost as a whole (its worker died twice, its budget spent) is asked again one item at
    a time, so an item that cannot be answered costs only its own line."""
    service = context.service
    lines: dict[int, tuple[bool, str]] = {}
    tasks: dict[int, Any] = {}
    for index in indices:
        try:
            tasks[index] = service.task(items[index])
        except Problem as problem:
            lines[index] = _problem_line(index, problem)
    if tasks:
        chunk = list(tasks.values())
        try:
            answers = await patiently(lambda: service.run_each("solve", chunk))
        except Problem:
            for index in tasks:
                lines[index] = await answer_item(context, index, items[index])
        else:
            for index, answer in zip(tasks, answers, strict=True):
                if isinstance(answer, Problem):
                    lines[index] = _problem_line(index, answer)
                else:
                    lines[index] = _ok_line(index, answer)
    return [lines[index] for index in indices]


class _Chunks:
    """Consecutive batch items for the lanes to take, in chunks sized to take about
    `seconds` of a worker's time each (at most `_CHUNK` items): many fast solves share one
    worker round trip, slow ones still stream one by one, and no chunk is larger than a lane's
    share of the items not yet answered, so the last chunks shrink and no lane is left with a
    long tail while the others idle.

    An item's worker time is its share of its chunk's time in flight, less the time the chunk
    queued: `lanes` chunks in flight share `parallelism` workers (Dask: 16 lanes on 2 threads;
    measured from the lane's clock alone, chunks came out up to 8x too small: a batch of 1,000
    paid ~110 Dask round trips instead of ~30, and Dask reached 79 % of the local pool's
    throughput where it now reaches 90 %, benchmarks/batch_benchmark.py)."""

    def __init__(self, items: int, lanes: int, parallelism: int, seconds: float = 0.05) -> None:
        self.items = items
        self.lanes = max(1, lanes)
        self.parallelism = max(1, parallelism)
        self.seconds = seconds
        self.next = 0
        self.per_item: float | None = None  # [s] an item's worker time, smoothed
        self.in_flight = 0  # chunks taken and not yet answered
        self.unanswered = 0  # their items

    def take(self) -> range | None:
        remaining = self.items - self.next
        if remaining <= 0:
            return None
        size = 1 if self.per_item is None else int(self.seconds / max(self.per_item, 1e-6))
        share = -(-(remaining + self.unanswered) // self.lanes)
        size = max(1, min(size, _CHUNK, remaining, share))
        start, self.next = self.next, self.next + size
        self.in_flight += 1
        self.unanswered += size
        return range(start, start + size)

    def took(self, size: int, seconds: float) -> None:
        """Chunk of `size` items answered `seconds` after it was taken."""
        share = seconds / size * min(1.0, self.parallelism / max(1, self.in_flight))
        self.in_flight -= 1
        self.unanswered -= size
        self.per_item = share if self.per_item is None else 0.7 * self.per_item + 0.3 * share


async def _run_batch(context: JobContext, request: BatchRequest) -> None:
    """Every item through the service in chunks of consecutive items (one worker task each),
    `context.lanes` chunks at a time (enough to keep every worker busy); each chunk's lines are
    recorded as it is answered."""
    items = request.items
    todo = [index for index in range(len(items)) if index not in context.answered]
    chunks = _Chunks(len(todo), context.lanes, context.parallelism, context.chunk_seconds)
    loop = asyncio.get_running_loop()

    async def lane() -> None:
        while (taken := chunks.take()) is not None:  # shared: the next unanswered chunk
            indices = [todo[position] for position in taken]
            started = loop.time()
            lines = await answer_chunk(context, indices, items)
            chunks.took(len(indices), loop.time() - started)
            for index, (ok, line) in zip(indices, lines, strict=True):
                context.item_answered(index, ok, line)

    await asyncio.gather(*(lane() for _ in range(min(context.lanes, len(todo)))))
    return None


for _operation in solver.OPERATION_TABLE:
    register(
        JobKind(
            name=_operation.name,
            summary=f"POST /{_operation.name} ({_operation.summary[0].lower()}"
            f"{_operation.summary[1:]})",
            request_model=REQUESTS[_operation.name],
            request_description=f"A POST /{_operation.name} body.",
            units=_parts(_operation.name),
            check=_check,
            run=_answering(_operation.name),
            result=_text,
        )
    )
register(
    JobKind(
        name="batch",
        summary="up to 10,000 independent solves",
        request_model=BatchRequest,
        request_description="{items: [a POST /solve body, ...]}.",
        units=lambda request: len(request.items),
        check=_check_batch,
        run=_run_batch,
        has_items=True,
    )
)


# ------------------------------------------------------------------ the POST /jobs body


def submission_type(operations: Mapping[str, JobKind]) -> Any:
    """The POST /jobs body: one model per operation, told apart by `operation`.

    Validation errors name fields from the body's root (`request.items[3].wing.chord[2]`): the
    union's tags start with "@", which `app.problems` leaves out of field paths. An operation that
    is not registered is an error on `operation` (a hidden last member of the union).
    """
    names = tuple(operations)

    def tag(value: Any) -> str:
        name = value.get("operation") if isinstance(value, dict) else None
        return f"@{name}" if isinstance(name, str) and name in operations else "@unknown"

    members: list[Any] = [
        Annotated[_submission_model(op), Tag(f"@{name}")] for name, op in operations.items()
    ]
    unknown = create_model(
        "UnknownJobSubmission",
        __base__=Request,
        operation=(Literal[names], Field(description="The operation to run.")),  # type: ignore[valid-type,arg-type]
        request=(Any, None),
    )
    members.append(Annotated[unknown, Tag("@unknown"), SkipJsonSchema()])
    return Annotated[Union[tuple(members)], Discriminator(tag)]  # noqa: UP007


def _submission_model(operation: JobKind) -> type[BaseModel]:
    name = operation.name
    model: type[BaseModel] = create_model(
        f"{name.capitalize()}JobSubmission",
        __base__=Request,
        __doc__=f"Run {operation.summary} as a job.",
        operation=(Literal[name], Field(description="The operation to run.")),  # type: ignore[valid-type,arg-type]
        request=(operation.request_model, Field(description=operation.request_description)),
    )
    return model
