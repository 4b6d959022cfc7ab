"""Hostile input against a live server: response time, answer, and the web process's memory.

    .venv/bin/python benchmarks/hostile_input_benchmark.py [--repeat 3] [--json results.json]

Starts `uvicorn app.main:app` on a free loopback port (2 workers, CasADi's VM so that N = 150
starts no C compilation, default limits: 1,000,000-byte bodies, N <= 150, <= 50 sweep points),
sends every request of tests/app/hostile.py (and the wrong-type and 330,000-bad-items requests),
each --repeat times, and prints per request: status and problem type, the first and the median
client-side time (a 200 is solved the first time only, then served from the result cache),
the web process's resident memory before and its peak (VmHWM, reset before each request) above
that, and the time of the next normal /solve. Bounded: every request has a 120 s timeout.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import sys
import time
from pathlib import Path
from typing import Any

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import httpx

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "benchmarks"))

from load_benchmark import local_server_process  # noqa: E402

from tests import study  # noqa: E402
from tests.app.hostile import AMPLIFIER, HOSTILE, WRONG_TYPES, Hostile, Memory  # noqa: E402

TIMEOUT = 120.0


def _send(base_url: str, case: Hostile) -> tuple[httpx.Response, float]:
    body = case.body()
    started = time.perf_counter()
    response = httpx.post(
        base_url + case.path,
        content=body() if callable(body) else body,
        headers={"content-type": "application/json"},
        timeout=TIMEOUT,
    )
    return response, time.perf_counter() - started


def measure(base_url: str, memory: Memory, case: Hostile, repeat: int, speed: float) -> dict:
    times, peaks, nexts = [], [], []
    answer = ""
    size = 0
    for i in range(repeat):
        before = memory.resident
        memory.reset_peak()
        response, seconds = _send(base_url, case)
        peaks.append(memory.peak - before)
        times.append(seconds)
        size = len(response.content)
        kind = response.json().get("type", "") if response.status_code != 200 else ""
        answer = f"{response.status_code} {kind.removeprefix('/problems/')}".strip()
        started = time.perf_counter()
        normal = httpx.post(
            base_url + "/solve", json=study.solve_request(speed + 0.001 * i), timeout=TIMEOUT
        )
        nexts.append(time.perf_counter() - started)
        assert normal.status_code == 200, normal.text
    return {
        "request": case.name,
        "path": case.path,
        "answer": answer,
        "expected": f"{case.status} {case.kind or ''}".strip(),
        "first_ms": 1e3 * times[0],  # a 200 is solved only the first time (result cache)
        "median_ms": 1e3 * statistics.median(times),
        "response_bytes": size,
        "rss_before_mb": before / 2**20,
        "peak_above_mb": max(peaks) / 2**20,
        "next_solve_ms": 1e3 * statistics.median(nexts),
    }


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--json", type=Path)
    args = parser.parse_args(argv)
    rows: list[dict[str, Any]] = []
    env = {"FLEXWING_COMPILE": "0", "FLEXWING_WORKERS": "2"}
    with local_server_process(env) as (base_url, process):
        memory = Memory(process.pid)
        print(f"server {base_url}; web process RSS {memory.resident / 2**20:.0f} MiB")
        names = ("first", "median", "body", "peak+", "next")
        print(f"{'request':<30} {'answer':<24} " + " ".join(f"{n:>9}" for n in names))
        cases = [*HOSTILE, *WRONG_TYPES, AMPLIFIER]
        for index, case in enumerate(cases):
            row = measure(base_url, memory, case, args.repeat, 8.0 + 0.01 * index)
            rows.append(row)
            flag = "" if row["answer"] == row["expected"] else f"  (expected {row['expected']})"
            print(
                f"{row['request']:<30} {row['answer']:<24} {row['first_ms']:7.1f}ms "
                f"{row['median_ms']:7.1f}ms "
                f"{row['response_bytes']:>10,d} {row['peak_above_mb']:6.1f}MB "
                f"{row['next_solve_ms']:6.1f}ms{flag}"
            )
        print(f"web process RSS at the end {memory.resident / 2**20:.0f} MiB")
    if args.json:
        args.json.write_text(json.dumps(rows, indent=2) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
