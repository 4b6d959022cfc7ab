"""Past one box (issue 39): real uvicorn replicas on loopback sharing a real PostgreSQL
(tests/postgres.py), as a load balancer would spread a team's requests over them.

- Any replica answers for any job, and one client's rate limit holds across replicas (keys kept
  in the database: each test has its own key, so its own bucket).
- The database lost mid-run: job operations are 503 database-unavailable with Retry-After while
  /solve keeps answering; when it returns the batch finishes, each item once.
- A replica killed (SIGKILL) mid-batch: the other finishes it; nothing lost, nothing twice.
- A database unreachable at the start: /readyz 503 naming it (not a crash loop), /solve
  answers, jobs wait for it; once it answers, the replica becomes ready.

Slow items: 60-station wings on CasADi's virtual machine, ~0.2 s each, each of its own stiffness.
`HANG_GUARD` only turns a hang into a failure; nothing here is timed but the rate limit's
bound, computed from the time the test measured.
"""

from __future__ import annotations

import asyncio
import contextlib
import json
import os
import signal
import subprocess
import sys
import time
from collections.abc import Callable, Iterator
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path
from typing import Any

import httpx
import pytest

from app.jobs.store import Store
from app.security.keys import digest, new_key
from tests import study
from tests.app.conftest import ROOT, Server
from tests.postgres import BINARIES, Cluster, free_port

pytestmark = pytest.mark.server

HANG_GUARD = 120.0  # [s]
FINISHED = {"succeeded", "failed", "cancelled"}
# The replicas' rate limit: low enough that a client on a loaded machine still outruns it.
BURST, RATE = 30, 2.0  # FLEXWING_RATE_BURST [requests], FLEXWING_RATE_LIMIT [1/s]
POLL = 0.5  # [s] between a test's polls: RATE sustained


def slow_item(index: int) -> dict[str, Any]:
    return {
        "wing": study.wing_json(stiffness_scale=1.0 + 0.01 * index, n=60),
        "flight": {"velocity": 10.0, "alpha": 5.0},
    }


def slow_batch(count: int, first: int = 0) -> dict[str, Any]:
    items = [slow_item(first + i) for i in range(count)]
    return {"operation": "batch", "request": {"items": items}}


@pytest.fixture(scope="module")
def shared(postgres: Cluster) -> str:
    """The replicas' database (a schema of its own), with an API key per test."""
    return postgres.schema()


def _add_keys(url: str, *names: str) -> dict[str, str]:
    async def add() -> dict[str, str]:
        store = Store.of(url, Path())
        await store.open()
        keys = {name: new_key() for name in names}
        for name, key in keys.items():
            assert await store.add_api_key(name, digest(key).hex(), time.time())
        await store.close()
        return keys

    return asyncio.run(add())


@pytest.fixture(scope="module")
def keys(shared: str) -> dict[str, str]:
    return _add_keys(shared, "limited", "outage", "killer", "metrics")


@pytest.fixture(scope="module")
def replicas(
    make_server: Callable[..., Server],
    tmp_path_factory: pytest.TempPathFactory,
    shared: str,
    keys: dict[str, str],
) -> list[Server]:
    """Two replicas: one worker each, one job runner, leases of 2 s, keys in the database."""
    env = {
        "FLEXWING_DATABASE_URL": shared,
        "FLEXWING_API_KEYS_IN_DATABASE": "true",
        "FLEXWING_COMPILE": "0",
        "FLEXWING_CACHE_DIR": str(tmp_path_factory.mktemp("replicas") / "cache"),
        "FLEXWING_WORKERS": "1",
        "FLEXWING_JOB_RUNNERS": "1",
        "FLEXWING_JOB_LEASE": "2",
        "FLEXWING_JOB_POLL_INTERVAL": "0.2",
        "FLEXWING_RATE_LIMIT": str(RATE),
        "FLEXWING_RATE_BURST": str(BURST),
    }
    with ThreadPoolExecutor(2) as starting:  # both at once: their starts overlap
        return list(starting.map(lambda name: make_server(f"replica_{name}", **env), "ab"))


def _client(server: Server, key: str) -> httpx.Client:
    headers = {"Authorization": f"Bearer {key}"}
    return httpx.Client(base_url=server.base_url, timeout=HANG_GUARD, headers=headers)


