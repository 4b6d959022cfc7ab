"""Prometheus metrics of one service instance, in a registry of its own (served at /metrics).

Only the web process records metrics; workers report what they did through their results.
"""

from __future__ import annotations

import time
from collections.abc import Awaitable, Callable, MutableMapping
from typing import Any

from prometheus_client import CollectorRegistry, Counter, Gauge, Histogram

__all__ = ["Metrics", "MetricsMiddleware"]

_LATENCY_BUCKETS = (
    0.001,
    0.002,
    0.003,
    0.005,
    0.0075,
    0.01,
    0.02,
    0.03,
    0.05,
    0.1,
    0.25,
    0.5,
    1.0,
    2.5,
    5.0,
    10.0,
    30.0,
)


class Metrics:
    def __init__(self) -> None:
        self.registry = CollectorRegistry()
        r = self.registry
        self.requests = Counter(
            "flexwing_http_requests",
            "HTTP requests answered, by route template, method and status.",
            ["route", "method", "status"],
            registry=r,
        )
        self.latency = Histogram(
            "flexwing_http_request_duration_seconds",
            "Time from request start to the end of the response [s].",
            ["route", "method"],
            buckets=_LATENCY_BUCKETS,
            registry=r,
        )
        self.solves = Counter(
            "flexwing_solves",
            "Jobs run in workers, by kind (solve, sweep) and outcome.",
            ["kind", "outcome"],
            registry=r,
        )
        self.solve_seconds = Histogram(
            "flexwing_solve_duration_seconds",
            "Wall time of a job from dispatch to result, by kind [s].",
            ["kind"],
            buckets=_LATENCY_BUCKETS,
            registry=r,
        )
        self.worker_seconds = Histogram(
            "flexwing_worker_task_duration_seconds",
            "Time a job ran inside a local worker process, without the trip there and back "
            "(FLEXWING_EXECUTOR=process) [s].",
            buckets=_LATENCY_BUCKETS,
            registry=r,
        )
        self.cache = Counter(
            "flexwing_cache_lookups",
            "Cache lookups by cache (result, warm_start) and result (hit, miss).",
            ["cache", "result"],
            registry=r,
        )
        self.worker_restarts = Counter(
            "flexwing_worker_restarts",
            "Worker processes replaced, by reason (died, timeout).",
            ["reason"],
            registry=r,
        )
        self.shed = Counter(
            "flexwing_requests_shed",
            "Solves refused with 503 because too many were pending.",
            registry=r,
        )
        self.pending = Gauge(
            "flexwing_pending_tasks",
            "Tasks (solves, sweeps, designs, batch items) running or waiting for a worker.",
            registry=r,
        )
        self.running = Gauge(
            "flexwing_running_tasks", "Tasks running in local workers now.", registry=r
        )
        self.ready = Gauge("flexwing_ready", "1 when the worker pool is warm.", registry=r)
        # Jobs (POST /jobs, issue 13).
        self.jobs = Gauge(
            "flexwing_jobs",
            "Jobs in the jobs database (not expired), by state.",
            ["state"],
            registry=r,
        )
        self.job_queue = Gauge(
            "flexwing_job_queue_length", "Jobs waiting for a runner to start them.", registry=r
        )
        self.jobs_submitted = Counter(
            "flexwing_jobs_submitted", "Jobs accepted, by operation.", ["operation"], registry=r
        )
        self.batch_items = Counter(
            "flexwing_batch_items",
            "Batch items answered, by outcome (ok, problem); its rate is items per second.",
            ["outcome"],
            registry=r,
        )


Scope = MutableMapping[str, Any]
Message = MutableMapping[str, Any]
ASGIApp = Callable[
    [Scope, Callable[[], Awaitable[Message]], Callable[[Message], Awaitable[None]]],
    Awaitable[None],
]


class MetricsMiddleware:
    """Counts and times every HTTP request by its route template (pure ASGI, no body copies)."""

    def __init__(self, app: ASGIApp, metrics: Metrics) -> None:
        self.app = app
        self.metrics = metrics

    async def __call__(
        self,
        scope: Scope,
        receive: Callable[[], Awaitable[Message]],
        send: Callable[[Message], Awaitable[None]],
    ) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return
        started = time.perf_counter()
        status = 500

        async def send_wrapper(message: Message) -> None:
            nonlocal status
            if message["type"] == "http.response.start":
                status = message["status"]
            await send(message)

        try:
            await self.app(scope, receive, send_wrapper)
        finally:
            route = scope.get("route")
            template = getattr(route, "path", None) or "<unmatched>"
            method = scope.get("method", "")
            self.metrics.requests.labels(template, method, str(status)).inc()
            self.metrics.latency.labels(template, method).observe(time.perf_counter() - started)
