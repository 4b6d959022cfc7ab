"""The request bodies of the operations, derived from the solver's operation inputs
(`solver.operations`, `app.schemas.derive`), with the design study's examples."""

from __future__ import annotations

from typing import Any

import solver
from app.schemas.derive import request_model
from app.schemas.examples import (
    GOLAND_FLUTTER,
    STUDY_CONTROLS,
    STUDY_OPTIMIZE,
    STUDY_ROLL,
    STUDY_SOLVE,
    STUDY_SWEEP_REQUEST,
    STUDY_WING,
)

__all__ = [
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


Wing = _with_example(request_model(solver.Wing), STUDY_WING)
Wing.__kept__ = 64  # the wings last asked about, built and digested once (a few kB each)
SolveRequest = _with_example(request_model(solver.SolveInput), STUDY_SOLVE)
SweepRequest = _with_example(request_model(solver.SweepInput), STUDY_SWEEP_REQUEST)
OptimizeRequest = _with_example(request_model(solver.OptimizeInput), STUDY_OPTIMIZE)
FlutterRequest = _with_example(request_model(solver.FlutterInput), GOLAND_FLUTTER)
RollRequest = _with_example(request_model(solver.RollInput), STUDY_ROLL)
ControlsRequest = _with_example(request_model(solver.ControlsInput), STUDY_CONTROLS)