def _wait(client: httpx.Client, location: str, until: Callable[[dict[str, Any]], bool]) -> Any:
    deadline = time.monotonic() + HANG_GUARD
    while True:
        response = client.get(location)
        if response.status_code == 200 and until(response.json()):
            return response.json()
        # 503 database-unavailable is the documented answer while the database (re)starts:
        # the job is polled again until the deadline, as a client honouring Retry-After does.
        unavailable = response.status_code == 503 and (
            response.json().get("type") == "/problems/database-unavailable"
        )
        assert response.status_code in (200, 429) or unavailable, response.text
        assert time.monotonic() < deadline, response.text
        time.sleep(POLL)


def _items(client: httpx.Client, location: str) -> list[dict[str, Any]]:
    with client.stream("GET", location + "/items.ndjson") as response:
        assert response.status_code == 200
        return [json.loads(line) for line in response.iter_lines() if line]


def _first_items(client: httpx.Client, location: str, count: int) -> list[dict[str, Any]]:
    """The first `count` lines of a running batch's items.ndjson (from any replica)."""
    lines: list[dict[str, Any]] = []
    with client.stream("GET", location + "/items.ndjson") as response:
        assert response.status_code == 200
        for line in response.iter_lines():
            if line:
                lines.append(json.loads(line))
            if len(lines) == count:
                break
    assert len(lines) == count, lines
    return lines


def _events(client: httpx.Client, location: str) -> list[dict[str, Any]]:
    """The data of a job's server-sent events, to its end."""
    with client.stream("GET", location + "/events") as response:
        assert response.status_code == 200
        return [
            json.loads(line.removeprefix("data: "))
            for line in response.iter_lines()
            if line.startswith("data: ")
        ]


def _batch_items(replicas: list[Server], key: str) -> list[float]:
    """Each replica's count of batch items answered (its /metrics)."""
    return [
        server.metric("flexwing_batch_items_total", key=key, outcome="ok") for server in replicas
    ]


def _runner(replicas: list[Server], key: str, before: list[float]) -> int:
    """Which replica runs the batch: the one whose batch item counter moves."""
    deadline = time.monotonic() + HANG_GUARD
    while time.monotonic() < deadline:
        time.sleep(2 * POLL)  # a request to each replica: RATE
        for n, count in enumerate(_batch_items(replicas, key)):
            if count > before[n]:
                return n
    raise TimeoutError("no replica answers the batch")


def _check_batch(final: dict[str, Any], items: list[dict[str, Any]], count: int) -> None:
    """Every item answered once, in request order in the result."""
    assert final["status"] == "succeeded", final
    assert final["progress"] == {"done": count, "total": count, "problems": 0}
    assert sorted(item["index"] for item in items) == list(range(count))
    assert [item["index"] for item in final["result"]["items"]] == list(range(count))


# ---------------------------------------------------------------------------------- tests


def test_one_clients_rate_limit_holds_across_replicas(
    replicas: list[Server], keys: dict[str, str]
) -> None:
    """Requests alternate between the replicas as fast as they are answered: one key's
    bucket is shared, so at most BURST + RATE x (the seconds taken) pass before the first 429,
    where buckets of each replica's own would let through twice BURST at least."""
    clients = [_client(server, keys["limited"]) for server in replicas]
    started = time.monotonic()
    passed, refused = 0, None
    while refused is None and passed < 4 * BURST:
        response = clients[passed % 2].get("/jobs?limit=1")
        if response.status_code == 429:
            refused = response
        else:
            assert response.status_code == 200, response.text
            passed += 1
    elapsed = time.monotonic() - started
    assert refused is not None and refused.json()["type"] == "/problems/rate-limited"
    assert BURST <= passed <= BURST + RATE * elapsed + 1, (passed, elapsed)
    assert passed < 2 * BURST, (passed, elapsed)  # what the test shows: not one per replica
    for client in clients:
        client.close()


def test_a_database_lost_mid_run_makes_jobs_503_while_solve_answers_and_loses_nothing(
    replicas: list[Server], keys: dict[str, str], postgres: Cluster
) -> None:
    a, b = (_client(server, keys["outage"]) for server in replicas)
    location = a.post("/jobs", json=slow_batch(12, first=100)).headers["location"]
    _wait(b, location, lambda job: job["progress"]["done"] >= 2)
    postgres.stop("immediate")
    try:
        deadline = time.monotonic() + HANG_GUARD
        while (refused := b.get(location)).status_code != 503:
            assert time.monotonic() < deadline, refused.text
            time.sleep(0.05)
        assert refused.json()["type"] == "/problems/database-unavailable"
        assert int(refused.headers["retry-after"]) >= 1
        assert "postgresql://flexwing@127.0.0.1" in refused.json()["detail"]
        solved = a.post("/solve", json=study.solve_request(10.0))
        assert solved.status_code == 200, solved.text
        ready = httpx.get(replicas[0].base_url + "/readyz", timeout=10)
        assert ready.status_code == 503 and "unavailable" in ready.json()["detail"]
    finally:
        postgres.start()
    final = _wait(a, location, lambda job: job["status"] in FINISHED)
    _check_batch(final, _items(b, location), 12)


