"""app.jobs.operations: the registry of what a job runs (solve, sweep, optimize, flutter,
batch), the POST /jobs body built from it, each job's progress units, a batch's items answered
in place, in chunks and in lanes, and `patiently`, which waits out an overloaded or restarting
pool where a synchronous request would get 503.

In process: requests validated by the published models, a stand-in job context; no worker."""

from __future__ import annotations

import asyncio
import functools
import json
from collections.abc import Callable
from types import SimpleNamespace
from typing import Any

import pytest
from pydantic import TypeAdapter, ValidationError

import solver
from app.jobs import operations
from app.jobs.models import STUDY_BATCH, BatchItem, BatchRequest
from app.jobs.operations import JOB_KINDS, JobKind, answer_item, patiently, submission_type
from app.problems import Problem, validation_errors
from app.schemas import (
    REQUESTS,
    RESPONSES,
    Answer,
    SolveRequest,
    SolveResponse,
)
from app.schemas.examples import (
    GOLAND_FLUTTER,
    STUDY_OPTIMIZE,
    STUDY_SOLVE,
    STUDY_SWEEP,
    STUDY_SWEEP_REQUEST,
)
from app.settings import Settings

WAIT = 10.0  # [s] a hang guard only


def _run(coroutine: Any) -> Any:
    async def guarded() -> Any:
        return await asyncio.wait_for(coroutine, WAIT)

    return asyncio.run(guarded())


@functools.cache
def _study_body() -> bytes:
    """What the service answers /solve for the study's example (one solve, ~0.2 s)."""
    request = SolveRequest.model_validate(STUDY_SOLVE)
    return Answer.of(request.to_solver().run()).body()


class Context:
    """A job context (`operations.JobContext`): a service whose `answer` (one request) and
    `run_each` (a chunk of inputs; here an input is its request) call `respond`."""

    def __init__(self, respond: Callable[[str, Any], Any], lanes: int = 2) -> None:
        self.lanes = lanes
        self.parallelism = 1
        self.chunk_seconds = 0.05
        self.answered: set[int] = set()
        self.service = SimpleNamespace(
            answer=self._answer, task=lambda request: request, run_each=self._run_each
        )
        self.respond = respond
        self.recorded: list[tuple[int, bool, str]] = []
        self.reported: list[tuple[int, int]] = []
        self.in_flight = 0
        self.most_in_flight = 0

    async def _answer(self, name: str, request: Any, progress: Any = None) -> bytes:
        return (await self.service.run_each(name, [request]))[0]  # type: ignore[no-any-return]

    async def _run_each(self, name: str, tasks: list[Any]) -> list[bytes | Problem]:
        """One worker task for the chunk: counted once in flight."""
        self.in_flight += 1
        self.most_in_flight = max(self.most_in_flight, self.in_flight)
        try:
            await asyncio.sleep(0)  # let the other lanes start theirs
            answers: list[bytes | Problem] = []
            for task in tasks:
                try:
                    answers.append(self.respond(name, task))
                except Problem as problem:
                    if len(tasks) == 1:
                        raise
                    answers.append(problem)
            return answers
        finally:
            self.in_flight -= 1

    def item_answered(self, index: int, ok: bool, line: str) -> None:
        self.recorded.append((index, ok, line))

    def progress(self, done: int, total: int) -> None:
        self.reported.append((done, total))


def _no_equilibrium(name: str, request: Any) -> bytes:
    raise Problem("no-equilibrium", "beyond the fold", extensions={"fold_velocity": 21.44})


# ------------------------------------------------------------------------------ registry

REGISTERED = {
    **{op.name: (REQUESTS[op.name], RESPONSES[op.name], False) for op in solver.OPERATION_TABLE},
    "batch": (BatchRequest, None, True),
}


def test_the_registry_holds_every_operation_of_the_table_and_the_batch() -> None:
    assert set(JOB_KINDS) == set(REGISTERED)
    for name, (request_model, response_model, has_items) in REGISTERED.items():
        operation = JOB_KINDS[name]
        assert operation.name == name
        assert operation.request_model is request_model
        assert operation.has_items is has_items
        # What a synchronous request past its wait records: every endpoint's, not the batch's.
        assert (operation.result is None) is (response_model is None)


def test_a_job_records_the_endpoints_response_as_its_result() -> None:
    """A solve job's result is what POST /solve answers, the body as the worker wrote it,
    whether it ran as a job or was adopted; the /solve response model describes it."""
    study = _study_body()
    context = Context(lambda name, request: study)
    request = SolveRequest.model_validate(STUDY_SOLVE)
    ran = _run(JOB_KINDS["solve"].run(context, request))  # type: ignore[arg-type]
    assert ran == study.decode()
    result = JOB_KINDS["solve"].result
    assert result is not None and result(study) == study.decode()
    SolveResponse.model_validate_json(ran, strict=True)


