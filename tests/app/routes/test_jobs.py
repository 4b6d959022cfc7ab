"""Jobs (issue 13) against real servers: submit, poll, server-sent events, NDJSON, cancel, the
queue limit, listing, expiry, and persistence across restarts (SIGINT mid-job and SIGKILL: the
unfinished jobs are finished by the next start). Several replicas sharing PostgreSQL:
tests/app/jobs/test_replicas.py.

Two kinds of server: `jobs_server` serves compiled code (a study-wing solve takes ~2 ms), the
slow ones run CasADi's virtual machine on 60-station wings of distinct stiffness (no warm start
between them), ~0.2 s per item: long enough to cancel, interrupt or kill a batch mid-way.
"""

from __future__ import annotations

import json
import os
import re
import signal
import time
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import httpx
import pytest

from app.routes import jobs as jobs_routes
from app.settings import Settings
from tests import study
from tests.app.conftest import Server, in_process_client

FINISHED = {"succeeded", "failed", "cancelled"}
HANG_GUARD = 120.0  # [s] only a hang fails on it


# ---------------------------------------------------------------------------------- helpers


def slow_item(index: int, velocity: float = 10.0) -> dict[str, Any]:
    """A /solve body of a 60-station wing whose stiffness differs by item (no warm start from
    another item): ~0.2 s per solve on the virtual machine."""
    return {
        "wing": study.wing_json(stiffness_scale=1.0 + 0.01 * index, n=60),
        "flight": {"velocity": velocity, "alpha": 5.0},
    }


def slow_batch(count: int) -> dict[str, Any]:
    return {"operation": "batch", "request": {"items": [slow_item(i) for i in range(count)]}}


def submit(client: httpx.Client, body: Any) -> httpx.Response:
    return client.post("/jobs", json=body)


def accepted(client: httpx.Client, body: Any) -> str:
    """Submit; the job's Location."""
    response = submit(client, body)
    assert response.status_code == 202, response.text
    return response.headers["location"]


def wait_job(
    client: httpx.Client,
    location: str,
    until: Callable[[dict[str, Any]], bool] = lambda job: job["status"] in FINISHED,
) -> dict[str, Any]:
    deadline = time.monotonic() + HANG_GUARD
    while True:
        job = client.get(location).json()
        if until(job):
            return job
        assert time.monotonic() < deadline, job
        time.sleep(0.02)


def ndjson(client: httpx.Client, location: str) -> list[dict[str, Any]]:
    with client.stream("GET", location + "/items.ndjson") as response:
        assert response.status_code == 200
        assert response.headers["content-type"].startswith("application/x-ndjson")
        return [json.loads(line) for line in response.iter_lines() if line]


def read_items(client: httpx.Client, location: str, count: int) -> list[dict[str, Any]]:
    """The first `count` lines of a running batch's items.ndjson: once read, they are committed
    (the store answers a read only after its commit), so they survive even a SIGKILL."""
    lines: list[dict[str, Any]] = []
    with client.stream("GET", location + "/items.ndjson") as response:
        assert response.status_code == 200
        for line in response.iter_lines():
            if line:
                lines.append(json.loads(line))
            if len(lines) == count:
                break
    assert len(lines) == count, lines
    return lines


def stop(server: Server, how: signal.Signals) -> None:
    """SIGINT: uvicorn's graceful stop; SIGKILL: the server and its workers die at once."""
    if how == signal.SIGKILL:
        os.killpg(server.process.pid, signal.SIGKILL)
    else:
        server.process.send_signal(how)
    server.process.wait(timeout=HANG_GUARD)


def comparable(solve_response: dict[str, Any]) -> dict[str, Any]:
    """A /solve response without what depends on how it was computed (timing, cache)."""
    return {key: value for key, value in solve_response.items() if key != "solver"}


# ---------------------------------------------------------------------------------- servers


@pytest.fixture(scope="module")
def jobs_server(
    make_server: Callable[..., Server], tmp_path_factory: pytest.TempPathFactory
) -> Server:
    db = tmp_path_factory.mktemp("jobs_db") / "jobs.sqlite3"
    return make_server("jobs_server", FLEXWING_JOBS_DB=str(db), FLEXWING_MAX_BATCH_ITEMS="20")


