"""solver.numerics.compiled: virtual machine at once, compiled C code once built, kept on disk, and
both bit-identical."""

from __future__ import annotations

import dataclasses
import fcntl
import shutil
import subprocess
import sys
import threading
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from solver import Layout, Wing
from solver.numerics import compiled
from solver.numerics.cache import clear_caches, model_for

# A small mesh keeps the C compile to a couple of seconds.
N_SMALL = 5


@pytest.fixture
def private_cache(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Iterator[Path]:
    """An empty library cache and an empty solver cache."""
    monkeypatch.setenv("FLEXWING_CACHE_DIR", str(tmp_path))
    monkeypatch.setenv("FLEXWING_COMPILE", "1")
    clear_caches()
    yield tmp_path
    clear_caches()


@pytest.fixture(scope="module")
def built_library(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """One compiled library of Layout(N_SMALL), built once for the tests that need a library
    on disk without being about how it gets there (a compile costs seconds of a core)."""
    with pytest.MonkeyPatch.context() as patch:
        patch.setenv("FLEXWING_CACHE_DIR", str(tmp_path_factory.mktemp("built")))
        patch.setenv("FLEXWING_COMPILE", "1")
        library = compiled._compile_library(Layout(N_SMALL), None, wait=True)
    assert library is not None
    return library


def _finish_compiling(built_library: Path, layout: Layout) -> None:
    """The library of `layout` appears in the cache as another process's compile leaves it: all
    at once (copied aside, then renamed into place)."""
    target = compiled._library_path(layout)
    partial = target.with_suffix(".partial")
    shutil.copyfile(built_library, partial)
    partial.rename(target)


def _values(n: int) -> dict[str, object]:
    """The model's parameters by name (`Layout.pack`): a swept, tapered wing at 4 deg."""
    y = np.linspace(0.0, 3.0, n)
    chord = np.linspace(1.0, 0.5, n)
    wing = Wing.create(y, chord, 0.35, 5e3 * chord**3, 4e2 * chord**3, sweep=10.0)
    values = Layout.wing_values(wing)
    return values | {"camber": np.zeros((n, 2)), "alpha": 4.0, "deformed_axis": False}


def _parameters(n: int) -> np.ndarray:
    return Layout(n).pack(_values(n))


def _random_state(n: int) -> np.ndarray:
    return np.random.default_rng(7).normal(scale=0.02, size=Layout(n).n_unknowns)


@pytest.mark.server  # compiles, or starts a process
def test_first_use_answers_from_the_virtual_machine_while_compiling(private_cache: Path) -> None:
    """The model answers at once from CasADi's virtual machine; the library it compiles
    meanwhile gives the same bits (the lattice's case of the test below)."""
    x, p = _random_state(N_SMALL), _parameters(N_SMALL)
    model = model_for(Layout(N_SMALL))
    # No library yet: the model must answer now, from CasADi's virtual machine.
    assert not model.compiled
    on_vm = model.evaluate(x, p)
    assert np.all(np.isfinite(on_vm.jacobian0))
    residual_vm, loads_vm = model.residual(x, p), model.panel_loads(x, p)
    model.wait_compiled(timeout=120)
    assert model.compiled
    libraries = list(private_cache.glob("*.so"))
    assert len(libraries) == 1
    # Keyed by mesh size, model version and CasADi version.
    name = libraries[0].name
    assert f"n{N_SMALL}-k1-" in name
    assert f"model{compiled.MODEL_VERSION}-" in name
    assert "casadi" in name
    assert "ffp_contract=off" in name
    _assert_same_bits(model, x, p, (on_vm, residual_vm, loads_vm))


def _assert_same_bits(
    model: compiled.CompiledModel, x: np.ndarray, p: np.ndarray, on_vm: tuple[Any, Any, Any]
) -> None:
    """The compiled `model`'s evaluation, residual and panel loads at (x, p) are `on_vm`'s to
    the bit."""
    evaluation, residual, loads = on_vm
    on_c = model.evaluate(x, p)
    for a, b in [
        (evaluation.r0, on_c.r0),
        (evaluation.r1, on_c.r1),
        (evaluation.jacobian0, on_c.jacobian0),
        (evaluation.jacobian1, on_c.jacobian1),
        *zip(residual, model.residual(x, p), strict=True),
        *zip(loads, model.panel_loads(x, p), strict=True),
    ]:
        np.testing.assert_array_equal(b, a)


@pytest.mark.server  # compiles, or starts a process
def test_compiled_code_and_virtual_machine_are_bit_identical(private_cache: Path) -> None:
    """Same operations in the same order, no multiply-add contraction: the same bits, so an
    answer never depends on whether the library had been compiled yet. Strip theory's model
    here; the lattice's in the test above."""
    x, p = _random_state(N_SMALL), _parameters(N_SMALL)
    model = model_for(Layout(N_SMALL, 1, "strip"))
    assert not model.compiled
    on_vm = (model.evaluate(x, p), model.residual(x, p), model.panel_loads(x, p))
    model.wait_compiled(timeout=120)
    assert model.compiled
    _assert_same_bits(model, x, p, on_vm)


def test_the_jacobians_are_whole_fortran_ordered_and_owned_by_the_caller(
    private_cache: Path,
) -> None:
    """The coupled function returns row blocks; the model places them. LAPACK factorises the
    matrices in place only when they are Fortran-ordered, and the next evaluation must not
    overwrite an earlier one's arrays."""
    x, p = _random_state(N_SMALL), _parameters(N_SMALL)
    layout = Layout(N_SMALL)
    model = model_for(layout)
    first = model.evaluate(x, p)
    arrays = (first.r0, first.r1, first.jacobian0, first.jacobian1)
    kept = [a.copy() for a in arrays]
    with_alpha, _ = model.evaluate_with_alpha(x + 0.01, p)
    for matrix in (first.jacobian0, first.jacobian1):
        assert matrix.shape == (layout.n_unknowns, layout.n_unknowns)
        assert matrix.flags.f_contiguous
    for array, copy in zip(arrays, kept, strict=True):
        np.testing.assert_array_equal(array, copy)
    assert not np.array_equal(with_alpha.jacobian0, first.jacobian0)
    # Only the bending and torsion rows of J1 carry the loads; the clamps and kinematics do not.
    outside = np.ones(layout.n_unknowns, dtype=bool)
    outside[layout.load_rows] = False
    assert np.all(first.jacobian1[outside] == 0.0)
    assert np.any(first.jacobian1[layout.load_rows] != 0.0)


@pytest.mark.server  # compiles, or starts a process
def test_a_new_process_loads_the_library_from_disk(
    private_cache: Path, built_library: Path
) -> None:
    _finish_compiling(built_library, Layout(N_SMALL))
    probe = (
        f"from solver import Layout; from solver.numerics.cache import model_for; "
        f"print(model_for(Layout({N_SMALL})).compiled)"
    )
    result = subprocess.run(
        [sys.executable, "-c", probe], capture_output=True, text=True, check=True
    )
    assert result.stdout.strip() == "True"


def test_compilation_can_be_switched_off(
    private_cache: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("FLEXWING_COMPILE", "0")
    model = model_for(Layout(N_SMALL))
    model.wait_compiled(timeout=5)
    assert not model.compiled
    assert not list(private_cache.glob("*.so"))


@pytest.mark.server  # compiles, or starts a process
def test_a_process_that_exits_mid_compile_still_leaves_the_library(private_cache: Path) -> None:
    # The first use starts the compile in the background; the process then exits at once.
    probe = (
        f"from solver import Layout; from solver.numerics.cache import model_for; "
        f"print(model_for(Layout({N_SMALL})).compiled)"
    )
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


@pytest.mark.server  # compiles, or starts a process
def test_a_process_that_lost_the_compile_lock_loads_the_winners_library(
    private_cache: Path, built_library: Path
) -> None:
    """Another process compiles (it holds the lock): this one stays on the virtual machine
    meanwhile, and swaps the library in once it exists."""
    layout = Layout(N_SMALL)
    library = compiled._library_path(layout)
    library.parent.mkdir(parents=True, exist_ok=True)
    with open(library.with_suffix(".lock"), "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)  # the "other process"
        model = model_for(layout)
        deadline = time.monotonic() + 30
        while model.compiling and time.monotonic() < deadline:
            time.sleep(0.05)
        assert not model.compiled and not model.compiling  # gave up: someone else compiles
        fcntl.flock(lock, fcntl.LOCK_UN)
    _finish_compiling(built_library, layout)  # the winner finishes
    assert model_for(layout).compiled


@pytest.mark.server  # compiles, or starts a process
def test_waiting_for_a_library_another_process_compiles_ends_at_the_timeout(
    private_cache: Path, built_library: Path
) -> None:
    """`wait_compiled(timeout)` returns on the virtual machine while another process still holds
    the compile lock, and picks the library up once it exists."""
    layout = Layout(N_SMALL)
    library = compiled._library_path(layout)
    library.parent.mkdir(parents=True, exist_ok=True)
    with open(library.with_suffix(".lock"), "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)  # the "other process", compiling for as long as it likes
        model = model_for(layout)
        waiting = threading.Thread(target=model.wait_compiled, args=(0.2,))
        waiting.start()
        # Far longer than the 0.2 s asked for: only a wait on the lock itself lasts this long.
        waiting.join(60)
        blocked = waiting.is_alive()
        fcntl.flock(lock, fcntl.LOCK_UN)
    waiting.join()
    assert not blocked
    assert not model.compiled
    _finish_compiling(built_library, layout)  # the other process finishes
    model.wait_compiled(timeout=30)
    assert model.compiled


V3_CPU = frozenset(
    [
        "fpu",
        "sse2",
        "cx16",
        "lahf_lm",
        "popcnt",
        "sse4_1",
        "sse4_2",
        "ssse3",
        "avx",
        "avx2",
        "bmi1",
        "bmi2",
        "f16c",
        "fma",
        "abm",
        "movbe",
        "xsave",
    ]
)
V4_CPU = V3_CPU | {"avx512f", "avx512bw", "avx512cd", "avx512dq", "avx512vl"}


@pytest.mark.parametrize(
    ("features", "accepted", "level"),
    [
        pytest.param(V4_CPU, {"x86-64-v4", "x86-64-v3"}, "x86-64-v4", id="avx512-cpu"),
        pytest.param(V3_CPU, {"x86-64-v4", "x86-64-v3"}, "x86-64-v3", id="avx2-cpu"),
        pytest.param(
            V4_CPU - {"avx512vl"}, {"x86-64-v4", "x86-64-v3"}, "x86-64-v3", id="v4-less-vl"
        ),
        pytest.param(V3_CPU - {"fma"}, {"x86-64-v4", "x86-64-v3"}, None, id="no-fma"),
        pytest.param(V4_CPU, {"x86-64-v3"}, "x86-64-v3", id="old-compiler"),
        pytest.param(V4_CPU, set(), None, id="compiler-without-levels"),
    ],
)
def test_the_library_targets_the_highest_isa_level_both_cpu_and_compiler_have(
    features: frozenset[str], accepted: set[str], level: str | None
) -> None:
    """A library built for a level this CPU lacks would die on an illegal instruction."""
    assert (
        compiled.isa_level(features, lambda flag: flag.removeprefix("-march=") in accepted) == level
    )


def test_the_isa_level_is_in_the_library_name(private_cache: Path) -> None:
    """So a machine without that level computes another name and never loads the library."""
    name = compiled._library_path(Layout(N_SMALL)).name
    flags = compiled._flags(compiled._compiler())
    march = [flag for flag in flags if flag.startswith("-march=")]
    assert all(flag.replace("-", "_") in name for flag in march)
    level = compiled.isa_level(
        compiled._cpu_features(),
        lambda flag: compiled._compiler_accepts(compiled._compiler(), flag),
    )
    assert march == ([] if level is None else [f"-march={level}"])


def test_strip_theory_has_a_library_of_its_own_and_the_lattices_name_is_unchanged(
    private_cache: Path,
) -> None:
    """Strip theory is another compiled model of the same mesh: another file, so neither can
    load the other's functions; the lattice's name (and so every library already on disk) is
    the one it had before strip theory existed."""
    lattice = compiled._library_path(Layout(N_SMALL)).name
    strip = compiled._library_path(Layout(N_SMALL, 1, "strip")).name
    assert strip != lattice
    assert lattice.startswith(f"flexwing-n{N_SMALL}-k1-model")
    assert strip.startswith(f"flexwing-n{N_SMALL}-k1-strip-model")


def test_a_flag_the_compiler_does_not_take_is_left_out(tmp_path: Path) -> None:
    """A compiler without GCC's vectorizer cost model (clang only warns about it) still gets
    the flags that keep the library bit-identical."""
    compiler = tmp_path / "cc-without-cost-model"
    compiler.write_text(
        '#!/bin/sh\nfor arg in "$@"; do case "$arg" in -fvect-cost-model*) exit 1;; esac; done\n'
    )
    compiler.chmod(0o755)
    flags = compiled._flags(str(compiler))
    assert "-fvect-cost-model=dynamic" not in flags
    assert {"-O2", "-ffp-contract=off", "-fno-semantic-interposition"} <= set(flags)


def _flow_parameters(n: int) -> np.ndarray:
    """The flow model's: the rotation about x, a roll rate, a control direction."""
    control = np.outer(np.linspace(0.0, 1.0, n), [0.0, -0.5])
    flow = {"image": -1.0, "image_jacobian": -1.0, "roll_rate": 0.03, "control": control}
    direction = np.zeros(Layout(n).n_unknowns)
    return Layout(n).pack(_values(n) | flow | {"direction": direction}, flow=True)


def test_the_flow_model_has_a_library_of_its_own_with_the_virtual_machines_bits(
    private_cache: Path,
) -> None:
    """The flow model (control surfaces, roll) compiles into its own library, keyed apart
    (flow version), and leaves the symmetric model's alone; its compiled code gives its
    virtual machine's bits, every output of `evaluate_with_controls` included."""
    layout = Layout(N_SMALL)
    x, p = _random_state(N_SMALL), _flow_parameters(N_SMALL)
    model = model_for(layout, flow=True)
    assert model.flow and model is not model_for(layout)
    on_vm = model.evaluate_with_controls(x, p)
    roll_vm = model.residual_with_roll(x, p)
    loads_vm = model.panel_loads(x, p)
    model.wait_compiled(timeout=180)
    assert model.compiled
    (library,) = private_cache.glob("*-flow-*.so")
    assert f"model{compiled.MODEL_VERSION}-flow" in library.name
    on_c = model.evaluate_with_controls(x, p)
    pairs = [
        *zip(
            (on_vm[0].r0, on_vm[0].r1, on_vm[0].jacobian0, on_vm[0].jacobian1),
            (on_c[0].r0, on_c[0].r1, on_c[0].jacobian0, on_c[0].jacobian1),
            strict=True,
        ),
        *(
            (getattr(on_vm[2], f.name), getattr(on_c[2], f.name))
            for f in dataclasses.fields(on_c[2])
        ),
        *zip(roll_vm, model.residual_with_roll(x, p), strict=True),
        *zip(loads_vm, model.panel_loads(x, p), strict=True),
    ]
    for a, b in pairs:
        np.testing.assert_array_equal(b, a)