def test_register_adds_an_operation_by_its_name(monkeypatch: pytest.MonkeyPatch) -> None:
    registry: dict[str, JobKind] = dict(JOB_KINDS)
    monkeypatch.setattr(operations, "JOB_KINDS", registry)
    echo = JobKind(
        name="echo",
        summary="an echo",
        request_model=SolveRequest,
        request_description="A POST /solve body.",
        units=lambda request: 1,
        check=lambda request, settings: None,
        run=JOB_KINDS["solve"].run,
    )
    operations.register(echo)
    assert registry["echo"] is echo and set(registry) == {*REGISTERED, "echo"}


# ----------------------------------------------------------------------- the POST /jobs body


def _fields(body: Any) -> list[str]:
    """The field paths a POST /jobs body's errors name (as the API's problems name them)."""
    with pytest.raises(ValidationError) as raised:
        TypeAdapter(submission_type(JOB_KINDS)).validate_python(body)
    return [error.field for error in validation_errors(raised.value.errors())]


@pytest.mark.parametrize(
    "operation",
    ["design", "Solve", "", 3, None],
    ids=["unknown", "miscased", "empty", "int", "null"],
)
def test_an_operation_that_is_not_registered_is_an_error_on_operation(operation: Any) -> None:
    assert _fields({"operation": operation, "request": STUDY_SOLVE}) == ["operation"]


def test_an_unknown_operation_is_told_which_are_registered() -> None:
    with pytest.raises(ValidationError) as raised:
        TypeAdapter(submission_type(JOB_KINDS)).validate_python({"operation": "design"})
    (error,) = raised.value.errors()
    assert all(f"'{name}'" in error["msg"] for name in JOB_KINDS), error["msg"]


BAD_REQUESTS = {
    "solve": (
        {
            "operation": "solve",
            "request": STUDY_SOLVE | {"flight": STUDY_SOLVE["flight"] | {"x": 1}},
        },
        "request.flight.x",
    ),
    "batch": (
        {"operation": "batch", "request": {"items": [STUDY_SOLVE, {"wing": {}}]}},
        "request.items[1]",
    ),
}


@pytest.mark.parametrize(("body", "where"), list(BAD_REQUESTS.values()), ids=list(BAD_REQUESTS))
def test_a_bad_request_is_named_from_the_bodys_root(body: dict[str, Any], where: str) -> None:
    """The union's tags (@solve, @batch) never show in a field's path."""
    fields = _fields(body)
    assert fields and all(field.startswith(where) for field in fields), fields
    assert not any("@" in field for field in fields)


def test_every_registered_operation_is_a_valid_submission() -> None:
    bodies = {
        "solve": STUDY_SOLVE,
        "sweep": STUDY_SWEEP_REQUEST,
        "optimize": STUDY_OPTIMIZE,
        "flutter": GOLAND_FLUTTER,
        "batch": STUDY_BATCH,
    }
    adapter: TypeAdapter[Any] = TypeAdapter(submission_type(JOB_KINDS))
    for name, request in bodies.items():
        body = adapter.validate_python({"operation": name, "request": request})
        assert body.operation == name
        assert isinstance(body.request, JOB_KINDS[name].request_model)


# ------------------------------------------------------------------------------- units

UNITS = {
    "a solve": ("solve", STUDY_SOLVE, 1),
    "an optimisation": ("optimize", STUDY_OPTIMIZE, 1),
    "a sweep's list": ("sweep", STUDY_SWEEP_REQUEST, len(STUDY_SWEEP)),
    "a sweep's range": (
        "sweep",
        STUDY_SWEEP_REQUEST | {"velocities": {"start": 6.0, "stop": 20.0, "count": 9}},
        9,
    ),
    "a flutter analysis": ("flutter", GOLAND_FLUTTER, GOLAND_FLUTTER["velocities"]["count"]),
    "a batch": ("batch", STUDY_BATCH, len(STUDY_BATCH["items"])),
}


@pytest.mark.parametrize(("name", "request_body", "units"), list(UNITS.values()), ids=list(UNITS))
def test_a_jobs_progress_counts_its_units(name: str, request_body: Any, units: int) -> None:
    """A sweep counts its airspeeds (a list or {start, stop, count}), a batch its items."""
    operation = JOB_KINDS[name]
    request = operation.request_model.model_validate(request_body)
    assert operation.units(request) == units
    operation.check(request, Settings(workers=1))  # and the service's limits let it through


# --------------------------------------------------------------------------- batch checks


