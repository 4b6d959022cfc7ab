"""Every kind of bad input gets its 4xx as RFC 9457 problem+json naming the field and why, in
process: validation needs no worker (`in_process`, tests/app/conftest.py)."""

from __future__ import annotations

import json
from collections.abc import Iterator
from typing import Any

import httpx
import pytest

from tests import study


def _problem(response: httpx.Response, status: int, kind: str) -> dict[str, Any]:
    assert response.status_code == status, response.text
    assert response.headers["content-type"] == "application/problem+json"
    problem = response.json()
    assert problem["type"] == f"/problems/{kind}"
    assert problem["status"] == status
    assert problem["title"] and problem["detail"]
    return problem


def _fields(problem: dict[str, Any]) -> dict[str, str]:
    return {e["field"]: e["reason"] for e in problem["errors"]}


def _with_wing(**changes: Any) -> dict[str, Any]:
    body = study.solve_request(10.0)
    body["wing"] = body["wing"] | changes
    return body


def _invalid(in_process: httpx.Client, body: Any, path: str = "/solve") -> dict[str, str]:
    response = in_process.post(path, json=body)
    return _fields(_problem(response, 422, "invalid-input"))


def test_non_finite_numbers(in_process: httpx.Client) -> None:
    chord = study.wing_json()["chord"]
    text = json.dumps(_with_wing(chord=chord)).replace(str(chord[3]), "NaN", 1)
    text = text.replace(str(chord[7]), "Infinity", 1).replace(str(chord[9]), "1e999", 1)
    response = in_process.post("/solve", content=text, headers={"content-type": "application/json"})
    fields = _fields(_problem(response, 422, "invalid-input"))
    assert set(fields) == {"wing.chord[3]", "wing.chord[7]", "wing.chord[9]"}
    assert all("finite" in reason for reason in fields.values())


def test_non_increasing_y(in_process: httpx.Client) -> None:
    y = study.wing_json()["y"]
    y[5], y[6] = y[6], y[5]
    assert _invalid(in_process, _with_wing(y=y)) == {
        "wing.y": "stations must be strictly increasing"
    }


def test_root_not_at_zero(in_process: httpx.Client) -> None:
    y = [v + 0.1 for v in study.wing_json()["y"]]
    fields = _invalid(in_process, _with_wing(y=y))
    assert list(fields) == ["wing.y"]
    assert "y[0] = 0" in fields["wing.y"]


def test_mismatched_lengths(in_process: httpx.Client) -> None:
    fields = _invalid(
        in_process, _with_wing(bending_stiffness=study.wing_json()["bending_stiffness"][:-1])
    )
    assert fields == {"wing.bending_stiffness": "has 29 values but y has 30 stations"}


def test_mismatched_elastic_axis_list(in_process: httpx.Client) -> None:
    fields = _invalid(in_process, _with_wing(elastic_axis=[0.4] * 3))
    assert fields == {"wing.elastic_axis": "has 3 values but y has 30 stations"}


def test_non_positive_chord_and_stiffness(in_process: httpx.Client) -> None:
    w = study.wing_json()
    chord, gj = w["chord"], w["torsional_stiffness"]
    chord[0], gj[4], gj[5] = 0.0, -1.0, 0.0
    fields = _invalid(in_process, _with_wing(chord=chord, torsional_stiffness=gj))
    assert set(fields) == {
        "wing.chord[0]",
        "wing.torsional_stiffness[4]",
        "wing.torsional_stiffness[5]",
    }
    minimum = {"wing.chord[0]": "0.001"} | dict.fromkeys(
        ("wing.torsional_stiffness[4]", "wing.torsional_stiffness[5]"), "0.001"
    )
    for field, reason in fields.items():
        assert f"greater than or equal to {minimum[field]}" in reason, (field, reason)


