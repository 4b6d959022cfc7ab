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


def _first(examples: dict[str, Any]) -> dict[str, Any]:
    value: dict[str, Any] = next(iter(examples.values()))["value"]
    return value


Wing = _with_example(request_model(solver.Wing), STUDY_WING)
Wing.__kept__ = 64  # the wings last asked about, built and digested once (a few kB each)
# Operation name -> its request body, derived from its solver input (`solver.OPERATION_TABLE`).
REQUESTS: dict[str, Any] = {
    operation.name: _with_example(request_model(operation.input), _first(EXAMPLES[operation.name]))
    for operation in solver.OPERATION_TABLE
}
SolveRequest = REQUESTS["solve"]
SweepRequest = REQUESTS["sweep"]
OptimizeRequest = REQUESTS["optimize"]
FlutterRequest = REQUESTS["flutter"]
RollRequest = REQUESTS["roll"]
ControlsRequest = REQUESTS["controls"]