def test_a_batch_over_max_batch_items_is_refused_on_items() -> None:
    request = BatchRequest.model_validate(STUDY_BATCH)
    with pytest.raises(Problem) as refused:
        JOB_KINDS["batch"].check(request, Settings(workers=1, max_batch_items=2))
    assert [e["field"] for e in refused.value.extensions["errors"]] == ["items"]
    assert "has 3 items; at most 2" in refused.value.extensions["errors"][0]["reason"]


def test_a_batch_item_over_the_station_limit_is_refused_naming_the_item() -> None:
    request = BatchRequest.model_validate(STUDY_BATCH)  # 30-station wings
    with pytest.raises(Problem) as refused:
        JOB_KINDS["batch"].check(request, Settings(workers=1, max_stations=20))
    fields = [e["field"] for e in refused.value.extensions["errors"]]
    assert fields == ["items[0].wing.y", "items[1].wing.y", "items[2].wing.y"]


# -------------------------------------------------------------------------- batch items


def test_a_batch_item_that_fails_is_answered_with_its_problem_in_place() -> None:
    context = Context(_no_equilibrium)
    request = SolveRequest.model_validate(STUDY_SOLVE)
    ok, line = _run(answer_item(context, 4, request))  # type: ignore[arg-type]
    assert ok is False
    item = BatchItem.model_validate_json(line)
    assert (item.index, item.status, item.result) == (4, "problem", None)
    assert item.problem is not None
    assert (item.problem.type, item.problem.status) == ("/problems/no-equilibrium", 422)
    assert item.problem.fold_velocity == 21.44


def test_a_batch_item_that_succeeds_is_answered_with_the_solve_response() -> None:
    study = _study_body()
    context = Context(lambda name, request: study)
    ok, line = _run(answer_item(context, 0, SolveRequest.model_validate(STUDY_SOLVE)))  # type: ignore[arg-type]
    assert ok is True
    item = json.loads(line)
    assert (item["index"], item["status"]) == (0, "ok")
    assert item["result"] == json.loads(study)


def test_a_chunk_answers_its_items_in_place_problems_included() -> None:
    """Consecutive items as one worker task: each line where its item is, a problem as a
    problem line beside its neighbours' results."""
    study = _study_body()
    requests = [SolveRequest.model_validate(STUDY_SOLVE) for _ in range(4)]
    failing = requests[2]

    def respond(name: str, request: Any) -> bytes:
        if request is failing:
            raise Problem("no-equilibrium", "beyond the fold")
        return study

    context = Context(respond)
    lines = _run(operations.answer_chunk(context, range(10, 14), [None] * 10 + requests))  # type: ignore[arg-type]
    assert [ok for ok, _ in lines] == [True, True, False, True]
    assert [json.loads(line)["index"] for _, line in lines] == [10, 11, 12, 13]
    assert context.most_in_flight == 1  # one worker task for the four


def test_a_chunk_lost_as_a_whole_is_asked_again_item_by_item() -> None:
    """Its worker died twice (or its budget was spent): each item on its own, so only an item
    that cannot be answered gets a problem."""
    study = _study_body()
    requests = [SolveRequest.model_validate(STUDY_SOLVE) for _ in range(3)]
    asked: list[int] = []

    async def lost(name: str, tasks: list[Any]) -> list[bytes | Problem]:
        if len(tasks) > 1:
            raise Problem("worker-lost", "the worker died twice")
        asked.append(next(i for i, r in enumerate(requests) if r is tasks[0]))
        return [study]

    context = Context(lambda name, request: study)
    context.service.run_each = lost
    lines = _run(operations.answer_chunk(context, range(3), requests))  # type: ignore[arg-type]
    assert [ok for ok, _ in lines] == [True, True, True] and sorted(asked) == [0, 1, 2]


@pytest.mark.parametrize(
    ("items", "lanes", "seconds", "per_item", "sizes"),
    [
        (1000, 4, 0.05, None, 1),  # nothing known yet: one item
        (1000, 4, 0.05, 0.003, 16),  # 3 ms solves: 50 ms of them
        (1000, 4, 0.05, 0.01, 5),  # 10 ms: about 50 ms of work
        (1000, 4, 0.05, 0.5, 1),  # slow items stream one by one
        (10, 4, 0.05, 0.001, 3),  # a small batch leaves no lane idle
        (1000, 4, 0.25, 0.01, 25),  # Dask's ~10 ms round trip: chunks of 250 ms
        (1000, 4, 0.25, 0.001, 64),  # at most 64 items
    ],
    ids=["first", "fast", "ten-ms", "slow", "small-batch", "dask", "dask-largest"],
)
def test_chunks_take_about_the_backends_chunk_time(
    items: int, lanes: int, seconds: float, per_item: float | None, sizes: int
) -> None:
    chunks = operations._Chunks(items, lanes, lanes, seconds)
    chunks.per_item = per_item
    taken = chunks.take()
    assert taken is not None and len(taken) == sizes


