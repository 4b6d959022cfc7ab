"""app.schemas.limits (through app.service.task_of): a request's model becomes the solver's
input, with the service's own limits (FLEXWING_MAX_STATIONS, FLEXWING_MAX_PANELS,
FLEXWING_MAX_SWEEP_POINTS) checked on the way."""

from __future__ import annotations

import numpy as np
import pytest
from pydantic import ValidationError

from app import schemas
from app.problems import Problem
from app.service import task_of
from app.settings import Settings
from solver import Layout
from tests import study


def _solve(n: int, k: int) -> schemas.SolveRequest:
    body = study.solve_request(10.0, options={"chordwise_panels": k})
    body["wing"] = study.wing_json(n=n)
    return schemas.SolveRequest.model_validate(body)


@pytest.mark.parametrize(
    ("n", "k"), [(31, 8), (61, 4), (121, 2), (150, 1)], ids=["k8", "k4", "k2", "k1-n150"]
)
def test_a_lattice_of_at_most_240_panels_is_accepted(n: int, k: int) -> None:
    inputs = task_of(_solve(n, k), Settings())
    assert inputs.wing.n_stations == n and inputs.modelled.chordwise_panels == k


@pytest.mark.parametrize(("n", "k"), [(32, 8), (62, 4), (122, 2)], ids=["k8", "k4", "k2"])
def test_one_strip_more_is_refused_naming_the_chordwise_panels(n: int, k: int) -> None:
    with pytest.raises(Problem) as raised:
        task_of(_solve(n, k), Settings())
    (error,) = raised.value.extensions["errors"]
    assert error["field"] == "options.chordwise_panels"
    assert f"{(n - 1) * k} panels" in error["reason"]
    assert "FLEXWING_MAX_PANELS" in error["reason"]


def test_the_panel_limit_is_the_services_setting() -> None:
    settings = Settings(max_panels=100)
    with pytest.raises(Problem):
        task_of(_solve(30, 4), settings)  # 116 panels
    body = study.solve_request(10.0, options={"chordwise_panels": 4})
    body["velocities"] = [8.0, 10.0]
    body["flight"].pop("velocity")
    with pytest.raises(Problem):
        task_of(schemas.SweepRequest.model_validate(body), settings)
    assert task_of(_solve(26, 4), settings).modelled.chordwise_panels == 4  # 100 panels


@pytest.mark.parametrize(
    ("value", "accepted"),
    [(4, True), (4.0, True), (4.5, False), ("4", False), (True, False)],
    ids=["int", "whole-float", "fraction", "string", "boolean"],
)
def test_a_count_is_a_json_schema_integer(value: object, accepted: bool) -> None:
    """JSON has one number type, and JSON Schema's "integer" is any whole number: 4.0 too."""
    body = study.solve_request(10.0, options={"chordwise_panels": value})
    body["wing"]["y"] = {"semispan": 1.5, "stations": value}
    body["velocities"] = {"start": 8.0, "stop": 12.0, "count": value}
    body["flight"].pop("velocity")
    if not accepted:
        with pytest.raises(ValidationError) as raised:
            schemas.SweepRequest.model_validate(body)
        fields = {".".join(map(str, e["loc"])) for e in raised.value.errors()}
        assert {"options.chordwise_panels", "wing.y.@object.stations"} <= fields
        assert any(field.endswith(".count") for field in fields)
        return
    request = schemas.SweepRequest.model_validate(body)
    assert request.options is not None and request.options.chordwise_panels == 4
    assert request.velocities.count == 4  # type: ignore[union-attr]
    assert request.wing.y.stations == 4  # type: ignore[union-attr]


@pytest.mark.parametrize(
    ("y", "reason"),
    [
        ([1.5, 1.0, 0.5, 0.0], "the first station must be the root"),
        ([0.0, 1.0, 0.5, 1.5], "strictly increasing"),
        ([0.0, 0.002, 0.004, 0.006], "the semispan (the last station) must be at least 0.01 m"),
    ],
    ids=["reversed", "not-increasing", "too-short"],
)
def test_stations_are_refused_for_what_is_wrong_with_them(y: list[float], reason: str) -> None:
    body = study.solve_request(10.0)
    body["wing"] = study.wing_json(n=4) | {"y": y}
    with pytest.raises(Problem) as raised:
        task_of(schemas.SolveRequest.model_validate(body), Settings())
    (error,) = raised.value.extensions["errors"]
    assert error["field"] == "wing.y" and reason in error["reason"]


@pytest.mark.parametrize("k", [1, 2, 4])
def test_a_guessed_deformation_is_a_state_of_the_lattice_the_options_ask_for(k: int) -> None:
    body = study.solve_request(10.0, options={"chordwise_panels": k})
    body["initial_guess"] = {"heave": [0.001 * i for i in range(30)], "twist": [0.5] * 30}
    inputs = task_of(schemas.SolveRequest.model_validate(body), Settings())
    layout = Layout(30, k)
    assert inputs.initial_guess is not None
    state = inputs.initial_guess.state(30, k)
    assert state.shape == (layout.n_unknowns,)
    assert state[layout.heave][-1] == pytest.approx(0.029)
    assert np.all(state[layout.twist] == 0.5)
    assert np.all(state[layout.circulation] == 0.0)


@pytest.mark.parametrize("count", [151, 500], ids=["past-the-stations-limit", "at-the-limit"])
def test_load_cases_are_held_to_their_own_limit_not_the_stations(count: int) -> None:
    """A list of load cases is not per station: FLEXWING_MAX_LOAD_CASES (500) bounds it, not
    FLEXWING_MAX_STATIONS (150)."""
    cases = [
        {"name": f"case {i}", "flight": {"velocity": 12.0, "weight": 300.0}} for i in range(count)
    ]
    body = {"wing": study.wing_json(), "cases": cases}
    task = task_of(schemas.REQUESTS["loads"].model_validate(body), Settings())
    assert task.case_count == count
    with pytest.raises(Problem) as refused:
        task_of(schemas.REQUESTS["loads"].model_validate(body), Settings(max_load_cases=150))
    assert refused.value.extensions["errors"][0]["field"] == "cases"
