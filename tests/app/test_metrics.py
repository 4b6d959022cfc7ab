"""app.metrics: the Prometheus metrics one service instance publishes (names dashboards and
alerts depend on), each instance in a registry of its own, and every HTTP request counted and
timed by its route template, method and status, however it ends.

In process: the metrics middleware driven through raw ASGI messages, the app through the
`in_process` client (tests/app/conftest.py)."""

from __future__ import annotations

import asyncio
from typing import Any

import httpx
import pytest
from prometheus_client.metrics import MetricWrapperBase
from prometheus_client.parser import text_string_to_metric_families

from app.metrics import Metrics, MetricsMiddleware

# The published metrics: name -> (type, labels). Counters are exposed with a _total suffix.
PUBLISHED = {
    "flexwing_http_requests": ("counter", ("route", "method", "status")),
    "flexwing_http_request_duration_seconds": ("histogram", ("route", "method")),
    "flexwing_solves": ("counter", ("kind", "outcome")),
    "flexwing_solve_duration_seconds": ("histogram", ("kind",)),
    "flexwing_worker_task_duration_seconds": ("histogram", ()),
    "flexwing_cache_lookups": ("counter", ("cache", "result")),
    "flexwing_worker_restarts": ("counter", ("reason",)),
    "flexwing_requests_shed": ("counter", ()),
    "flexwing_pending_tasks": ("gauge", ()),
    "flexwing_running_tasks": ("gauge", ()),
    "flexwing_ready": ("gauge", ()),
    "flexwing_jobs": ("gauge", ("state",)),
    "flexwing_job_queue_length": ("gauge", ()),
    "flexwing_jobs_submitted": ("counter", ("operation",)),
    "flexwing_batch_items": ("counter", ("outcome",)),
}


def test_the_registry_holds_the_published_metrics_and_no_others() -> None:
    metrics = Metrics()
    # prometheus_client names a counter's family without its _total suffix.
    found = {family.name: family.type for family in metrics.registry.collect()}
    assert found == {name: kind for name, (kind, _) in PUBLISHED.items()}
    collectors = {
        family.name: collector
        for collector in vars(metrics).values()
        if isinstance(collector, MetricWrapperBase)
        for family in collector.collect()
    }
    assert set(collectors) == set(PUBLISHED)  # every one is an attribute of Metrics
    for name, (_, labels) in PUBLISHED.items():
        if not labels:
            continue
        collector = collectors[name]
        collector.labels(**dict.fromkeys(labels, "x"))  # ValueError for other label names
        (family,) = collector.collect()
        assert {frozenset(set(sample.labels) - {"le"}) for sample in family.samples} == {
            frozenset(labels)
        }, name


def test_each_instance_has_a_registry_of_its_own() -> None:
    """Two apps in one process (the tests make dozens) neither clash nor share counts."""
    first, second = Metrics(), Metrics()
    first.shed.inc()
    assert first.registry.get_sample_value("flexwing_requests_shed_total") == 1.0
    assert second.registry.get_sample_value("flexwing_requests_shed_total") == 0.0


def _samples(client: httpx.Client) -> dict[tuple[str, frozenset[tuple[str, str]]], float]:
    text = client.get("/metrics").text
    return {
        (sample.name, frozenset(sample.labels.items())): sample.value
        for family in text_string_to_metric_families(text)
        for sample in family.samples
    }


def _value(
    samples: dict[tuple[str, frozenset[tuple[str, str]]], float], name: str, **labels: str
) -> float:
    return samples.get((name, frozenset(labels.items())), 0.0)


REQUESTS = {
    "a route": ("GET", "/healthz", "/healthz", "200"),
    "a templated route": ("GET", "/problems/not-ready", "/problems/{slug}", "200"),
    "an unmatched path": ("GET", "/no-such-thing", "<unmatched>", "404"),
    "a refused body": ("POST", "/solve", "/solve", "422"),
}


@pytest.mark.parametrize(
    ("method", "path", "route", "status"), list(REQUESTS.values()), ids=list(REQUESTS)
)
def test_a_request_is_counted_and_timed_by_its_route_template_and_status(
    in_process: httpx.Client, method: str, path: str, route: str, status: str
) -> None:
    before = _samples(in_process)
    answered = in_process.request(method, path, json={} if method == "POST" else None)
    assert str(answered.status_code) == status
    after = _samples(in_process)
    counted = {"route": route, "method": method, "status": status}
    assert _value(after, "flexwing_http_requests_total", **counted) == (
        _value(before, "flexwing_http_requests_total", **counted) + 1
    )
    timed = {"route": route, "method": method}
    assert _value(after, "flexwing_http_request_duration_seconds_count", **timed) == (
        _value(before, "flexwing_http_request_duration_seconds_count", **timed) + 1
    )


def test_a_request_whose_app_fails_is_counted_as_a_500() -> None:
    """The middleware counts in a `finally`: an exception out of the app is a 500, and passes."""
    metrics = Metrics()

    async def failing(scope: Any, receive: Any, send: Any) -> None:
        raise RuntimeError("a defect")

    middleware = MetricsMiddleware(failing, metrics)
    scope = {"type": "http", "method": "GET", "path": "/x"}

    async def receive() -> dict[str, Any]:
        return {"type": "http.request", "body": b""}

    async def send(message: Any) -> None:
        pass

    with pytest.raises(RuntimeError):
        asyncio.run(middleware(scope, receive, send))
    labels = {"route": "<unmatched>", "method": "GET", "status": "500"}
    assert metrics.registry.get_sample_value("flexwing_http_requests_total", labels) == 1.0


def test_the_job_queue_gauge_reads_the_queue_when_scraped(in_process: httpx.Client) -> None:
    """No job runs in process: the gauge is read from the manager (0), never left unset."""
    samples = _samples(in_process)
    assert ("flexwing_job_queue_length", frozenset()) in samples
    assert _value(samples, "flexwing_job_queue_length") == 0.0
    assert _value(samples, "flexwing_ready") == 0.0  # no worker has started in process
