"""app.routes.answers: a synchronous operation answers at once within its wait, and past it
becomes a job (202 with Location) whose result is the answer it would have given; a client may
ask for a longer wait (Prefer: wait=N, RFC 7240). No valid request ends in a 504."""

from __future__ import annotations

import asyncio
import time
from typing import Any

import httpx
import pytest

from app.routes.answers import RESPONSE_RESERVE, Arrival, preferred_wait, remaining_wait
from tests import study
from tests.app.conftest import Server


@pytest.mark.parametrize(
    ("prefer", "seconds"),
    [
        (None, None),
        ("wait=30", 30.0),
        ("respond-async, wait=5", 5.0),
        ('wait="2.5"', 2.5),
        ("handling=lenient", None),
        ("wait=soon", None),
        ("wait=-1", None),
    ],
    ids=["none", "wait", "with-others", "quoted", "other-preference", "not-a-number", "negative"],
)
def test_the_wait_a_client_prefers(prefer: str | None, seconds: float | None) -> None:
    assert preferred_wait(prefer) == seconds


@pytest.mark.parametrize(
    ("wait", "spent", "left"),
    [
        (10.0, 0.0, 10.0 - RESPONSE_RESERVE),
        (10.0, 2.5, 7.5 - RESPONSE_RESERVE),
        (10.0, 12.0, 0.0),
        (0.05, 0.0, 0.045),
        (0.0, 0.0, 0.0),
    ],
    ids=["fresh", "body-read-slowly", "past-it", "short-wait", "respond-async"],
)
def test_the_wait_counts_from_the_arrival_and_keeps_a_reserve_for_the_202(
    wait: float, spent: float, left: float
) -> None:
    """Issue 40: a 202 arrived after 10.008 s with a 10 s wait (the wait counted from the
    route, after the body was read and checked): a client with a 10 s timeout saw a timeout.
    The wait now counts from the arrival and keeps a reserve (a tenth of a short wait) for
    writing the 202."""
    assert remaining_wait(wait, 100.0, 100.0 + spent) == pytest.approx(left, abs=1e-12)
    assert remaining_wait(wait, None, 100.0 + spent) == pytest.approx(
        remaining_wait(wait, 100.0, 100.0), abs=1e-12
    )


def test_every_request_is_stamped_with_its_arrival_before_anything_else_runs() -> None:
    seen: dict[str, float] = {}

    async def app(scope: Any, receive: Any, send: Any) -> None:
        seen["arrived"] = scope["state"]["arrived"]

    before = time.perf_counter()
    asyncio.run(Arrival(app)({"type": "http"}, None, None))
    assert before <= seen["arrived"] <= time.perf_counter()


@pytest.fixture(scope="module")
def impatient(make_server: Any) -> Server:
    """A server that waits 50 ms for an answer, on CasADi's virtual machine, where a never-seen
    mesh's first solve takes far longer than that."""
    return make_server("impatient", FLEXWING_SYNC_WAIT="0.05", FLEXWING_COMPILE="0")


def _body(n: int, velocity: float = 10.0) -> dict[str, Any]:
    return study.solve_request(velocity) | {"wing": study.wing_json(n=n)}


def _finished(client: httpx.Client, location: str) -> dict[str, Any]:
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline:
        job = client.get(location).json()
        if job["status"] in ("succeeded", "failed", "cancelled"):
            return job  # type: ignore[no-any-return]
        time.sleep(0.05)
    raise AssertionError(f"{location} did not finish")


def test_past_its_wait_a_solve_becomes_a_job_with_the_same_answer(impatient: Server) -> None:
    with impatient.client() as client:
        accepted = client.post("/solve", json=_body(41))
        assert accepted.status_code == 202, accepted.text
        location = accepted.headers["location"]
        assert accepted.json()["status"] == "running" and location.startswith("/jobs/")
        job = _finished(client, location)
        assert job["status"] == "succeeded" and job["operation"] == "solve"
        waited = client.post("/solve", json=_body(41), headers={"Prefer": "wait=60"})
        assert waited.status_code == 200
        # The job's result is the synchronous answer (this one from the result cache).
        assert job["result"]["totals"] == waited.json()["totals"]
        assert waited.json()["solver"]["cached"] is True


def test_past_its_wait_a_sweep_counts_its_airspeeds(impatient: Server) -> None:
    body = {
        "wing": study.wing_json(n=43),
        "flight": {"alpha": study.ALPHA, "density": study.DENSITY},
        "velocities": [8.0, 12.0, 23.0],
    }
    with impatient.client() as client:
        accepted = client.post("/sweep", json=body)
        assert accepted.status_code == 202
        assert accepted.json()["progress"]["total"] == 3
        job = _finished(client, accepted.headers["location"])
        statuses = [point["status"] for point in job["result"]["points"]]
        assert statuses == ["equilibrium", "equilibrium", "no_equilibrium"]


def test_a_problem_found_after_the_wait_is_the_jobs(impatient: Server) -> None:
    """23 m/s is past the study's fold: the job fails with the problem /solve answers."""
    with impatient.client() as client:
        accepted = client.post("/solve", json=_body(45, velocity=23.0))
        assert accepted.status_code == 202
        job = _finished(client, accepted.headers["location"])
        assert job["status"] == "failed"
        assert job["problem"]["type"] == "/problems/no-equilibrium"
        assert 21.0 < job["problem"]["fold_velocity"] < 22.0


def test_an_invalid_request_is_refused_at_once_never_a_job(impatient: Server) -> None:
    body = _body(41)
    body["wing"]["chord"][3] = -1.0
    with impatient.client() as client:
        refused = client.post("/solve", json=body)
    assert refused.status_code == 422
    assert refused.json()["errors"][0]["field"] == "wing.chord[3]"


def test_an_answer_within_the_wait_is_the_plain_answer(client: httpx.Client) -> None:
    """The default server (10 s): the study's wing is answered at once."""
    response = client.post("/solve", json=study.solve_request(10.0))
    assert response.status_code == 200
    assert response.json()["totals"]["lift"] == pytest.approx(304.13, abs=0.01)
