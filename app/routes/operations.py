"""POST /{name} for every operation of `solver.OPERATION_TABLE`: one router each, derived from
its row (request and response models, examples, tag, summary, description, error responses), so
a new operation needs no route of its own.

Each answers at once when its answer is ready within the wait, else 202 with the job it became
(`app.routes.answers`); `Prefer: respond-async` makes it a job at once (`app.routes.jobs`)."""

# No `from __future__ import annotations`: FastAPI reads each endpoint's body annotation, which
# names the operation's own request model, when the endpoint is defined.
from typing import Annotated, Any

from fastapi import APIRouter, Body, Request

import solver
from app.routes.answers import answer
from app.routes.deps import ServiceDep
from app.routes.responses import errors_of
from app.schemas import EXAMPLES, REQUESTS, RESPONSES

__all__ = ["router_of", "routers"]


def router_of(operation: solver.Operation) -> APIRouter:
    """The router of one operation: POST /{name}."""
    name = operation.name
    body_model = REQUESTS[name]
    examples = EXAMPLES[name]
    router = APIRouter(tags=[operation.tag])

    async def endpoint(
        body: Annotated[body_model, Body(openapi_examples=examples)],  # type: ignore[valid-type]
        request: Request,
        service: ServiceDep,
    ) -> Any:
        return await answer(name, body, request, service)

    endpoint.__name__ = name
    router.add_api_route(
        f"/{name}",
        endpoint,
        methods=["POST"],
        operation_id=name,
        response_model=RESPONSES[name],
        responses=errors_of(operation),
        summary=operation.summary,
        description=operation.description,
    )
    return router


def routers() -> dict[str, APIRouter]:
    """Operation name -> its router, in the table's order."""
    return {operation.name: router_of(operation) for operation in solver.OPERATION_TABLE}
