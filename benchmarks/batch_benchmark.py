"""Batch throughput: 1,000 solves of varied wings as one batch job (POST /jobs), local pool vs Dask.

    OPENBLAS_NUM_THREADS=1 .venv/bin/python benchmarks/batch_benchmark.py [--items 1000]

Deployments measured, each a real uvicorn service on loopback (and real `dask scheduler` /
`dask worker` processes, one thread each, sharing FLEXWING_CACHE_DIR, their statistical profiler
off and their housekeeping less frequent, see docs/deployment.md):

- the local pool, FLEXWING_WORKERS=2 (the default on this 2-core machine);
- Dask with 1 worker, then with 2 workers.

Items: the design study's wing (N = 30, compiled) with its stiffness scaled by 0.8-2.0 and airspeeds
6-15 m/s at alpha 5 deg, every item a different wing (no warm start, no cached result). Items per
second are the service's own (started_at to finished_at of the job); "wall" adds the upload and
parsing of the body. Each deployment runs two batches of new items and reports both, with the CPU
time per item of the service process and of the workers (Linux /proc; remote workers would need
their own accounting).

The capacity the service is held to is measured in the same run: 300 items of the same kind
solved one after another in this process (`solver`, compiled, no HTTP, no workers), and
capacity = workers / (time per item). Each deployment prints its throughput as a share of it
(issue 27: the local pool >= 70 %; Dask with 2 workers >= 80 % of the local pool).

The scheduler's own cost is measured with no-op tasks from a Dask client: the round trip of one
task at a time, and the throughput of 2,000 tasks submitted at once.
"""

from __future__ import annotations

import argparse
import asyncio
import contextlib
import os
import signal
import socket
import subprocess
import sys
import tempfile
import time
from collections.abc import Iterator
from datetime import datetime
from pathlib import Path
from typing import Any

import httpx
import numpy as np

ROOT = Path(__file__).resolve().parents[1]
DASK = Path(sys.executable).with_name("dask")
DASK_HOUSEKEEPING = {
    "DASK_DISTRIBUTED__ADMIN__TICK__INTERVAL": "1s",
    "DASK_DISTRIBUTED__ADMIN__SYSTEM_MONITOR__INTERVAL": "5s",
    "DASK_DISTRIBUTED__WORKER__MEMORY__MONITOR_INTERVAL": "1s",
}
READY_TIMEOUT = 300.0  # [s]


def item(index: int, count: int, run: int = 0) -> dict[str, Any]:
    """A /solve body: the study's wing, stiffness x 0.8-2.0, 6-15 m/s (distinct per item and
    per run, so no run is answered from the result cache)."""
    rng = np.random.default_rng([index, run])
    scale = 0.8 + 1.2 * rng.random()
    y = np.linspace(0, 5, 30)
    chord = np.sqrt(np.linspace(2, 0.02, 30))
    return {
        "wing": {
            "y": y.tolist(),
            "chord": chord.tolist(),
            "elastic_axis": 0.4,
            "bending_stiffness": (2e4 * chord**3 * scale).tolist(),
            "torsional_stiffness": (1e3 * chord**3 * scale).tolist(),
        },
        "flight": {"velocity": 6.0 + 9.0 * index / max(1, count - 1), "alpha": 5.0},
    }


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


@contextlib.contextmanager
def process(args: list[str], log: Path, env: dict[str, str]) -> Iterator[subprocess.Popen[bytes]]:
    with open(log, "wb") as out:
        child = subprocess.Popen(
            args, cwd=ROOT, env=env, stdout=out, stderr=subprocess.STDOUT, start_new_session=True
        )
    try:
        yield child
    finally:
        with contextlib.suppress(ProcessLookupError):
            os.killpg(child.pid, signal.SIGTERM)
        try:
            child.wait(timeout=20)
        except subprocess.TimeoutExpired:
            os.killpg(child.pid, signal.SIGKILL)
            child.wait()


