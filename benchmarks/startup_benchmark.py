"""First start of the service on a machine without the compiled cache (issue 27).

    OPENBLAS_NUM_THREADS=1 .venv/bin/python benchmarks/startup_benchmark.py [--stations 41]

Starts `uvicorn app.main:app` as the README does, with an empty FLEXWING_CACHE_DIR (a new
temporary directory: no compiled library, nothing warmed) and the default settings otherwise,
and measures from the process's start:

- when /readyz first answers 200 (the workers up, serving on CasADi's virtual machine);
- the first /solve of the design study's wing (N = 30), answered on the virtual machine;
- a never-seen mesh (--stations, default 41) answered at once while its library compiles:
  its status and time (never a 503 or a 504 for a valid request because a compile runs);
- when /readyz lists N = 30 as compiled (the library swapped in), and a /solve after it.

Prints the figures and the load average; asserts nothing.
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import argparse
import contextlib
import signal
import socket
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

import httpx

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from app.schemas.examples import STUDY_SOLVE, study_wing  # noqa: E402


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def _wing(n: int) -> dict[str, Any]:
    """The study's planform on n stations (the same formulas as its 30)."""
    y = [5.0 * i / (n - 1) for i in range(n)]
    chord = [(2.0 + (0.02 - 2.0) * i / (n - 1)) ** 0.5 for i in range(n)]
    return {
        "y": y,
        "chord": chord,
        "elastic_axis": 0.4,
        "bending_stiffness": [2e4 * c**3 for c in chord],
        "torsional_stiffness": [1e3 * c**3 for c in chord],
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--stations", type=int, default=41, help="the never-seen mesh")
    parser.add_argument("--compile-wait", type=float, default=300.0, help="[s] at most")
    args = parser.parse_args()
    assert study_wing()["y"]  # the example module's wing is the one sent
    with tempfile.TemporaryDirectory() as cache:
        port = _free_port()
        env = os.environ | {"FLEXWING_CACHE_DIR": cache, "FLEXWING_JOBS_DB": f"{cache}/jobs.db"}
        started = time.perf_counter()
        process = subprocess.Popen(
            [
                *(sys.executable, "-m", "uvicorn", "app.main:app"),
                *("--host", "127.0.0.1", "--port", str(port), "--log-level", "warning"),
                *("--timeout-keep-alive", "75"),
            ],
            cwd=ROOT,
            env=env,
            start_new_session=True,
        )
        client = httpx.Client(base_url=f"http://127.0.0.1:{port}", timeout=120)
        try:
            ready_at = None
            while ready_at is None:
                with contextlib.suppress(httpx.TransportError):
                    if client.get("/readyz").status_code == 200:
                        ready_at = time.perf_counter() - started
                time.sleep(0.02)
            ready = client.get("/readyz").json()
            print(f"load average {os.getloadavg()[0]:.2f} (2 cores)")
            print(f"/readyz 200 after {ready_at:.2f} s: {ready.get('detail', '')}")
            t = time.perf_counter()
            first = client.post("/solve", json=STUDY_SOLVE)
            print(
                f"first /solve (N = 30): {first.status_code} in "
                f"{(time.perf_counter() - t) * 1e3:.0f} ms"
            )
            n = args.stations
            body = STUDY_SOLVE | {"wing": _wing(n)}
            t = time.perf_counter()
            other = client.post("/solve", json=body)
            print(
                f"never-seen mesh N = {n}: {other.status_code} in "
                f"{(time.perf_counter() - t) * 1e3:.0f} ms (its library compiling)"
            )
            deadline = time.perf_counter() + args.compile_wait
            while 30 not in client.get("/readyz").json().get("compiled", []):
                if time.perf_counter() > deadline:
                    print(f"N = 30 not compiled within {args.compile_wait:.0f} s")
                    break
                time.sleep(0.5)
            else:
                swapped = time.perf_counter() - started
                body = STUDY_SOLVE | {"flight": STUDY_SOLVE["flight"] | {"velocity": 11.0}}
                t = time.perf_counter()
                after = client.post("/solve", json=body)
                print(
                    f"N = 30 library swapped in after {swapped:.0f} s; a /solve then: "
                    f"{after.status_code} in {(time.perf_counter() - t) * 1e3:.1f} ms"
                )
            print(f"load average {os.getloadavg()[0]:.2f}")
        finally:
            client.close()
            process.send_signal(signal.SIGINT)
            try:
                process.wait(timeout=30)
            except subprocess.TimeoutExpired:
                process.kill()
            with contextlib.suppress(ProcessLookupError):
                os.killpg(process.pid, signal.SIGKILL)


if __name__ == "__main__":
    main()
