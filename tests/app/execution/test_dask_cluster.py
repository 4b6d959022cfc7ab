"""FLEXWING_EXECUTOR=dask against a real dask.distributed cluster on loopback.

The module starts `dask scheduler` and two `dask worker` processes (one thread each, no nanny, so
the process killed is the worker itself), with OPENBLAS_NUM_THREADS=1 and one FLEXWING_CACHE_DIR
shared by both (the default one, where the other tests' servers keep the compiled N = 30), then a
service pointed at the scheduler. /solve, /sweep and a batch job must give the local pool's
answers; a batch must survive one worker killed with SIGKILL in its middle: Dask reruns that
worker's tasks on the other, and every item is answered, correctly.
"""

from __future__ import annotations

import contextlib
import os
import signal
import socket
import subprocess
import sys
import time
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import httpx
import pytest

import solver
from app.schemas.examples import LOADS_EXAMPLES
from app.schemas.requests import REQUESTS
from solver.numerics.compiled import cache_dir
from tests import study
from tests.app.conftest import ROOT, Server

# Run with the live-server tests, after the fast loop: a Dask scheduler and workers.
pytestmark = pytest.mark.server

pytest.importorskip("distributed", reason="FLEXWING_EXECUTOR=dask needs flexwing[dask]")

DASK = Path(sys.executable).with_name("dask")
START_TIMEOUT = 300.0  # [s] the first start on a machine compiles N = 30 (~17 s)
WARM_VS_COLD = 1e-8  # relative: a warm-started equilibrium against a cold one (test_determinism)
WORKER_OPTIONS = ("--nthreads", "1", "--no-nanny", "--no-dashboard")
BATCH = 400  # items: a few seconds on two workers, long enough to kill one mid-way


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def _wait(condition: Any, what: str, limit: float = START_TIMEOUT) -> Any:
    deadline = time.monotonic() + limit
    while True:
        with contextlib.suppress(httpx.TransportError):
            value = condition()
            if value:
                return value
        assert time.monotonic() < deadline, f"never happened: {what}"
        time.sleep(0.05)


@dataclass
class Cluster:
    scheduler: str  # tcp://127.0.0.1:PORT
    workers: dict[str, subprocess.Popen[bytes]]  # by name


def _spawn(args: list[str], log: Path, env: dict[str, str]) -> subprocess.Popen[bytes]:
    with open(log, "wb") as out:
        return subprocess.Popen(
            args, cwd=ROOT, env=env, stdout=out, stderr=subprocess.STDOUT, start_new_session=True
        )


def _end(process: subprocess.Popen[bytes]) -> None:
    with contextlib.suppress(ProcessLookupError):
        os.killpg(process.pid, signal.SIGTERM)
    try:
        process.wait(timeout=15)
    except subprocess.TimeoutExpired:
        with contextlib.suppress(ProcessLookupError):
            os.killpg(process.pid, signal.SIGKILL)
        process.wait()


@pytest.fixture(scope="module")
def cluster(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Cluster]:
    tmp = tmp_path_factory.mktemp("dask")
    env = os.environ | {
        "OPENBLAS_NUM_THREADS": "1",
        "FLEXWING_CACHE_DIR": str(cache_dir()),  # one directory every worker sees
        "PYTHONUNBUFFERED": "1",
    }
    address = f"tcp://127.0.0.1:{_free_port()}"
    port = address.rsplit(":", 1)[1]
    processes = [
        _spawn(
            [str(DASK), "scheduler", "--host", "127.0.0.1", "--port", port, "--no-dashboard"],
            tmp / "scheduler.log",
            env,
        )
    ]
    workers = {}
    for name in ("w1", "w2"):
        workers[name] = _spawn(
            [str(DASK), "worker", address, "--name", name, *WORKER_OPTIONS],
            tmp / f"{name}.log",
            env,
        )
    processes += workers.values()
    try:
        yield Cluster(address, workers)
    finally:
        for process in reversed(processes):
            _end(process)


@pytest.fixture(scope="module")
def dask_service(cluster: Cluster, tmp_path_factory: pytest.TempPathFactory) -> Iterator[Server]:
    tmp = tmp_path_factory.mktemp("dask_service")
    port = _free_port()
    env = os.environ | {
        "FLEXWING_EXECUTOR": "dask",
        "FLEXWING_DASK_SCHEDULER": cluster.scheduler,
        "FLEXWING_JOBS_DB": str(tmp / "jobs.sqlite3"),
        "PYTHONUNBUFFERED": "1",
    }
    args = [sys.executable, "-m", "uvicorn", "app.main:app", "--host", "127.0.0.1"]
    process = _spawn([*args, "--port", str(port), "--log-level", "warning"], tmp / "log", env)
    server = Server(f"http://127.0.0.1:{port}", process, tmp / "log")
    try:
        _wait(lambda: len(warm_workers(server)) == 2, "both Dask workers warm")
        yield server
    finally:
        _end(process)


