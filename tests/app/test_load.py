"""Load (issue 5, part 4), bounded for CI: the load generator of benchmarks/load_benchmark.py for
a few seconds. No latency is asserted here; the 60-second figures are in docs/performance.md.

- 16 clients on mixed /solve and /sweep traffic for 5 s: every request answered with 200.
- Sustained overload (32 clients against FLEXWING_MAX_PENDING=4): the excess is shed with 503
  /problems/overloaded and Retry-After, never queued beyond the limit, and every request is
  accounted for: answered or shed, as the server's own counters confirm.
"""

from __future__ import annotations

import asyncio
import http.client
import importlib.util
import sys
import time
from collections.abc import Callable
from pathlib import Path
from types import ModuleType

import pytest

from tests import study
from tests.app.conftest import ROOT, Server


def _load_benchmark() -> ModuleType:
    path = Path(ROOT) / "benchmarks" / "load_benchmark.py"
    spec = importlib.util.spec_from_file_location("load_benchmark", path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module  # dataclasses resolve their module
    spec.loader.exec_module(module)
    return module


load = _load_benchmark()


def test_16_clients_on_mixed_traffic_get_no_errors(server: Server) -> None:
    result = asyncio.run(load.run_phase(server.base_url, "ci", 16, 5.0, seed=7))
    kinds = {sample.kind for sample in result.answered}
    assert result.errors == {}, result.errors
    assert result.shed == 0
    assert kinds == {"solve", "sweep"}
    assert len(result.answered) == len(result.samples) > 16


@pytest.fixture(scope="module")
def small_queue_server(make_server: Callable[..., Server]) -> Server:
    return make_server("small_queue_server", FLEXWING_MAX_PENDING="4")


def test_sustained_overload_is_shed_not_queued(small_queue_server: Server) -> None:
    server = small_queue_server
    shed_before = server.metric("flexwing_requests_shed_total")
    answered_before = {
        path: server.metric("flexwing_http_requests_total", route=path, method="POST", status="200")
        for path in ("/solve", "/sweep")
    }
    result = asyncio.run(load.run_phase(server.base_url, "overload", 32, 4.0, seed=8))
    assert result.errors == {}, result.errors  # nothing but 200 and 503 overloaded
    assert result.shed > 0
    assert len(result.answered) > 0
    assert result.max_pending <= 4
    # Every request is accounted for by the server: shed ones and answered ones.
    assert server.metric("flexwing_requests_shed_total") - shed_before == result.shed
    for kind, path in (("solve", "/solve"), ("sweep", "/sweep")):
        answered = sum(sample.kind == kind for sample in result.answered)
        counted = server.metric(
            "flexwing_http_requests_total", route=path, method="POST", status="200"
        )
        assert counted - answered_before[path] == answered, kind
    # and the service answers normally once the load is gone
    with server.client() as client:
        assert client.post("/solve", json=study.solve_request(9.125)).status_code == 200


KEEP_ALIVE_CLIENT_EXPIRY = 5.0  # [s] httpx's default keepalive_expiry


def test_an_idle_connection_outlives_the_clients_keep_alive_expiry(server: Server) -> None:
    # uvicorn runs with --timeout-keep-alive 75 (README, Dockerfile): a connection idle for longer
    # than a client's own expiry is still open, so no client races the server's close.
    host, port = server.base_url.removeprefix("http://").split(":")
    connection = http.client.HTTPConnection(host, int(port), timeout=10)
    try:
        connection.request("GET", "/healthz")
        first = connection.getresponse()
        assert first.status == 200 and first.read()
        time.sleep(KEEP_ALIVE_CLIENT_EXPIRY + 1.0)
        connection.request("GET", "/healthz")  # same socket: http.client does not reconnect
        assert connection.getresponse().status == 200  # RemoteDisconnected once it is closed
    finally:
        connection.close()
