"""app.schemas.responses: an answer's body, serialised once in the worker, is exactly what the
response model of its operation describes (the models are not applied again on the way out), and
a cached answer differs from a fresh one only in its `solver` block's service fields."""

from __future__ import annotations

import json
from typing import Any

import pytest
from pydantic import BaseModel

from app.execution import worker
from app.schemas import (
    FLUTTER_EXAMPLES,
    OPTIMIZE_EXAMPLES,
    SOLVE_EXAMPLES,
    SWEEP_EXAMPLES,
    Answer,
    FlutterRequest,
    FlutterResponse,
    OptimizeRequest,
    OptimizeResponse,
    SolveRequest,
    SolveResponse,
    SweepRequest,
    SweepResponse,
    payload,
)
from app.service import task_of
from app.settings import Settings

OPERATIONS: dict[str, tuple[type[BaseModel], type[BaseModel], dict[str, Any]]] = {
    "solve": (SolveRequest, SolveResponse, SOLVE_EXAMPLES),
    "sweep": (SweepRequest, SweepResponse, SWEEP_EXAMPLES),
    "optimize": (OptimizeRequest, OptimizeResponse, OPTIMIZE_EXAMPLES),
    "flutter": (FlutterRequest, FlutterResponse, FLUTTER_EXAMPLES),
}
# Every example that has an answer (the others are documented problems): equilibria with and
# without trim, a spar, a load factor; sweeps with failures and trim; both optimisations;
# flutter on strip theory and the lattice, about the jig and about an equilibrium.
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
    ("flutter", "goland"),
    ("flutter", "goland_lattice"),
    ("flutter", "study_loaded"),
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
