"""Faults under traffic, the long form of tests/app/execution/test_fault_injection.py.

    .venv/bin/python benchmarks/fault_benchmark.py [--seconds 60] [--interval 3] [--clients 8]
        [--json results.json]

1. Kills: a server (2 workers, CasADi's VM, 120-station study wing: ~0.4 s per solve) serves
   --clients threads posting distinct /solve speeds for --seconds while one worker is killed with
   SIGKILL every --interval seconds. Reported: kills, answers (200 / 503 worker-lost / anything
   else), the time from each kill until /readyz shows a full pool of new processes, and p50/p99
   latency of the answered requests.
2. Time budget: FLEXWING_SOLVE_TIMEOUT=1 and a solve that needs ~10 s (find the fold of a
   150-station wing on the VM): the answer (504) and how long it took, and the time until the
   recycled pool is ready.
3. SIGTERM with --clients solves in flight: how many are answered correctly, and the time from
   the signal to the server's exit.
Loopback only, bounded (every request has a 120 s timeout; the script stops by itself).
"""

from __future__ import annotations

import argparse
import json
import os
import signal
import statistics
import sys
import threading
import time
from collections import Counter
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path
from typing import Any

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import httpx
import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "benchmarks"))

from load_benchmark import local_server_process  # noqa: E402

from tests.app.execution.test_fault_injection import alive, kill, solve_body  # noqa: E402

TIMEOUT = 120.0


def _ready_pids(base_url: str, exclude: set[int]) -> list[int]:
    while True:
        try:
            body = httpx.get(base_url + "/readyz", timeout=5).json()
            full = body["ready"] and len(body["pids"]) == body["workers"]
            if full and not exclude & set(body["pids"]):
                return list(body["pids"])
        except (httpx.TransportError, ValueError):
            pass
        time.sleep(0.01)


def _percentiles(values: list[float]) -> dict[str, float | None]:
    if not values:
        return {"p50_ms": None, "p99_ms": None}
    p50, p99 = np.percentile(values, [50, 99])
    return {"p50_ms": 1e3 * p50, "p99_ms": 1e3 * p99}


def kills(seconds: float, interval: float, clients: int) -> dict[str, Any]:
    env = {"FLEXWING_COMPILE": "0", "FLEXWING_WORKERS": "2"}
    with local_server_process(env) as (base_url, _):
        stop = threading.Event()
        answers: list[tuple[str, float]] = []
        counter = iter(range(10**9))
        lock = threading.Lock()

        def client_loop() -> None:
            with httpx.Client(base_url=base_url, timeout=TIMEOUT) as client:
                while not stop.is_set():
                    with lock:
                        velocity = 6.0 + 1e-4 * next(counter)  # distinct: never cached
                    started = time.perf_counter()
                    try:
                        response = client.post("/solve", json=solve_body(velocity))
                        outcome = str(response.status_code)
                        if response.status_code == 503:
                            outcome += " " + response.json()["type"].removeprefix("/problems/")
                    except httpx.TransportError as error:
                        outcome = type(error).__name__
                    answers.append((outcome, time.perf_counter() - started))

        heal_times: list[float] = []
        with ThreadPoolExecutor(clients) as pool:
            loops = [pool.submit(client_loop) for _ in range(clients)]
            deadline = time.monotonic() + seconds
            while time.monotonic() + interval < deadline:
                time.sleep(interval)
                pids = _ready_pids(base_url, set())
                killed_at = time.perf_counter()
                kill(pids[0])
                _ready_pids(base_url, set(pids))
                heal_times.append(time.perf_counter() - killed_at)
            stop.set()
            for loop in loops:
                loop.result()
        outcomes = Counter(outcome for outcome, _ in answers)
        return {
            "seconds": seconds,
            "clients": clients,
            "kills": len(heal_times),
            "answers": dict(outcomes),
            "heal_s_median": statistics.median(heal_times) if heal_times else None,
            "heal_s_max": max(heal_times, default=None),
            "answered": _percentiles([s for outcome, s in answers if outcome == "200"]),
        }


def budget() -> dict[str, Any]:
    env = {"FLEXWING_COMPILE": "0", "FLEXWING_WORKERS": "2", "FLEXWING_SOLVE_TIMEOUT": "1"}
    with local_server_process(env) as (base_url, _):
        pids = _ready_pids(base_url, set())
        started = time.perf_counter()
        response = httpx.post(
            base_url + "/solve",
            json=solve_body(12.0, n=150, options={"find_fold": True}),
            timeout=TIMEOUT,
        )
        answered = time.perf_counter() - started
        _ready_pids(base_url, set(pids))
        ready = time.perf_counter() - started
        return {
            "status": response.status_code,
            "type": response.json().get("type"),
            "answered_after_s": answered,
            "pool_ready_after_s": ready,
            "old_workers_alive": sum(alive(p) for p in pids),
        }


def sigterm(clients: int) -> dict[str, Any]:
    env = {"FLEXWING_COMPILE": "0", "FLEXWING_WORKERS": "2"}
    with local_server_process(env) as (base_url, process):
        pids = _ready_pids(base_url, set())
        speeds = [8.0 + 0.5 * i for i in range(clients)]
        with ThreadPoolExecutor(clients) as pool:
            futures = [
                pool.submit(
                    lambda v: httpx.post(base_url + "/solve", json=solve_body(v), timeout=TIMEOUT),
                    v,
                )
                for v in speeds
            ]
            while True:  # all in flight
                text = httpx.get(base_url + "/metrics", timeout=10).text
                pending = [line for line in text.splitlines() if line.startswith("flexwing_pend")]
                if pending and float(pending[0].split()[1]) >= clients:
                    break
                time.sleep(0.01)
            signalled = time.perf_counter()
            process.send_signal(signal.SIGTERM)
            statuses = Counter(str(f.result().status_code) for f in futures)
        code = process.wait(timeout=TIMEOUT)
        return {
            "in_flight": clients,
            "answers": dict(statuses),
            "exit_after_s": time.perf_counter() - signalled,
            "exit_status": code,
            "workers_left": sum(alive(p) for p in pids),
        }


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--seconds", type=float, default=60.0)
    parser.add_argument("--interval", type=float, default=3.0)
    parser.add_argument("--clients", type=int, default=8)
    parser.add_argument("--json", type=Path)
    args = parser.parse_args(argv)
    results = {
        "kills": kills(args.seconds, args.interval, args.clients),
        "budget": budget(),
        "sigterm": sigterm(args.clients),
    }
    for name, result in results.items():
        print(f"{name}: {json.dumps(result)}")
    if args.json:
        args.json.write_text(json.dumps(results, indent=2) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
