"""The service through HTTP on loopback, against the bare solver on the same requests.

    .venv/bin/python benchmarks/http_benchmark.py [--url http://127.0.0.1:8000] [--seconds 10]

Without --url it starts `uvicorn app.main:app` on a free loopback port with the default settings
(FLEXWING_WORKERS = CPU count), as tests/app/conftest.py does (its own process group, stopped
with SIGINT at the end), and waits for /readyz. All requests use the design study's wing
(N = 30, alpha 5 deg). Measured:

- /solve latency, one client, sequential: airspeeds drawn uniformly from 6-20 m/s, all distinct,
  so every request is solved (from the jig shape: the service keeps no earlier states), never
  answered from the result cache; and, apart, a repeated request (result cache).
- /sweep of the study's six speeds [6, 10, 12, 15, 18, 20]: for a wing the worker has seen (its
  branch to the fold is cached; the density varies by 1e-12 so the result cache misses) and for a
  new wing (the stiffness varies: the fold continuation runs).
- throughput: 16 concurrent clients (asyncio + httpx) posting distinct /solve requests for
  --seconds; solves per second and errors.
- the bare solver in this process on the same requests (`solver.solve` from the jig, as the
  workers run it; a hint-warm-started solve is shown for comparison): its share is the solver's
  time, the rest of the HTTP figure is the web layer (HTTP, validation, JSON, inter-process
  transfer). The ratio HTTP / bare is printed for each kind.

Figures are reported, never asserted; the load average is printed with them.
"""

from __future__ import annotations

import argparse
import asyncio
import contextlib
import json
import os
import random
import signal
import socket
import statistics
import subprocess
import sys
import time
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

# One BLAS thread, as in the service's workers (set before numpy loads OpenBLAS).
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import httpx
import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from app import schemas  # noqa: E402

SWEEP = [6.0, 10.0, 12.0, 15.0, 18.0, 20.0]


def study_wing(stiffness_scale: float = 1.0) -> dict[str, Any]:
    """The design study's wing as /docs sends it (app.schemas), stiffness scaled."""
    wing = schemas.study_wing()
    for key in ("bending_stiffness", "torsional_stiffness"):
        wing[key] = [v * stiffness_scale for v in wing[key]]
    return wing


def percentile(values: list[float], q: float) -> float:
    return float(np.percentile(np.asarray(values), q))


def ms(seconds: float) -> str:
    return f"{seconds * 1e3:.2f} ms"


def load_average() -> str:
    one, five, fifteen = os.getloadavg()
    return f"load average {one:.2f}, {five:.2f}, {fifteen:.2f} on {os.cpu_count()} CPUs"


@contextmanager
def server(url: str | None) -> Iterator[str]:
    if url is not None:
        yield url
        return
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    process = subprocess.Popen(
        [
            *(sys.executable, "-m", "uvicorn", "app.main:app", "--port", str(port)),
            *("--host", "127.0.0.1", "--log-level", "warning", "--no-access-log"),
        ],
        cwd=ROOT,
        env=os.environ | {"FLEXWING_RATE_LIMIT": "0", "FLEXWING_WARMUP_TIMEOUT": "600"},  # compiled
        start_new_session=True,  # its own process group: the workers go with it at the end
    )
    base = f"http://127.0.0.1:{port}"
    try:
        deadline = time.monotonic() + 300
        while time.monotonic() < deadline:
            if process.poll() is not None:
                raise RuntimeError("the server exited")
            try:
                if httpx.get(base + "/readyz", timeout=5).status_code == 200:
                    break
            except httpx.TransportError:
                pass
            time.sleep(0.1)
        else:
            raise TimeoutError("the server did not become ready")
        yield base
    finally:
        process.send_signal(signal.SIGINT)
        try:
            process.wait(timeout=30)
        except subprocess.TimeoutExpired:
            process.kill()
            process.wait()
        with contextlib.suppress(ProcessLookupError):
            os.killpg(process.pid, signal.SIGKILL)


def distinct_velocities(seed: int) -> Iterator[float]:
    rng = random.Random(seed)
    while True:
        yield rng.uniform(6.0, 20.0)


def solve_body(wing: dict[str, Any], velocity: float) -> bytes:
    return json.dumps({"wing": wing, "flight": {"velocity": velocity, "alpha": 5.0}}).encode()


