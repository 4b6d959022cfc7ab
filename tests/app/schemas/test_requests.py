"""app.schemas.requests: the request bodies of /solve, /sweep and /optimize (and their wing)
carry the design study's example in their JSON Schema, which validates against its own model;
the OpenAPI document publishes those schemas and each endpoint's named examples."""

from __future__ import annotations

from typing import Any

import httpx
import pytest

from app.schemas import OptimizeRequest, SolveRequest, SweepRequest, Wing
from app.schemas.examples import (
    OPTIMIZE_EXAMPLES,
    SOLVE_EXAMPLES,
    STUDY_OPTIMIZE,
    STUDY_SOLVE,
    STUDY_SWEEP_REQUEST,
    STUDY_WING,
    SWEEP_EXAMPLES,
)

MODELS = {
    "Wing": (Wing, STUDY_WING),
    "SolveRequest": (SolveRequest, STUDY_SOLVE),
    "SweepRequest": (SweepRequest, STUDY_SWEEP_REQUEST),
    "OptimizeRequest": (OptimizeRequest, STUDY_OPTIMIZE),
}


@pytest.mark.parametrize(("model", "example"), list(MODELS.values()), ids=list(MODELS))
def test_a_request_models_json_schema_carries_the_studys_example(
    model: Any, example: dict[str, Any]
) -> None:
    schema = model.model_json_schema()
    assert schema["examples"] == [example]
    assert model.model_validate(schema["examples"][0]) == model.model_validate(example)


@pytest.mark.parametrize("name", list(MODELS), ids=list(MODELS))
def test_the_document_publishes_each_models_example(in_process: httpx.Client, name: str) -> None:
    schemas = in_process.get("/openapi.json").json()["components"]["schemas"]
    assert schemas[name]["examples"] == [MODELS[name][1]]


ENDPOINT_EXAMPLES = {
    "/solve": SOLVE_EXAMPLES,
    "/sweep": SWEEP_EXAMPLES,
    "/optimize": OPTIMIZE_EXAMPLES,
}


def _offered(client: httpx.Client, path: str) -> dict[str, Any]:
    body = client.get("/openapi.json").json()["paths"][path]["post"]["requestBody"]
    assert body["required"] is True
    offered: dict[str, Any] = body["content"]["application/json"]["examples"]
    return offered


@pytest.mark.parametrize(
    "path",
    ["/solve", "/sweep", "/optimize"],
    ids=list(ENDPOINT_EXAMPLES),
)
def test_each_endpoint_offers_its_named_examples_as_written(
    in_process: httpx.Client, path: str
) -> None:
    assert _offered(in_process, path) == ENDPOINT_EXAMPLES[path]


@pytest.mark.parametrize("path", list(ENDPOINT_EXAMPLES), ids=list(ENDPOINT_EXAMPLES))
def test_each_endpoint_offers_the_study_first(in_process: httpx.Client, path: str) -> None:
    offered = _offered(in_process, path)
    assert list(offered) == list(ENDPOINT_EXAMPLES[path])
    assert next(iter(offered)) == "study"  # what /docs shows first
    assert offered["study"] == ENDPOINT_EXAMPLES[path]["study"]


@pytest.mark.parametrize(
    ("change", "field"),
    [
        ({"note": "x"}, "note"),  # another member
        ({"flight": STUDY_SOLVE["flight"] | {"velocity": "10"}}, "flight"),  # a string number
    ],
    ids=["extra-member", "string-number"],
)
def test_the_request_models_take_nothing_but_what_they_document(
    change: dict[str, Any], field: str
) -> None:
    """As the examples are written: strict JSON types, no member the schema does not list."""
    with pytest.raises(ValueError, match=field):
        SolveRequest.model_validate(STUDY_SOLVE | change)