def readyz(server: Server) -> httpx.Response:
    assert server.process.poll() is None, server.log.read_text()
    return httpx.get(server.base_url + "/readyz", timeout=10)


def warm_workers(server: Server) -> list[str]:
    response = readyz(server)
    cluster = response.json().get("cluster") or []
    return sorted(worker["name"] for worker in cluster if worker["warm"])


def test_the_service_reports_the_dask_cluster_in_readyz(dask_service: Server) -> None:
    response = readyz(dask_service)
    assert response.status_code == 200
    body = response.json()
    assert body["ready"] is True
    assert body["pids"] == []  # no local workers
    assert sorted(worker["name"] for worker in body["cluster"]) == ["w1", "w2"]
    assert all(w["warm"] and w["threads"] == 1 and w["pid"] > 0 for w in body["cluster"])
    assert "2 of 2 Dask worker(s) warm" in body["detail"]


def test_solve_and_sweep_on_dask_give_the_studys_numbers(dask_service: Server) -> None:
    with dask_service.client() as client:
        response = client.post("/solve", json=_item(0))
        assert response.status_code == 200, response.text
        totals = response.json()["totals"]
        assert totals["lift"] == pytest.approx(304.13, abs=0.005)
        assert totals["tip_twist"] == pytest.approx(1.708, abs=0.0005)
        body = {
            "wing": study.wing_json(),
            "flight": {"alpha": 5.0},
            "velocities": [6.0, 12.0, 22.0],
        }
        swept = client.post("/sweep", json=body).json()
    assert [p["status"] for p in swept["points"]] == ["equilibrium"] * 2 + ["no_equilibrium"]
    assert 21.43 < swept["divergence"]["fold"]["velocity"] < 21.45


def test_load_cases_spread_over_dask_workers_answer_as_in_process(dask_service: Server) -> None:
    """/loads's cases run as Dask tasks, chunk by chunk, the envelope assembled in one: the
    same cases' loads as solved here (Newton's 1e-10 residual bounds the difference)."""
    body = LOADS_EXAMPLES["envelope"]["value"]
    with dask_service.client() as client:
        response = client.post("/loads", json=body)
    assert response.status_code == 200, response.text
    answer = response.json()
    expected = REQUESTS["loads"].model_validate(body).to_solver().run()
    assert [c["status"] for c in answer["cases"]] == [c.status for c in expected.cases]
    assert answer["envelope"]["max_bending_moment"] == pytest.approx(
        expected.envelope.max_bending_moment.tolist(), rel=1e-8
    )


def _speed(index: int) -> float:
    """6 to 20 m/s across the batch; every 50th item at the study's 10 m/s."""
    return 10.0 if index % 50 == 0 else 6.0 + 14.0 * index / (BATCH - 1)


def _item(index: int) -> dict[str, Any]:
    return {
        "wing": study.wing_json(),
        "flight": {"velocity": _speed(index), "alpha": 5.0, "density": 1.225},
    }


def _expected_lift(velocity: float) -> float:
    wing = solver.Wing.create(**study.wing_json())
    return solver.solve(wing, solver.FlightCondition(velocity, 5.0, 1.225)).lift


def test_a_batch_survives_a_killed_dask_worker(dask_service: Server, cluster: Cluster) -> None:
    items = [_item(i) for i in range(BATCH)]
    with dask_service.client(timeout=120) as client:
        response = client.post("/jobs", json={"operation": "batch", "request": {"items": items}})
        assert response.status_code == 202, response.text
        location = response.headers["location"]
        progress = _wait(
            lambda: (p := client.get(location).json()["progress"])["done"] >= BATCH // 5 and p,
            "a fifth of the batch answered",
            limit=120,
        )
        cluster.workers["w1"].send_signal(signal.SIGKILL)
        assert progress["done"] < BATCH, "the batch finished before the kill: make it longer"
        job = _wait(
            lambda: (j := client.get(location).json())["status"] != "running" and j,
            "the batch ends",
            limit=120,
        )
    assert cluster.workers["w1"].wait(timeout=10) == -signal.SIGKILL
    assert job["status"] == "succeeded", job
    assert job["progress"] == {"done": BATCH, "total": BATCH, "problems": 0}
    answers = job["result"]["items"]
    assert [a["status"] for a in answers] == ["ok"] * BATCH
    for index in range(0, BATCH, 50):  # the study's numbers
        assert answers[index]["result"]["totals"]["lift"] == pytest.approx(304.13, abs=0.005)
        assert answers[index]["result"]["totals"]["tip_twist"] == pytest.approx(1.708, abs=5e-4)
    for index in range(1, BATCH, 13):  # and the others, against this process's own solves
        lift = answers[index]["result"]["totals"]["lift"]
        assert lift == pytest.approx(_expected_lift(_speed(index)), rel=WARM_VS_COLD)
    # The service follows the cluster: one worker left, still warm and ready.
    assert _wait(lambda: warm_workers(dask_service) == ["w2"], "w1 gone from /readyz", 30)
    assert readyz(dask_service).status_code == 200
