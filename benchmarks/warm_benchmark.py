"""Warm starts per wing: a wing asked again, at airspeeds 1e-9 apart, after its first answer.

    .venv/bin/python benchmarks/warm_benchmark.py [--stations 138] [--service] [--compile]

The case (issue 40): a trimmed sweep of a many-station wing past its fold, on a never-seen mesh,
then the same wing at airspeeds 1e-9 apart. Nothing of the first answer can be reused as it is
(the requests differ), and answers never depend on what was asked before; what a wing's answers
share and rebuild bit for bit stays in the worker's solver cache (its trimmed divergence limit,
its branch from the jig, its compiled mesh), so the second should take a third of the first or
less.

In process: the first sweep from an empty solver cache, then the second; on CasADi's virtual
machine unless --compile (a compile in the background would race the measurement).
--service: the same two requests as jobs (Prefer: respond-async) through a real service, 2
workers, a fresh compile cache (the mesh never seen), one after the other: the second goes to the
worker that ran the wing (`app.execution.pool.affinity_of`). Prints each time and the ratio.
"""

from __future__ import annotations

import argparse
import json
import os
import socket
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

VELOCITIES = [10.0, 14.0, 18.0, 20.0, 22.0, 24.0, 26.0, 28.0]  # the study's fold: ~24 m/s
LIFT = 300.0  # [N] the study's weight


def _wing_json(stations: int) -> dict[str, Any]:
    from tests import study

    return study.wing_json(n=stations)


def _apart(velocities: list[float]) -> list[float]:
    return [v + 1e-9 for v in velocities]


def in_process(stations: int) -> tuple[float, float]:
    import solver
    from tests import study

    wing = solver.Wing.create(**study.study_arrays(stations))
    flight = solver.FlightCondition(None, lift=LIFT)
    solver.clear_caches()
    started = time.perf_counter()
    first = solver.airspeed_sweep(wing, VELOCITIES, flight)
    cold = time.perf_counter() - started
    started = time.perf_counter()
    second = solver.airspeed_sweep(wing, _apart(VELOCITIES), flight)
    warm = time.perf_counter() - started
    assert [p.status for p in first.points] == [p.status for p in second.points]
    return cold, warm


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def _job(base: str, body: dict[str, Any]) -> float:
    import httpx

    started = time.perf_counter()
    with httpx.Client(base_url=base, timeout=60) as client:
        accepted = client.post("/sweep", json=body, headers={"Prefer": "respond-async"})
        assert accepted.status_code == 202, accepted.text
        location = accepted.headers["location"]
        while True:
            job = client.get(location).json()
            if job["status"] in ("succeeded", "failed", "cancelled"):
                assert job["status"] == "succeeded", job
                return time.perf_counter() - started
            time.sleep(0.05)


def through_the_service(stations: int) -> tuple[float, float]:
    import httpx

    port = _free_port()
    with tempfile.TemporaryDirectory() as scratch:
        env = os.environ | {
            "FLEXWING_CACHE_DIR": str(Path(scratch) / "cache"),
            "FLEXWING_JOBS_DB": str(Path(scratch) / "jobs.sqlite3"),
            "FLEXWING_WORKERS": "2",
            "FLEXWING_SWEEP_TIMEOUT": "3600",
        }
        command = [sys.executable, "-m", "uvicorn", "app.main:app", "--port", str(port)]
        server = subprocess.Popen(command, cwd=ROOT, env=env, stderr=subprocess.DEVNULL)
        base = f"http://127.0.0.1:{port}"
        try:
            deadline = time.monotonic() + 600
            while time.monotonic() < deadline:
                try:
                    if httpx.get(base + "/readyz", timeout=5).status_code == 200:
                        break
                except httpx.TransportError:
                    pass
                time.sleep(0.2)
            body = {
                "wing": _wing_json(stations),
                "flight": {"lift": LIFT},
                "velocities": VELOCITIES,
            }
            cold = _job(base, body)
            warm = _job(base, body | {"velocities": _apart(VELOCITIES)})
            return cold, warm
        finally:
            server.terminate()
            server.wait(30)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--stations", type=int, default=138)
    parser.add_argument("--service", action="store_true")
    parser.add_argument("--compile", action="store_true")
    args = parser.parse_args()
    if not args.compile:
        os.environ["FLEXWING_COMPILE"] = "0"
    print(f"load average {os.getloadavg()} on {os.cpu_count()} CPUs")
    figures: dict[str, Any] = {"stations": args.stations, "velocities": VELOCITIES}
    cold, warm = in_process(args.stations)
    figures["in_process"] = {"first_s": cold, "second_s": warm, "ratio": warm / cold}
    print(json.dumps(figures, indent=1))
    if args.service:
        cold, warm = through_the_service(args.stations)
        figures["service"] = {"first_s": cold, "second_s": warm, "ratio": warm / cold}
        print(json.dumps(figures["service"], indent=1))


if __name__ == "__main__":
    main()