def time_posts(client: httpx.Client, path: str, bodies: list[bytes]) -> list[float]:
    """Wall time of each POST (bodies are built beforehand, outside the timing)."""
    headers = {"content-type": "application/json"}
    times = []
    for body in bodies:
        started = time.perf_counter()
        response = client.post(path, content=body, headers=headers)
        times.append(time.perf_counter() - started)
        if response.status_code != 200:
            raise RuntimeError(f"{response.status_code}: {response.text}")
    return times


def histogram(client: httpx.Client, name: str, labels: str = "") -> tuple[float, int]:
    """Sum and count of one of the server's histograms, from /metrics (`labels` as written
    there, e.g. '{kind="solve"}')."""
    total, count = 0.0, 0
    for line in client.get("/metrics").text.splitlines():
        if line.startswith(f"{name}_sum{labels} "):
            total = float(line.split()[-1])
        if line.startswith(f"{name}_count{labels} "):
            count = int(float(line.split()[-1]))
    return total, count


def pool_seconds(client: httpx.Client) -> tuple[float, int, float, int]:
    """Sum and count of the server's /solve jobs from dispatch to result, and of the time
    they ran inside the workers."""
    pool = histogram(client, "flexwing_solve_duration_seconds", '{kind="solve"}')
    own = histogram(client, "flexwing_worker_task_duration_seconds")
    return (*pool, *own)


def sweep_body(wing: dict[str, Any], density: float = 1.225) -> bytes:
    body = {"wing": wing, "flight": {"alpha": 5.0, "density": density}, "velocities": SWEEP}
    return json.dumps(body).encode()