def wait_ready(base_url: str, workers: int) -> None:
    deadline = time.monotonic() + READY_TIMEOUT
    while time.monotonic() < deadline:
        with contextlib.suppress(httpx.TransportError):
            body = httpx.get(base_url + "/readyz", timeout=5).json()
            cluster = body.get("cluster")
            warm = len(body["pids"]) if cluster is None else sum(w["warm"] for w in cluster)
            if body["ready"] and warm >= workers:
                return
        time.sleep(0.1)
    raise TimeoutError(f"{base_url} not ready")


@contextlib.contextmanager
def service(tmp: Path, env: dict[str, str], workers: int) -> Iterator[tuple[str, int]]:
    port = free_port()
    args = [sys.executable, "-m", "uvicorn", "app.main:app", "--host", "127.0.0.1"]
    args += ["--port", str(port), "--log-level", "warning", "--timeout-keep-alive", "75"]
    env = env | {"FLEXWING_JOBS_DB": str(tmp / f"jobs-{port}.sqlite3")}
    with process(args, tmp / f"service-{port}.log", env) as child:
        base_url = f"http://127.0.0.1:{port}"
        wait_ready(base_url, workers)
        yield base_url, child.pid


def cpu_seconds(pid: int) -> float:
    """User + system CPU time of a process so far [s] (Linux /proc)."""
    fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def worker_pids(base_url: str) -> list[int]:
    body = httpx.get(base_url + "/readyz", timeout=5).json()
    cluster = body.get("cluster")
    return list(body["pids"]) if cluster is None else [w["pid"] for w in cluster if w["pid"]]


def run_batch(base_url: str, items: list[dict[str, Any]]) -> tuple[float, float, dict[str, Any]]:
    """(items/s of the job, items/s of the wall clock incl. upload, progress)."""
    with httpx.Client(base_url=base_url, timeout=600) as client:
        started = time.perf_counter()
        response = client.post("/jobs", json={"operation": "batch", "request": {"items": items}})
        response.raise_for_status()
        location = response.headers["location"]
        while (job := client.get(location).json())["status"] in ("queued", "running"):
            time.sleep(0.05)
        wall = time.perf_counter() - started
    assert job["status"] == "succeeded", job
    run = datetime.fromisoformat(job["finished_at"]) - datetime.fromisoformat(job["started_at"])
    return len(items) / run.total_seconds(), len(items) / wall, job["progress"]


@contextlib.contextmanager
def dask_cluster(tmp: Path, env: dict[str, str], workers: int) -> Iterator[tuple[str, int]]:
    """(scheduler address, scheduler pid) of a scheduler and `workers` workers (no nanny: the
    worker pids /readyz reports are the processes doing the work)."""
    port = free_port()
    address = f"tcp://127.0.0.1:{port}"
    with contextlib.ExitStack() as stack:
        # Dask's own housekeeping less often on the two shared cores (docs/deployment.md: its
        # event-loop health check every 20 ms, system monitor every 0.5 s, memory monitor every
        # 0.1 s, here 1 s, 5 s and 1 s; measured: 2-3 points of the share).
        env = env | DASK_HOUSEKEEPING
        scheduler = [str(DASK), "scheduler", "--host", "127.0.0.1", "--port", str(port)]
        log = tmp / "scheduler.log"
        child = stack.enter_context(process([*scheduler, "--no-dashboard"], log, env))
        # Without Dask's statistical profiler (nobody reads a dashboard here): it samples the
        # worker's threads every 10 ms, a few per cent of their CPU (docs/deployment.md).
        quiet = env | {"DASK_DISTRIBUTED__WORKER__PROFILE__ENABLED": "False"}
        for n in range(workers):
            args = [str(DASK), "worker", address, "--nthreads", "1", "--no-dashboard"]
            args += ["--no-nanny", "--name", f"w{n}"]
            stack.enter_context(process(args, tmp / f"w{n}.log", quiet))
        yield address, child.pid


def noop(x: int) -> int:
    return x


