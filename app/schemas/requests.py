"""The request bodies of the operations, derived from the solver's operation inputs
(`solver.operations`, `app.schemas.derive`), with the design study's examples."""

from __future__ import annotations

from typing import Any

import solver
from app.schemas.derive import request_model
from app.schemas.examples import EXAMPLES, STUDY_WING

__all__ = [
    "REQUESTS",
    "ControlsRequest",
    "FlutterRequest",
    "OptimizeRequest",
    "RollRequest",
    "SolveRequest",
    "SweepRequest",
    "Wing",
]


def _with_example(model: Any, example: dict[str, Any]) -> Any:
    """The model, with `example` in its JSON Schema (what /docs shows first)."""
    model.model_config["json_schema_extra"] = {"examples": [example]}
    model.model_rebuild(force=True)
    return model


def _requiring(model: Any, requires: tuple[str, ...]) -> Any:
    """The model, its JSON Schema saying which optional parts the operation needs (the row's
    `requires`, "wing.mass"): required there, not null, and a list at least one long. Only the
    document changes: the solver's own check refuses a request without them (422 naming the
    part), with or without this."""
    if not requires:
        return model
    examples = model.model_config.get("json_schema_extra", {})

    def refine(schema: dict[str, Any]) -> None:
        schema.update(examples)
        for path in requires:
            parent, part = path.split(".")
            field = schema["properties"][parent]
            needed: dict[str, Any] = {"not": {"type": "null"}}
            if part in _LISTS:
                needed["minItems"] = 1
            described = {k: field.pop(k) for k in ("description",) if k in field}
            schema["properties"][parent] = {
                "allOf": [field, {"required": [part], "properties": {part: needed}}],
                **described,
            }

    model.model_config["json_schema_extra"] = refine
    model.model_rebuild(force=True)
    return model


# Parts that are lists (the wing's items): needed means at least one.
_LISTS = frozenset(name for name, spec in solver.specs(solver.Wing).items() if spec.form == "items")


def _first(examples: dict[str, Any]) -> dict[str, Any]:
    value: dict[str, Any] = next(iter(examples.values()))["value"]
    return value


Wing = _with_example(request_model(solver.Wing), STUDY_WING)
Wing.__kept__ = 64  # the wings last asked about, built and digested once (a few kB each)
# Operation name -> its request body, derived from its solver input (`solver.OPERATION_TABLE`).
REQUESTS: dict[str, Any] = {
    operation.name: _requiring(
        _with_example(request_model(operation.input), _first(EXAMPLES[operation.name])),
        operation.requires,
    )
    for operation in solver.OPERATION_TABLE
}
SolveRequest = REQUESTS["solve"]
SweepRequest = REQUESTS["sweep"]
OptimizeRequest = REQUESTS["optimize"]
FlutterRequest = REQUESTS["flutter"]
RollRequest = REQUESTS["roll"]
ControlsRequest = REQUESTS["controls"]