def http_latency(base: str, count: int) -> tuple[dict[str, list[float]], float, dict[str, float]]:
    """Sequential latencies, the mean time of a /solve job in the pool (dispatch to result)
    and the mean time the /solve runs ran inside their workers, by run [s]."""
    wing = study_wing()
    velocities = distinct_velocities(1)
    out: dict[str, list[float]] = {}
    with httpx.Client(base_url=base, timeout=60) as client:
        # Prime the connection and the state cache (one stored equilibrium).
        time_posts(client, "/solve", [solve_body(wing, 10.0)])
        before = pool_seconds(client)
        out["solve"] = time_posts(
            client, "/solve", [solve_body(wing, next(velocities)) for _ in range(count)]
        )
        after = pool_seconds(client)
        pool_mean = (after[0] - before[0]) / (after[1] - before[1])
        in_worker_mean = (after[2] - before[2]) / (after[3] - before[3])
        out["cached"] = time_posts(client, "/solve", [solve_body(wing, 10.0)] * count)
        before = pool_seconds(client)
        out["solve_raw"] = asyncio.run(raw_posts(base, "/solve", wing, count))
        after = pool_seconds(client)
        in_worker_raw = (after[2] - before[2]) / (after[3] - before[3])
        sweeps = max(count // 10, 20)
        # The density varies by 1e-12 so the result cache misses; each worker has traced the
        # branch of this wing (the first two sweeps), which the solver caches per wing and alpha.
        seen = [sweep_body(wing, 1.225 * (1 + 1e-12 * i)) for i in range(sweeps + 2)]
        time_posts(client, "/sweep", seen[:2])
        out["sweep_seen"] = time_posts(client, "/sweep", seen[2:])
        new = [sweep_body(study_wing(1 + 1e-9 * (i + 1))) for i in range(max(count // 20, 10))]
        out["sweep_new"] = time_posts(client, "/sweep", new)
    return out, pool_mean, {"solve": in_worker_mean, "solve_raw": in_worker_raw}


class RawClient:
    """A minimal keep-alive HTTP/1.1 client on asyncio streams: a load generator that costs the
    shared CPUs far less per request than httpx (the server cannot tell the difference)."""

    def __init__(self, base: str) -> None:
        self.host, port = base.removeprefix("http://").split(":")
        self.port = int(port)
        self.streams: tuple[asyncio.StreamReader, asyncio.StreamWriter] | None = None

    async def post(self, path: str, body: bytes) -> tuple[int, bytes]:
        if self.streams is None:
            self.streams = await asyncio.open_connection(self.host, self.port)
        reader, writer = self.streams
        writer.write(
            f"POST {path} HTTP/1.1\r\nHost: {self.host}\r\nContent-Type: application/json\r\n"
            f"Content-Length: {len(body)}\r\n\r\n".encode()
            + body
        )
        head = await reader.readuntil(b"\r\n\r\n")
        lines = head.decode("latin-1").split("\r\n")
        status = int(lines[0].split()[1])
        length = next(
            int(line.split(":", 1)[1])
            for line in lines
            if line.lower().startswith("content-length")
        )
        return status, await reader.readexactly(length)

    async def close(self) -> None:
        if self.streams is not None:
            self.streams[1].close()


async def raw_posts(base: str, path: str, wing: dict[str, Any], count: int) -> list[float]:
    """Sequential distinct /solve requests from the raw client: the latency without httpx's
    own cost."""
    raw, velocities, times = RawClient(base), distinct_velocities(4), []
    for _ in range(count):
        body = solve_body(wing, next(velocities))
        started = time.perf_counter()
        status, content = await raw.post(path, body)
        times.append(time.perf_counter() - started)
        if status != 200:
            raise RuntimeError(f"{status}: {content[:200]!r}")
    await raw.close()
    return times


async def throughput(
    base: str, clients: int, seconds: float, kind: str
) -> tuple[int, int, float, list[float]]:
    """`clients` concurrent clients posting distinct /solve requests for `seconds`."""
    wing = study_wing()
    velocities = distinct_velocities({"httpx": 2, "raw": 3}[kind])  # not another run's airspeeds
    ok = errors = 0
    latencies: list[float] = []
    limits = httpx.Limits(max_connections=clients, max_keepalive_connections=clients)
    shared = httpx.AsyncClient(base_url=base, timeout=60, limits=limits)
    deadline = time.perf_counter() + seconds

    async def one_client() -> None:
        nonlocal ok, errors
        raw = RawClient(base)
        while time.perf_counter() < deadline:
            body = solve_body(wing, next(velocities))
            started = time.perf_counter()
            try:
                if kind == "raw":
                    status, content = await raw.post("/solve", body)
                    solved = status == 200 and b'"cached":false' in content
                else:
                    r = await shared.post(
                        "/solve", content=body, headers={"content-type": "application/json"}
                    )
                    solved = r.status_code == 200 and not r.json()["solver"]["cached"]
            except (OSError, httpx.HTTPError, asyncio.IncompleteReadError):
                errors += 1
                continue
            latencies.append(time.perf_counter() - started)
            if solved:
                ok += 1
            else:
                errors += 1
        await raw.close()

    started = time.perf_counter()
    await asyncio.gather(*(one_client() for _ in range(clients)))
    elapsed = time.perf_counter() - started
    await shared.aclose()
    return ok, errors, elapsed, latencies


def bare_solver(count: int) -> dict[str, list[float]]:
    """The same work in this process: what the service adds is the difference."""
    import solver

    if not solver.warm_up(30):
        print("bare solver: no compiled library for N = 30, timing CasADi's VM")
    raw = study_wing()
    wing = solver.Wing.create(
        raw["y"], raw["chord"], 0.4, raw["bending_stiffness"], raw["torsional_stiffness"]
    )
    velocities = distinct_velocities(1)
    stored = solver.solve(wing, solver.FlightCondition(10.0, 5.0))
    answers = {10.0: stored}
    out: dict[str, list[float]] = {"solve_warm": [], "solve_cold": [], "sweep_seen": []}
    for _ in range(count):
        v = next(velocities)
        nearest = min(answers, key=lambda s: abs(s**2 - v**2))
        started = time.perf_counter()
        eq = solver.solve(wing, solver.FlightCondition(v, 5.0))
        out["solve_cold"].append(time.perf_counter() - started)
        started = time.perf_counter()
        solver.solve(wing, solver.FlightCondition(v, 5.0), hint=answers[nearest])
        out["solve_warm"].append(time.perf_counter() - started)
        answers[v] = eq
    # What a worker does for one /solve: the operation input the service built from the
    # request, solved and its answer serialised (app.execution.worker.run).
    from app.execution import worker
    from app.schemas import SolveRequest
    from app.service import task_of
    from app.settings import Settings

    settings, own = Settings(), distinct_velocities(5)
    out["worker_run"] = []
    for _ in range(count):
        request = SolveRequest.model_validate_json(solve_body(raw, next(own)))
        task = task_of(request, settings)
        started = time.perf_counter()
        worker.run(task)
        out["worker_run"].append(time.perf_counter() - started)
    solver.airspeed_sweep(wing, SWEEP, solver.FlightCondition(None, 5.0, 1.225))
    for _ in range(max(count // 10, 20)):
        started = time.perf_counter()
        solver.airspeed_sweep(wing, SWEEP, solver.FlightCondition(None, 5.0, 1.225))
        out["sweep_seen"].append(time.perf_counter() - started)
    out["sweep_new"] = []
    for i in range(max(count // 20, 10)):
        scaled = study_wing(1 + 1e-9 * (i + 1))
        new = solver.Wing.create(
            scaled["y"],
            scaled["chord"],
            0.4,
            scaled["bending_stiffness"],
            scaled["torsional_stiffness"],
        )
        started = time.perf_counter()
        solver.airspeed_sweep(new, SWEEP, solver.FlightCondition(None, 5.0, 1.225))
        out["sweep_new"].append(time.perf_counter() - started)
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--url", help="benchmark a running server instead of starting one")
    parser.add_argument("--requests", type=int, default=1000, help="sequential /solve requests")
    parser.add_argument("--clients", type=int, default=16)
    parser.add_argument("--seconds", type=float, default=10.0, help="throughput run length")
    args = parser.parse_args()

    print(f"study's wing, N = 30, alpha 5 deg; {load_average()}")
    bare = bare_solver(args.requests // 2)
    with server(args.url) as base:
        http, pool_mean, in_worker = http_latency(base, args.requests)
        loads = {
            kind: asyncio.run(throughput(base, args.clients, args.seconds, kind))
            for kind in ("httpx", "raw")
        }

    def row(name: str, values: list[float]) -> None:
        print(
            f"  {name:<46} p50 {ms(statistics.median(values)):>10}   "
            f"p99 {ms(percentile(values, 99)):>10}   n={len(values)}"
        )

    print("HTTP, one client, sequential:")
    row("/solve, distinct airspeeds (from the jig)", http["solve"])
    row("/solve, distinct airspeeds, raw client", http["solve_raw"])
    row("/solve, repeated request (result cache)", http["cached"])
    row("/sweep 6 speeds, wing seen (branch cached)", http["sweep_seen"])
    row("/sweep 6 speeds, new wing (fold continuation)", http["sweep_new"])
    print("bare solver, same process, same requests:")
    row("solve, cold (from the jig, as the workers)", bare["solve_cold"])
    row("solve, hint: the nearest earlier answer", bare["solve_warm"])
    row("a worker's own /solve (worker.run: solve + answer)", bare["worker_run"])
    row("sweep 6 speeds, wing seen", bare["sweep_seen"])
    row("sweep 6 speeds, new wing", bare["sweep_new"])
    print("where a sequential /solve spends its time (medians, means):")
    http_p50 = statistics.median(http["solve"])
    bare_p50 = statistics.median(bare["solve_cold"])
    web = http_p50 - pool_mean
    print(f"  whole request {ms(http_p50)}: job in the worker pool {ms(pool_mean)} (mean),")
    print(f"  of which the solver {ms(bare_p50)}; HTTP + validation + JSON {ms(web)},")
    print(f"  dispatch to the process and back {ms(pool_mean - bare_p50)}")
    own = statistics.median(bare["worker_run"])
    print("/solve p50 over the worker's own solve p50 (issue 27: within 1 ms):")
    for name, label in (("solve", "httpx client"), ("solve_raw", "raw client")):
        print(f"  {label:<12} {ms(statistics.median(http[name]) - own):>10}")
    # Side by side in the same requests: the workers time each task themselves.
    print("/solve mean over the mean time the same requests ran in the workers:")
    for name, label in (("solve", "httpx client"), ("solve_raw", "raw client")):
        mean = statistics.mean(http[name])
        print(
            f"  {label:<12} {ms(mean - in_worker[name]):>10}   "
            f"({ms(mean)} - {ms(in_worker[name])} in the worker)"
        )
    print("web-layer overhead (HTTP p50 minus bare p50, and their ratio):")
    for name, bare_name in (
        ("solve", "solve_cold"),
        ("sweep_seen", "sweep_seen"),
        ("sweep_new", "sweep_new"),
    ):
        http_median, bare_median = statistics.median(http[name]), statistics.median(bare[bare_name])
        print(
            f"  {name:<10} {ms(http_median - bare_median):>10}   "
            f"HTTP / bare {http_median / bare_median:6.2f}x"
        )
    for kind, (ok, errors, elapsed, latencies) in loads.items():
        print(f"throughput, {args.clients} concurrent {kind} clients, {elapsed:.1f} s:")
        print(f"  {ok / elapsed:.0f} solves/s, {errors} errors")
        row("latency under load", latencies)
    print(load_average())


if __name__ == "__main__":
    main()