@pytest.fixture(scope="module")
def in_process(tmp_path_factory: pytest.TempPathFactory) -> Iterator[httpx.Client]:
    """As `jobs_server` is configured, in this process (for what only validation answers)."""
    db = tmp_path_factory.mktemp("in_process_jobs") / "jobs.sqlite3"
    with in_process_client(Settings(workers=1, jobs_db=db, max_batch_items=20)) as client:
        yield client


def slow_env(tmp: Path, **extra: str) -> dict[str, str]:
    return {
        "FLEXWING_COMPILE": "0",
        "FLEXWING_CACHE_DIR": str(tmp / "cache"),
        "FLEXWING_JOBS_DB": str(tmp / "jobs.sqlite3"),
        "FLEXWING_JOB_RUNNERS": "1",
    } | extra


@pytest.fixture(scope="module")
def slow_server(
    make_server: Callable[..., Server], tmp_path_factory: pytest.TempPathFactory
) -> Server:
    env = slow_env(tmp_path_factory.mktemp("slow_jobs"), FLEXWING_MAX_QUEUED_JOBS="2")
    return make_server("slow_jobs_server", **env)


@pytest.fixture
def client(jobs_server: Server) -> Iterator[httpx.Client]:
    with jobs_server.client(timeout=HANG_GUARD) as c:
        yield c


# ------------------------------------------------------------------------ submit and poll


def test_a_solve_job_answers_what_solve_answers(client: httpx.Client) -> None:
    response = submit(client, {"operation": "solve", "request": study.solve_request(10.0)})
    assert response.status_code == 202
    job = response.json()
    assert response.headers["location"] == f"/jobs/{job['id']}" == job["links"]["self"]
    assert job["status"] in {"queued", "running", "succeeded"}
    assert job["progress"]["total"] == 1
    done = wait_job(client, response.headers["location"])
    assert done["status"] == "succeeded", done
    assert done["progress"] == {"done": 1, "total": 1, "problems": 0}
    assert done["created_at"] <= done["started_at"] <= done["finished_at"] < done["expires_at"]
    totals = done["result"]["totals"]
    assert totals["lift"] == pytest.approx(304.13, abs=0.005)
    assert totals["tip_twist"] == pytest.approx(1.708, abs=0.0005)
    direct = client.post("/solve", json=study.solve_request(10.0)).json()
    assert comparable(done["result"]) == comparable(direct)


def test_job_ids_are_unguessable(client: httpx.Client) -> None:
    """128 random bits each: 22 characters of URL-safe base64, never repeated."""
    ids = {
        submit(client, {"operation": "solve", "request": study.solve_request(9.0)}).json()["id"]
        for _ in range(20)
    }
    assert len(ids) == 20
    assert all(len(job_id) == 22 and job_id.isascii() for job_id in ids)
    assert client.get("/jobs/AAAAAAAAAAAAAAAAAAAAAA").status_code == 404


def test_a_sweep_with_prefer_respond_async_becomes_a_job(client: httpx.Client) -> None:
    body = {"wing": study.wing_json(), "flight": {"alpha": 5.0}, "velocities": [6.0, 10.0, 22.0]}
    response = client.post("/sweep", json=body, headers={"Prefer": "respond-async, wait=10"})
    assert response.status_code == 202, response.text
    assert response.headers["preference-applied"] == "respond-async"
    job = wait_job(client, response.headers["location"])
    assert job["operation"] == "sweep" and job["status"] == "succeeded"
    assert job["progress"] == {"done": 3, "total": 3, "problems": 0}
    direct = client.post("/sweep", json=body).json()
    statuses = [point["status"] for point in job["result"]["points"]]
    assert statuses == [point["status"] for point in direct["points"]]
    assert statuses == ["equilibrium", "equilibrium", "no_equilibrium"]
    assert job["result"]["divergence"] == direct["divergence"]
    # Without the preference, /sweep answers at once as before.
    assert client.post("/sweep", json=body, headers={"Prefer": "return=minimal"}).status_code == 200


# ------------------------------------------------------------------- bad bodies: 422 at POST


def _fields(response: httpx.Response) -> list[str]:
    assert response.status_code == 422, response.text
    assert response.headers["content-type"] == "application/problem+json"
    problem = response.json()
    assert problem["type"] == "/problems/invalid-input"
    return [error["field"] for error in problem["errors"]]


