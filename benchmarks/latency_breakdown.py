"""Where a sequential /solve spends its time outside the worker, stage by stage, live.

    OPENBLAS_NUM_THREADS=1 .venv/bin/python benchmarks/latency_breakdown.py [--requests 2000]

Starts the service (uvicorn, the default settings, FLEXWING_WORKERS = CPU count) in a child
process with timestamps taken at the seams of one request (`time.perf_counter`, the system's
monotonic clock, so the client's and the service's stamps compare): the ASGI app's entry, the
body read, the route's entry and return, the solver input built (`Service.task`), the pool
entered (`Service.run`), the task pickled and written to a worker's pipe, the worker's answer
read (with the time the worker itself says it ran the task), the response's start and its
body written. A raw keep-alive client (`http_benchmark.RawClient`) posts distinct /solve
requests one after another (the study's wing, 6-20 m/s, alpha 5 deg: every one solved from the
jig) and stamps its send and its receipt of the whole answer.

Printed: each stage's mean and median over the last 90 % of the requests, and the whole
request's time outside the worker (issue 27's "within 1 ms of the worker's own solve time").
The probes wrap private seams (`LocalWorkers._hand_over`, `_on_done`): this script follows them
when they move. Figures are reported, never asserted.
"""

from __future__ import annotations

import argparse
import asyncio
import json
import os
import signal
import socket
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import httpx
import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "benchmarks"))

from http_benchmark import RawClient, distinct_velocities, solve_body, study_wing  # noqa: E402

# (label, later stamp, earlier stamp): consecutive seams of one request; the worker's own time
# is taken out of the trip to the worker and back.
STAGES = [
    ("client sends -> the ASGI app is called", "entered", "sent"),
    ("body read", "body", "entered"),
    ("middlewares, routing, validation, dependencies", "route", "body"),
    ("solver input built (Service.task)", "task", "route"),
    ("the work scheduled as its own asyncio task", "run", "task"),
    ("result cache looked up, a worker's slot taken", "hand_over", "run"),
    ("task pickled and written to the worker's pipe", "handed", "hand_over"),
    ("to the worker and back, outside its own time", "read", "handed"),
    ("answer read -> Service.run returns", "ran", "read"),
    ("-> the route returns its Response", "routed", "ran"),
    ("-> the response's start reaches the server", "start", "routed"),
    ("headers written, the body through the middlewares", "body_out", "start"),
    ("body written -> the client has the whole answer", "received", "body_out"),
]


def serve(port: int, requests: int, trace: Path) -> None:
    """The service with its probes; writes the stamps to `trace` after the `requests`-th
    /solve."""
    import app.routes.solve as solve_route
    import uvicorn

    from app.execution.processes import LocalWorkers
    from app.main import app as service_app
    from app.service import Service

    clock = time.perf_counter
    stamps: dict[str, list[float]] = {}

    def stamp(name: str, value: float | None = None) -> None:
        stamps.setdefault(name, []).append(clock() if value is None else value)

    def after(name: str, fn: Any) -> Any:
        def probed(*args: Any, **kwargs: Any) -> Any:
            value = fn(*args, **kwargs)
            stamp(name)
            return value

        return probed

    hand_over, on_done, answer = LocalWorkers._hand_over, LocalWorkers._on_done, solve_route.answer
    task, run = Service.task, Service.run

    def probed_hand_over(*args: Any, **kwargs: Any) -> Any:
        stamp("hand_over")
        return after("handed", hand_over)(*args, **kwargs)

    def probed_on_done(self: Any, w: Any, seq: int, ok: bool, value: Any, seconds: float) -> Any:
        stamp("read")
        stamp("in_worker", seconds)
        return on_done(self, w, seq, ok, value, seconds)

    async def probed_answer(*args: Any, **kwargs: Any) -> Any:
        stamp("route")
        response = await answer(*args, **kwargs)
        stamp("routed")
        return response

    async def probed_run(*args: Any, **kwargs: Any) -> Any:
        stamp("run")
        body = await run(*args, **kwargs)
        stamp("ran")
        return body

    LocalWorkers._hand_over = probed_hand_over  # type: ignore[method-assign]
    LocalWorkers._on_done = probed_on_done  # type: ignore[method-assign]
    Service.task = after("task", task)  # type: ignore[method-assign]
    Service.run = probed_run  # type: ignore[method-assign]
    solve_route.answer = probed_answer  # type: ignore[assignment]

    async def probed_app(scope: Any, receive: Any, send: Any) -> None:
        if scope["type"] != "http" or scope["path"] != "/solve":
            return await service_app(scope, receive, send)
        stamp("entered")

        async def probed_receive() -> Any:
            message = await receive()
            stamp("body")
            return message

        async def probed_send(message: Any) -> None:
            if message["type"] == "http.response.start":
                stamp("start")
            if message["type"] == "http.response.body":
                stamp("body_out")
            await send(message)
            if message["type"] == "http.response.body" and len(stamps["body_out"]) == requests:
                trace.write_text(json.dumps(stamps))

        await service_app(scope, probed_receive, probed_send)

    uvicorn.run(probed_app, host="127.0.0.1", port=port, log_level="warning", access_log=False)