@pytest.mark.parametrize(
    ("flight", "field"),
    [
        pytest.param({"density": 5e-324}, "flight.density", id="denormal-density"),
        pytest.param({"density": 2001.0}, "flight.density", id="denser-than-water"),
        pytest.param({"velocity": 1000.5}, "flight.velocity", id="past-1000-mps"),
        pytest.param({"velocity": 5e-324}, "flight.velocity", id="denormal-velocity"),
        pytest.param({"alpha": 30.5}, "flight.alpha", id="alpha-past-30-deg"),
    ],
)
def test_a_number_outside_the_published_limits_is_invalid_input(
    in_process: httpx.Client, flight: dict, field: str
) -> None:
    """Found by schema fuzzing with another seed: density 5e-324 got HTTP 500 (ZeroDivisionError).
    The limits are in the OpenAPI document (minimum, maximum) and enforced before any solve."""
    body = study.solve_request(10.0)
    body["flight"] |= flight
    fields = _invalid(in_process, body)
    assert list(fields) == [field]


def test_a_sweep_of_denormal_airspeeds_is_invalid_input(in_process: httpx.Client) -> None:
    """Found by schema fuzzing with another seed: velocities {start: 5e-324, stop: 5e-324,
    count: 2} got HTTP 500."""
    body = {
        "wing": study.wing_json(),
        "flight": {"alpha": 5.0},
        "velocities": {"start": 5e-324, "stop": 5e-324, "count": 2},
    }
    assert set(_invalid(in_process, body, "/sweep")) == {"velocities.start", "velocities.stop"}


def test_stiffness_beyond_the_published_limit_is_invalid_input(in_process: httpx.Client) -> None:
    assert list(_invalid(in_process, _with_wing(bending_stiffness=1e13))) == [
        "wing.bending_stiffness"
    ]


def test_stations_closer_than_the_limit_are_invalid_input(in_process: httpx.Client) -> None:
    y = study.wing_json()["y"]
    y[1] = 1e-5
    fields = _invalid(in_process, _with_wing(y=y))
    assert list(fields) == ["wing.y"] and "0.0001 of the semispan" in fields["wing.y"]


def test_too_few_and_too_many_stations(in_process: httpx.Client) -> None:
    few = {k: (v[:2] if isinstance(v, list) else v) for k, v in study.wing_json().items()}
    fields = _invalid(in_process, _with_wing(**few))
    assert set(fields) == {
        "wing.y",
        "wing.chord",
        "wing.bending_stiffness",
        "wing.torsional_stiffness",
    }
    n = 151  # FLEXWING_MAX_STATIONS defaults to 150
    many = {
        "y": [i / n for i in range(n)],
        "chord": [1.0] * n,
        "elastic_axis": 0.4,
        "bending_stiffness": [1e4] * n,
        "torsional_stiffness": [1e3] * n,
    }
    fields = _invalid(in_process, _with_wing(**many))
    assert list(fields) == ["wing.y"]
    assert "at most 150" in fields["wing.y"]


def test_bad_flight_condition(in_process: httpx.Client) -> None:
    body = study.solve_request(10.0)
    body["flight"] = {"velocity": 0, "alpha": 95, "density": -1}
    fields = _invalid(in_process, body)
    assert set(fields) == {"flight.velocity", "flight.alpha", "flight.density"}


def test_too_many_velocities(in_process: httpx.Client) -> None:
    body = {"wing": study.wing_json(), "flight": {"alpha": 5}, "velocities": [10.0] * 51}
    fields = _invalid(in_process, body, "/sweep")
    assert list(fields) == ["velocities"]
    assert "1 to 50" in fields["velocities"]
    body["velocities"] = {"start": 5, "stop": 10, "count": 10**9}
    assert list(_invalid(in_process, body, "/sweep")) == ["velocities.count"]
    body["velocities"] = [10, -1]
    assert list(_invalid(in_process, body, "/sweep")) == ["velocities[1]"]


