"""The per-mesh model: virtual machine at once, compiled C code once built, kept on disk."""

from __future__ import annotations

import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from solver import compiled

# A small mesh keeps the C compile to a couple of seconds.
N_SMALL = 5


@pytest.fixture
def private_cache(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """An empty library cache and an empty in-process model table."""
    monkeypatch.setenv("FLEXWING_CACHE_DIR", str(tmp_path))
    monkeypatch.setenv("FLEXWING_COMPILE", "1")
    monkeypatch.setattr(compiled, "_models", {})
    monkeypatch.setattr(compiled, "_compile_threads", {})
    return tmp_path


def _parameters(n: int) -> np.ndarray:
    y = np.linspace(0.0, 3.0, n)
    chord = np.linspace(1.0, 0.5, n)
    return np.concatenate([y, chord, np.full(n, 0.35), 5e3 * chord**3, 4e2 * chord**3, [4.0]])


def _random_state(n: int) -> np.ndarray:
    return np.random.default_rng(7).normal(scale=0.02, size=4 * n - 1)


def test_first_use_answers_from_the_virtual_machine_while_compiling(private_cache: Path) -> None:
    model = compiled.model_for(N_SMALL)
    # No library yet: the model must answer now, from CasADi's virtual machine.
    assert not model.compiled
    evaluation = model.evaluate(_random_state(N_SMALL), _parameters(N_SMALL))
    assert np.all(np.isfinite(evaluation.jacobian0))
    model = compiled.compile_now(N_SMALL, timeout=120)
    assert model.compiled
    libraries = list(private_cache.glob("*.so"))
    assert len(libraries) == 1
    # Keyed by mesh size, model version and CasADi version.
    name = libraries[0].name
    assert f"n{N_SMALL}-" in name
    assert f"model{compiled.MODEL_VERSION}-" in name
    assert "casadi" in name


def test_compiled_code_and_virtual_machine_agree(private_cache: Path) -> None:
    x, p = _random_state(N_SMALL), _parameters(N_SMALL)
    vm = compiled.model_for(N_SMALL)
    on_vm = vm.evaluate(x, p)
    residual_vm = vm.residual(x, p)
    loads_vm = vm.panel_loads(x, p)
    model = compiled.compile_now(N_SMALL, timeout=120)
    assert model.compiled
    on_c = model.evaluate(x, p)
    # Same expression graph, same operation order: only compiler reassociation-free rounding.
    for a, b in [
        (on_vm.r0, on_c.r0),
        (on_vm.r1, on_c.r1),
        (on_vm.jacobian0, on_c.jacobian0),
        (on_vm.jacobian1, on_c.jacobian1),
        *zip(residual_vm, model.residual(x, p), strict=True),
        *zip(loads_vm, model.panel_loads(x, p), strict=True),
    ]:
        np.testing.assert_allclose(b, a, rtol=1e-12, atol=1e-14)


def test_a_new_process_loads_the_library_from_disk(private_cache: Path) -> None:
    compiled.compile_now(N_SMALL, timeout=120)
    probe = (
        f"from solver import compiled; model = compiled.model_for({N_SMALL}); print(model.compiled)"
    )
    result = subprocess.run(
        [sys.executable, "-c", probe], capture_output=True, text=True, check=True
    )
    assert result.stdout.strip() == "True"


def test_compilation_can_be_switched_off(
    private_cache: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("FLEXWING_COMPILE", "0")
    model = compiled.compile_now(N_SMALL, timeout=5)
    assert not model.compiled
    assert not list(private_cache.glob("*.so"))


def test_a_process_that_exits_mid_compile_still_leaves_the_library(private_cache: Path) -> None:
    # The first use starts the compile in the background; the process then exits at once.
    probe = f"from solver import compiled; print(compiled.model_for({N_SMALL}).compiled)"
    result = subprocess.run(
        [sys.executable, "-c", probe], capture_output=True, text=True, check=True
    )
    assert result.stdout.strip() == "False"
    deadline = time.monotonic() + 120
    while not list(private_cache.glob("*.so")) and time.monotonic() < deadline:
        time.sleep(0.2)
    assert len(list(private_cache.glob("*.so"))) == 1
    # The detached compiler cleans its work directory up after itself.
    while list(private_cache.glob("build-*")) and time.monotonic() < deadline:
        time.sleep(0.2)
    assert not list(private_cache.glob("build-*"))


def test_a_process_keeps_a_bounded_number_of_mesh_sizes(
    private_cache: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("FLEXWING_COMPILE", "0")
    monkeypatch.setenv("FLEXWING_MODEL_CACHE_SIZE", "2")
    first = compiled.model_for(4)
    compiled.model_for(5)
    assert compiled.model_for(4) is first  # a hit makes N = 4 the most recently used
    compiled.model_for(6)  # evicts N = 5, the least recently used
    assert sorted(compiled._models) == [4, 6]
    assert compiled.model_for(4) is first
