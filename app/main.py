"""The ASGI application: ``uvicorn app.main:app``.

`create_app` wires settings, metrics, the worker pool and the service together; the pool starts
(and warms in the background) in the lifespan, so importing this module starts no process and
`openapi/generate.py` can build the schema without workers.
"""

from __future__ import annotations

from collections.abc import AsyncIterator, Awaitable, Callable, Iterator, Mapping
from contextlib import asynccontextmanager
from typing import Any

from fastapi import Depends, FastAPI
from fastapi.encoders import jsonable_encoder
from fastapi.openapi.utils import get_openapi
from fastapi.routing import APIRoute
from fastapi.staticfiles import StaticFiles

import solver
from app import __version__, security
from app.execution.pool import WorkerPool
from app.jobs import JobManager
from app.jobs.store import Store
from app.metrics import ASGIApp, Message, Metrics, MetricsMiddleware, Scope
from app.problems import PROBLEM_MEDIA_TYPE, Problem, install_handlers, problem_response
from app.routes import health, operations, page, wing
from app.routes import jobs as job_routes
from app.routes.answers import Arrival
from app.service import Service
from app.settings import Settings, get_settings

__all__ = ["app", "create_app"]

DESCRIPTION = """\
Static aeroelastic equilibrium of flexible wings: a vortex lattice (1 to 8 chordwise panels per
strip; the study's model has one) coupled to a cantilever beam, solved as one nonlinear system by
Newton's method on an exact Jacobian (see the design study, chapter 14).

Units are SI, angles in degrees. Errors are RFC 9457 `application/problem+json`; the `type` of
each problem is a URI under `/problems/`. The examples are the design study's wing.
"""


class BodyLimitMiddleware:
    """413 for a request body over `limit` bytes, declared or streamed (pure ASGI); paths in
    `path_limits` have limits of their own (POST /jobs: a batch of 10,000 solves)."""

    def __init__(
        self, app: ASGIApp, limit: int, path_limits: Mapping[str, tuple[int, str]] | None = None
    ) -> None:
        self.app = app
        self.limit = limit
        self.path_limits = dict(path_limits or {})

    def _too_large(self, size: str, limit: int, setting: str) -> Problem:
        return Problem(
            "body-too-large",
            f"the request body has {size} bytes; at most {limit} are accepted ({setting})",
            extensions={"max_body_bytes": limit},
        )

    async def __call__(
        self,
        scope: Scope,
        receive: Callable[[], Awaitable[Message]],
        send: Callable[[Message], Awaitable[None]],
    ) -> None:
        if scope["type"] != "http" or scope["method"] not in ("POST", "PUT", "PATCH"):
            await self.app(scope, receive, send)
            return
        limit, setting = self.path_limits.get(
            scope["path"], (self.limit, "FLEXWING_MAX_BODY_BYTES")
        )
        headers = dict(scope.get("headers") or [])
        declared = headers.get(b"content-length")
        if declared is not None and declared.isdigit() and int(declared) > limit:
            too_large = self._too_large(declared.decode(), limit, setting)
            await problem_response(too_large, scope["path"])(scope, receive, send)
            return
        chunks: list[bytes] = []
        size = 0
        while True:
            message = await receive()
            if message["type"] != "http.request":
                break  # disconnected
            chunks.append(message.get("body", b""))
            size += len(chunks[-1])
            if size > limit:
                too_large = self._too_large(f"more than {limit}", limit, setting)
                await problem_response(too_large, scope["path"])(scope, receive, send)
                return
            if not message.get("more_body", False):
                break
        body = b"".join(chunks)
        replayed = False

        async def replay() -> Message:
            nonlocal replayed
            if not replayed:
                replayed = True
                return {"type": "http.request", "body": body, "more_body": False}
            return await receive()

        await self.app(scope, replay, send)


def _apply_limits(node: Any, settings: Settings) -> None:
    """Write the configured limits where the schema marks them (`x-flexwing-limit`): maxItems of
    a list, maximum of a count."""
    if isinstance(node, dict):
        limit = node.pop("x-flexwing-limit", None)
        if limit is not None:
            value = getattr(settings, limit)
            node["maxItems" if node.get("type") == "array" else "maximum"] = value
        for child in node.values():
            _apply_limits(child, settings)
    elif isinstance(node, list):
        for child in node:
            _apply_limits(child, settings)


