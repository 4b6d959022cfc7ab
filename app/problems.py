"""RFC 9457 problem details: every error the service returns is one of the types below.

A problem's `type` is a relative URI, ``/problems/<slug>``, that the service itself serves with a
description; clients should switch on it (or on the status) rather than parse `detail`.
"""

from __future__ import annotations

import logging
from collections.abc import Awaitable, Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from fastapi import FastAPI, Request
from fastapi.exceptions import RequestValidationError
from fastapi.responses import JSONResponse
from pydantic import BaseModel, ConfigDict, Field
from starlette.exceptions import HTTPException as StarletteHTTPException
from starlette.routing import Match
from starlette.types import ASGIApp, Message, Receive, Scope

from solver import (
    ConvergenceError,
    DynamicInstability,
    FoldedWing,
    InfeasibleDesign,
    InvalidInput,
    NoEquilibrium,
    SolverError,
)

__all__ = [
    "PROBLEM_MEDIA_TYPE",
    "SOLVER_PROBLEMS",
    "FieldError",
    "Problem",
    "ProblemDetails",
    "ProblemType",
    "PROBLEM_TYPES",
    "UnexpectedErrors",
    "install_handlers",
    "problem_body",
    "problem_of",
    "problem_response",
]

log = logging.getLogger(__name__)

PROBLEM_MEDIA_TYPE = "application/problem+json"


@dataclass(frozen=True)
class ProblemType:
    slug: str
    title: str
    status: int
    description: str

    @property
    def uri(self) -> str:
        return f"/problems/{self.slug}"


def _types(*types: ProblemType) -> dict[str, ProblemType]:
    return {t.slug: t for t in types}


PROBLEM_TYPES = _types(
    ProblemType(
        "invalid-input",
        "Invalid input",
        422,
        "The request does not describe a valid wing, flight condition or option. `errors` lists "
        "each bad field (a dotted path with list indices) and why.",
    ),
    ProblemType(
        "no-equilibrium",
        "No static equilibrium",
        422,
        "The wing has no static aeroelastic equilibrium at this airspeed on the branch from the "
        "jig shape: it lies beyond the fold (torsional divergence). `fold_velocity` [m/s] says "
        "where the branch ends, when it could be located.",
    ),
    ProblemType(
        "not-converged",
        "Solver did not converge",
        422,
        "Newton's method stopped without meeting the tolerance (`iterations`, `residual_norm`, "
        "`reason`). Try an initial guess, more iterations, or a lower airspeed.",
    ),
    ProblemType(
        "infeasible-design",
        "No feasible optimum",
        422,
        "The design problem has no acceptable optimum: `constraint` names the constraint that "
        "could not be met (lift, jig_twist, von_mises, tip_heave, stability_margin) or "
        "`optimizer` when IPOPT failed otherwise, and with load cases `case` the case it could "
        "not be met in. Relax it, or give the design more freedom.",
    ),
    ProblemType(
        "unstable",
        "Dynamically unstable",
        422,
        "The wing flutters or diverges at this airspeed: its linear aeroelastic system has a "
        "growing root (`growth_rate` [1/s], `frequency` [rad/s], 0 for divergence), so a gust "
        "has no bounded response. Fly slower, or stiffen the wing.",
    ),
    ProblemType(
        "body-too-large",
        "Request body too large",
        413,
        "The request body exceeds the limit (`max_body_bytes`, setting FLEXWING_MAX_BODY_BYTES).",
    ),
    ProblemType(
        "overloaded",
        "Service overloaded",
        503,
        "Too many solves are running or waiting (FLEXWING_MAX_PENDING). Retry after the "
        "Retry-After header's seconds.",
    ),
    ProblemType(
        "worker-lost",
        "Worker process lost",
        503,
        "The worker process running this request died (killed or out of memory). It has been "
        "replaced; the request may be retried.",
    ),
    ProblemType(
        "not-ready",
        "Service not ready",
        503,
        "The worker pool is still starting (compiling or loading solver code).",
    ),
    ProblemType(
        "solve-timeout",
        "Solve exceeded its time budget",
        504,
        "The solve ran longer than its budget (FLEXWING_SOLVE_TIMEOUT, FLEXWING_SWEEP_TIMEOUT "
        "or FLEXWING_OPTIMIZE_TIMEOUT, `timeout` [s]); its worker was recycled.",
    ),
    ProblemType("not-found", "Not found", 404, "No such resource."),
    ProblemType("method-not-allowed", "Method not allowed", 405, "Use another HTTP method."),
    ProblemType(
        "http-error", "HTTP error", 400, "A protocol-level error; see `status` and `detail`."
    ),
    ProblemType(
        "internal-error",
        "Internal error",
        500,
        "A bug in the service. Solve failures never end here: they have their own types.",
    ),
)


# A problem lists this many field errors at most: its size stays bounded whatever the request.
MAX_LISTED_ERRORS = 50