def test_wrong_types_unknown_fields_and_missing_fields(in_process: httpx.Client) -> None:
    body = _with_wing(elastic_axis=[0.4, "a"])
    body["flght"] = {}
    del body["flight"]
    fields = _invalid(in_process, body)
    assert set(fields) == {"wing.elastic_axis[1]", "flght", "flight"}


def test_initial_guess_of_the_wrong_length(in_process: httpx.Client) -> None:
    body = study.solve_request(10.0, initial_guess={"heave": [0.0] * 29, "twist": [0.0] * 30})
    assert _invalid(in_process, body) == {"initial_guess.heave": "has 29 values but y has 30"}


def test_invalid_options(in_process: httpx.Client) -> None:
    body = study.solve_request(10.0, options={"tolerance": 0, "max_iterations": 0})
    assert set(_invalid(in_process, body)) == {"options.tolerance", "options.max_iterations"}


def test_invalid_json(in_process: httpx.Client) -> None:
    response = in_process.post(
        "/solve", content=b"{not json", headers={"content-type": "application/json"}
    )
    fields = _fields(_problem(response, 422, "invalid-input"))
    assert list(fields) == ["body"]
    assert fields["body"].startswith("invalid JSON")


def test_a_body_that_is_not_utf8(in_process: httpx.Client) -> None:
    response = in_process.post(
        "/solve", content=b"\xff", headers={"content-type": "application/json"}
    )
    fields = _fields(_problem(response, 422, "invalid-input"))
    assert list(fields) == ["body"]
    assert fields["body"].startswith("invalid JSON")


def test_oversized_body_declared(in_process: httpx.Client) -> None:
    response = in_process.post("/solve", content=b" " * 1_000_001)  # default limit: 1,000,000 bytes
    problem = _problem(response, 413, "body-too-large")
    assert problem["max_body_bytes"] == 1_000_000


def test_oversized_body_streamed(in_process: httpx.Client) -> None:
    def chunks() -> Iterator[bytes]:
        for _ in range(20):
            yield b" " * 100_000

    response = in_process.post("/solve", content=chunks())  # chunked: no Content-Length
    _problem(response, 413, "body-too-large")


def test_a_body_under_the_limit_passes_the_streamed_check(in_process: httpx.Client) -> None:
    body = json.dumps(study.solve_request(10.0)).encode()

    def chunks() -> Iterator[bytes]:
        yield from (body[i : i + 1000] for i in range(0, len(body), 1000))

    headers = {"content-type": "application/json"}
    response = in_process.post("/solve", content=chunks(), headers=headers)
    # Past the body limit and validation, it reaches the pool: not started in process.
    _problem(response, 503, "not-ready")


def test_unknown_path_and_method(in_process: httpx.Client) -> None:
    _problem(in_process.get("/nowhere"), 404, "not-found")
    _problem(in_process.get("/solve"), 405, "method-not-allowed")


@pytest.mark.parametrize(
    ("method", "path", "allowed"),
    [
        ("GET", "/solve", {"POST"}),
        ("OPTIONS", "/jobs", {"GET", "POST"}),
        ("PUT", "/jobs/some-id", {"GET", "DELETE"}),
    ],
    ids=["solve", "jobs", "one-job"],
)
def test_a_405_lists_every_method_the_path_serves(
    in_process: httpx.Client, method: str, path: str, allowed: set[str]
) -> None:
    # RFC 9110 15.5.6: Allow lists the target's methods, whichever route serves each of them
    # (HEAD comes with GET).
    response = in_process.request(method, path)
    _problem(response, 405, "method-not-allowed")
    listed = {m.strip() for m in response.headers["allow"].split(",")}
    assert listed - {"HEAD"} == allowed


def test_problem_types_are_described(in_process: httpx.Client) -> None:
    response = in_process.get("/problems/no-equilibrium")
    assert response.status_code == 200
    assert response.json()["status"] == 422
    _problem(in_process.get("/problems/nonsense"), 404, "not-found")