def test_a_batch_item_that_is_not_a_solve_request_is_a_422_naming_it(
    in_process: httpx.Client,
) -> None:
    items = [study.solve_request(10.0) for _ in range(5)]
    items[3]["wing"]["chord"][2] = -1.0
    response = submit(in_process, {"operation": "batch", "request": {"items": items}})
    assert _fields(response) == ["request.items[3].wing.chord[2]"]


def test_a_batch_item_beyond_the_published_station_limit_is_a_422_naming_it(
    in_process: httpx.Client,
) -> None:
    # The document says at most FLEXWING_MAX_STATIONS (150) stations and values per station:
    # a body that breaks it is invalid as a whole, not an item answered with a problem.
    items = [study.solve_request(10.0) for _ in range(3)]
    items[1]["wing"]["y"] = {"semispan": 5.0, "stations": 151}
    items[2]["wing"]["chord"] = [1.0] * 151
    response = submit(in_process, {"operation": "batch", "request": {"items": items}})
    assert _fields(response) == ["request.items[1].wing.y.stations", "request.items[2].wing.chord"]


@pytest.mark.parametrize(
    ("body", "fields"),
    [
        ({"operation": "design", "request": {}}, ["operation"]),  # no such operation
        ({"request": {}}, ["operation"]),
        ([1, 2], ["body"]),
        ({"operation": "batch", "request": {"items": []}}, ["request.items"]),
        (  # FLEXWING_MAX_BATCH_ITEMS=20
            {"operation": "batch", "request": {"items": [study.solve_request(10.0)] * 21}},
            ["request.items"],
        ),
        ({"operation": "batch", "request": [study.solve_request(10.0)]}, ["request"]),
        ({"operation": "solve", "request": study.solve_request(10.0) | {"x": 1}}, ["request.x"]),
        (
            {
                "operation": "sweep",
                "request": {"wing": study.wing_json(), "flight": {"alpha": 5.0}},
            },
            ["request.velocities"],
        ),
    ],
    ids=[
        "unknown",
        "no-operation",
        "not-an-object",
        "empty",
        "too-many",
        "no-items",
        "extra",
        "sweep",
    ],
)
def test_bodies_that_are_not_jobs_are_422_naming_the_field(
    in_process: httpx.Client, body: Any, fields: list[str]
) -> None:
    assert set(_fields(submit(in_process, body))) == set(fields)


def test_the_endpoints_own_checks_apply_at_submission(client: httpx.Client) -> None:
    """What /solve refuses beyond the schema (stations not increasing) is refused here too."""
    request = study.solve_request(10.0)
    request["wing"]["y"][3] = request["wing"]["y"][2]
    assert _fields(client.post("/solve", json=request)) == ["wing.y"]
    assert _fields(submit(client, {"operation": "solve", "request": request})) == ["request.wing.y"]
    prefer = {"Prefer": "respond-async"}
    sweep = {"wing": request["wing"], "flight": {"alpha": 5.0}, "velocities": [10.0]}
    assert _fields(client.post("/sweep", json=sweep, headers=prefer)) == ["wing.y"]
    sweep["flight"]["alpha"] = "5"
    assert _fields(client.post("/sweep", json=sweep, headers=prefer)) == ["flight.alpha"]


@pytest.mark.parametrize(
    ("content_type", "content", "reason"),
    [
        ("application/json", b"", "Field required"),
        ("application/json", b'{"wing": ', "invalid JSON"),
        ("text/plain", b"{}", "Input should be a valid dictionary"),
        (None, b"{}", "Input should be a valid dictionary"),
    ],
    ids=["empty-body", "broken-json", "text-plain", "no-content-type"],
)
def test_a_body_that_is_not_json_is_refused_with_or_without_respond_async(
    in_process: httpx.Client, content_type: str | None, content: bytes, reason: str
) -> None:
    headers = {} if content_type is None else {"Content-Type": content_type}
    for prefer in ({}, {"Prefer": "respond-async"}):
        response = in_process.post("/sweep", content=content, headers=headers | prefer)
        assert response.status_code == 422, response.text
        problem = response.json()
        assert problem["type"] == "/problems/invalid-input"
        assert problem["errors"][0]["field"] == "body"
        assert problem["errors"][0]["reason"].startswith(reason)


