"""app.schemas.responses: the response models derived from the solver's result dataclasses,
and `payload`, which turns a result into the JSON those models describe.

- `payload`: arrays become lists, numpy scalars Python numbers, NaN and infinities null (JSON
  has neither), dataclasses dicts of their API fields (internal ones stay in Python).
- Every API field of every result type reachable from an answer is a field of its response
  model, described with its unit; the model has no other field but the few the service adds.
- MODEL_NAMES keep the published component names of the OpenAPI document.
- `Answer`: an answer's body, serialised once in the worker, is exactly what the response model
  of its operation describes (the models are not applied again on the way out), and a cached
  answer differs from a fresh one only in its `solver` block's service fields.
"""

from __future__ import annotations

import dataclasses
import functools
import json
import math
import typing
from typing import Any

import numpy as np
import pytest
from pydantic import BaseModel, ValidationError

import solver
from app.execution import worker
from app.schemas import (
    API_ONLY_FIELDS,
    CONTROLS_EXAMPLES,
    FLUTTER_EXAMPLES,
    MODEL_NAMES,
    OPTIMIZE_EXAMPLES,
    ROLL_EXAMPLES,
    SOLVE_EXAMPLES,
    SWEEP_EXAMPLES,
    Answer,
    ControlsRequest,
    ControlsResponse,
    FlutterRequest,
    FlutterResponse,
    OptimizeRequest,
    OptimizeResponse,
    RollRequest,
    RollResponse,
    SolveRequest,
    SolveResponse,
    SweepRequest,
    SweepResponse,
    api_fields,
    payload,
    response_model,
)
from app.service import task_of
from app.settings import Settings
from openapi.generate import PATH as OPENAPI_PATH
from tests import study


@functools.cache
def _equilibrium() -> solver.Equilibrium:
    return solver.solve(study.study_wing(), study.flight(10.0))


# ------------------------------------------------------------------------------ payload

SCALARS = {
    "nan": (float("nan"), None),
    "inf": (float("inf"), None),
    "-inf": (-math.inf, None),
    "numpy nan": (np.float64("nan"), None),
    "numpy float": (np.float64(2.5), 2.5),
    "numpy int": (np.int64(3), 3),
    "numpy bool": (np.bool_(True), True),
    "finite float": (0.1, 0.1),
    "text": ("jig", "jig"),
    "null": (None, None),
}


@pytest.mark.parametrize(("value", "expected"), list(SCALARS.values()), ids=list(SCALARS))
def test_a_scalar_becomes_its_json_value(value: Any, expected: Any) -> None:
    converted = payload(value)
    assert converted == expected and type(converted) is type(expected)


ARRAYS = {
    "finite": (np.array([0.0, -1.5, 2.0]), [0.0, -1.5, 2.0]),
    "with nan and inf": (np.array([1.0, np.nan, np.inf]), [1.0, None, None]),
    "a tuple": ((1.0, float("nan")), [1.0, None]),
    "nested lists": ([np.array([1.0]), [np.float64(np.inf)]], [[1.0], [None]]),
}


@pytest.mark.parametrize(("value", "expected"), list(ARRAYS.values()), ids=list(ARRAYS))
def test_an_array_becomes_a_list_with_null_for_what_is_not_finite(
    value: Any, expected: Any
) -> None:
    converted = payload(value)
    assert converted == expected
    json.dumps(converted, allow_nan=False)  # strict JSON: no NaN, no Infinity
    assert all(type(v) in (float, type(None), list) for v in converted)


def test_a_result_becomes_the_dict_of_its_api_fields_only() -> None:
    point = solver.AirspeedPoint(
        RuntimeError("for Python callers only"),
        np.float64(23.0),
        "no_equilibrium",
        None,
        solver.PointFailure("beyond the fold", float("nan")),
    )
    assert payload(point) == {
        "velocity": 23.0,
        "status": "no_equilibrium",
        "equilibrium": None,
        "no_equilibrium": {"reason": "beyond the fold", "fold_velocity": None},
    }
    model = response_model(solver.AirspeedPoint)
    assert model.model_validate(payload(point)).no_equilibrium.fold_velocity is None  # type: ignore[attr-defined]


