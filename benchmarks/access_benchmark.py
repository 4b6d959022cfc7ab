"""What API keys, rate limits and security headers cost per request (issue 16).

    .venv/bin/python benchmarks/access_benchmark.py [--requests 3000] [--rounds 5] [--keys 10]

1. In process: `app.security.AccessMiddleware` and `SecurityHeadersMiddleware` around an ASGI app
   that answers at once, against that app alone (a key ring of --keys keys, a token bucket): the
   CPU microseconds each layer adds.
2. Over HTTP: two servers started here on loopback, one with keys (--keys keys), the default rate
   limit and a CORS origin, one with none of it (no keys, FLEXWING_RATE_LIMIT=0); sequential
   requests on one keep-alive connection (http.client) to a cheap route (GET /problems/overloaded,
   a few hundred bytes, no solve) and to POST /solve (a repeated request: the result cache), the
   keyed server's with a key. Interleaved rounds of --requests each; medians and p99 per server.
Prints the machine's load average: the figures move with it on a shared machine.
"""

from __future__ import annotations

import argparse
import asyncio
import http.client
import json
import os
import statistics
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
sys.path.insert(0, str(Path(__file__).resolve().parent))

from load_benchmark import local_server_process

from app.metrics import Message, Metrics, Scope
from app.security import AccessMiddleware, SecurityHeadersMiddleware
from app.security.access import AccessMetrics
from app.security.keys import KeyRing, add_key
from app.security.ratelimit import TokenBuckets
from tests import study


async def _bare(scope: Scope, receive: Any, send: Any) -> None:
    await send({"type": "http.response.start", "status": 200, "headers": [(b"a", b"b")]})
    await send({"type": "http.response.body", "body": b"{}"})


def in_process(keys_file: Path, key: str, calls: int) -> dict[str, float]:
    """Microseconds per call of each stack."""
    ring = KeyRing(keys_file)
    buckets = TokenBuckets(rate=1e9, burst=10**9)  # never refuses: what a pass costs
    access = AccessMiddleware(_bare, ring, buckets, AccessMetrics(Metrics().registry))
    stacks = {
        "bare app": _bare,
        "+ key check and rate limit": access,
        "+ security headers": SecurityHeadersMiddleware(access),
    }
    scope = {
        "type": "http",
        "method": "GET",
        "path": "/jobs",
        "headers": [(b"authorization", f"Bearer {key}".encode()), (b"host", b"x")],
        "client": ("127.0.0.1", 5000),
    }

    async def receive() -> Message:
        return {"type": "http.request", "body": b"", "more_body": False}

    async def send(message: Message) -> None:
        return None

    async def run(app: Any) -> float:
        for _ in range(1000):
            await app(dict(scope), receive, send)
        started = time.process_time()  # CPU time: less at the mercy of a shared machine
        for _ in range(calls):
            await app(dict(scope), receive, send)
        return (time.process_time() - started) / calls * 1e6

    return {name: asyncio.run(run(app)) for name, app in stacks.items()}


def _times(
    port: int, method: str, path: str, body: bytes | None, headers: dict[str, str], n: int
) -> list[float]:
    connection = http.client.HTTPConnection("127.0.0.1", port, timeout=60)
    times = []
    try:
        for _ in range(n):
            started = time.perf_counter()
            connection.request(method, path, body=body, headers=headers)
            response = connection.getresponse()
            response.read()
            times.append(time.perf_counter() - started)
            assert response.status == 200, (path, response.status)
    finally:
        connection.close()
    return times


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--requests", type=int, default=3000)
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--keys", type=int, default=10)
    args = parser.parse_args()
    print(f"load average before: {os.getloadavg()}")
    with tempfile.TemporaryDirectory() as name:
        tmp = Path(name)
        keys_file = tmp / "keys.txt"
        key = add_key(keys_file, "bench")
        for n in range(args.keys - 1):
            add_key(keys_file, f"other-{n}")
        for stack, microseconds in in_process(keys_file, key, 100_000).items():
            print(f"in process, {stack:<28} {microseconds:7.2f} us per request")

        base = {"FLEXWING_WORKERS": "1", "FLEXWING_JOBS_DB": str(tmp / "jobs.sqlite3")}
        keyed = base | {
            "FLEXWING_API_KEYS_FILE": str(keys_file),
            "FLEXWING_RATE_LIMIT": "1000000",  # the default's work, never refusing the loop
            "FLEXWING_CORS_ORIGINS": '["https://wings.example.org"]',
        }
        solve = json.dumps(study.solve_request(10.0)).encode()
        routes = {
            "GET /problems/overloaded": ("GET", "/problems/overloaded", None),
            "POST /solve (cached)": ("POST", "/solve", solve),
        }
        samples: dict[tuple[str, str], list[float]] = {}
        with (
            local_server_process(base | {"FLEXWING_RATE_LIMIT": "0"}) as (open_url, _),
            local_server_process(keyed) as (keyed_url, _),
        ):
            servers = {
                "open (no keys, no limit)": (open_url, {}),
                "keys + limit + CORS": (keyed_url, {"Authorization": f"Bearer {key}"}),
            }
            for _ in range(args.rounds):
                for server, (url, auth) in servers.items():
                    port = int(url.rsplit(":", 1)[1])
                    for route, (method, path, body) in routes.items():
                        headers = auth | {"content-type": "application/json"}
                        times = _times(port, method, path, body, headers, args.requests)
                        samples.setdefault((server, route), []).extend(times)
        for (server, route), times in samples.items():
            times.sort()
            p50 = statistics.median(times) * 1e3
            p99 = times[int(0.99 * len(times))] * 1e3
            print(f"HTTP, {server:<26} {route:<24} p50 {p50:6.3f} ms  p99 {p99:6.3f} ms")
    print(f"load average after: {os.getloadavg()}")


if __name__ == "__main__":
    main()
