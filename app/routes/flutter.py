"""POST /flutter: the wing's vibration modes and its flutter and divergence speeds."""

from __future__ import annotations

from typing import Annotated, Any

from fastapi import APIRouter, Body, Request

from app.routes.answers import answer
from app.routes.deps import ServiceDep
from app.routes.responses import FLUTTER_ERRORS
from app.schemas import FLUTTER_EXAMPLES, FlutterRequest, FlutterResponse

__all__ = ["router"]

router = APIRouter(tags=["dynamics"])


@router.post(
    "/flutter",
    operation_id="flutter",
    response_model=FlutterResponse,
    responses=FLUTTER_ERRORS,
    summary="Vibration modes, V-g and V-f diagrams, flutter and divergence speeds of a wing",
)
async def flutter(
    body: Annotated[FlutterRequest, Body(openapi_examples=FLUTTER_EXAMPLES)],
    request: Request,
    service: ServiceDep,
) -> Any:
    """The p-k method (Hassig) over the airspeeds: damping and frequency of every mode at each
    (`points`), the flutter speed and frequency (the first crossing to negative damping; damping
    = -Re(s)/|s|, positive decays) and the mode that flutters, the divergence speed (the
    zero-frequency root: the static linear divergence about the jig, the fold or the trimmed
    limit about a loaded wing), and the natural modes with their shapes.

    Linearised about the static equilibrium of `flight` at each airspeed (its tangent
    stiffness, aerodynamic stiffness included), or about the unloaded jig (`flutter.about`).
    `options.aerodynamics`: strip (Theodorsen's strip theory, the model of the published
    results) or lattice (the lattice's steady 3D circulation with Theodorsen's lag). Needs
    `wing.mass` (422 naming it without). No flutter in the range: `status`
    `no_flutter_in_range`, with the least damped mode.
    """
    return await answer("flutter", body, request, service)