@dataclass(frozen=True)
class FieldError:
    """One bad input: `field` is a dotted path (``wing.chord[3]``), `reason` says what is wrong."""

    field: str
    reason: str


class Problem(Exception):
    """Raise to answer with a problem+json response of the given type."""

    def __init__(
        self,
        slug: str,
        detail: str,
        *,
        extensions: Mapping[str, Any] | None = None,
        headers: Mapping[str, str] | None = None,
        status: int | None = None,
    ) -> None:
        super().__init__(detail)
        self.type = PROBLEM_TYPES[slug]
        self.detail = detail
        self.extensions = dict(extensions or {})
        self.headers = dict(headers or {})
        self.status = status or self.type.status

    @classmethod
    def invalid(cls, errors: Sequence[FieldError]) -> Problem:
        """At most MAX_LISTED_ERRORS errors are listed; `error_count` gives them all."""
        listed = errors[:MAX_LISTED_ERRORS]
        fields = ", ".join(sorted({e.field for e in listed}))
        more = len(errors) - len(listed)
        return cls(
            "invalid-input",
            f"{len(errors)} invalid field(s): {fields}" + (f" and {more} more" if more else ""),
            extensions={
                "errors": [{"field": e.field, "reason": e.reason} for e in listed],
                "error_count": len(errors),
            },
        )


def _finite_or_none(value: float | None) -> float | None:
    return None if value is None or value != value or abs(value) == float("inf") else value


# The one table from the solver's typed errors to problem types: a solver error becomes a
# problem here and nowhere else (the worker passes the error itself along).
SOLVER_PROBLEMS: dict[type[Exception], Callable[[Any], Problem]] = {
    InvalidInput: lambda e: Problem.invalid([FieldError(e.field or "body", e.reason)]),
    FoldedWing: lambda e: Problem(
        "no-equilibrium",
        str(e),
        extensions={
            "velocity": e.velocity,
            "fold_velocity": None,
            "station": e.station,
            "field": f"stations[{e.station}]",
        },
    ),
    NoEquilibrium: lambda e: Problem(
        "no-equilibrium",
        str(e),
        extensions={"velocity": e.velocity, "fold_velocity": e.fold_velocity},
    ),
    ConvergenceError: lambda e: Problem(
        "not-converged",
        str(e),
        extensions={
            "velocity": e.velocity,
            "iterations": e.iterations,
            "residual_norm": _finite_or_none(e.residual_norm),
            "reason": e.reason,
        },
    ),
    InfeasibleDesign: lambda e: Problem(
        "infeasible-design",
        str(e),
        extensions={"constraint": e.constraint} | ({} if e.case is None else {"case": e.case}),
    ),
    DynamicInstability: lambda e: Problem(
        "unstable",
        str(e),
        extensions={
            "velocity": e.velocity,
            "growth_rate": e.growth_rate,
            "frequency": e.frequency,
        },
    ),
}


def problem_of(error: SolverError | InvalidInput) -> Problem:
    """The problem a solver error is answered with (`SOLVER_PROBLEMS`, by its class)."""
    for kind in type(error).__mro__:
        make = SOLVER_PROBLEMS.get(kind)
        if make is not None:
            return make(error)
    return Problem("not-converged", str(error), extensions={"reason": str(error)})


def problem_body(problem: Problem, instance: str | None = None) -> dict[str, Any]:
    """A problem as its problem+json body."""
    body: dict[str, Any] = {
        "type": problem.type.uri,
        "title": problem.type.title,
        "status": problem.status,
        "detail": problem.detail,
    }
    if instance is not None:
        body["instance"] = instance
    body.update(problem.extensions)
    return body


class ProblemFieldError(BaseModel):
    field: str = Field(description="Dotted path of the bad input, e.g. `wing.chord[3]`.")
    reason: str = Field(description="What is wrong with it.")


class ProblemDetails(BaseModel):
    """An RFC 9457 problem detail; extension members depend on `type`."""

    model_config = ConfigDict(extra="allow")

    type: str = Field(description="URI reference of the problem type, e.g. /problems/invalid-input")
    title: str = Field(description="Short summary of the problem type.")
    status: int = Field(description="HTTP status code.")
    detail: str = Field(description="What happened in this occurrence.")
    instance: str | None = Field(default=None, description="The request path.")
    errors: list[ProblemFieldError] | None = Field(
        default=None,
        description=f"invalid-input: each bad field and why (the first {MAX_LISTED_ERRORS}).",
    )
    error_count: int | None = Field(
        default=None, description="invalid-input: [-] how many fields are invalid in all."
    )
    fold_velocity: float | None = Field(
        default=None, description="no-equilibrium: [m/s] where the equilibrium branch ends."
    )
    constraint: str | None = Field(
        default=None, description="infeasible-design: the constraint that could not be met."
    )
    case: str | None = Field(
        default=None,
        description="infeasible-design of a problem with load cases: the case it could not be "
        "met in ('flight': the design flight; else a load case's name).",
    )


