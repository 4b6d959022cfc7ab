"""Worker death, time budgets and overload against a live server (`fault_server`: CasADi's
virtual machine, so a wing of 150 stations takes about a second per solve, long enough to kill
its worker while it runs; the sweep budget is 0.5 s, and at most 3 solves may be pending); and
the pipes between the pool and a worker, in process."""

from __future__ import annotations

import contextlib
import multiprocessing
import os
import pickle
import signal
import time
from collections.abc import Iterator
from concurrent.futures import Future, ThreadPoolExecutor
from multiprocessing.connection import Connection
from multiprocessing.process import BaseProcess
from typing import Any

import httpx
import pytest

from app.execution.processes import (
    _REMEMBERED_WINGS,
    LocalWorkers,
    _frame,
    _Frames,
    _Worker,
    serve,
)
from app.metrics import Metrics
from app.settings import Settings
from tests import study
from tests.app.conftest import Server


def _big_wing(n: int = 150) -> dict[str, Any]:
    """The study's wing on 150 stations: ~0.3 s to build its model and ~0.6 s per solve on the
    virtual machine, against ~20 ms for 30 stations."""
    return study.wing_json(n=n)


def _post_big(server: Server, velocity: float) -> httpx.Response:
    body = {"wing": _big_wing(), "flight": {"velocity": velocity, "alpha": 5.0}}
    with server.client(timeout=120) as client:
        return client.post("/solve", json=body)


def _wait_pending(server: Server, count: int) -> None:
    """Wait until `count` solves are running or queued in the server (no timing assumed)."""
    deadline = time.monotonic() + 60
    while server.metric("flexwing_pending_tasks") < count:
        assert time.monotonic() < deadline, "requests never reached the pool"
        time.sleep(0.01)


def _kill(pids: list[int]) -> None:
    for pid in pids:
        # Killing one worker breaks the pool, which may end the others first: gone is the goal.
        with contextlib.suppress(ProcessLookupError):
            os.kill(pid, signal.SIGKILL)


def _wait_running(server: Server, count: int) -> None:
    """Wait until `count` jobs run in workers (a job killed while queued is resubmitted for
    free: these tests kill running ones)."""
    deadline = time.monotonic() + 60
    while server.metric("flexwing_running_tasks") < count:
        assert time.monotonic() < deadline, "no job started"
        time.sleep(0.01)


def _small_solve_works(server: Server) -> None:
    with server.client() as client:
        response = client.post("/solve", json=study.solve_request(9.0 + time.time() % 1))
    assert response.status_code == 200, response.text


def test_killed_worker_is_replaced_and_its_request_retried(fault_server: Server) -> None:
    pids = fault_server.wait_ready()
    died = fault_server.metric("flexwing_worker_restarts_total", reason="died")
    with ThreadPoolExecutor(1) as pool:
        future = pool.submit(_post_big, fault_server, 10.0)
        _wait_running(fault_server, 1)
        _kill(pids)
        response = future.result()
    assert response.status_code == 200, response.text  # retried once on the new pool
    new_pids = fault_server.wait_ready(exclude_pids=frozenset(pids))
    assert len(new_pids) == 2
    assert fault_server.metric("flexwing_worker_restarts_total", reason="died") == died + 2
    _small_solve_works(fault_server)


def test_a_request_whose_workers_die_twice_gets_503(fault_server: Server) -> None:
    pids = fault_server.wait_ready()
    with ThreadPoolExecutor(1) as pool:
        future = pool.submit(_post_big, fault_server, 11.0)
        _wait_running(fault_server, 1)
        _kill(pids)
        new_pids = fault_server.wait_ready(exclude_pids=frozenset(pids))
        _wait_running(fault_server, 1)  # the retry
        _kill(new_pids)
        response = future.result()
    assert response.status_code == 503
    assert response.headers["content-type"] == "application/problem+json"
    assert response.json()["type"] == "/problems/worker-lost"
    assert int(response.headers["retry-after"]) >= 0
    fault_server.wait_ready(exclude_pids=frozenset(pids))
    _small_solve_works(fault_server)


def test_a_worker_killed_while_idle_is_replaced(fault_server: Server) -> None:
    pids = fault_server.wait_ready()
    _kill(pids[:1])
    assert len(fault_server.wait_ready(exclude_pids=frozenset(pids))) == 2
    _small_solve_works(fault_server)


def test_a_sweep_past_its_budget_gets_504_and_recycles_the_pool(fault_server: Server) -> None:
    """Following the 150-station branch to its fold takes seconds on the virtual machine."""
    pids = fault_server.wait_ready()
    timeouts = fault_server.metric("flexwing_worker_restarts_total", reason="timeout")
    body = {"wing": _big_wing(), "flight": {"alpha": 5.0}, "velocities": [10, 15]}
    with fault_server.client() as client:
        response = client.post("/sweep", json=body)
    assert response.status_code == 504
    problem = response.json()
    assert problem["type"] == "/problems/solve-timeout"
    assert problem["timeout"] == 0.5
    assert fault_server.metric("flexwing_worker_restarts_total", reason="timeout") > timeouts
    fault_server.wait_ready(exclude_pids=frozenset(pids))
    _small_solve_works(fault_server)


def test_overload_is_shed_with_503_and_retry_after(fault_server: Server) -> None:
    fault_server.wait_ready()
    shed = fault_server.metric("flexwing_requests_shed_total")
    with ThreadPoolExecutor(3) as pool:
        futures: list[Future[httpx.Response]] = [
            pool.submit(_post_big, fault_server, v) for v in (12.0, 13.0, 14.0)
        ]
        _wait_pending(fault_server, 3)  # FLEXWING_MAX_PENDING=3: two running, one waiting
        with fault_server.client() as client:
            response = client.post("/solve", json=study.solve_request(8.5))
        results = [f.result() for f in futures]
    assert response.status_code == 503
    assert response.json()["type"] == "/problems/overloaded"
    assert response.headers["retry-after"] == "1"
    assert [r.status_code for r in results] == [200, 200, 200]
    assert fault_server.metric("flexwing_requests_shed_total") == shed + 1