# -------------------------------------------------------------------------------- batches


def test_a_batch_answers_every_item_in_order_with_problems_in_place(
    client: httpx.Client,
) -> None:
    speeds = [6.0, 8.0, 10.0, 12.0, 15.0, 23.0, 10.0, 18.0]
    items = [study.solve_request(v) for v in speeds]
    items[6]["wing"]["y"][3] = items[6]["wing"]["y"][2]  # valid JSON, not a wing
    location = accepted(client, {"operation": "batch", "request": {"items": items}})
    job = wait_job(client, location)
    assert job["status"] == "succeeded"
    assert job["progress"] == {"done": 8, "total": 8, "problems": 2}
    answers = job["result"]["items"]
    assert [a["index"] for a in answers] == list(range(8))
    assert [a["status"] for a in answers] == ["ok"] * 5 + ["problem"] * 2 + ["ok"]
    assert answers[5]["problem"]["type"] == "/problems/no-equilibrium"
    assert 21.43 < answers[5]["problem"]["fold_velocity"] < 21.45
    assert answers[6]["problem"]["type"] == "/problems/invalid-input"
    assert answers[6]["problem"]["errors"] == [
        {"field": "wing.y", "reason": "stations must be strictly increasing"}
    ]
    assert answers[2]["result"]["totals"]["lift"] == pytest.approx(304.13, abs=0.005)
    for speed, answer in zip(speeds, answers, strict=True):
        if answer["status"] == "ok":
            direct = client.post("/solve", json=study.solve_request(speed)).json()
            ours, theirs = answer["result"]["totals"], direct["totals"]
            numbers = {k: v for k, v in theirs.items() if v is not None}  # null: no spar, no trim
            assert {k for k, v in ours.items() if v is None} == theirs.keys() - numbers.keys()
            assert {k: ours[k] for k in numbers} == pytest.approx(numbers, rel=1e-8)
    streamed = ndjson(client, location)
    assert sorted(line["index"] for line in streamed) == list(range(8))
    assert sorted(streamed, key=lambda line: line["index"]) == answers
    assert client.get(f"/jobs/{job['id']}x/items.ndjson").status_code == 404


def test_events_stream_progress_then_the_final_state(slow_server: Server) -> None:
    with slow_server.client(timeout=HANG_GUARD) as client:
        location = accepted(client, slow_batch(10))
        events: list[tuple[str, dict[str, Any]]] = []
        with client.stream("GET", location + "/events") as stream:
            assert stream.headers["content-type"].startswith("text/event-stream")
            kind = ""
            for line in stream.iter_lines():
                if line.startswith("event: "):
                    kind = line.removeprefix("event: ")
                elif line.startswith("data: "):
                    events.append((kind, json.loads(line.removeprefix("data: "))))
        kinds = [kind for kind, _ in events]
        assert kinds[-1] == "end" and set(kinds[:-1]) == {"progress"}
        done = [data["progress"]["done"] for _, data in events]
        assert done == sorted(done) and len(events) >= 3
        assert events[-1][1]["status"] == "succeeded" and done[-1] == 10
        # A finished job's stream is its final state at once.
        with client.stream("GET", location + "/events") as stream:
            again = [line for line in stream.iter_lines() if line.startswith("event: ")]
        assert again == ["event: end"]


def test_cancelling_a_batch_stops_the_work_not_yet_started(slow_server: Server) -> None:
    with slow_server.client(timeout=HANG_GUARD) as client:
        location = accepted(client, slow_batch(60))
        wait_job(client, location, until=lambda job: job["progress"]["done"] >= 2)
        response = client.delete(location)
        assert response.status_code == 200
        cancelled = response.json()
        assert cancelled["status"] == "cancelled"
        assert 2 <= cancelled["progress"]["done"] < 60
        # Whatever a worker still had has finished: nothing pending in the pool.
        deadline = time.monotonic() + HANG_GUARD
        while slow_server.metric("flexwing_pending_tasks") > 0:
            assert time.monotonic() < deadline, "the pool never drained"
            time.sleep(0.01)
        later = client.get(location).json()
        assert later["status"] == "cancelled" and later["result"] is None
        assert later["progress"] == cancelled["progress"]
        assert len(ndjson(client, location)) == cancelled["progress"]["done"]
        assert client.delete(location).json()["status"] == "cancelled"  # stays as it is