def problem_response(
    problem: Problem, instance: str | None = None, *, status: int | None = None
) -> JSONResponse:
    body = problem_body(problem, instance)
    if status is not None:
        body["status"] = status
    return JSONResponse(
        body,
        status_code=status or problem.status,
        media_type=PROBLEM_MEDIA_TYPE,
        headers=problem.headers or None,
    )


def _location(loc: Iterable[int | str]) -> str:
    """("body", "wing", "chord", 3) -> "wing.chord[3]"."""
    path = ""
    for part in loc:
        if isinstance(part, int):
            path += f"[{part}]"
        else:
            path += f".{part}" if path else str(part)
    return path


def validation_errors(raw: Sequence[Any]) -> list[FieldError]:
    """FastAPI/pydantic errors as field errors; `body.` is dropped from the paths."""
    errors: list[FieldError] = []
    for error in raw:
        loc = list(error.get("loc", ()))
        if loc and loc[0] == "body":
            loc = loc[1:]
        kind = error.get("type", "")
        # Drop the tags of the schemas' tagged unions ("@number", "@list", "@object", ...).
        loc = [p for p in loc if not (isinstance(p, str) and p.startswith("@"))]
        field = _location(loc) or "body"
        reason = str(error.get("msg", "invalid"))
        if kind == "json_invalid":
            field = "body"
            reason = f"invalid JSON: {error.get('ctx', {}).get('error', reason)}"
        errors.append(FieldError(field, reason))
    return errors


def _allowed_methods(request: Request) -> str:
    """Every method some route serves at this path (RFC 9110: a 405 lists them all in Allow;
    Starlette lists only those of the first route whose path matched). FastAPI's routes do not
    answer HEAD, so it is listed only where a route does (the static files)."""
    allowed = []
    for method in ("DELETE", "GET", "HEAD", "PATCH", "POST", "PUT"):
        scope = {**request.scope, "method": method}
        if any(route.matches(scope)[0] == Match.FULL for route in request.app.router.routes):
            allowed.append(method)
    return ", ".join(allowed)


def _internal_error(error: Exception, path: str) -> JSONResponse:
    """The answer to a defect: its exception's type, never its message or traceback."""
    return problem_response(Problem("internal-error", f"unexpected {type(error).__name__}"), path)


class UnexpectedErrors:
    """An exception no handler maps (a bug) becomes the internal-error problem here, inside every
    other middleware (pure ASGI). Starlette's own last resort sits outside them all, so its 500
    missed the security headers and the metrics, and it re-raises, which makes the server drop
    the connection: a client's next request on it failed too."""

    def __init__(self, app: ASGIApp) -> None:
        self.app = app

    async def __call__(
        self, scope: Scope, receive: Receive, send: Callable[[Message], Awaitable[None]]
    ) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return
        started = False

        async def send_tracked(message: Message) -> None:
            nonlocal started
            started = started or message["type"] == "http.response.start"
            await send(message)

        try:
            await self.app(scope, receive, send_tracked)
        except Exception as error:
            if started:
                raise  # half an answer is out: only closing the connection can say so
            log.exception("unexpected error answering %s %s", scope["method"], scope["path"])
            await _internal_error(error, scope["path"])(scope, receive, send)


def install_handlers(app: FastAPI) -> None:
    """Map every exception the app can see to a problem+json response. Call before adding any
    other middleware: `UnexpectedErrors` must be the innermost."""

    async def on_problem(request: Request, exc: Exception) -> JSONResponse:
        assert isinstance(exc, Problem)
        return problem_response(exc, request.url.path)

    async def on_validation(request: Request, exc: Exception) -> JSONResponse:
        assert isinstance(exc, RequestValidationError)
        return problem_response(Problem.invalid(validation_errors(exc.errors())), request.url.path)

    async def on_http(request: Request, exc: Exception) -> JSONResponse:
        assert isinstance(exc, StarletteHTTPException)
        if exc.status_code == 400:
            # FastAPI's only 400: a body it could not decode at all (e.g. not UTF-8).
            field = FieldError("body", f"invalid JSON: {exc.detail}")
            return problem_response(Problem.invalid([field]), request.url.path)
        slug = {404: "not-found", 405: "method-not-allowed", 413: "body-too-large"}.get(
            exc.status_code, "http-error"
        )
        headers = dict(exc.headers or {})
        if exc.status_code == 405:
            headers["Allow"] = _allowed_methods(request)
        problem = Problem(slug, str(exc.detail), headers=headers)
        return problem_response(problem, request.url.path, status=exc.status_code)

    async def on_error(request: Request, exc: Exception) -> JSONResponse:
        return _internal_error(exc, request.url.path)

    app.add_exception_handler(Problem, on_problem)
    app.add_exception_handler(RequestValidationError, on_validation)
    app.add_exception_handler(StarletteHTTPException, on_http)
    app.add_exception_handler(Exception, on_error)  # an error in a middleware itself
    app.add_middleware(UnexpectedErrors)