def test_chunks_cover_every_item_once_in_order() -> None:
    chunks = operations._Chunks(103, 3, 2)
    covered: list[int] = []
    while (taken := chunks.take()) is not None:
        covered.extend(taken)
        chunks.took(len(taken), 0.002 * len(taken))
    assert covered == list(range(103))


@pytest.mark.parametrize(
    ("lanes", "parallelism", "per_item"),
    [(16, 2, 0.0035), (4, 2, 0.0035), (2, 2, 0.01), (1, 1, 0.01)],
    ids=["dask-16-lanes-2-threads", "local-4-lanes-2-workers", "no-queue", "one-lane"],
)
def test_an_items_worker_time_leaves_out_the_time_its_chunk_queued(
    lanes: int, parallelism: int, per_item: float
) -> None:
    # Every lane's chunk in flight at once; `lanes / parallelism` of them share each worker,
    # so each comes back after that many times its own worker time.
    chunks = operations._Chunks(10_000, lanes, parallelism)
    taken = [chunks.take() for _ in range(lanes)]
    size = len(taken[0] or ())
    chunks.per_item = per_item
    chunks.took(size, size * per_item * lanes / parallelism)
    assert chunks.per_item == pytest.approx(per_item, rel=1e-12)


@pytest.mark.parametrize(
    ("items", "first", "last_at_most"),
    [(100, 25, 25), (1000, 64, 63)],
    ids=["fits-the-lanes-evenly", "tail-shrinks"],
)
def test_no_chunk_is_larger_than_a_lanes_share_of_the_unanswered_items(
    items: int, first: int, last_at_most: int
) -> None:
    lanes = 4
    chunks = operations._Chunks(items, lanes, 2)
    chunks.per_item = 1e-6  # fast items: as large as the share and _CHUNK allow
    sizes: list[int] = []
    while True:
        share = -(-(items - chunks.next + chunks.unanswered) // lanes)
        if (taken := chunks.take()) is None:
            break
        assert len(taken) <= share
        sizes.append(len(taken))
        if chunks.in_flight == lanes:  # the oldest is answered, its lane takes the next
            chunks.took(sizes[-lanes], 0.01)
    assert sum(sizes) == items and sizes[:lanes] == [first] * lanes and sizes[-1] <= last_at_most


@pytest.mark.parametrize("lanes", [1, 3], ids=["one-lane", "three-lanes"])
def test_a_batch_answers_every_item_once_with_at_most_lanes_in_flight(lanes: int) -> None:
    items = [STUDY_SOLVE] * 7
    request = BatchRequest.model_validate({"items": items})
    context = Context(_no_equilibrium, lanes=lanes)
    assert _run(JOB_KINDS["batch"].run(context, request)) is None  # type: ignore[arg-type]
    assert sorted(index for index, _, _ in context.recorded) == list(range(len(items)))
    assert all(not ok for _, ok, _ in context.recorded)
    assert context.most_in_flight == lanes


def test_a_batch_taken_up_from_a_stopped_replica_asks_only_the_items_not_answered() -> None:
    items = [STUDY_SOLVE] * 6
    request = BatchRequest.model_validate({"items": items})
    context = Context(_no_equilibrium, lanes=2)
    context.answered = {0, 3, 4}
    assert _run(JOB_KINDS["batch"].run(context, request)) is None  # type: ignore[arg-type]
    assert sorted(index for index, _, _ in context.recorded) == [1, 2, 5]


# ---------------------------------------------------------------------------- patiently


def test_patiently_waits_out_an_overloaded_or_restarting_pool() -> None:
    outcomes: list[Any] = [
        Problem("overloaded", "64 pending"),
        Problem("not-ready", "warming"),
        "answered",
    ]
    calls = 0

    async def call() -> str:
        nonlocal calls
        calls += 1
        outcome = outcomes[calls - 1]
        if isinstance(outcome, Problem):
            raise outcome
        return str(outcome)

    assert _run(patiently(call)) == "answered"
    assert calls == 3


@pytest.mark.parametrize(
    "slug", ["invalid-input", "no-equilibrium", "worker-lost", "solve-timeout"]
)
def test_patiently_passes_any_other_problem_on_at_once(slug: str) -> None:
    calls = 0

    async def call() -> str:
        nonlocal calls
        calls += 1
        raise Problem(slug, "no")

    with pytest.raises(Problem) as raised:
        _run(patiently(call))
    assert raised.value.type.slug == slug and calls == 1
