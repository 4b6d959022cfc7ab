"""POST /sweep: equilibria over airspeeds and the divergence estimates."""

from __future__ import annotations

from typing import Annotated, Any

from fastapi import APIRouter, Body, Request

from app.routes.answers import answer
from app.routes.deps import ServiceDep
from app.routes.responses import SWEEP_ERRORS
from app.schemas import SWEEP_EXAMPLES, SweepRequest, SweepResponse

__all__ = ["router"]

router = APIRouter(tags=["equilibrium"])


@router.post(
    "/sweep",
    operation_id="sweep",
    response_model=SweepResponse,
    responses=SWEEP_ERRORS,
    summary="Equilibria of a wing over airspeeds, and its torsional divergence",
)
async def sweep(
    body: Annotated[SweepRequest, Body(openapi_examples=SWEEP_EXAMPLES)],
    request: Request,
    service: ServiceDep,
) -> Any:
    """Solves the airspeeds, answered in the given order, each on its own.

    At a fixed alpha the branch from the jig is traced to its fold first and each point is
    Newton from the branch's state at its dynamic pressure; trimmed (`flight.lift` or
    `flight.weight`) each point is trimmed at its speed. Either way a point depends on its own
    speed only, never on the order or on the other speeds, and agrees with /solve there.

    A point without equilibrium (beyond the fold) is reported in place with the reason; the
    response still succeeds. `divergence` holds three estimates: linear (eigenvalue at the
    unloaded jig), fit (the study's 1/A against q extrapolation) and fold (where the branch
    ends), each null with a reason when it does not exist; `validity` says from which airspeed
    on each finding about the points appears.
    """
    return await answer("sweep", body, request, service)
