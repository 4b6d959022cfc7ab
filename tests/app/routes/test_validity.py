"""`validity` through the API (issue 15): on every equilibrium, settable per request, summarised
by sweeps, and documented code by code in the OpenAPI document."""

from __future__ import annotations

import dataclasses
import json
from typing import Any

import httpx
import pytest

import solver
from openapi.generate import render
from tests import study

CODES = list(solver.FINDING_CODES)
# What the study's wing, which has no control surfaces, can be found to do.
STUDY_CODES = [code for code in CODES if code != "control_deflection"]
FINDING_FIELDS = {
    "code",
    "message",
    "measure",
    "where",
    "indices",
    "y",
    "value",
    "limit",
    "unit",
    "sensitivity",
    "half",
}


def _solve(client: httpx.Client, body: dict[str, Any]) -> dict[str, Any]:
    response = client.post("/solve", json=body)
    assert response.status_code == 200, response.text
    return response.json()


def _numbers(body: dict[str, Any]) -> dict[str, Any]:
    """A response less what is said about it and how it was obtained."""
    return {k: v for k, v in body.items() if k not in ("validity", "solver")}


def test_the_study_wing_within_the_model_at_10_ms(client: httpx.Client):
    body = _solve(client, study.solve_request(10.0))
    assert body["validity"] == []  # present, never absent


def test_the_study_wing_at_20_ms_is_said_to_stall(client: httpx.Client):
    body = _solve(client, study.solve_request(20.0))
    findings = {f["code"]: f for f in body["validity"]}
    assert list(findings) == STUDY_CODES
    for finding in body["validity"]:
        assert set(finding) == FINDING_FIELDS
        assert finding["message"].endswith(".")
    stall = findings["section_stall"]
    assert stall["value"] == pytest.approx(1.70, abs=0.005) and stall["limit"] == 1.2
    assert stall["where"] == "panels"
    assert stall["y"] == [body["panels"]["y"][i] for i in stall["indices"]]
    assert findings["large_twist"]["y"] == [
        body["stations"]["y"][i] for i in findings["large_twist"]["indices"]
    ]
    assert findings["near_divergence"]["sensitivity"] > 5


def test_options_validity_changes_what_is_said_never_the_numbers(client: httpx.Client):
    plain = _solve(client, study.solve_request(15.0))
    strict = _solve(
        client,
        study.solve_request(
            15.0,
            options={
                "validity": {
                    "heave_fraction": 0.02,
                    "slope": 0.04,
                    "twist": 4.0,
                    "cl_max": 0.8,
                    "divergence_margin": 0.3,
                }
            },
        ),
    )
    assert plain["validity"] == []
    assert [f["code"] for f in strict["validity"]] == [
        "large_deflection",
        "large_deflection",
        "large_twist",
        "section_stall",
        "near_divergence",
    ]
    assert strict["solver"]["cached"] is False  # the limits are a part of the request's key
    assert _numbers(strict) == _numbers(plain)
    # One limit alone: the others keep their defaults.
    one = _solve(client, study.solve_request(15.0, options={"validity": {"cl_max": 0.8}}))
    assert [f["code"] for f in one["validity"]] == ["section_stall"]


def test_the_wings_cl_max_one_number_or_per_station(client: httpx.Client):
    request = study.solve_request(20.0)
    high = _solve(client, request | {"wing": request["wing"] | {"cl_max": 2.0}})
    assert "section_stall" not in [f["code"] for f in high["validity"]]
    assert _numbers(high) == _numbers(_solve(client, request))
    falling = [2.0 - 1.4 * i / 29 for i in range(30)]
    low = _solve(
        client, study.solve_request(15.0) | {"wing": request["wing"] | {"cl_max": falling}}
    )
    (stall,) = low["validity"]
    assert stall["code"] == "section_stall" and stall["indices"] == list(range(24, 29))
    assert "wing.cl_max" in stall["message"]


@pytest.mark.parametrize(
    ("wing", "options", "field"),
    [
        ({"cl_max": 0.0}, None, "wing.cl_max"),
        ({"cl_max": [1.2] * 29}, None, "wing.cl_max"),
        ({}, {"validity": {"divergence_margin": 1.5}}, "options.validity.divergence_margin"),
        ({}, {"validity": {"twist": -1.0}}, "options.validity.twist"),
        ({}, {"validity": {"stall": 1.0}}, "options.validity.stall"),
    ],
)
def test_bad_limits_are_invalid_input(
    in_process: httpx.Client, wing: dict[str, Any], options: dict[str, Any] | None, field: str
):
    request = study.solve_request(10.0)
    body = request | {"wing": request["wing"] | wing}
    if options is not None:
        body["options"] = options
    response = in_process.post("/solve", json=body)
    assert response.status_code == 422, response.text
    assert field in [e["field"] for e in response.json()["errors"]]


def test_trimmed_answers_carry_validity(client: httpx.Client):
    body = _solve(
        client, study.solve_request(20.0) | {"flight": {"velocity": 20.0, "weight": 300.0}}
    )
    assert [f["code"] for f in body["validity"]] == ["near_divergence"]


def test_a_sweep_says_from_which_airspeed_on_each_finding_appears(client: httpx.Client):
    request = {
        "wing": study.wing_json(),
        "flight": {"alpha": study.ALPHA, "density": study.DENSITY},
        "velocities": [6.0, 10.0, 15.0, 18.0, 20.0, 23.0],
    }
    response = client.post("/sweep", json=request)
    assert response.status_code == 200, response.text
    body = response.json()
    onsets = {o["code"]: o for o in body["validity"]}
    assert list(onsets) == STUDY_CODES
    assert onsets["section_stall"]["velocity"] == 18.0
    assert onsets["section_stall"]["velocities"] == [18.0, 20.0]
    assert "from 18 m/s on" in onsets["section_stall"]["message"]
    assert all(onsets[c]["velocity"] == 20.0 for c in STUDY_CODES if c != "section_stall")
    for point in body["points"]:
        if point["equilibrium"] is not None:
            assert isinstance(point["equilibrium"]["validity"], list)


# ----------------------------------------------------------------------- the document


@pytest.fixture(scope="module")
def document() -> dict[str, Any]:
    return dict(json.loads(render()))


def test_openapi_documents_every_code_with_its_meaning(document: dict[str, Any]):
    schemas = document["components"]["schemas"]
    code = schemas["Finding"]["properties"]["code"]
    assert code["enum"] == CODES
    for name, meaning in solver.FINDING_CODES.items():
        assert f"{name}: {meaning}" in code["description"]
    assert schemas["FindingOnset"]["properties"]["code"]["enum"] == CODES
    assert "validity" in schemas["SolveResponse"]["required"]
    assert "validity" in schemas["SweepResponse"]["required"]


def test_openapi_documents_every_default_and_its_reason(document: dict[str, Any]):
    properties = document["components"]["schemas"]["ValidityLimits"]["properties"]
    for field in dataclasses.fields(solver.ValidityLimits):
        documented = properties[field.name]
        assert documented["default"] == field.default
        assert "default" in documented["description"]
        described = solver.spec_of(solver.ValidityLimits, field.name).description
        assert described[1:40] in documented["description"]
    assert "cl_max" in document["components"]["schemas"]["Wing"]["properties"]
