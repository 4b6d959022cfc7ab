"""The HTTP API's models: request bodies derived from the solver's input types
(`app.schemas.derive`), responses from its result types (`app.schemas.responses`), the study's
examples, the operations routes' models, and the checks of the limits the settings set."""

from __future__ import annotations

from app.schemas.derive import RequestModel, request_model, to_solver
from app.schemas.examples import (
    CONTROLS_EXAMPLES,
    EXAMPLES,
    FLUTTER_EXAMPLES,
    OPTIMIZE_EXAMPLES,
    ROLL_EXAMPLES,
    SOLVE_EXAMPLES,
    SWEEP_EXAMPLES,
    study_wing,
)
from app.schemas.health import ClusterWorker, HealthResponse, ReadyResponse
from app.schemas.requests import (
    REQUESTS,
    ControlsRequest,
    FlutterRequest,
    OptimizeRequest,
    RollRequest,
    SolveRequest,
    SweepRequest,
    Wing,
)
from app.schemas.responses import (
    API_ONLY_FIELDS,
    MODEL_NAMES,
    RESPONSES,
    Answer,
    ControlsResponse,
    FlutterResponse,
    OptimizeResponse,
    RollResponse,
    SolveResponse,
    SweepResponse,
    api_fields,
    payload,
    response_model,
)

__all__ = [
    "API_ONLY_FIELDS",
    "EXAMPLES",
    "REQUESTS",
    "RESPONSES",
    "CONTROLS_EXAMPLES",
    "FLUTTER_EXAMPLES",
    "MODEL_NAMES",
    "OPTIMIZE_EXAMPLES",
    "ROLL_EXAMPLES",
    "SOLVE_EXAMPLES",
    "SWEEP_EXAMPLES",
    "Answer",
    "ControlsRequest",
    "ControlsResponse",
    "ClusterWorker",
    "FlutterRequest",
    "FlutterResponse",
    "HealthResponse",
    "OptimizeRequest",
    "OptimizeResponse",
    "ReadyResponse",
    "RequestModel",
    "RollRequest",
    "RollResponse",
    "SolveRequest",
    "SolveResponse",
    "SweepRequest",
    "SweepResponse",
    "Wing",
    "api_fields",
    "payload",
    "request_model",
    "response_model",
    "study_wing",
    "to_solver",
]
