"""POST /solve: one static aeroelastic equilibrium."""

from __future__ import annotations

from typing import Annotated, Any

from fastapi import APIRouter, Body, Request

from app.routes.answers import answer
from app.routes.deps import ServiceDep
from app.routes.responses import SOLVE_ERRORS
from app.schemas import SOLVE_EXAMPLES, SolveRequest, SolveResponse

__all__ = ["router"]

router = APIRouter(tags=["equilibrium"])


@router.post(
    "/solve",
    operation_id="solve",
    response_model=SolveResponse,
    responses=SOLVE_ERRORS,
    summary="Static aeroelastic equilibrium of a wing at one flight condition",
)
async def solve(
    body: Annotated[SolveRequest, Body(openapi_examples=SOLVE_EXAMPLES)],
    request: Request,
    service: ServiceDep,
) -> Any:
    """Deformation, loads, totals and stability of the wing's equilibrium.

    The answer is the equilibrium on the branch from the jig shape at this condition, followed
    in dynamic pressure from the jig: it depends on the request only, never on what was asked
    before. A repeated request is answered from the result cache (`solver.cached`, the same
    numbers). Past torsional divergence there is no equilibrium: 422 `/problems/no-equilibrium`
    with the fold speed. `validity` says where the answer leaves the model's validity.
    """
    return await answer("solve", body, request, service)