async def post_all(base: str, requests: int) -> dict[str, list[float]]:
    """The client's stamps of `requests` sequential distinct /solve requests."""
    client, velocities, wing = RawClient(base), distinct_velocities(5), study_wing()
    stamps: dict[str, list[float]] = {"sent": [], "received": []}
    for _ in range(requests):
        body = solve_body(wing, next(velocities))
        stamps["sent"].append(time.perf_counter())
        status, content = await client.post("/solve", body)
        stamps["received"].append(time.perf_counter())
        if status != 200:
            raise RuntimeError(f"{status}: {content[:200]!r}")
    await client.close()
    return stamps


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--requests", type=int, default=2000)
    parser.add_argument("--serve", nargs=3, help=argparse.SUPPRESS)  # port requests trace
    args = parser.parse_args()
    if args.serve:
        port, requests, trace = args.serve
        serve(int(port), int(requests), Path(trace))
        return
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    base = f"http://127.0.0.1:{port}"
    with tempfile.TemporaryDirectory() as tmp:
        trace = Path(tmp) / "stamps.json"
        command = [sys.executable, __file__, "--serve", str(port), str(args.requests), str(trace)]
        env = os.environ | {"FLEXWING_RATE_LIMIT": "0", "FLEXWING_WARMUP_TIMEOUT": "600"}
        server = subprocess.Popen(command, cwd=ROOT, env=env, start_new_session=True)
        try:
            deadline = time.monotonic() + 300
            while True:
                try:
                    if httpx.get(base + "/readyz", timeout=5).status_code == 200:
                        break
                except httpx.TransportError:
                    if time.monotonic() > deadline or server.poll() is not None:
                        raise RuntimeError("the service did not become ready") from None
                time.sleep(0.2)
            client = asyncio.run(post_all(base, args.requests))
            while not trace.exists():
                time.sleep(0.1)
            stamps = {**json.loads(trace.read_text()), **client}
        finally:
            os.killpg(server.pid, signal.SIGINT)
            server.wait(30)
    skip = args.requests // 10  # the first requests warm the caches of both processes
    t = {name: np.asarray(values[skip:]) for name, values in stamps.items()}
    print(f"/solve, one raw client, {args.requests - skip} sequential distinct requests")
    print(f"{'stage':58s} {'mean':>8s} {'p50':>8s}")
    for label, later, earlier in STAGES:
        d = (t[later] - t[earlier] - (t["in_worker"] if later == "read" else 0.0)) * 1e3
        print(f"{label:58s} {d.mean():6.3f} ms {np.median(d):6.3f} ms")
    total = (t["received"] - t["sent"]) * 1e3
    in_worker = t["in_worker"] * 1e3
    outside = total - in_worker
    label = "in the worker (its own time)"
    print(f"{label:58s} {in_worker.mean():6.3f} ms {np.median(in_worker):6.3f} ms")
    print(f"{'whole request':58s} {total.mean():6.3f} ms {np.median(total):6.3f} ms")
    print(
        f"outside the worker: mean {outside.mean():.3f} ms, p50 {np.median(outside):.3f} ms, "
        f"p50 of the request minus p50 in the worker {np.median(total) - np.median(in_worker):.3f} "
        f"ms (issue 27: within 1 ms)"
    )


if __name__ == "__main__":
    main()
