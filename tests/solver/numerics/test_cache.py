"""solver.numerics.cache: one cache, bounded in bytes, that makes solves faster and never
different."""

from __future__ import annotations

import contextlib
from collections.abc import Iterator

import numpy as np
import pytest

import solver
from tests.study import flight, rect_public, study_wing, tapered_forward_ea


@pytest.fixture
def small_budget(monkeypatch: pytest.MonkeyPatch) -> Iterator[None]:
    """An empty cache of 12 MiB: two or three models (~5 MB each at these meshes) with their
    jigs and branches, so a few wings of other mesh sizes evict one another."""
    monkeypatch.setenv("FLEXWING_SOLVER_CACHE_BYTES", str(12 * 2**20))
    solver.clear_caches()
    yield
    solver.clear_caches()


def _same(a: solver.Equilibrium, b: solver.Equilibrium) -> None:
    np.testing.assert_array_equal(a.state, b.state)
    assert a.totals == b.totals and a.stability == b.stability


@pytest.mark.server  # compiles, or starts a process
def test_an_answer_is_the_same_in_a_fresh_process_and_after_many_unrelated_requests(small_budget):
    """Bit for bit: every cache entry is a deterministic function of its key."""
    wing, condition = study_wing(), flight(17.0)
    fresh = solver.solve(wing, condition)
    others = [study_wing(n) for n in (12, 20)] + [rect_public(), tapered_forward_ea()]
    for index in range(40):
        other = others[index % len(others)]
        with contextlib.suppress(solver.SolverError):
            solver.solve(other, flight(4.0 + index % 9, alpha=(index % 7) - 3.0))
        if index % 10 == 0:
            solver.airspeed_sweep(
                wing, [6.0 + index / 10, 23.0], solver.FlightCondition(None, 5.0, condition.density)
            )
    meshes = {w.n_stations for w in [wing, *others]}
    # Entries were evicted and rebuilt on the way: fewer models are kept than meshes were used.
    assert solver.cache_info().entries.get("model", 0) < len(meshes)
    _same(solver.solve(wing, condition), fresh)
    solver.clear_caches()
    _same(solver.solve(wing, condition), fresh)


def test_the_cache_stays_within_its_byte_budget(small_budget):
    for n in (5, 8, 11, 14):
        solver.solve(study_wing(n), flight(10.0))
    info = solver.cache_info()
    # Each model is ~5 MB: at most two fit with their jig solutions (the newest always stays).
    assert info.bytes <= info.budget
    assert info.entries.get("model", 0) <= 2
    assert info.budget == 12 * 2**20


def test_clearing_the_cache_forgets_everything(small_budget):
    solver.solve(study_wing(), flight(10.0))
    assert solver.cache_info().entries
    solver.clear_caches()
    info = solver.cache_info()
    assert info.entries == {} and info.bytes == 0


def test_a_repeated_solve_hits_the_cache(small_budget):
    solver.solve(study_wing(), flight(10.0))
    before = solver.cache_info()
    solver.solve(study_wing(), flight(11.0))
    after = solver.cache_info()
    assert after.hits > before.hits
    assert after.entries == before.entries
