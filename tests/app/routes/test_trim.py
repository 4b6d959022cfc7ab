"""Trimmed flight through the API: `flight` takes alpha, lift, or weight with a load factor."""

from __future__ import annotations

from typing import Any

import httpx
import pytest

from tests import study
from tests.reference import extended_references

WEIGHT = 300.0  # [N] the study's wing at its weight (the trimmed references')


def _request(flight: dict[str, Any], **extra: Any) -> dict[str, Any]:
    return {"wing": study.wing_json(), "flight": flight} | extra


@pytest.mark.parametrize(
    "flight",
    [
        {"velocity": 12.0, "lift": WEIGHT},
        {"velocity": 12.0, "weight": WEIGHT},
        {"velocity": 12.0, "weight": WEIGHT / 2, "load_factor": 2.0},
    ],
    ids=["lift", "weight", "weight-2g"],
)
def test_every_way_to_ask_for_a_lift_carries_it(client: httpx.Client, flight: dict[str, Any]):
    response = client.post("/solve", json=_request(flight))
    assert response.status_code == 200, response.text
    totals = response.json()["totals"]
    assert totals["lift"] == pytest.approx(WEIGHT, rel=1e-9)
    assert totals["rigid_lift"] == pytest.approx(WEIGHT, rel=1e-9)
    # The study's wing twists nose-up under load: it needs less alpha than the rigid jig.
    assert 0 < totals["alpha"] < totals["rigid_alpha"]
    assert totals["lift_effectiveness"] > 1


def test_the_trimmed_answer_is_aerosandboxs(client: httpx.Client):
    (reference,) = [r for r in extended_references() if r.name == "trim_study"]
    flight = {"velocity": 14.0, "weight": WEIGHT, "density": reference.rho}
    response = client.post("/solve", json=_request(flight))
    assert response.status_code == 200, response.text
    theirs = reference.equilibrium_at(14)
    body = response.json()
    assert body["totals"]["alpha"] == pytest.approx(theirs["alpha_deg"], abs=1e-6)
    assert body["stations"]["twist"][-1] == pytest.approx(theirs["elastic_stream_twist_deg"][-1])


def test_an_alpha_solve_at_the_trimmed_alpha_answers_the_same(client: httpx.Client):
    trimmed = client.post("/solve", json=_request({"velocity": 16.0, "lift": WEIGHT})).json()
    alpha = trimmed["totals"]["alpha"]
    at_alpha = client.post("/solve", json=_request({"velocity": 16.0, "alpha": alpha})).json()
    assert at_alpha["totals"]["lift"] == pytest.approx(WEIGHT, rel=1e-8)
    assert at_alpha["stations"]["heave"] == pytest.approx(trimmed["stations"]["heave"], rel=1e-8)
    # Compared with the rigid jig at the same alpha, not the same lift: amplification > 1.
    assert at_alpha["totals"]["lift_amplification"] > 1
    assert at_alpha["totals"]["rigid_alpha"] is None


def test_a_trimmed_sweep_reports_alpha_and_the_trimmed_divergence_limit(client: httpx.Client):
    body = {
        "wing": study.wing_json(),
        "flight": {"weight": WEIGHT},
        "velocities": [8.0, 16.0, 26.0],
    }
    response = client.post("/sweep", json=body)
    assert response.status_code == 200, response.text
    result = response.json()
    points = result["points"]
    assert [p["status"] for p in points] == ["equilibrium", "equilibrium", "no_equilibrium"]
    alphas = [p["equilibrium"]["totals"]["alpha"] for p in points[:2]]
    assert alphas[0] > alphas[1] > 0  # faster, less alpha for the same lift
    assert "statically unstable" in points[2]["no_equilibrium"]["reason"]
    limit = result["divergence"]["fold"]
    assert limit["kind"] == "trimmed_stability_limit"
    assert 16.0 < limit["velocity"] < 26.0
    assert result["divergence"]["fit"]["amplification"] == "lift_effectiveness"


@pytest.mark.parametrize(
    ("flight", "field"),
    [
        pytest.param({"velocity": 10.0}, "flight", id="none"),
        pytest.param(
            {"velocity": 10.0, "alpha": 5.0, "lift": WEIGHT}, "flight", id="alpha-and-lift"
        ),
        pytest.param(
            {"velocity": 10.0, "lift": WEIGHT, "weight": WEIGHT}, "flight", id="two-lifts"
        ),
        pytest.param({"velocity": 10.0, "lift": 0.0}, "flight.lift", id="zero-lift"),
        pytest.param({"velocity": 10.0, "weight": 0.0}, "flight.weight", id="zero-weight"),
        pytest.param(
            {"velocity": 10.0, "weight": WEIGHT, "load_factor": 0.0},
            "flight.load_factor",
            id="zero-load-factor",
        ),
        pytest.param(
            {"velocity": 10.0, "weight": WEIGHT, "load_factor": 11.0},
            "flight.load_factor",
            id="load-factor-11",
        ),
    ],
)
def test_a_flight_given_any_other_way_is_a_422_naming_the_field(
    in_process: httpx.Client, flight: dict[str, Any], field: str
):
    response = in_process.post("/solve", json=_request(flight))
    assert response.status_code == 422, response.text
    assert response.headers["content-type"].startswith("application/problem+json")
    fields = [error["field"] for error in response.json()["errors"]]
    assert field in fields, response.text
    if field == "flight":
        assert "exactly one of alpha" in response.text


def test_a_starting_deformation_with_a_trimmed_flight_is_a_422(in_process: httpx.Client):
    guess = {"heave": [0.0] * 30, "twist": [0.0] * 30}
    response = in_process.post(
        "/solve", json=_request({"velocity": 10.0, "lift": WEIGHT}, initial_guess=guess)
    )
    assert response.status_code == 422
    assert [e["field"] for e in response.json()["errors"]] == ["initial_guess"]


def test_a_lift_beyond_the_wing_is_a_domain_answer_not_an_error_of_input(client: httpx.Client):
    response = client.post("/solve", json=_request({"velocity": 4.5, "weight": WEIGHT}))
    assert response.status_code == 422
    problem = response.json()
    assert problem["type"].endswith("/no-equilibrium")
    assert "beyond +-30 deg" in problem["detail"]
