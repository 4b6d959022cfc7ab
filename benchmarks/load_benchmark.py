"""Load on loopback: mixed /solve and /sweep traffic held by N concurrent clients, then overload.

    .venv/bin/python benchmarks/load_benchmark.py [--url http://127.0.0.1:PORT]
        [--clients 16 64] [--seconds 60] [--overload-clients 256] [--overload-seconds 20]
        [--transport raw|httpx] [--json results.json]

Without --url it starts `uvicorn app.main:app --timeout-keep-alive 75` (as the README runs it) on a
free loopback port with the default settings (FLEXWING_WORKERS = CPU count, FLEXWING_MAX_PENDING =
64) and stops it at the end; --url must be a loopback address. Everything is bounded: each phase
ends after --seconds (or --max-requests), every request has a 60 s timeout, and the script stops
by itself.

Traffic (asyncio, one keep-alive connection per client; each client sends its next request when
the previous one is answered; --transport raw, the default, is a minimal HTTP/1.1 client: on this
2-core machine httpx's own CPU per request starves the server from ~64 clients on): 80 % /solve,
20 % /sweep of 3-6 speeds, over four N = 30 wings (the design study's and three variants: stiffer,
elastic axis at 35 %, linear taper) at alpha 3 or 5 deg, speeds on a 0.01 m/s grid below each
wing's fold. Requests repeat by chance (result-cache hits) but mostly do not (solves warm-started
from the state cache). Every answer must be 200: any other status or transport error counts as an
error.

Overload: --overload-clients (4x FLEXWING_MAX_PENDING by default) clients for --overload-seconds.
Each client honours Retry-After on 503 before sending again. Reported: answered / shed (503
overloaded, with Retry-After) / errors, the latency of answered requests, and the largest number
of pending solves /metrics showed (sampled every 0.2 s): shedding, not an unbounded queue, keeps
it at or below FLEXWING_MAX_PENDING.
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
import subprocess
import sys
import time
from collections import Counter
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any
from urllib.parse import urlsplit

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

__all__ = ["PhaseResult", "Sample", "local_server", "local_server_process", "run_phase"]

import httpx
import numpy as np

ROOT = Path(__file__).resolve().parents[1]
REQUEST_TIMEOUT = 60.0  # [s]
LOOPBACK = {"127.0.0.1", "localhost", "::1"}
SWEEP_SHARE = 0.2
ALPHAS = (3.0, 5.0)
SPEED_GRID = np.round(np.arange(6.0, 20.0 + 1e-9, 0.01), 2)  # all below every wing's fold


def _wing(scale: float = 1.0, elastic_axis: float = 0.4, taper: bool = False) -> dict[str, Any]:
    n = 30
    chord = 1.4 - 0.9 * np.linspace(0, 1, n) if taper else np.sqrt(np.linspace(2, 0.02, n))
    return {
        "y": np.linspace(0, 5, n).tolist(),
        "chord": chord.tolist(),
        "elastic_axis": elastic_axis,
        "bending_stiffness": (2e4 * scale * chord**3).tolist(),
        "torsional_stiffness": (1e3 * scale * chord**3).tolist(),
    }


WINGS = [
    _wing(),
    _wing(scale=1.5),
    _wing(elastic_axis=0.35),
    _wing(scale=2.0, taper=True),
]
_WING_JSON = [json.dumps(w) for w in WINGS]


@dataclass(frozen=True)
class Sample:
    kind: str  # "solve" or "sweep"
    outcome: str  # "200", "shed", or the error: another status or a transport error's name
    seconds: float
    cached: bool = False


@dataclass
class PhaseResult:
    name: str
    clients: int
    seconds: float
    samples: list[Sample] = field(default_factory=list)
    max_pending: float = 0.0

    @property
    def answered(self) -> list[Sample]:
        return [s for s in self.samples if s.outcome == "200"]

    @property
    def errors(self) -> Counter[str]:
        return Counter(s.outcome for s in self.samples if s.outcome not in ("200", "shed"))

    @property
    def shed(self) -> int:
        return sum(s.outcome == "shed" for s in self.samples)

    def summary(self) -> dict[str, Any]:
        def latency(kind: str | None) -> dict[str, float | None]:
            times = [s.seconds for s in self.answered if kind in (None, s.kind)]
            if not times:
                return {"p50_ms": None, "p99_ms": None, "count": 0}
            p50, p99 = np.percentile(times, [50, 99])
            return {"p50_ms": 1e3 * p50, "p99_ms": 1e3 * p99, "count": len(times)}

        return {
            "phase": self.name,
            "clients": self.clients,
            "seconds": self.seconds,
            "requests": len(self.samples),
            "answered": len(self.answered),
            "throughput_per_s": len(self.answered) / self.seconds,
            "errors": dict(self.errors),
            "shed_503": self.shed,
            "cache_hits": sum(s.cached for s in self.answered),
            "max_pending_seen": self.max_pending,
            "all": latency(None),
            "solve": latency("solve"),
            "sweep": latency("sweep"),
        }


def _request(rng: random.Random) -> tuple[str, str, bytes]:
    """(kind, path, body) of the next request."""
    wing = rng.randrange(len(WINGS))
    alpha = rng.choice(ALPHAS)
    if rng.random() < SWEEP_SHARE:
        count = rng.randint(3, 6)
        speeds = sorted(float(v) for v in rng.sample(list(SPEED_GRID[::50]), count))
        text = (
            f'{{"wing": {_WING_JSON[wing]}, "flight": {{"alpha": {alpha}}}, '
            f'"velocities": {json.dumps(speeds)}}}'
        )
        return "sweep", "/sweep", text.encode()
    velocity = float(rng.choice(SPEED_GRID))
    text = f'{{"wing": {_WING_JSON[wing]}, "flight": {{"velocity": {velocity}, "alpha": {alpha}}}}}'
    return "solve", "/solve", text.encode()


async def _pending(client: httpx.AsyncClient) -> float:
    text = (await client.get("/metrics")).text
    for line in text.splitlines():
        if line.startswith("flexwing_pending_tasks "):
            return float(line.split()[1])
    return 0.0


@dataclass(frozen=True)
class Answer:
    status: int
    headers: dict[str, str]  # lower-case names
    body: bytes


class RawConnection:
    """A minimal keep-alive HTTP/1.1 client on asyncio streams (Content-Length bodies only, as
    uvicorn sends them). On a 2-core machine shared with the server, httpx's own CPU cost per
    request becomes the bottleneck from ~64 clients on; this one costs a fraction of it."""

    def __init__(self, base_url: str) -> None:
        parts = urlsplit(base_url)
        self.host, self.port = parts.hostname or "127.0.0.1", parts.port or 80
        self.streams: tuple[asyncio.StreamReader, asyncio.StreamWriter] | None = None

    async def post(self, path: str, body: bytes) -> Answer:
        if self.streams is None:
            self.streams = await asyncio.open_connection(self.host, self.port)
        reader, writer = self.streams
        try:
            writer.write(
                f"POST {path} HTTP/1.1\r\nHost: {self.host}\r\n"
                f"Content-Type: application/json\r\nContent-Length: {len(body)}\r\n\r\n".encode()
                + body
            )
            head = (await reader.readuntil(b"\r\n\r\n")).decode("latin-1").split("\r\n")
            headers = {
                name.strip().lower(): value.strip()
                for name, _, value in (line.partition(":") for line in head[1:] if line)
            }
            answer = Answer(
                int(head[0].split()[1]),
                headers,
                await reader.readexactly(int(headers["content-length"])),
            )
        except BaseException:
            await self.close()
            raise
        if answer.headers.get("connection", "").lower() == "close":
            await self.close()
        return answer

    async def close(self) -> None:
        if self.streams is not None:
            self.streams[1].close()
            self.streams = None


class HttpxConnection:
    def __init__(self, client: httpx.AsyncClient) -> None:
        self.client = client

    async def post(self, path: str, body: bytes) -> Answer:
        response = await self.client.post(
            path, content=body, headers={"content-type": "application/json"}
        )
        return Answer(response.status_code, dict(response.headers), response.content)

    async def close(self) -> None:
        pass


TRANSPORT_ERRORS = (httpx.TransportError, OSError, asyncio.IncompleteReadError, ValueError)


def _outcome(answer: Answer) -> tuple[str, float | None, bool]:
    """(outcome, Retry-After if shed, cached) of an answer."""
    if answer.status == 200:
        return "200", None, b'"cached":true' in answer.body
    if (
        answer.status == 503
        and answer.headers.get("content-type") == "application/problem+json"
        and json.loads(answer.body).get("type") == "/problems/overloaded"
        and "retry-after" in answer.headers
    ):
        return "shed", float(answer.headers["retry-after"]), False
    return str(answer.status), None, False


async def run_phase(
    base_url: str,
    name: str,
    clients: int,
    seconds: float,
    *,
    seed: int = 0,
    max_requests: int = 1_000_000,
    honour_retry_after: bool = True,
    transport: str = "raw",
) -> PhaseResult:
    """`clients` concurrent clients for `seconds` (or `max_requests` in all), then stop.

    transport "raw" (`RawConnection`, one per client) or "httpx" (one AsyncClient, one pooled
    connection per client, so that none idles into the server's keep-alive timeout).
    """
    result = PhaseResult(name, clients, seconds)
    limits = httpx.Limits(max_connections=clients, max_keepalive_connections=clients)
    loop = asyncio.get_running_loop()
    async with (
        httpx.AsyncClient(base_url=base_url, timeout=REQUEST_TIMEOUT, limits=limits) as shared,
        httpx.AsyncClient(base_url=base_url, timeout=REQUEST_TIMEOUT) as monitor,
    ):
        started = loop.time()
        deadline = started + seconds

        async def one_client(index: int) -> None:
            rng = random.Random(seed * 100_003 + index)
            connection = RawConnection(base_url) if transport == "raw" else HttpxConnection(shared)
            while loop.time() < deadline and len(result.samples) < max_requests:
                kind, path, body = _request(rng)
                sent = time.perf_counter()
                retry_after, cached = None, False
                try:
                    answer = await asyncio.wait_for(connection.post(path, body), REQUEST_TIMEOUT)
                    outcome, retry_after, cached = _outcome(answer)
                except (*TRANSPORT_ERRORS, TimeoutError) as error:
                    outcome = type(error).__name__
                result.samples.append(Sample(kind, outcome, time.perf_counter() - sent, cached))
                if retry_after is not None and honour_retry_after:
                    await asyncio.sleep(min(retry_after, max(0.0, deadline - loop.time())))
            await connection.close()

        async def watch_pending() -> None:
            while loop.time() < deadline:
                with contextlib.suppress(httpx.TransportError):
                    result.max_pending = max(result.max_pending, await _pending(monitor))
                await asyncio.sleep(0.2)

        watcher = asyncio.create_task(watch_pending())
        await asyncio.gather(*(one_client(i) for i in range(clients)))
        watcher.cancel()
        with contextlib.suppress(asyncio.CancelledError):
            await watcher
        result.seconds = loop.time() - started
    return result


# ---------------------------------------------------------------------------------- script


@contextlib.contextmanager
def local_server(env: dict[str, str] | None = None) -> Iterator[str]:
    """`uvicorn app.main:app` on a free loopback port until the block ends: its base URL."""
    with local_server_process(env) as (base_url, _):
        yield base_url


@contextlib.contextmanager
def local_server_process(
    env: dict[str, str] | None = None,
) -> Iterator[tuple[str, subprocess.Popen[bytes]]]:
    """`uvicorn app.main:app` on a free loopback port until the block ends: URL and process."""
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    process = subprocess.Popen(
        [
            *(sys.executable, "-m", "uvicorn", "app.main:app", "--port", str(port)),
            *("--host", "127.0.0.1", "--log-level", "warning", "--no-access-log"),
            *("--timeout-keep-alive", "75"),  # as the README and the Dockerfile run it
        ],
        cwd=ROOT,
        # The benchmarks measure the service from one address, not its per-client rate limit.
        env=os.environ
        | {"FLEXWING_RATE_LIMIT": "0", "FLEXWING_WARMUP_TIMEOUT": "600"}
        | (env or {}),
    )
    base = f"http://127.0.0.1:{port}"
    try:
        deadline = time.monotonic() + 300
        while time.monotonic() < deadline:
            with contextlib.suppress(httpx.TransportError):
                if httpx.get(base + "/readyz", timeout=5).status_code == 200:
                    break
            if process.poll() is not None:
                raise RuntimeError("the server exited")
            time.sleep(0.1)
        else:
            raise TimeoutError("the server did not become ready")
        yield base, process
    finally:
        process.send_signal(signal.SIGINT)
        try:
            process.wait(timeout=30)
        except subprocess.TimeoutExpired:
            process.kill()
            process.wait()


def _print(summary: dict[str, Any]) -> None:
    def ms(value: float | None) -> str:
        return "-" if value is None else f"{value:8.1f}"

    s = summary
    print(
        f"{s['phase']:>9} {s['clients']:>4} clients {s['seconds']:5.1f} s: "
        f"{s['answered']:>6} answered ({s['throughput_per_s']:6.1f}/s), "
        f"errors {s['errors'] or 0}, shed {s['shed_503']}, cache hits {s['cache_hits']}, "
        f"max pending {s['max_pending_seen']:g}"
    )
    for kind in ("all", "solve", "sweep"):
        k = s[kind]
        print(
            f"{'':>16}{kind:>6}: p50 {ms(k['p50_ms'])} ms  p99 {ms(k['p99_ms'])} ms  n={k['count']}"
        )


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--url", help="a running server (loopback only)")
    parser.add_argument("--clients", type=int, nargs="+", default=[16, 64])
    parser.add_argument("--seconds", type=float, default=60.0)
    parser.add_argument("--overload-clients", type=int, default=256)
    parser.add_argument("--overload-seconds", type=float, default=20.0)
    parser.add_argument("--max-requests", type=int, default=1_000_000)
    parser.add_argument("--transport", choices=["raw", "httpx"], default="raw")
    parser.add_argument("--json", type=Path, help="write the figures here")
    args = parser.parse_args(argv)
    if args.url and urlsplit(args.url).hostname not in LOOPBACK:
        parser.error("--url must point at a loopback address")

    server = contextlib.nullcontext(args.url) if args.url else local_server()
    summaries = []
    with server as base_url:
        print(f"server {base_url}, {os.cpu_count()} CPUs, {args.transport} clients, warm-up...")
        asyncio.run(run_phase(base_url, "warm-up", 4, 5.0, seed=99, transport=args.transport))
        phases = [("load", n, args.seconds) for n in args.clients]
        if args.overload_clients:
            phases.append(("overload", args.overload_clients, args.overload_seconds))
        for seed, (name, clients, seconds) in enumerate(phases, start=1):
            result = asyncio.run(
                run_phase(
                    base_url,
                    name,
                    clients,
                    seconds,
                    seed=seed,
                    max_requests=args.max_requests,
                    transport=args.transport,
                )
            )
            summaries.append(result.summary())
            _print(summaries[-1])
    if args.json:
        args.json.write_text(json.dumps(summaries, indent=2) + "\n")
    load_errors = sum(sum(s["errors"].values()) for s in summaries if s["phase"] == "load")
    return 1 if load_errors else 0


if __name__ == "__main__":
    sys.exit(main())
