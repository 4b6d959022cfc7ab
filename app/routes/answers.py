"""How a synchronous operation answers: at once when its answer is ready within the wait
(FLEXWING_SYNC_WAIT, or the client's `Prefer: wait=<seconds>` up to the operation's time
budget, RFC 7240), else 202 Accepted with `Location: /jobs/{id}`: the work runs on as a job,
nothing is lost and no valid request ends in a 504.

The wait counts from the request's arrival (`Arrival`, the outermost middleware), not from the
route: reading and checking the body, and writing the 202, are inside it, so a client whose
timeout is the wait gets its answer or its job."""

from __future__ import annotations

import asyncio
import time
from collections.abc import Callable
from typing import Any

from fastapi import Request
from fastapi.responses import JSONResponse, Response
from pydantic import BaseModel
from starlette.types import ASGIApp, Receive, Scope, Send

from app.jobs.manager import JobManager
from app.jobs.views import job_view
from app.security import owner
from app.service import Service, budget_of, parts_of

__all__ = ["RESPONSE_RESERVE", "Arrival", "answer", "preferred_wait", "remaining_wait"]

# [s] kept from the wait for what follows it, adopting the job and writing the 202 (measured
# ~1 ms idle; tens of times that on a loaded two-core machine): at most a tenth of the wait.
RESPONSE_RESERVE = 0.1


class Arrival:
    """Stamps each HTTP request with its arrival (`time.perf_counter()`, in its scope's state):
    the outermost middleware, so the wait counts everything the service does with it."""

    def __init__(self, app: ASGIApp) -> None:
        self.app = app

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] == "http":
            scope.setdefault("state", {})["arrived"] = time.perf_counter()
        await self.app(scope, receive, send)


def remaining_wait(wait: float, arrived: float | None, now: float) -> float:
    """[s] how long to wait for an answer: `wait` from the arrival, less what has passed and
    the reserve for writing the 202 (never negative)."""
    spent = 0.0 if arrived is None else now - arrived
    return max(0.0, wait - spent - min(RESPONSE_RESERVE, wait / 10))


class _Relay:
    """A running call's progress, passed on to whoever takes it (the job it becomes)."""

    def __init__(self) -> None:
        self.to: Callable[[int, int], None] | None = None

    def __call__(self, done: int, total: int) -> None:
        if self.to is not None:
            self.to(done, total)


def preferred_wait(prefer: str | None) -> float | None:
    """[s] the `wait` preference of a Prefer header (RFC 7240), or None."""
    for part in (prefer or "").split(","):
        token, _, value = part.split(";")[0].partition("=")
        if token.strip().lower() == "wait":
            try:
                seconds = float(value.strip().strip('"'))
            except ValueError:
                return None
            return seconds if seconds >= 0 else None
    return None


async def answer(operation: str, body: BaseModel, request: Request, service: Service) -> Any:
    """The answer of `body` to `operation`, or a 202 for the job it became past the wait."""
    task = service.task(body)  # an invalid request is its 422 here, never a job
    settings = service.settings
    budget = budget_of(operation, settings)
    wait = preferred_wait(request.headers.get("prefer"))
    wait = settings.sync_wait if wait is None else min(wait, budget)
    reports = _Relay()
    running = asyncio.ensure_future(service.run(operation, task, reports))
    # Waiting never cancels the work (past the wait it goes on as a job).
    arrived = request.scope.get("state", {}).get("arrived")
    await asyncio.wait((running,), timeout=remaining_wait(wait, arrived, time.perf_counter()))
    if running.done():
        # The worker's bytes as they are: the response model documents them, and is not
        # applied again here (tests/app/schemas/test_responses.py holds them to it).
        return Response(running.result(), media_type="application/json")
    manager: JobManager = request.app.state.jobs
    total = parts_of(operation, task)
    job = manager.adopt(operation, running, total, principal=owner(request))
    reports.to = lambda done, total: manager.progressed(job, done)
    view = job_view(job.row(), manager.operations)
    return JSONResponse(view, status_code=202, headers={"Location": view["links"]["self"]})