async def scheduler_cost(address: str) -> tuple[float, float]:
    """(ms per no-op task one at a time, ms per no-op task of 2,000 submitted at once)."""
    from distributed import Client

    client = await Client(address, asynchronous=True)
    try:
        for warm_up in range(20):
            await client.submit(noop, warm_up, pure=False).result()
        started = time.perf_counter()
        for n in range(200):
            await client.submit(noop, n, pure=False).result()
        one_at_a_time = (time.perf_counter() - started) / 200
        started = time.perf_counter()
        await client.gather(client.map(noop, range(2000), pure=False))
        many = (time.perf_counter() - started) / 2000
    finally:
        await client.close()
    return 1000 * one_at_a_time, 1000 * many


def in_process_seconds(count: int = 300) -> float:
    """[s] median time per item solved in this process, items like the batch's (run 99)."""
    import solver
    from app.schemas import SolveRequest

    solver.warm_up(30)
    tasks = [SolveRequest.model_validate(item(i, count, 99)).to_solver() for i in range(count)]
    times = []
    for task in tasks:
        started = time.perf_counter()
        task.run(None)
        times.append(time.perf_counter() - started)
    return float(np.median(times))


def report(
    label: str,
    count: int,
    base_url: str,
    service_pid: int,
    capacity: float,
    scheduler_pid: int | None = None,
) -> list[float]:
    """Two runs of `count` new items; CPU per item of the service, the workers and the Dask
    scheduler [ms]; the job's items/s of each run."""
    rates = []
    for run in (1, 2):
        items = [item(i, count, run) for i in range(count)]
        pids = [[service_pid], worker_pids(base_url), [scheduler_pid] if scheduler_pid else []]
        before = [sum(cpu_seconds(p) for p in group) for group in pids]
        job_rate, wall_rate, progress = run_batch(base_url, items)
        after = [sum(cpu_seconds(p) for p in group) for group in pids]
        web, work, scheduler = ((a - b) * 1000 / count for a, b in zip(after, before, strict=True))
        rates.append(job_rate)
        print(
            f"{label:<22} run {run}: {job_rate:5.0f} items/s (job, {job_rate / capacity:.0%} of "
            f"capacity), {wall_rate:5.0f} items/s (wall); CPU per item: service {web:.2f} ms, "
            f"workers {work:.2f} ms"
            + (f", scheduler {scheduler:.2f} ms" if scheduler_pid else "")
            + f"; problems {progress['problems']}"
        )
    return rates


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--items", type=int, default=1000)
    parser.add_argument("--no-dask", action="store_true", help="the local pool only")
    args = parser.parse_args()
    quiet = {"OPENBLAS_NUM_THREADS": "1", "PYTHONUNBUFFERED": "1", "FLEXWING_RATE_LIMIT": "0"}
    quiet |= {"FLEXWING_WARMUP_TIMEOUT": "600"}  # measured on compiled code
    env = os.environ | quiet
    per_item = in_process_seconds()
    workers = 2
    capacity = workers / per_item
    print(
        f"{args.items} solves of varied wings (N = 30) in one batch job; in this process "
        f"{per_item * 1e3:.2f} ms per item (median of 300): capacity of {workers} workers "
        f"{capacity:.0f} items/s; load average {os.getloadavg()[0]:.2f}"
    )
    with tempfile.TemporaryDirectory() as name:
        tmp = Path(name)
        with service(tmp, env | {"FLEXWING_WORKERS": str(workers)}, workers) as (base_url, pid):
            local = report("local pool, 2 workers", args.items, base_url, pid, capacity)
        if args.no_dask:
            return
        for count in (1, 2):
            with dask_cluster(tmp, env, count) as (address, scheduler):
                dask = {"FLEXWING_EXECUTOR": "dask", "FLEXWING_DASK_SCHEDULER": address}
                with service(tmp, env | dask, count) as (base_url, pid):
                    label = f"dask, {count} worker(s)"
                    rates = report(label, args.items, base_url, pid, capacity, scheduler)
                one, many = asyncio.run(scheduler_cost(address))
                print(
                    f"dask scheduler, {count} worker(s): a no-op task takes {one:.1f} ms one at "
                    f"a time, {many:.2f} ms each when 2,000 are submitted at once"
                )
        print(
            f"dask with 2 workers / local pool: {max(rates) / max(local):.0%} (best runs); "
            f"load average {os.getloadavg()[0]:.2f}"
        )


if __name__ == "__main__":
    main()
