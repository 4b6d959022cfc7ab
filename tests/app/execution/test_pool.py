"""The worker pool on its own (no HTTP): public APIs only, budgets from a job's start, errors."""

from __future__ import annotations

import ast
import asyncio
from collections.abc import Awaitable, Callable
from pathlib import Path
from typing import Any

import pytest

import solver
from app.execution.dask_cluster import _rendezvous
from app.execution.pool import BudgetExceeded, Capacity, WorkerPool, affinity_of
from app.metrics import Metrics
from app.settings import Settings
from tests import study
from tests.app import pool_jobs

# Run with the live-server tests, after the fast loop: real worker processes.
pytestmark = pytest.mark.server

APP = Path(__file__).resolve().parents[3] / "app"
# What app/pool.py used to read from ProcessPoolExecutor; none of it is public.
PRIVATE_POOL_ATTRIBUTES = {
    "_processes",
    "_executor_manager_thread",
    "_broken",
    "_pending_work_items",
}


def test_the_pool_reads_no_private_attribute_of_the_standard_library() -> None:
    for path in APP.rglob("*.py"):
        tree = ast.parse(path.read_text())
        names = {node.attr for node in ast.walk(tree) if isinstance(node, ast.Attribute)}
        strings = {
            node.value
            for node in ast.walk(tree)
            if isinstance(node, ast.Constant) and isinstance(node.value, str)
        }
        assert not (names | strings) & PRIVATE_POOL_ATTRIBUTES, path
        assert "concurrent.futures.process" not in path.read_text(), path


def test_capacity_hands_out_slots_in_arrival_order_and_follows_a_resize() -> None:
    async def scenario() -> list[str]:
        capacity = Capacity(1)
        order: list[str] = []

        async def hold(name: str, release: asyncio.Event) -> None:
            async with capacity.slot():
                order.append(name)
                await release.wait()

        gates = {name: asyncio.Event() for name in "abc"}
        tasks = [asyncio.create_task(hold(name, gates[name])) for name in "abc"]
        await asyncio.sleep(0.01)
        assert order == ["a"] and capacity.held == 1
        capacity.resize(2)  # a cluster grew: the next waiter gets in at once
        await asyncio.sleep(0.01)
        assert order == ["a", "b"]
        for gate in gates.values():
            gate.set()
        await asyncio.gather(*tasks)
        assert capacity.held == 0
        return order

    assert asyncio.run(scenario()) == ["a", "b", "c"]


def test_a_cancelled_waiter_gives_its_place_to_the_next() -> None:
    async def scenario() -> None:
        capacity = Capacity(1)
        async with capacity.slot():
            waiter = asyncio.create_task(capacity.slot().__aenter__())
            await asyncio.sleep(0.01)
            waiter.cancel()
            with pytest.raises(asyncio.CancelledError):
                await waiter
        assert capacity.held == 0

    asyncio.run(scenario())


def _with_pool(settings: Settings, scenario: Callable[[WorkerPool], Awaitable[Any]]) -> Any:
    async def run() -> Any:
        pool = WorkerPool(settings, Metrics())
        await pool.start()
        try:
            assert await pool.wait_ready(timeout=120)
            return await scenario(pool)
        finally:
            await pool.close()

    return asyncio.run(run())


LOCAL = Settings(workers=1, tasks_per_worker=2, warm_stations=[], start_method="forkserver")


def test_a_job_queued_behind_another_has_its_budget_counted_from_its_own_start() -> None:
    """One worker: a job of 2 s (budget 10 s), then one of 0.1 s with a budget of 1 s. The
    second waits 2 s behind the first, twice its budget, and runs well within it: only a budget
    counted from submission would stop it (ample slack both ways on a loaded machine)."""

    async def scenario(pool: WorkerPool) -> list[int]:
        jobs = [
            pool.run(pool_jobs.sleep_then_pid, 2.0, timeout=10.0, kind="solve"),
            pool.run(pool_jobs.sleep_then_pid, 0.1, timeout=1.0, kind="solve"),
        ]
        return list(await asyncio.gather(*jobs))

    pids = _with_pool(LOCAL, scenario)
    assert pids[0] == pids[1]


def test_a_job_past_its_budget_times_out_and_its_worker_is_replaced() -> None:
    async def scenario(pool: WorkerPool) -> tuple[list[int], list[int]]:
        before = pool.pids()
        with pytest.raises(BudgetExceeded):
            await pool.run(pool_jobs.sleep_then_pid, 30.0, timeout=0.3, kind="solve")
        assert await pool.wait_ready(timeout=60)
        after = await pool.run(pool_jobs.sleep_then_pid, 0.0, timeout=5.0, kind="solve")
        return before, [after]

    before, after = _with_pool(LOCAL, scenario)
    assert before and after and set(before).isdisjoint(after)


def test_an_exception_in_a_job_reaches_its_caller_and_the_worker_lives_on() -> None:
    async def scenario(pool: WorkerPool) -> tuple[list[int], list[int]]:
        before = pool.pids()
        with pytest.raises(ValueError, match="bad wing"):
            await pool.run(pool_jobs.fail, "bad wing", timeout=5.0, kind="solve")
        return before, pool.pids()

    before, after = _with_pool(LOCAL, scenario)
    assert before == after


def test_a_tasks_progress_reaches_its_caller_as_the_worker_reports_it() -> None:
    """What a sweep's job shows as its airspeeds are answered: every report, in order, before
    the answer."""
    reports: list[tuple[int, int]] = []

    async def scenario(pool: WorkerPool) -> int:
        return await pool.run(
            pool_jobs.counts_to,
            5,
            timeout=10.0,
            kind="sweep",
            progress=lambda *r: reports.append(r),
        )

    assert _with_pool(LOCAL, scenario) == 5
    assert reports == [(done, 5) for done in range(1, 6)]


def test_a_tasks_affinity_is_its_wing_and_a_batch_chunk_has_none() -> None:
    wing = study.study_wing()
    task = solver.SolveInput(wing, solver.FlightCondition(10.0, 5.0))
    assert affinity_of(task) == wing.key
    assert affinity_of((task, task)) is None
    assert affinity_of(object()) is None


def test_a_wing_prefers_one_dask_worker_and_a_leaving_worker_moves_only_its_own() -> None:
    """Rendezvous hashing: the same wing, the same worker; a worker that leaves moves only
    the wings it had, spread over the others."""
    addresses = [f"tcp://127.0.0.1:{port}" for port in (4001, 4002, 4003)]
    wings = [i.to_bytes(2, "big") for i in range(300)]
    before = {wing: _rendezvous(wing, addresses) for wing in wings}
    assert before == {wing: _rendezvous(wing, list(reversed(addresses))) for wing in wings}
    assert set(before.values()) == set(addresses)  # every worker gets some
    after = {wing: _rendezvous(wing, addresses[:2]) for wing in wings}
    moved = {wing for wing in wings if after[wing] != before[wing]}
    assert moved == {wing for wing in wings if before[wing] == addresses[2]}
    assert _rendezvous(None, addresses) is None and _rendezvous(b"x", []) is None
