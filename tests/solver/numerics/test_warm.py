"""solver.numerics.warm: a process prepares the meshes it will serve, compiled when it can."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest

from solver import Layout, warm_up
from solver.numerics.cache import clear_caches, model_for

N_SMALL = 5  # compiles in a couple of seconds


@pytest.fixture
def private_cache(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Iterator[Path]:
    monkeypatch.setenv("FLEXWING_CACHE_DIR", str(tmp_path))
    clear_caches()
    yield tmp_path
    clear_caches()


@pytest.mark.server  # compiles, or starts a process
def test_warming_compiles_the_mesh_and_says_so(private_cache: Path, monkeypatch) -> None:
    monkeypatch.setenv("FLEXWING_COMPILE", "1")
    assert warm_up(N_SMALL, timeout=120) is True
    assert model_for(Layout(N_SMALL)).compiled
    assert len(list(private_cache.glob(f"*n{N_SMALL}-k1-*.so"))) == 1


def test_without_compilation_the_virtual_machine_serves_and_warming_says_so(
    private_cache: Path, monkeypatch
) -> None:
    monkeypatch.setenv("FLEXWING_COMPILE", "0")
    assert warm_up(N_SMALL, timeout=120, chordwise_panels=2) is False
    assert not model_for(Layout(N_SMALL, 2)).compiled
    assert not list(private_cache.glob("*.so"))