@pytest.mark.parametrize("path", ["/healthz", "/readyz"])
def test_the_service_still_answers_after_the_faults(fault_server: Server, path: str) -> None:
    assert httpx.get(fault_server.base_url + path, timeout=10).status_code == 200


@contextlib.contextmanager
def _a_worker() -> Iterator[tuple[Connection, Connection, BaseProcess]]:
    """A real worker process started as the pool starts them (forkserver), with no mesh to
    warm: (its inbox, its outbox, the process); killed on the way out if still running."""
    context = multiprocessing.get_context("forkserver")
    inbox_end, inbox = context.Pipe(duplex=False)
    outbox, outbox_end = context.Pipe(duplex=False)
    process = context.Process(target=serve, args=(inbox_end, outbox_end, (), 1.0), daemon=True)
    process.start()
    inbox_end.close()
    outbox_end.close()
    try:
        assert outbox.recv()[0] == "warm"
        yield inbox, outbox, process
    finally:
        if process.is_alive():
            process.kill()


@pytest.mark.parametrize("how", ["told-to-stop", "service-gone"])
def test_a_worker_stops_when_told_or_when_the_service_is_gone(how: str) -> None:
    """A worker runs tasks until an empty message, or until its inbox ends (the service
    died): it never outlives the service waiting on a pipe nobody writes."""
    with _a_worker() as (inbox, outbox, process):
        inbox.send_bytes(pickle.dumps((7, abs, -2.5, False)))
        assert outbox.recv() == ("started", 7)
        assert pickle.loads(outbox.recv_bytes())[:4] == ("done", 7, True, 2.5)
        if how == "told-to-stop":
            inbox.send_bytes(b"")  # the pool's stop message
        else:
            inbox.close()
        process.join(30)
        assert process.exitcode == 0


def test_a_worker_says_how_long_each_task_ran_inside_it() -> None:
    """The time in the worker, apart from the trip there and back: what the service's own
    overhead is measured against (flexwing_worker_task_duration_seconds)."""
    with _a_worker() as (inbox, outbox, process):
        inbox.send_bytes(pickle.dumps((3, time.sleep, 0.2, False)))
        assert outbox.recv() == ("started", 3)
        kind, seq, ok, value, seconds = pickle.loads(outbox.recv_bytes())
        assert (kind, seq, ok, value) == ("done", 3, True, None)
        # About the sleep (a margin for the clock's granularity); the bounds catch a clock in
        # the wrong unit or a time that leaves the task out.
        assert 0.15 <= seconds < 10
        inbox.send_bytes(b"")
        process.join(30)
        assert process.exitcode == 0


@pytest.mark.parametrize("chunk", [1, 3, 4096, 1 << 20], ids=["bytewise", "3", "4k", "whole"])
def test_the_outbox_is_read_as_whole_messages_however_the_pipe_splits_it(chunk: int) -> None:
    """A worker's messages reach the pool one by one and complete, whatever sizes the pipe
    hands the bytes over in (a batch chunk's answers are megabytes)."""

    messages = [("started", 1), ("done", 1, True, bytes(70_000), 0.5), ("progress", 2, 1, 3)]
    stream = b"".join(_frame(pickle.dumps(m)) for m in messages)
    got: list[Any] = []
    ended: list[bool] = []
    frames = _Frames(got.append, lambda: ended.append(True))
    for start in range(0, len(stream), chunk):
        frames.data_received(stream[start : start + chunk])
    assert got == messages
    frames.connection_lost(None)
    assert ended == [True]


# ----------------------------------------------------------------- which worker runs a task


def _workers(*loads: int) -> tuple[LocalWorkers, list[_Worker]]:
    """A pool of worker records (no processes) with `loads` tasks assigned each."""
    pool = LocalWorkers(Settings(workers=len(loads)), Metrics())
    workers = [
        _Worker(0, process=None, assigned={seq: None for seq in range(load)})  # type: ignore[arg-type,misc]
        for load in loads
    ]
    pool._workers = workers
    return pool, workers


def test_a_wing_asked_again_goes_to_the_idle_worker_that_ran_it() -> None:
    """Issue 40: warm starts per wing reach every operation. A worker's solver cache holds what
    the wing's answers share (its branch, its trimmed limit): the same wing asked again, both
    workers idle, goes to the one that ran it (before: always the first worker)."""
    pool, (first, second) = _workers(0, 0)
    second.ran(b"wing-a")
    assert pool._least_busy(b"wing-a") is second
    assert pool._least_busy(b"wing-b") is first  # a wing neither ran: the first, as before
    assert pool._least_busy(None) is first
    assert pool._least_busy(b"wing-b") is first  # and now it remembers it
    assert first.recency(b"wing-b") > 0 and second.recency(b"wing-b") == 0


def test_a_busier_worker_is_never_chosen_for_its_cache() -> None:
    pool, (first, second) = _workers(0, 1)
    second.ran(b"wing-a")
    assert pool._least_busy(b"wing-a") is first


def test_a_worker_remembers_its_last_wings_only() -> None:
    _, (only,) = _workers(0)
    for i in range(_REMEMBERED_WINGS + 1):
        only.ran(bytes([i]))
    assert only.recency(bytes([0])) == 0
    assert only.recency(bytes([_REMEMBERED_WINGS])) == _REMEMBERED_WINGS