def test_an_equilibrium_becomes_strict_json_its_response_model_accepts() -> None:
    equilibrium = _equilibrium()
    body = payload(equilibrium)
    text = json.dumps(body, allow_nan=False)
    assert set(body) == {f.name for f in api_fields(solver.Equilibrium)}
    assert not {"wing", "flight", "options", "state", "evaluation"} & set(body)  # internal
    assert body["stations"]["heave"] == equilibrium.stations.heave.tolist()
    assert body["totals"]["lift"] == equilibrium.totals.lift
    again = SolveResponse.model_validate_json(text)
    assert again.totals.lift == equilibrium.totals.lift  # type: ignore[attr-defined]


# ------------------------------------------------------------------------ the models


def _reachable(cls: type, found: dict[str, type] | None = None) -> dict[str, type]:
    """Every result dataclass an answer of type `cls` holds, through its API fields."""
    found = {} if found is None else found
    if cls.__name__ in found:
        return found
    found[cls.__name__] = cls
    hints = typing.get_type_hints(cls)
    for field in api_fields(cls):
        stack = [hints[field.name]]
        while stack:
            hint = stack.pop()
            if dataclasses.is_dataclass(hint):
                _reachable(hint, found)  # type: ignore[arg-type]
            stack.extend(typing.get_args(hint))
    return found


# Every operation's result type, and every result type it holds (from the table: a new
# operation's answers are checked here without an edit).
RESULTS: dict[str, type] = {}
for _operation in solver.OPERATION_TABLE:
    RESULTS |= _reachable(_operation.result)


def test_the_answers_hold_every_result_type_the_names_speak_of() -> None:
    assert set(MODEL_NAMES) <= set(RESULTS)
    assert {"Stations", "Panels", "Totals", "Stability", "Fold", "Finding"} <= set(RESULTS)


@pytest.mark.parametrize("cls", list(RESULTS.values()), ids=list(RESULTS))
def test_every_result_field_is_in_its_response_model_with_its_unit(cls: type) -> None:
    model = response_model(cls)
    fields = api_fields(cls)
    added = API_ONLY_FIELDS.get(cls.__name__, {})
    assert set(model.model_fields) == {f.name for f in fields} | set(added)
    for field in fields:
        description = model.model_fields[field.name].description or ""
        unit = field.metadata["unit"]
        if unit:
            assert description.startswith(f"[{unit}] "), (field.name, description)
        text = field.metadata["description"].rstrip(".")
        assert text[1:] in description, (field.name, description)  # first letter capitalised
    for name, (_, default, text) in added.items():
        assert model.model_fields[name].default == default
        assert model.model_fields[name].description == text


@pytest.mark.parametrize("cls", list(RESULTS.values()), ids=list(RESULTS))
def test_a_response_model_refuses_a_member_the_result_has_not(cls: type) -> None:
    """extra=forbid: a payload with a field the solver did not declare is a defect, caught."""
    assert response_model(cls).model_config.get("extra") == "forbid"


def test_a_payload_with_an_undeclared_member_is_refused() -> None:
    body = payload(_equilibrium())
    body["totals"] = body["totals"] | {"lift_in_pounds": 68.7}
    with pytest.raises(ValidationError, match="lift_in_pounds"):
        SolveResponse.model_validate(body)


def test_array_fields_are_lists_of_numbers() -> None:
    heave = SolveResponse.model_json_schema()["$defs"]["Stations"]["properties"]["heave"]
    assert heave["type"] == "array" and heave["items"] == {"type": "number"}


# ---------------------------------------------------------------------------- the names


@pytest.mark.parametrize(("solver_name", "published"), list(MODEL_NAMES.items()))
def test_model_names_keep_the_published_component_names(solver_name: str, published: str) -> None:
    model = response_model(getattr(solver, solver_name))
    assert model.__name__ == published
    committed = json.loads(OPENAPI_PATH.read_text())["components"]["schemas"]
    assert published in committed
    assert solver_name not in committed or solver_name in MODEL_NAMES.values()


def test_the_top_level_responses_are_the_answers_models() -> None:
    assert SolveResponse is response_model(solver.Equilibrium)
    assert SweepResponse is response_model(solver.AirspeedSweep)
    assert OptimizeResponse is response_model(solver.OptimalDesign)
    assert response_model(solver.Equilibrium) is response_model(solver.Equilibrium)  # once


