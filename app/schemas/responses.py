"""The solver's result types as the API's response models and JSON payloads.

Result types are defined once, as dataclasses in `solver` with a unit and a description on every
field. This module derives the pydantic response models from them (`response_model`) and turns
solver results into JSON-ready dicts of the same shape (`payload`), so a field the solver reports
appears in the API, with its unit, and none can be dropped or invented by a copy that drifted.
The only fields the API adds are listed in `API_ONLY_FIELDS` (what the service itself knows, such
as whether the answer came from its cache).

An answer crosses the service as `Answer`: its JSON body, serialised once in the worker that
computed it (pydantic-core's serialiser, compact), and sent as it is. The response models
describe that body exactly (tests/app/schemas/test_responses.py validates every operation's
answers against them); they are not re-applied field by field on the way out.
"""

from __future__ import annotations

import dataclasses
import math
import types
import typing
from dataclasses import dataclass
from typing import Any, Literal, Union

import numpy as np
from pydantic import BaseModel, ConfigDict, Field, create_model
from pydantic_core import to_json

import solver

__all__ = [
    "API_ONLY_FIELDS",
    "Answer",
    "MODEL_NAMES",
    "RESPONSES",
    "ControlsResponse",
    "FlutterResponse",
    "LoadsResponse",
    "OptimizeResponse",
    "RollResponse",
    "SolveResponse",
    "SweepResponse",
    "api_fields",
    "payload",
    "response_model",
]

# Response model names that differ from the solver's class names (stable OpenAPI components).
MODEL_NAMES = {
    "AirspeedPoint": "SweepPoint",
    "AirspeedSweepInfo": "SweepInfo",
    "SolveInfo": "SolverInfo",
    "DivergenceSummary": "Divergence",
    "PointFailure": "NoEquilibrium",
    "ControlSweepPoint": "ControlsPoint",
}
# An operation's result model is named after it: POST /{name} answers {Name}Response.
MODEL_NAMES.update(
    {op.result.__name__: f"{op.name.title()}Response" for op in solver.OPERATION_TABLE}
)

# Fields the service adds to a solver type: name -> (type, default, description).
API_ONLY_FIELDS: dict[str, dict[str, tuple[Any, Any, str]]] = {
    "SolveInfo": {"cached": (bool, False, "Answered from the result cache without solving.")},
    "AirspeedSweepInfo": {
        "cached": (bool, False, "Answered from the result cache without solving.")
    },
    "FlutterInfo": {"cached": (bool, False, "Answered from the result cache without solving.")},
}

_models: dict[type, type[BaseModel]] = {}


def api_fields(cls: type) -> list[dataclasses.Field[Any]]:
    """The dataclass fields of `cls` the API carries (all but the internal ones)."""
    return [f for f in dataclasses.fields(cls) if not f.metadata.get("internal")]


def _describe(field: dataclasses.Field[Any]) -> str:
    unit = field.metadata.get("unit", "")
    text = str(field.metadata.get("description", ""))
    text = text[:1].upper() + text[1:] + ("" if text.endswith(".") else ".")
    return f"[{unit}] {text}" if unit else text


def _annotation(hint: Any) -> Any:
    """The pydantic type for a solver field's type."""
    if hint is np.ndarray:
        return list[float]
    origin = typing.get_origin(hint)
    if origin in (Union, types.UnionType):
        return Union[tuple(_annotation(arg) for arg in typing.get_args(hint))]  # noqa: UP007
    if origin is list:
        return list[_annotation(typing.get_args(hint)[0])]  # type: ignore[misc]
    if origin is Literal:
        return hint
    if dataclasses.is_dataclass(hint):
        return response_model(hint)  # type: ignore[arg-type]
    return hint


def response_model(cls: type) -> type[BaseModel]:
    """The pydantic model of a solver result dataclass (built once, nested types included)."""
    model = _models.get(cls)
    if model is not None:
        return model
    hints = typing.get_type_hints(cls)
    definitions: dict[str, Any] = {}
    for field in api_fields(cls):
        kwargs: dict[str, Any] = {"description": _describe(field)}
        if field.default is not dataclasses.MISSING:
            kwargs["default"] = field.default
        definitions[field.name] = (_annotation(hints[field.name]), Field(**kwargs))
    for name, (kind, default, description) in API_ONLY_FIELDS.get(cls.__name__, {}).items():
        definitions[name] = (kind, Field(default=default, description=description))
    name = MODEL_NAMES.get(cls.__name__, cls.__name__)
    model = create_model(  # type: ignore[call-overload]
        name,
        __config__=ConfigDict(extra="forbid"),
        __doc__=(cls.__doc__ or "").strip().splitlines()[0],
        **definitions,
    )
    _models[cls] = model
    return model  # type: ignore[no-any-return]


def payload(result: Any) -> Any:
    """A solver result as JSON-ready data: dataclasses as dicts of their API fields (and the
    service's own fields at their defaults), arrays as lists, non-finite numbers as None (JSON
    has no NaN or infinity)."""
    if dataclasses.is_dataclass(result) and not isinstance(result, type):
        data = {f.name: payload(getattr(result, f.name)) for f in api_fields(type(result))}
        for name, (_, default, _) in API_ONLY_FIELDS.get(type(result).__name__, {}).items():
            data[name] = default
        return data
    if isinstance(result, np.ndarray):
        if np.all(np.isfinite(result)):
            return result.tolist()
        return [payload(float(v)) for v in result]
    if isinstance(result, list | tuple):
        return [payload(v) for v in result]
    if isinstance(result, float | np.floating):
        value = float(result)
        return value if math.isfinite(value) else None
    if isinstance(result, np.integer):
        return int(result)
    if isinstance(result, np.bool_):
        return bool(result)
    return result


@dataclass(frozen=True)
class Answer:
    """A solver result as its response body, serialised once.

    `head`: the body's JSON object without its `solver` block; `info`: that block (None for a
    result without one). A fresh and a cached answer differ only there (`body`), so the cache
    keeps one copy and the service never parses or re-serialises a body.
    """

    head: bytes
    info: dict[str, Any] | None = None

    @classmethod
    def of(cls, result: Any) -> Answer:
        """The answer of a solver result (a dataclass of `solver`)."""
        data = payload(result)
        info = data.pop("solver", None)
        return cls(to_json(data), info)

    def body(self, cached: bool = False) -> bytes:
        """The JSON response body; `cached`: as answered from the result cache (no time spent
        solving)."""
        if self.info is None:
            return self.head
        info = self.info | {"cached": True, "seconds": 0.0} if cached else self.info
        # The block goes last: `head` is a JSON object, so it ends with "}".
        separator = b"," if len(self.head) > 2 else b""
        return self.head[:-1] + separator + b'"solver":' + to_json(info) + b"}"

    @property
    def nbytes(self) -> int:
        """[bytes] about what it holds in memory."""
        return len(self.head) + 64 * len(self.info or ()) + 200


# Operation name -> its response model, built at import from its result type (every nested
# model follows).
RESPONSES: dict[str, type[BaseModel]] = {
    operation.name: response_model(operation.result) for operation in solver.OPERATION_TABLE
}
SolveResponse = RESPONSES["solve"]
SweepResponse = RESPONSES["sweep"]
OptimizeResponse = RESPONSES["optimize"]
FlutterResponse = RESPONSES["flutter"]
RollResponse = RESPONSES["roll"]
ControlsResponse = RESPONSES["controls"]
LoadsResponse = RESPONSES["loads"]
