"""POST /optimize: the jig twist (and spar wall) of the wing that flies."""

from __future__ import annotations

from typing import Annotated, Any

from fastapi import APIRouter, Body, Request

from app.routes.answers import answer
from app.routes.deps import ServiceDep
from app.routes.responses import OPTIMIZE_ERRORS
from app.schemas import OPTIMIZE_EXAMPLES, OptimizeRequest, OptimizeResponse

__all__ = ["router"]

router = APIRouter(tags=["design"])


@router.post(
    "/optimize",
    operation_id="optimize",
    response_model=OptimizeResponse,
    responses=OPTIMIZE_ERRORS,
    summary="Optimal jig twist (and spar wall) of a flexible wing carrying a lift",
)
async def optimize(
    body: Annotated[OptimizeRequest, Body(openapi_examples=OPTIMIZE_EXAMPLES)],
    request: Request,
    service: ServiceDep,
) -> Any:
    """Minimises the deformed wing's induced drag (near field or Trefftz plane) or its spar's
    mass while it carries the lift, by IPOPT on exact gradients of the coupled equilibrium.

    Answers the optimal design, the optimal wing's equilibrium (as /solve answers it), every
    constraint with its activity, span efficiencies and the rigid wing's optimum. No feasible
    optimum: 422 `/problems/infeasible-design` naming the constraint. Long problems can run as
    jobs (`POST /jobs` with operation `optimize`).
    """
    return await answer("optimize", body, request, service)