OPERATIONS: dict[str, tuple[type[BaseModel], type[BaseModel], dict[str, Any]]] = {
    "solve": (SolveRequest, SolveResponse, SOLVE_EXAMPLES),
    "sweep": (SweepRequest, SweepResponse, SWEEP_EXAMPLES),
    "optimize": (OptimizeRequest, OptimizeResponse, OPTIMIZE_EXAMPLES),
    "flutter": (FlutterRequest, FlutterResponse, FLUTTER_EXAMPLES),
    "roll": (RollRequest, RollResponse, ROLL_EXAMPLES),
    "controls": (ControlsRequest, ControlsResponse, CONTROLS_EXAMPLES),
}
# Every example that has an answer (the others are documented problems): equilibria with and
# without trim, a spar, a load factor; sweeps with failures and trim; both optimisations;
# flutter on strip theory and the lattice, about the jig and about an equilibrium; roll linearised,
# free and exact; control sweeps at an alpha and trimmed.
ANSWERED = [
    ("solve", "study"),
    ("solve", "at_its_weight"),
    ("solve", "tube_spar"),
    ("solve", "pull_up"),
    ("sweep", "study"),
    ("sweep", "to_the_fold"),
    ("sweep", "at_its_weight"),
    ("optimize", "study"),
    ("optimize", "aerosandbox_reference"),
    ("optimize", "multipoint"),
    ("flutter", "goland"),
    ("flutter", "goland_lattice"),
    ("flutter", "study_loaded"),
    ("roll", "study"),
    ("roll", "free_roll"),
    ("roll", "exact"),
    ("controls", "study"),
    ("controls", "at_its_weight"),
]


def _answer(operation: str, example: str) -> tuple[Answer, type[BaseModel]]:
    request_model, response_model, examples = OPERATIONS[operation]
    request = request_model.model_validate(examples[example]["value"])
    outcome = worker.run(task_of(request, Settings()))
    assert outcome.error is None and outcome.answer is not None, outcome.error
    return outcome.answer, response_model


@pytest.fixture(scope="module", params=ANSWERED, ids=["-".join(case) for case in ANSWERED])
def answered(request: pytest.FixtureRequest) -> tuple[Answer, type[BaseModel]]:
    return _answer(*request.param)


def test_every_answered_example_is_listed() -> None:
    """A new example with an answer is checked here too (or named a problem below)."""
    problems = {("solve", "beyond_divergence")}
    listed = set(ANSWERED) | problems
    every = {(op, name) for op, (_, _, examples) in OPERATIONS.items() for name in examples}
    assert every - listed == set()


@pytest.mark.parametrize("cached", [False, True], ids=["fresh", "cached"])
def test_the_body_is_exactly_what_the_response_model_describes(
    answered: tuple[Answer, type[BaseModel]], cached: bool
) -> None:
    """Strictly valid (no field missing, none extra: the models forbid extras), and the model's
    own serialisation of it is the same JSON value: every default present, every type its own."""
    answer, model = answered
    body = json.loads(answer.body(cached))
    validated = model.model_validate_json(answer.body(cached), strict=True)
    assert validated.model_dump(mode="json") == body


def test_a_cached_body_differs_only_in_its_service_fields(
    answered: tuple[Answer, type[BaseModel]],
) -> None:
    answer, _ = answered
    fresh, cached = json.loads(answer.body()), json.loads(answer.body(cached=True))
    if "solver" not in fresh:
        assert cached == fresh  # an optimum has no solver block to mark
        return
    assert fresh["solver"]["cached"] is False and cached["solver"]["cached"] is True
    assert cached["solver"]["seconds"] == 0.0
    service_fields = {"cached", "seconds"}
    assert {k: v for k, v in cached["solver"].items() if k not in service_fields} == {
        k: v for k, v in fresh["solver"].items() if k not in service_fields
    }
    assert {k: v for k, v in cached.items() if k != "solver"} == {
        k: v for k, v in fresh.items() if k != "solver"
    }


def test_numbers_survive_the_serialiser_to_the_bit() -> None:
    """pydantic-core writes the shortest decimal that reads back as the same double."""
    answer, _ = _answer("solve", "study")
    request = SolveRequest.model_validate(SOLVE_EXAMPLES["study"]["value"])
    result = task_of(request, Settings()).run(None)
    expected = payload(result)
    body = json.loads(answer.body())
    assert body["stations"] == expected["stations"]
    assert body["totals"] == expected["totals"]