def test_a_replica_killed_mid_batch_leaves_it_to_the_other_nothing_lost_nothing_twice(
    replicas: list[Server], keys: dict[str, str]
) -> None:
    key = keys["killer"]
    clients = [_client(server, key) for server in replicas]
    before = _batch_items(replicas, keys["metrics"])
    location = clients[0].post("/jobs", json=slow_batch(16)).headers["location"]
    runner = _runner(replicas, keys["metrics"], before)
    survivor = clients[1 - runner]
    seen = _first_items(survivor, location, 3)  # read: committed, never lost
    os.killpg(replicas[runner].process.pid, signal.SIGKILL)
    replicas[runner].process.wait(timeout=HANG_GUARD)
    events = _events(survivor, location)  # followed across the takeover, to its end
    assert events[-1]["status"] == "succeeded"
    final = survivor.get(location).json()
    items = _items(survivor, location)
    _check_batch(final, items, 16)
    assert items[:3] == seen
    done = [event["progress"]["done"] for event in events]
    assert done == sorted(done)  # progress never goes back across the takeover
    for client in clients:
        client.close()


# ------------------------------------------------------- a database unreachable at the start


@contextlib.contextmanager
def _unready_server(tmp: Path, env: dict[str, str]) -> Iterator[str]:
    """A uvicorn replica whose start is not waited for (its database is not there)."""
    port = free_port()
    log = tmp / "unready.log"
    with open(log, "wb") as out:
        command = [sys.executable, "-m", "uvicorn", "app.main:app", "--host", "127.0.0.1"]
        process = subprocess.Popen(
            [*command, "--port", str(port), "--log-level", "warning"],
            cwd=ROOT,
            env=os.environ | {"FLEXWING_WORKERS": "1", "PYTHONUNBUFFERED": "1"} | env,
            stdout=out,
            stderr=subprocess.STDOUT,
            start_new_session=True,
        )
    try:
        yield f"http://127.0.0.1:{port}"
        assert process.poll() is None, log.read_text()  # never exited: no crash loop
    finally:
        process.send_signal(signal.SIGINT)
        try:
            process.wait(timeout=30)
        except subprocess.TimeoutExpired:
            process.kill()
        with contextlib.suppress(ProcessLookupError):
            os.killpg(process.pid, signal.SIGKILL)


def test_an_unreachable_database_at_the_start_is_a_refusal_to_become_ready_not_a_crash(
    tmp_path: Path,
) -> None:
    assert BINARIES is not None
    port = free_port()
    url = f"postgresql://flexwing:secret@127.0.0.1:{port}/postgres"
    env = {
        "FLEXWING_DATABASE_URL": url,
        "FLEXWING_COMPILE": "0",
        "FLEXWING_CACHE_DIR": str(tmp_path / "cache"),
    }
    with _unready_server(tmp_path, env) as base, httpx.Client(base_url=base, timeout=60) as client:
        deadline = time.monotonic() + HANG_GUARD
        while True:
            with contextlib.suppress(httpx.TransportError):
                ready = client.get("/readyz")
                if ready.json()["detail"].startswith("ready"):  # the pool is warm
                    break
            assert time.monotonic() < deadline
            time.sleep(0.1)
        assert ready.status_code == 503
        named = f"jobs database postgresql://flexwing@127.0.0.1:{port}/postgres unavailable"
        assert named in ready.json()["detail"] and "secret" not in ready.text
        assert client.get("/healthz").status_code == 200
        assert client.post("/solve", json=study.solve_request(10.0)).status_code == 200
        refused = client.post("/jobs", json={"operation": "solve", "request": slow_item(0)})
        assert refused.status_code == 503 and refused.headers["retry-after"] == "1"
        assert refused.json()["type"] == "/problems/database-unavailable"
        cluster = Cluster(port=port)  # the database comes up
        cluster.start()
        try:
            while client.get("/readyz").status_code != 200:
                assert time.monotonic() < deadline
                time.sleep(0.1)
            job = client.post("/jobs", json={"operation": "solve", "request": slow_item(0)})
            assert job.status_code == 202, job.text
            final = _wait(client, job.headers["location"], lambda j: j["status"] in FINISHED)
            assert final["status"] == "succeeded"
        finally:
            cluster.remove()
