"""POST /roll and POST /controls: ailerons and flaps, control effectiveness and reversal."""

from __future__ import annotations

from typing import Annotated, Any

from fastapi import APIRouter, Body, Request

from app.routes.answers import answer
from app.routes.deps import ServiceDep
from app.routes.responses import CONTROLS_ERRORS, ROLL_ERRORS
from app.schemas import (
    CONTROLS_EXAMPLES,
    ROLL_EXAMPLES,
    ControlsRequest,
    ControlsResponse,
    RollRequest,
    RollResponse,
)

__all__ = ["effectiveness_router", "roll_router"]

# One router per operation: each is its own job operation with Prefer: respond-async.
roll_router = APIRouter(tags=["controls"])
effectiveness_router = APIRouter(tags=["controls"])


@roll_router.post(
    "/roll",
    operation_id="roll",
    response_model=RollResponse,
    responses=ROLL_ERRORS,
    summary="The antisymmetric response to the ailerons: rolling moment, both halves, free roll",
)
async def roll(
    body: Annotated[RollRequest, Body(openapi_examples=ROLL_EXAMPLES)],
    request: Request,
    service: ServiceDep,
) -> Any:
    """Both wings' heave, twist and loads with the ailerons deflected (the right wing's
    trailing edge down for a positive deflection, the left's up) and a steady roll rate; the
    rolling moment about the x axis through the root chord (positive raising the right wing)
    elastic and rigid; the hinge moments; with `free_roll`, the roll rate at which the rolling
    moment vanishes and its helix angle pb/2V.

    `method`: at alpha 0 with sections symmetric in z (no camber at the chordwise nodes, no
    jig twist, no flap deflected) the exact antisymmetric equilibrium; elsewhere the symmetric
    equilibrium (flaps included; trimmed, the one carrying the lift) with the antisymmetric
    disturbance linearised about it, as Nastran's antisymmetric subcase does about the jig.
    """
    return await answer("roll", body, request, service)


@effectiveness_router.post(
    "/controls",
    operation_id="controls",
    response_model=ControlsResponse,
    responses=CONTROLS_ERRORS,
    summary="Control effectiveness against airspeed, reversal and which comes first",
)
async def controls(
    body: Annotated[ControlsRequest, Body(openapi_examples=CONTROLS_EXAMPLES)],
    request: Request,
    service: ServiceDep,
) -> Any:
    """For every control surface at each airspeed: the rigid and the elastic control
    derivative (a flap's lift, an aileron's rolling moment, per degree), their ratio (the
    effectiveness: 1 rigid, 0 at reversal) and the hinge moment; for each surface the reversal
    speed as the eigenvalue of the exact Jacobians at the unloaded jig (Nastran SOL 144's
    question) and again where the sweep's derivative changes sign, the divergence of its
    problem (symmetric for a flap, antisymmetric for an aileron) and which comes first.
    A speed without an equilibrium is answered in its point (`status` no_equilibrium).
    """
    return await answer("controls", body, request, service)