def test_queued_jobs_beyond_the_limit_are_shed_and_a_queued_job_cancels_unrun(
    slow_server: Server,
) -> None:
    """One runner, at most 2 queued jobs: a long batch runs, two solves wait, a third is shed."""
    with slow_server.client(timeout=HANG_GUARD) as client:
        batch = accepted(client, slow_batch(60))
        wait_job(client, batch, until=lambda job: job["status"] == "running")
        waiting = [
            accepted(client, {"operation": "solve", "request": slow_item(100 + i)})
            for i in range(2)
        ]
        response = submit(client, {"operation": "solve", "request": slow_item(102)})
        assert response.status_code == 503
        assert response.json()["type"] == "/problems/overloaded"
        assert response.headers["retry-after"] == "1"
        assert slow_server.metric("flexwing_job_queue_length") == 2
        cancelled = client.delete(waiting[0]).json()
        assert cancelled["status"] == "cancelled"
        assert cancelled["started_at"] is None and cancelled["progress"]["done"] == 0
        assert client.delete(batch).json()["status"] == "cancelled"
        assert wait_job(client, waiting[1])["status"] == "succeeded"


# ------------------------------------------------------------------------ listing, metrics


def test_jobs_are_listed_newest_first_page_by_page(client: httpx.Client) -> None:
    mine = [
        accepted(client, {"operation": "solve", "request": study.solve_request(7.0 + i / 8)})
        for i in range(5)
    ]
    seen: list[str] = []
    page = client.get("/jobs?limit=2").json()
    while True:
        assert len(page["jobs"]) <= 2
        seen += [job["links"]["self"] for job in page["jobs"]]
        if page["next"] is None:
            break
        page = client.get(page["next"]).json()
    assert seen[:5] == mine[::-1]
    assert len(seen) == len(set(seen))
    assert all("result" not in job or job["result"] is None for job in page["jobs"])
    running = client.get("/jobs?status=cancelled").json()["jobs"]
    assert all(job["status"] == "cancelled" for job in running)
    assert _fields(client.get("/jobs?cursor=nonsense")) == ["query.cursor"]
    assert _fields(client.get("/jobs?limit=0")) == ["query.limit"]


def test_metrics_count_jobs_by_state_the_queue_and_batch_items(jobs_server: Server) -> None:
    with jobs_server.client() as client:
        before = jobs_server.metric("flexwing_batch_items_total", outcome="ok")
        items = [study.solve_request(11.0 + i / 16) for i in range(4)]
        location = accepted(client, {"operation": "batch", "request": {"items": items}})
        wait_job(client, location)
    assert jobs_server.metric("flexwing_batch_items_total", outcome="ok") == before + 4
    assert jobs_server.metric("flexwing_jobs", state="succeeded") >= 1
    assert jobs_server.metric("flexwing_job_queue_length") == 0
    assert jobs_server.metric("flexwing_jobs_submitted_total", operation="batch") >= 1


# ------------------------------------------------------------------- retention, restarts


def test_finished_jobs_expire_after_the_retention(
    make_server: Callable[..., Server], tmp_path_factory: pytest.TempPathFactory
) -> None:
    tmp = tmp_path_factory.mktemp("retention")
    server = make_server(
        "retention_server", FLEXWING_JOBS_DB=str(tmp / "jobs.sqlite3"), FLEXWING_JOB_RETENTION="1"
    )
    with server.client() as client:
        location = accepted(client, {"operation": "solve", "request": study.solve_request(10.0)})
        job = wait_job(client, location)
        assert job["status"] == "succeeded"
        time.sleep(1.2)
        assert client.get(location).status_code == 404
        assert client.get("/jobs").json()["jobs"] == []
        deadline = time.monotonic() + 10
        while server.metric("flexwing_jobs", state="succeeded") != 0:  # deleted by the janitor
            assert time.monotonic() < deadline
            time.sleep(0.1)


