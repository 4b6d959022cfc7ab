"""POST /wing/stations: a wing's stations as the solver takes them.

A wing may be given in several forms (`y` as {semispan, stations}, one number for every
station, the stiffnesses from a tube spar...); the solver expands each into one value per
station (`solver.Wing.create`). This route answers that expansion, so that a client that shows
or edits a wing station by station (the page's station table) needs no second implementation
of it: the numbers are the solver's own, to the last digit. It runs no solve (no worker), and
validates the wing exactly as every operation does (`app.service.task_of`: the service's limits,
then the solver's checks, each bad field named from `wing`).

The answer has one list of N values for every per-station field of `solver.Wing` (derived from
its declarations, so a new per-station field appears here without an edit), null for an
optional one the wing does not have.
"""

from __future__ import annotations

import re
import types
import typing
from typing import Annotated, Any, ClassVar

import numpy as np
from fastapi import APIRouter, Body
from pydantic import BaseModel, Field, create_model

import solver
from app.problems import ProblemDetails
from app.routes.deps import ServiceDep
from app.schemas import Wing
from app.schemas.derive import RequestModel
from app.schemas.examples import GOLAND_WING

__all__ = ["WingBody", "WingStations", "router"]

router = APIRouter(tags=["wing"])

# The solver's forms of one value per station: the positions and every per-station field.
_STATION_FORMS = ("positions", "per_station")
STATION_FIELDS: dict[str, solver.Spec] = {
    name: spec
    for name, spec in solver.fields.specs(solver.Wing).items()
    if spec.form in _STATION_FORMS
}


def _wing(wing: Any) -> Any:
    return wing


class WingBody(RequestModel):
    """A wing, as every operation's body carries it."""

    __solver__: ClassVar[Any] = staticmethod(_wing)

    wing: Wing = Field(description="The wing, in any form the operations accept.")  # type: ignore[valid-type]


def _station_field(name: str, spec: solver.Spec) -> tuple[Any, Any]:
    unit = f"[{spec.unit}] " if spec.unit else ""
    # The spec's first clause, without what it says of the request ("(required unless...)").
    text = re.sub(r" \(required [^)]*\)", "", spec.description.split(":")[0])
    description = f"{unit}{text[:1].upper()}{text[1:]}: N values"
    # Optional in the solver's wing (None after `Wing.create` when not given): null here too.
    hint = typing.get_type_hints(solver.Wing)[name]
    if isinstance(hint, types.UnionType) and type(None) in typing.get_args(hint):
        return list[float] | None, Field(description=f"{description}, or null when not given.")
    return list[float], Field(description=f"{description}.")


WING_ERRORS: dict[int | str, dict[str, Any]] = {
    413: {
        "model": ProblemDetails,
        "description": "Request body too large (/problems/body-too-large).",
    },
    422: {
        "model": ProblemDetails,
        "description": "Invalid input (/problems/invalid-input, `errors` names each bad field).",
    },
}


WingStations: type[BaseModel] = create_model(  # type: ignore[call-overload]
    "WingStations",
    __doc__="The wing's stations as the solver takes them: every per-station field at every "
    "station (y first, root to tip).",
    **{name: _station_field(name, spec) for name, spec in STATION_FIELDS.items()},
)


@router.post(
    "/wing/stations",
    operation_id="wing_stations",
    response_model=WingStations,
    responses=WING_ERRORS,
    summary="A wing's stations as the solver takes them: every per-station value at each station",
)
async def stations(
    body: Annotated[
        WingBody,
        Body(
            openapi_examples={
                "goland": {
                    "summary": "The Goland wing: 30 evenly spaced stations, one chord and "
                    "stiffness for all",
                    "value": {"wing": GOLAND_WING},
                }
            }
        ),
    ],
    service: ServiceDep,
) -> Any:
    """The wing's per-station fields, each as its N values: `y` from {semispan, stations},
    one number for every station repeated, the stiffnesses a tube spar gives. The same
    validation as every operation's (a 422 names each bad field from `wing`); no solve."""
    wing = service.task(body)
    return {
        name: None if getattr(wing, name) is None else np.asarray(getattr(wing, name)).tolist()
        for name in STATION_FIELDS
    }
