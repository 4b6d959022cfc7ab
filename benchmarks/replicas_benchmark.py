"""Past one box: two replicas sharing PostgreSQL against one service with SQLite, same machine.

    OPENBLAS_NUM_THREADS=1 .venv/bin/python benchmarks/replicas_benchmark.py [--jobs 300]

Deployments, each real uvicorn processes on loopback, with the same two worker processes in all:

- one service, FLEXWING_WORKERS=2, its jobs in an SQLite file (the default);
- two replicas, FLEXWING_WORKERS=1 each, sharing a PostgreSQL cluster that this script makes
  with Debian's binaries (tests/postgres.py; fsync on, as a deployment runs it), the client
  alternating between them as a load balancer would.

Both run with a rate limit that never refuses (FLEXWING_RATE_LIMIT=1e6): the shared deployment
consults its token bucket in PostgreSQL on every request, the single one in memory; the
replicas' /solve is measured once more without a rate limit, which isolates the bucket's cost.

Measured in each deployment:

- jobs per second: `--jobs` solve jobs (POST /jobs, each a distinct study wing, N = 30,
  compiled: a few ms of solving) submitted by 16 concurrent clients, each polling its job until
  it ends; jobs/s from the first created_at to the last finished_at; with the CPU per job of the
  service processes (not their workers) and of the PostgreSQL server (its processes, /proc);
- a batch of `--items` solves as one job: items per second (its items are store rows);
- /solve p50 and p90: one client, sequential, distinct wings (never from the result cache).

And in this process, with no HTTP and no service, the store's own time per job: what a job asks
of it (submit, claim, finish, two reads) one job after another, SQLite against PostgreSQL, and
one rate-limit token. Every deployment is up at once and measured in turn, `--rounds` times, so
the machine's drift falls on all alike. Ratios to the single service are printed; nothing is
asserted.
"""

from __future__ import annotations

import argparse
import asyncio
import contextlib
import os
import signal
import subprocess
import sys
import tempfile
import time
from collections.abc import Iterator
from dataclasses import dataclass, field
from datetime import datetime
from pathlib import Path
from typing import Any

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import httpx
import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from app.jobs.store import Store, new_job_id  # noqa: E402
from tests.postgres import Cluster, free_port  # noqa: E402

READY_TIMEOUT = 300.0  # [s]
CLOCK_TICK = os.sysconf("SC_CLK_TCK")


def wing_item(index: int, run: str) -> dict[str, Any]:
    """A /solve body: the study's wing, stiffness x 0.8-2.0, 6-15 m/s, distinct per index and
    run (no result cache, no warm start)."""
    rng = np.random.default_rng([index, sum(map(ord, run))])
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
        "flight": {"velocity": 6.0 + 9.0 * rng.random(), "alpha": 5.0},
    }


# ------------------------------------------------------------------------------- processes


def cpu_seconds(pid: int, children: bool = False) -> float:
    """User + system CPU of a process [s] (with its waited-for children's when asked)."""
    fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    ticks = int(fields[11]) + int(fields[12])
    if children:
        ticks += int(fields[13]) + int(fields[14])
    return ticks / CLOCK_TICK


def postgres_cpu(cluster: Cluster) -> float:
    """CPU of the cluster's postmaster, its live children and the children it reaped [s]."""
    postmaster = int((cluster.data / "postmaster.pid").read_text().split()[0])
    total = cpu_seconds(postmaster, children=True)
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            with contextlib.suppress(OSError, IndexError):
                fields = (entry / "stat").read_text().rsplit(")", 1)[1].split()
                if int(fields[1]) == postmaster:
                    total += cpu_seconds(int(entry.name))
    return total


@contextlib.contextmanager
def service(tmp: Path, env: dict[str, str]) -> Iterator[tuple[str, int]]:
    """(base URL, pid) of a uvicorn service on a free port, once /readyz says ready."""
    port = free_port()
    args = [sys.executable, "-m", "uvicorn", "app.main:app", "--host", "127.0.0.1"]
    args += ["--port", str(port), "--log-level", "warning", "--timeout-keep-alive", "75"]
    log = tmp / f"service-{port}.log"
    with open(log, "wb") as out:
        child = subprocess.Popen(
            args,
            cwd=ROOT,
            env=os.environ | env,
            stdout=out,
            stderr=subprocess.STDOUT,
            start_new_session=True,
        )
    base_url = f"http://127.0.0.1:{port}"
    try:
        deadline = time.monotonic() + READY_TIMEOUT
        while True:
            with contextlib.suppress(httpx.TransportError):
                if httpx.get(base_url + "/readyz", timeout=5).status_code == 200:
                    break
            if child.poll() is not None or time.monotonic() > deadline:
                raise RuntimeError(f"service did not start:\n{log.read_text()}")
            time.sleep(0.1)
        yield base_url, child.pid
    finally:
        with contextlib.suppress(ProcessLookupError):
            os.killpg(child.pid, signal.SIGTERM)
        try:
            child.wait(timeout=30)
        except subprocess.TimeoutExpired:
            os.killpg(child.pid, signal.SIGKILL)
            child.wait()


