"""POST /loads: the sizing loads through HTTP are the solver's, the cases spread over the
workers and assembled in order; a job counts its cases; more cases than the service's limit, given
or derived, is refused naming the limit before any work; a case the wing cannot fly is answered
in its place."""

from __future__ import annotations

import time
from typing import Any

import httpx
import numpy as np
import pytest

from app.schemas.examples import LOADS_EXAMPLES
from app.schemas.requests import REQUESTS
from app.settings import Settings
from tests.app.conftest import in_process_client

ENVELOPE = LOADS_EXAMPLES["envelope"]["value"]
# Each case is the same solve on the server's workers as here: Newton's residual (1e-10 of
# its scale) bounds how far two runs of it on other processes can differ.
SAME = 1e-8


def _in_process(body: dict[str, Any]) -> Any:
    return REQUESTS["loads"].model_validate(body).to_solver().run()


def test_the_envelope_through_http_is_the_solvers(client: httpx.Client) -> None:
    response = client.post("/loads", json=ENVELOPE)
    assert response.status_code == 200, response.text
    body = response.json()
    expected = _in_process(ENVELOPE)
    assert [c["name"] for c in body["cases"]] == [c.name for c in expected.cases]
    assert [c["status"] for c in body["cases"]] == [c.status for c in expected.cases]
    for ours, theirs in zip(body["cases"], expected.cases, strict=True):
        if theirs.answered:
            np.testing.assert_allclose(
                ours["bending_moment"], theirs.bending_moment, rtol=SAME, atol=SAME
            )
    envelope = body["envelope"]
    scale = np.max(np.abs(expected.envelope.max_bending_moment))
    np.testing.assert_allclose(
        envelope["max_bending_moment"], expected.envelope.max_bending_moment, atol=SAME * scale
    )
    assert envelope["max_bending_moment_case"][0] == expected.envelope.max_bending_moment_case[0]
    assert [d["weight"] for d in body["vn"]] == [250.0, 300.0]
    assert body["info"]["cases"] == len(expected.cases)


def test_a_case_past_divergence_is_answered_in_its_place(client: httpx.Client) -> None:
    body = LOADS_EXAMPLES["cases"]["value"] | {
        "cases": [
            {"name": "cruise", "flight": {"velocity": 14.0, "weight": 300.0}},
            {"name": "too fast", "flight": {"velocity": 40.0, "weight": 300.0}},
        ]
    }
    response = client.post("/loads", json=body)
    assert response.status_code == 200, response.text
    cases = response.json()["cases"]
    assert [c["status"] for c in cases] == ["equilibrium", "no_equilibrium"]
    assert cases[1]["reason"] and cases[1]["bending_moment"] is None
    assert response.json()["info"]["answered"] == 1


def test_a_loads_job_counts_its_cases(client: httpx.Client) -> None:
    accepted = client.post("/jobs", json={"operation": "loads", "request": ENVELOPE})
    assert accepted.status_code == 202, accepted.text
    deadline = time.monotonic() + 120.0
    while (job := client.get(accepted.headers["location"]).json())["status"] in (
        "queued",
        "running",
    ):
        assert time.monotonic() < deadline
        time.sleep(0.1)
    expected = REQUESTS["loads"].model_validate(ENVELOPE).to_solver().case_count
    assert job["status"] == "succeeded" and job["progress"]["total"] == expected
    assert len(job["result"]["cases"]) == expected


@pytest.mark.parametrize(
    ("body", "reason"),
    [
        (ENVELOPE, "gives 20 load cases (0 given, 20 from the envelope); at most 12"),
        (
            LOADS_EXAMPLES["cases"]["value"]
            | {
                "cases": [
                    {"name": f"case {i}", "flight": {"velocity": 12.0, "weight": 300.0}}
                    for i in range(13)
                ]
            },
            "gives 13 load cases (13 given, 0 from the envelope); at most 12",
        ),
    ],
    ids=["derived", "given"],
)
def test_more_cases_than_the_limit_is_refused_naming_it(body: dict[str, Any], reason: str) -> None:
    """Checked before any work, in process (no worker answers it)."""
    with in_process_client(Settings(workers=1, max_load_cases=12)) as client:
        response = client.post("/loads", json=body)
    assert response.status_code == 422
    (error,) = response.json()["errors"]
    assert error["field"] == "cases"
    assert reason in error["reason"] and "FLEXWING_MAX_LOAD_CASES" in error["reason"]


def test_the_published_limit_on_given_cases_is_the_settings() -> None:
    with in_process_client(Settings(workers=1, max_load_cases=12)) as client:
        document = client.get("/openapi.json").json()
    schemas = document["components"]["schemas"]
    (request,) = [s for name, s in schemas.items() if name.startswith("LoadsRequest")]
    assert request["properties"]["cases"]["maxItems"] == 12
