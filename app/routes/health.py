"""Liveness, readiness, metrics and problem-type descriptions."""

from __future__ import annotations

from typing import Any

from fastapi import APIRouter, Request
from fastapi.responses import JSONResponse, Response
from prometheus_client import CONTENT_TYPE_LATEST, generate_latest

from app.problems import PROBLEM_TYPES, Problem
from app.schemas import HealthResponse, ReadyResponse
from solver import is_compiled

__all__ = ["router"]

router = APIRouter(tags=["operations"])


@router.get("/healthz", operation_id="healthz", response_model=HealthResponse)
async def healthz() -> Any:
    """The process is alive and its event loop answers."""
    return {"status": "ok"}


@router.get(
    "/readyz",
    operation_id="readyz",
    response_model=ReadyResponse,
    responses={
        503: {
            "model": ReadyResponse,
            "description": (
                "Workers are not warm yet, or the jobs database cannot be reached (`detail` "
                "names it and says why)."
            ),
        }
    },
)
async def readyz(request: Request) -> Any:
    """Ready once every worker has built (compiled, loaded, or on CasADi's virtual machine
    while its library compiles) the solver for the warm mesh sizes, and the jobs database
    (FLEXWING_DATABASE_URL, or the SQLite file) answers: a replica whose database is away is
    taken out of the load balancer's rotation, not restarted (/healthz stays 200)."""
    pool = request.app.state.pool
    store = request.app.state.jobs.store
    compiled = [n for n in pool.warm_stations if is_compiled(n)]
    detail = pool.detail
    on_the_vm = [str(n) for n in pool.warm_stations if n not in compiled]
    if pool.ready and on_the_vm:
        detail += (
            f"; N = {', '.join(on_the_vm)} on CasADi's virtual machine (no compiled library yet)"
        )
    if store.available:
        detail += f"; jobs database {store.name}"
    elif store.is_open:  # (not open: the app has not started, which "not started" says)
        detail += f"; jobs database {store.name} unavailable: {store.reason}"
    ready = pool.ready and store.available
    body = ReadyResponse(
        ready=ready,
        workers=pool.settings.workers,
        pids=pool.pids(),
        warm_stations=list(pool.warm_stations),
        compiled=compiled,
        detail=detail,
        cluster=pool.cluster(),
    )
    return JSONResponse(body.model_dump(), status_code=200 if ready else 503)


@router.get("/metrics", include_in_schema=False)
async def metrics(request: Request) -> Response:
    return Response(
        generate_latest(request.app.state.metrics.registry), media_type=CONTENT_TYPE_LATEST
    )


@router.get("/problems/{slug}", include_in_schema=False)
async def problem_type(slug: str) -> Any:
    """The description of a problem type (the target of a problem's `type` URI)."""
    kind = PROBLEM_TYPES.get(slug)
    if kind is None:
        raise Problem("not-found", f"no problem type {slug!r}")
    return {
        "type": kind.uri,
        "title": kind.title,
        "status": kind.status,
        "description": kind.description,
    }