# ------------------------------------------------------------------------------- the load


async def jobs_per_second(urls: list[str], count: int, run: str) -> tuple[float, float]:
    """(jobs/s from first created to last finished, jobs/s of the wall clock)."""
    bodies = [{"operation": "solve", "request": wing_item(n, run)} for n in range(count)]
    clients = [httpx.AsyncClient(base_url=url, timeout=120) for url in urls]
    pending = list(enumerate(bodies))
    rows: list[dict[str, Any]] = []

    async def submitter() -> None:
        while pending:
            n, body = pending.pop()
            client = clients[n % len(clients)]
            response = await client.post("/jobs", json=body)
            response.raise_for_status()
            location = response.headers["location"]
            while (job := (await client.get(location)).json())["status"] in ("queued", "running"):
                await asyncio.sleep(0.02)
            assert job["status"] == "succeeded", job
            rows.append(job)

    started = time.perf_counter()
    await asyncio.gather(*(submitter() for _ in range(16)))
    wall = time.perf_counter() - started
    for client in clients:
        await client.aclose()
    first = min(datetime.fromisoformat(row["created_at"]) for row in rows)
    last = max(datetime.fromisoformat(row["finished_at"]) for row in rows)
    return count / (last - first).total_seconds(), count / wall


def batch_items_per_second(url: str, count: int, run: str) -> float:
    items = [wing_item(n, run) for n in range(count)]
    with httpx.Client(base_url=url, timeout=600) as client:
        response = client.post("/jobs", json={"operation": "batch", "request": {"items": items}})
        response.raise_for_status()
        location = response.headers["location"]
        while (job := client.get(location).json())["status"] in ("queued", "running"):
            time.sleep(0.05)
    assert job["status"] == "succeeded", job
    seconds = datetime.fromisoformat(job["finished_at"]) - datetime.fromisoformat(job["started_at"])
    return count / seconds.total_seconds()


def solve_latencies(urls: list[str], count: int, run: str) -> tuple[float, float]:
    """(p50, p90) [ms] of sequential /solve requests, alternating between `urls`."""
    p50, p90 = np.percentile(solve_times(urls, count, run), [50, 90])
    return float(p50), float(p90)


def solve_times(urls: list[str], count: int, run: str) -> list[float]:
    """[ms] of sequential /solve requests, alternating between `urls`."""
    clients = [httpx.Client(base_url=url, timeout=60) for url in urls]
    times = []
    for n in range(count):
        body = wing_item(n, run)
        started = time.perf_counter()
        response = clients[n % len(clients)].post("/solve", json=body)
        times.append(time.perf_counter() - started)
        response.raise_for_status()
    for client in clients:
        client.close()
    return [1e3 * t for t in times]


# ------------------------------------------------------------------------ the store alone


async def store_per_job(store: Store, count: int) -> tuple[float, float, float]:
    """[ms] of the store: per job (submit, claim, finish, two reads), per token, per read of
    a job (what a stream polling a job on another replica asks)."""
    await store.open()
    try:
        started = time.perf_counter()
        for n in range(count):
            job_id = new_job_id()
            row: dict[str, Any] = {"id": job_id, "operation": "solve", "status": "queued"}
            row["owner"] = "me"
            row |= {"principal": "", "created": time.time() + n, "total": 1, "request": "{}"}
            assert await store.submit(row, 10_000)
            claim = await store.claim("me", time.time(), 10.0)
            assert claim is not None
            await store.get_job(job_id)
            store.update_job(job_id, "me", {"status": "succeeded", "result": "{}", "done": 1})
            await store.get_job(job_id, with_result=True)
        per_job = (time.perf_counter() - started) / count
        started = time.perf_counter()
        for _ in range(count):
            await store.take_token("key:x", 1e6, 1_000_000, time.time())
        per_token = (time.perf_counter() - started) / count
        started = time.perf_counter()
        for _ in range(count):
            await store.get_job(job_id)
        per_read = (time.perf_counter() - started) / count
    finally:
        await store.close()
    return 1e3 * per_job, 1e3 * per_token, 1e3 * per_read


# ------------------------------------------------------------------------------------ main