def test_a_restart_keeps_finished_jobs_and_finishes_the_unfinished_ones(
    make_server: Callable[..., Server], tmp_path_factory: pytest.TempPathFactory
) -> None:
    """Stopped with SIGINT while a batch runs and a solve waits: the stopping service hands
    both back to the queue; after the restart the finished job is there as it was, the batch
    goes on from the items it had answered (each answered once) and the solve runs."""
    env = slow_env(tmp_path_factory.mktemp("restart"))
    first = make_server("before_restart", **env)
    with first.client(timeout=HANG_GUARD) as client:
        finished = accepted(client, {"operation": "solve", "request": study.solve_request(10.0)})
        result = wait_job(client, finished)
        running = accepted(client, slow_batch(16))
        queued = accepted(client, {"operation": "solve", "request": slow_item(99)})
        seen = read_items(client, running, 3)
    stop(first, signal.SIGINT)
    second = make_server("after_restart", **env)
    with second.client(timeout=HANG_GUARD) as client:
        assert client.get(finished).json() == result
        batch = wait_job(client, running)
        assert batch["status"] == "succeeded", batch
        assert batch["progress"] == {"done": 16, "total": 16, "problems": 0}
        stored = ndjson(client, running)
        assert sorted(item["index"] for item in stored) == list(range(16))
        assert stored[:3] == seen
        assert [item["index"] for item in batch["result"]["items"]] == list(range(16))
        assert wait_job(client, queued)["status"] == "succeeded"


def test_jobs_of_a_killed_service_are_finished_by_the_next_once_their_lease_expires(
    make_server: Callable[..., Server], tmp_path_factory: pytest.TempPathFactory
) -> None:
    """SIGKILL: no chance to record anything; the next start finds the batch still leased to
    the dead service, and takes it up once that lease (2 s here) has expired, from the items
    it had answered. Items a client has read are never lost (an item answered in the last
    moment before the kill, not yet committed, is answered again, once)."""
    env = slow_env(tmp_path_factory.mktemp("killed"), FLEXWING_JOB_LEASE="2")
    first = make_server("killed", **env)
    with first.client(timeout=HANG_GUARD) as client:
        running = accepted(client, slow_batch(16))
        seen = read_items(client, running, 3)
    stop(first, signal.SIGKILL)
    second = make_server("after_kill", **env)
    with second.client(timeout=HANG_GUARD) as client:
        batch = wait_job(client, running)
        assert batch["status"] == "succeeded", batch
        stored = ndjson(client, running)
        assert sorted(item["index"] for item in stored) == list(range(16))
        assert stored[:3] == seen


# ------------------------------------------------------------------------------ registry


def test_a_new_operation_is_one_registry_entry() -> None:
    """What POST /jobs accepts is built from the registry: an operation added to it is accepted
    (here one that takes a /solve body), one that is not there is an error on `operation`."""
    from pydantic import TypeAdapter, ValidationError

    from app.jobs.operations import JOB_KINDS, JobKind, submission_type
    from app.schemas import SolveRequest

    async def run(context: Any, request: SolveRequest) -> str:
        return "{}"

    echo = JobKind(
        name="echo",
        summary="an echo",
        request_model=SolveRequest,
        request_description="A POST /solve body.",
        units=lambda request: 1,
        check=lambda request, settings: None,
        run=run,
    )
    adapter: TypeAdapter[Any] = TypeAdapter(submission_type(JOB_KINDS | {"echo": echo}))
    body = adapter.validate_python({"operation": "echo", "request": study.solve_request(10.0)})
    assert body.operation == "echo" and body.request.flight.velocity == 10.0
    with pytest.raises(ValidationError) as raised:
        adapter.validate_python({"operation": "design", "request": {}})
    assert [error["loc"][-1] for error in raised.value.errors()] == ["operation"]


@pytest.mark.parametrize("created", [1764864000.0, 1764864000.1234567, 5.0, 1e-3 + 1764864000])
def test_a_page_cursor_is_the_exact_creation_time_and_id_in_the_documents_pattern(
    created: float,
) -> None:
    """Every string of the document's pattern is a cursor (the fuzzers' GET /jobs was 'mostly
    rejected' with an opaque base64 one), and the page's end round-trips exactly."""
    cursor = jobs_routes._cursor({"created": created, "id": "X-ffe858wnd9pEj4wYsmig"})
    assert re.fullmatch(jobs_routes.CURSOR_PATTERN, cursor)
    assert jobs_routes._parse_cursor(cursor) == (created, "X-ffe858wnd9pEj4wYsmig")