def _api_routes(routes: list[Any]) -> Iterator[APIRoute]:
    """Every API route, those of included routers too."""
    for route in routes:
        if isinstance(route, APIRoute):
            yield route
        included = getattr(route, "original_router", None)  # an include_router wrapper
        if included is not None:
            yield from _api_routes(included.routes)


def _restore_examples(schema: dict[str, Any], app: FastAPI) -> None:
    """Request body examples exactly as written: FastAPI writes the document without nulls,
    which would change an example's meaning (a null `control_points` is every station)."""
    for route in _api_routes(app.routes):
        examples = getattr(
            route.body_field.field_info if route.body_field else None, "openapi_examples", None
        )
        if not examples:
            continue
        for method in route.methods or ():
            operation = schema["paths"].get(route.path_format, {}).get(method.lower())
            content = (operation or {}).get("requestBody", {}).get("content", {})
            if "application/json" in content:
                content["application/json"]["examples"] = jsonable_encoder(examples)


def _openapi(app: FastAPI, settings: Settings) -> Callable[[], dict[str, Any]]:
    """The OpenAPI document, with error responses as application/problem+json and the
    configured limits."""

    def build() -> dict[str, Any]:
        if app.openapi_schema is not None:
            return app.openapi_schema
        schema = get_openapi(
            title=app.title,
            version=app.version,
            description=app.description,
            routes=app.routes,
            tags=[
                *({"name": tag, "description": text} for tag, text in solver.TAGS.items()),
                {"name": "jobs", "description": "Long work in the background, and batches."},
                {"name": "wing", "description": "A wing as the solver takes it."},
                {"name": "operations", "description": "Liveness, readiness and metrics."},
            ],
        )
        for path in schema.get("paths", {}).values():
            for operation in path.values():
                for response in operation.get("responses", {}).values():
                    content = response.get("content", {})
                    ref = content.get("application/json", {}).get("schema", {}).get("$ref", "")
                    if ref.endswith("/ProblemDetails"):
                        content[PROBLEM_MEDIA_TYPE] = content.pop("application/json")
        _restore_examples(schema, app)
        _apply_limits(schema, settings)
        security.document(schema, settings)
        app.openapi_schema = schema
        return schema

    return build


def create_app(settings: Settings | None = None) -> FastAPI:
    settings = settings or get_settings()
    metrics = Metrics()
    pool = WorkerPool(settings, metrics)
    service = Service(settings, pool, metrics)
    # The jobs, and with replicas (PostgreSQL) the API keys and rate-limit buckets: opened in
    # the lifespan; an unreachable database is retried there, not a failed start (/readyz).
    store = Store.of(settings.database_url, settings.jobs_db, settings.retry_after)
    jobs = JobManager(settings, service, metrics, store=store)

    @asynccontextmanager
    async def lifespan(app: FastAPI) -> AsyncIterator[None]:
        await pool.start()
        await jobs.start()
        try:
            yield
        finally:
            await jobs.close()
            await pool.close()

    app = FastAPI(
        title="flexwing",
        version=__version__,
        description=DESCRIPTION,
        lifespan=lifespan,
        docs_url=None,  # /docs is app.routes.page's: Swagger UI from vendored files, no CDN
        redoc_url=None,
    )
    app.state.settings = settings
    app.state.metrics = metrics
    app.state.pool = pool
    app.state.service = service
    install_handlers(app)
    # Each operation answers 202 with a job past its wait (app.routes.answers), or at once
    # with Prefer: respond-async.
    for name, router in operations.routers().items():
        at_once = Depends(job_routes.respond_async(name))
        app.include_router(router, dependencies=[at_once], responses=job_routes.ACCEPTED)
    for module in (health, page, wing):
        app.include_router(module.router)
    job_routes.install(app, jobs)
    app.mount("/static", StaticFiles(directory=page.STATIC_DIR), name="static")
    job_body = (settings.max_job_body_bytes, "FLEXWING_MAX_JOB_BODY_BYTES")
    app.add_middleware(
        BodyLimitMiddleware, limit=settings.max_body_bytes, path_limits={"/jobs": job_body}
    )
    # API keys and rate limits, inside the metrics
    security.install_access(app, settings, metrics, store)
    app.add_middleware(MetricsMiddleware, metrics=metrics)
    security.install_headers(app, settings)  # CORS and security headers on every response
    app.add_middleware(Arrival)  # outermost: a synchronous wait counts from the arrival
    app.openapi = _openapi(app, settings)  # type: ignore[method-assign]
    return app


app = create_app()
