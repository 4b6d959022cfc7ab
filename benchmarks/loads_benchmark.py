"""Sizing loads' throughput: 200 trimmed load cases of the study's wing with inertia relief and
their envelope, answered by POST /loads, against what the pool's workers solve in process.

    OPENBLAS_NUM_THREADS=1 .venv/bin/python benchmarks/loads_benchmark.py [--cases 200] [--runs 3]

The cases: the design study's wing (N = 30, compiled) with a light mass (1 kg/m, its centre of
gravity at 42 % of the chord), trimmed at 200-320 N and load factors -1 to 3 (nonzero), at 10-17
m/s: every run's cases are new (its weights shifted), so no answer comes from the result cache.
Some cases ask for more lift than the wing carries before its trimmed limit: they are answered
in their place (`status`), and counted like the others.

The capacity the service is held to is measured in the same run: the same kind of cases solved
one after another in this process (`solver`, compiled, no HTTP, no workers), capacity = workers
/ (time per case). /loads is timed from the request to its whole answer (the envelope assembled
and serialised), on a real uvicorn service with FLEXWING_WORKERS workers; its cases per second
are printed as a share of the capacity (issue 36: >= 70 %).
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

import httpx
import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from batch_benchmark import service

from app.schemas.examples import STUDY_MASS, STUDY_WING


def body(count: int, run: int) -> dict[str, Any]:
    """A /loads body of `count` trimmed cases, distinct per run."""
    rng = np.random.default_rng(run)
    cases = []
    for i in range(count):
        load_factor = float(rng.choice([-1.0, -0.5, 1.0, 1.5, 2.0, 2.5, 3.0]))
        flight = {
            "velocity": float(rng.uniform(10.0, 17.0)),
            "weight": 200.0 + 120.0 * i / count + 0.01 * run,
            "load_factor": load_factor,
        }
        cases.append({"name": f"case {i}", "flight": flight})
    return {"wing": STUDY_WING | {"mass": STUDY_MASS}, "cases": cases}


def in_process_seconds(count: int) -> tuple[float, int]:
    """([s] time per case solved here, one after another; cases answered) for cases like the
    service's (run 99)."""
    import solver
    from app.schemas.requests import REQUESTS

    solver.warm_up(30)
    task = REQUESTS["loads"].model_validate(body(count, 99)).to_solver()
    plan = task.plan
    started = time.perf_counter()
    answers = [part.run() for part in plan]
    seconds = time.perf_counter() - started
    task.assemble(answers)
    return seconds / len(plan), sum(a.answered for a in answers)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--cases", type=int, default=200)
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--workers", type=int, default=2)
    args = parser.parse_args()
    env = os.environ | {
        "OPENBLAS_NUM_THREADS": "1",
        "FLEXWING_WORKERS": str(args.workers),
        "FLEXWING_LOG_LEVEL": "warning",
    }
    with tempfile.TemporaryDirectory() as tmp, service(Path(tmp), env, args.workers) as (url, _):
        per_case, answered = in_process_seconds(args.cases)
        capacity = args.workers / per_case
        print(f"in process: {1e3 * per_case:.2f} ms per case ({answered}/{args.cases} answered)")
        print(f"capacity: {args.workers} workers / per case = {capacity:.0f} cases/s")
        with httpx.Client(base_url=url, timeout=600.0) as client:
            client.post("/loads", json=body(args.cases, 1000))  # every worker warm at this size
            rates = []
            for run in range(args.runs):
                started = time.perf_counter()
                response = client.post("/loads", json=body(args.cases, run))
                seconds = time.perf_counter() - started
                response.raise_for_status()
                answer = response.json()
                rate = len(answer["cases"]) / seconds
                rates.append(rate)
                print(
                    f"/loads run {run}: {seconds:.3f} s, {rate:.0f} cases/s, "
                    f"{answer['info']['answered']}/{len(answer['cases'])} answered, "
                    f"{rate / capacity:.0%} of capacity"
                )
        best, median = max(rates), float(np.median(rates))
        print(
            f"/loads: median {median:.0f} cases/s = {median / capacity:.0%} of capacity "
            f"(best {best / capacity:.0%}; issue 36: >= 70 %)"
        )


if __name__ == "__main__":
    main()