@dataclass
class Deployment:
    """One deployment's services (URLs and the pids of their uvicorn processes) and what was
    measured of it, round after round."""

    name: str
    urls: list[str]
    pids: list[int]
    cluster: Cluster | None = None
    jobs: int = 0
    job_seconds: float = 0.0  # first created to last finished, summed over rounds
    service_cpu: float = 0.0  # [s] during its job rounds
    database_cpu: float = 0.0
    items: int = 0
    item_seconds: float = 0.0
    solves: list[float] = field(default_factory=list)  # [ms]

    def cpu(self) -> tuple[float, float]:
        database = postgres_cpu(self.cluster) if self.cluster else 0.0
        return sum(cpu_seconds(pid) for pid in self.pids), database

    def job_round(self, count: int, run: str) -> None:
        service, database = self.cpu()
        rate, _ = asyncio.run(jobs_per_second(self.urls, count, run))
        service_after, database_after = self.cpu()
        self.jobs += count
        self.job_seconds += count / rate
        self.service_cpu += service_after - service
        self.database_cpu += database_after - database

    def batch_round(self, count: int, run: str) -> None:
        self.items += count
        self.item_seconds += count / batch_items_per_second(self.urls[0], count, run)

    def figures(self) -> dict[str, float]:
        p50, p90 = np.percentile(self.solves, [50, 90]) if self.solves else (np.nan, np.nan)
        jobs = max(self.jobs, 1)
        return {
            "jobs/s": self.jobs / self.job_seconds if self.job_seconds else np.nan,
            "service CPU ms/job": 1e3 * self.service_cpu / jobs,
            "postgres CPU ms/job": 1e3 * self.database_cpu / jobs,
            "batch items/s": self.items / self.item_seconds if self.item_seconds else np.nan,
            "/solve p50 ms": float(p50),
            "/solve p90 ms": float(p90),
        }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--jobs", type=int, default=300, help="solve jobs per deployment")
    parser.add_argument("--items", type=int, default=1000, help="batch items per deployment")
    parser.add_argument("--solves", type=int, default=300, help="/solve requests per deployment")
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--store-jobs", type=int, default=500)
    args = parser.parse_args()
    print(f"load average before: {os.getloadavg()}")
    limited = {"FLEXWING_RATE_LIMIT": "1000000", "FLEXWING_RATE_BURST": "1000000"}
    with tempfile.TemporaryDirectory() as tmp_name, contextlib.ExitStack() as stack:
        tmp = Path(tmp_name)
        cluster = Cluster(fsync=True)
        cluster.start()
        stack.callback(cluster.remove)
        count = args.store_jobs
        sqlite_ms = asyncio.run(store_per_job(Store.of(None, tmp / "alone.sqlite3"), count))
        postgres_ms = asyncio.run(store_per_job(Store.of(cluster.schema(), tmp), count))
        print("\nthe store alone, in process, one after another [ms]")
        print("              per job   per token  per read")
        for name, ms in (("SQLite", sqlite_ms), ("PostgreSQL", postgres_ms)):
            print(f"  {name:10s}  {ms[0]:7.3f}   {ms[1]:7.3f}    {ms[2]:7.3f}")
        # Every deployment up at once (the idle ones cost next to nothing), measured in turn,
        # round after round: the machine's drift falls on all of them alike.
        single_env = limited | {"FLEXWING_WORKERS": "2", "FLEXWING_JOBS_DB": str(tmp / "j.db")}
        single = Deployment("one service, SQLite", [], [])
        shared = Deployment("two replicas, PostgreSQL", [], [], cluster)
        unlimited = Deployment("two replicas, PostgreSQL, no rate limit (/solve only)", [], [])
        replica_env = {"FLEXWING_WORKERS": "1", "FLEXWING_DATABASE_URL": cluster.schema()}
        for target, env, copies in (
            (single, single_env, 1),
            (shared, limited | replica_env, 2),
            (unlimited, replica_env | {"FLEXWING_DATABASE_URL": cluster.schema()}, 2),
        ):
            for _ in range(copies):
                url, pid = stack.enter_context(service(tmp, env))
                target.urls.append(url)
                target.pids.append(pid)
        everyone = (single, shared, unlimited)
        for deployment in everyone:
            solve_latencies(deployment.urls, 20, f"{deployment.name}-warm")
        for n in range(args.rounds):
            for deployment in (single, shared):
                deployment.job_round(args.jobs // args.rounds, f"{deployment.name}-{n}")
                deployment.batch_round(args.items // args.rounds, f"{deployment.name}-{n}")
            for deployment in everyone:
                run = f"{deployment.name}-solve-{n}"
                deployment.solves += solve_times(deployment.urls, args.solves // args.rounds, run)
        results = {deployment.name: deployment.figures() for deployment in everyone}
    for name, figures in results.items():
        print(f"\n{name}")
        for key, value in figures.items():
            print(f"  {key:22s} {value:9.2f}")
    one, two = results[single.name], results[shared.name]
    print("\ntwo replicas / one service")
    for key in ("jobs/s", "batch items/s", "/solve p50 ms", "/solve p90 ms"):
        print(f"  {key:22s} {two[key] / one[key]:9.2f}")
    extra = two["service CPU ms/job"] + two["postgres CPU ms/job"] - one["service CPU ms/job"]
    print(f"  shared store's CPU per job (services + PostgreSQL - single service): {extra:.2f} ms")
    bucket = results[shared.name]["/solve p50 ms"] - results[unlimited.name]["/solve p50 ms"]
    print(f"  the shared rate-limit bucket in /solve p50: {bucket:+.2f} ms")
    print(f"load average after: {os.getloadavg()}")


if __name__ == "__main__":
    main()
