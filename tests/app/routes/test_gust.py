"""POST /gust: the gust loads through HTTP are the solver's; a wing without mass or a flight
without weight is refused naming the field; a wing past flutter is the typed 422
/problems/unstable; never a 5xx."""

from __future__ import annotations

import copy
from typing import Any

import httpx
import numpy as np
import pytest

from app.schemas.examples import GOLAND_WING, GUST_EXAMPLES
from app.schemas.requests import REQUESTS

CLAMPED = GUST_EXAMPLES["clamped"]["value"]


def _in_process(body: dict[str, Any]) -> Any:
    return REQUESTS["gust"].model_validate(body).to_solver().run()


def test_the_gust_loads_through_http_are_the_solvers(client: httpx.Client) -> None:
    response = client.post("/gust", json=CLAMPED)
    assert response.status_code == 200, response.text
    body = response.json()
    expected = _in_process(CLAMPED)
    assert len(body["gusts"]) == 5 and body["clamped"] is True
    np.testing.assert_allclose(
        body["envelope"]["max_bending_moment"], expected.envelope.max_bending_moment, rtol=1e-9
    )
    assert body["gusts"][0]["name"].startswith("1-cos H = 9 m up")
    assert body["turbulence"] is None


def test_the_study_example_answers_with_turbulence(client: httpx.Client) -> None:
    response = client.post("/gust", json=GUST_EXAMPLES["study"]["value"])
    assert response.status_code == 200, response.text
    body = response.json()
    assert len(body["gusts"]) == 20 and body["turbulence"]["load_factor"] > 0
    assert body["envelope"]["max_bending_moment"][0] > body["one_g_bending_moment"][0]


@pytest.mark.parametrize(
    ("drop", "field"),
    [(("wing", "mass"), "wing.mass"), (("flight", "weight"), "flight.weight")],
    ids=["no-mass", "no-weight"],
)
def test_a_request_without_what_it_needs_is_refused_naming_it(
    in_process: httpx.Client, drop: tuple[str, str], field: str
) -> None:
    body = copy.deepcopy(CLAMPED)
    del body[drop[0]][drop[1]]
    if drop == ("flight", "weight"):
        body["flight"]["alpha"] = 5.0
    response = in_process.post("/gust", json=body)
    assert response.status_code == 422, response.text
    assert field in [e["field"] for e in response.json()["errors"]]


def test_settings_outside_their_limits_are_refused_naming_them(in_process: httpx.Client) -> None:
    body = copy.deepcopy(CLAMPED)
    body["gust"] = {"gradients": 0, "alleviation": 2.0}
    response = in_process.post("/gust", json=body)
    assert response.status_code == 422
    fields = {e["field"] for e in response.json()["errors"]}
    assert fields == {"gust.gradients", "gust.alleviation"}


def test_a_wing_past_flutter_is_a_typed_unstable_answer(client: httpx.Client) -> None:
    # Goland's wing, strip theory, flutters at ~137 m/s (~70 rad/s).
    body = {
        "wing": GOLAND_WING,
        "flight": {"velocity": 160.0, "weight": 20000.0, "density": 1.225},
        "gust": {"gradients": 2, "turbulence": False},
        "options": {"aerodynamics": "strip"},
    }
    response = client.post("/gust", json=body)
    assert response.status_code == 422, response.text
    problem = response.json()
    assert problem["type"].endswith("/problems/unstable")
    assert problem["growth_rate"] > 0 and problem["frequency"] == pytest.approx(70.0, rel=0.06)


def test_gust_conditions_join_the_loads_envelope_through_http(client: httpx.Client) -> None:
    study = GUST_EXAMPLES["study"]["value"]
    body = {
        "wing": study["wing"],
        "cases": [{"name": "cruise", "flight": {"velocity": 14.0, "weight": 300.0}}],
        "gusts": [
            {
                "name": "V_C gusts",
                "flight": study["flight"],
                "gust": {"gradients": 4, "turbulence": False},
            }
        ],
    }
    response = client.post("/loads", json=body)
    assert response.status_code == 200, response.text
    cases = response.json()["cases"]
    assert [c["name"] for c in cases] == ["cruise", "V_C gusts up", "V_C gusts down"]
    assert [c["kind"] for c in cases] == ["given", "gust_dynamic", "gust_dynamic"]
    expected = REQUESTS["loads"].model_validate(body).to_solver().run()
    np.testing.assert_allclose(
        cases[1]["bending_moment"], expected.cases[1].bending_moment, rtol=1e-8
    )
