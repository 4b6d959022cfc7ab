"""One mesh's compiled model: served by CasADi's virtual machine at once and by generated C code
as soon as it has been compiled.

The first solve of a never-seen mesh must not wait for a C compiler: `build_model(layout)`
returns at once with functions evaluated by CasADi's virtual machine and, if compilation is
enabled, starts a background thread that generates C code, compiles it with the system C
compiler and swaps the library in. Libraries are cached on disk, keyed by the mesh, the model
version, the CasADi version, the platform and the compiler flags (with the CPU's ISA level), so
a process that finds one loads it in milliseconds. A file lock stops several processes from
compiling the same library at once; a process that loses the lock loads the winner's library as
soon as it exists.

The virtual machine and the compiled code perform the same floating-point operations in the same
order, and the code is compiled without contracting multiply-adds, so both give bit-identical
results: an answer never depends on which of the two served it.

The flow model (control surfaces and roll, `solver.model.residual`) is a mesh's second model, with a
library of its own: built, compiled and loaded the same way, but only once something first
asks for it (`flow_model`), so that a symmetric solve's library and its compile time stay what
they were.

Environment:
    FLEXWING_CACHE_DIR  where compiled libraries live (default: ~/.cache/flexwing)
    FLEXWING_COMPILE    "0" to never compile (virtual machine only); default "1"
    FLEXWING_CC         C compiler (default: "cc")
"""

from __future__ import annotations

import atexit
import contextlib
import fcntl
import functools
import logging
import os
import platform
import shutil
import subprocess
import tempfile
import threading
import time
from collections.abc import Callable
from pathlib import Path
from typing import TypeVar

import casadi as ca
import numpy as np

from solver.model.layout import Layout
from solver.model.residual import (
    MODEL_VERSION,
    build_coupled_function,
    build_full_span_function,
    build_panel_loads_function,
    build_residual_function,
    model_tag,
)
from solver.numerics.evaluation import AlphaTerms, ControlTerms, Evaluation

__all__ = ["CompiledModel", "build_model", "cache_dir", "compilation_enabled", "isa_level"]

log = logging.getLogger(__name__)

# No FMA contraction keeps the library bit-identical to the virtual machine on every
# architecture. Without semantic interposition the compiler may inline CasADi's small helpers
# (casadi_sq, casadi_copy, ...) into the kernels, as it could not in a shared library otherwise:
# 10-13 % off the Jacobian, the same bits. GCC's dynamic vectorizer cost model (-O3's) lets it
# pack the hand-written kernel derivatives into vector registers: 10-20 % off the Jacobian
# (N = 30 to 120, k = 4), the same bits (IEEE operations, none reassociated), where all of -O3
# compiles 2.5x slower at N = 60 for a few % more.
_BASE_FLAGS = (
    "-O2",
    "-fvect-cost-model=dynamic",
    "-ffp-contract=off",
    "-fno-semantic-interposition",
)
_PROBED_FLAGS = frozenset({"-fvect-cost-model=dynamic"})

# The x86-64 psABI's ISA levels, highest first, with the CPU features (as /proc/cpuinfo names
# them) each needs. Compiling for the highest level this CPU has gives wider vectors (AVX2,
# AVX-512): another 8-12 % off the Jacobian at N = 30, the same bits (the same IEEE operations,
# still no contraction). The level is part of the library's name, so a machine without it never
# loads a library built for it (a shared cache directory, an image built elsewhere).
_V2 = frozenset({"cx16", "lahf_lm", "popcnt", "sse4_1", "sse4_2", "ssse3"})
_V3 = _V2 | {"avx", "avx2", "bmi1", "bmi2", "f16c", "fma", "abm", "movbe", "xsave"}
_V4 = _V3 | {"avx512f", "avx512bw", "avx512cd", "avx512dq", "avx512vl"}
_ISA_LEVELS = (("x86-64-v4", _V4), ("x86-64-v3", _V3))
# How often a process waiting for another one's library looks for it [s].
_LIBRARY_POLL = 0.05


def _cpu_features() -> frozenset[str]:
    """This CPU's feature flags as the Linux kernel reports them (empty elsewhere)."""
    try:
        with open("/proc/cpuinfo", encoding="ascii", errors="replace") as cpuinfo:
            for line in cpuinfo:
                if line.startswith("flags"):
                    return frozenset(line.partition(":")[2].split())
    except OSError:
        pass
    return frozenset()


def _compiler_accepts(compiler: str, flag: str) -> bool:
    try:
        probe = subprocess.run(
            [compiler, "-Werror", flag, "-x", "c", "-c", "-o", os.devnull, "-"],
            input=b"int probe;\n",
            capture_output=True,
            timeout=30,
        )
    except (OSError, subprocess.SubprocessError):
        return False
    return probe.returncode == 0


def isa_level(features: frozenset[str], accepts: Callable[[str], bool]) -> str | None:
    """The highest x86-64 ISA level whose features are all in `features` and whose -march flag
    the compiler `accepts`; None for the baseline."""
    for level, needs in _ISA_LEVELS:
        if needs <= features and accepts(f"-march={level}"):
            return level
    return None


@functools.cache
def _flags(compiler: str) -> tuple[str, ...]:
    """The compile flags for `compiler`: GCC's vectorizer cost model only where the compiler
    takes it (clang ignores it with a warning), the ISA level only where CPU and compiler have
    it."""
    accepts = functools.partial(_compiler_accepts, compiler)
    flags = tuple(flag for flag in _BASE_FLAGS if flag not in _PROBED_FLAGS or accepts(flag))
    if platform.machine() != "x86_64":
        return flags
    level = isa_level(_cpu_features(), accepts)
    return flags if level is None else (*flags, f"-march={level}")


def cache_dir() -> Path:
    return Path(os.environ.get("FLEXWING_CACHE_DIR", Path.home() / ".cache" / "flexwing"))


def _compiler() -> str:
    return os.environ.get("FLEXWING_CC", "cc")


def compilation_enabled() -> bool:
    return os.environ.get("FLEXWING_COMPILE", "1") != "0" and shutil.which(_compiler()) is not None


def _library_path(layout: Layout, flow: bool = False) -> Path:
    casadi_version = ca.__version__  # type: ignore[attr-defined]
    flags = "".join(_flags(_compiler())).replace("-", "_")
    strip = "-strip" if layout.aerodynamics == "strip" else ""  # the lattice's names unchanged
    exact = "-exact" if layout.exact else ""
    exact += "-lag" if layout.lag else ""
    mesh = f"n{layout.n}-k{layout.chordwise}{strip}{exact}"
    model = f"model{MODEL_VERSION}" + ("-flow" if flow else "")
    tag = f"{mesh}-{model}-casadi{casadi_version}-{platform.machine()}{flags}"
    return cache_dir() / f"flexwing-{tag}.so"


def library_on_disk(layout: Layout) -> bool:
    """A compiled library of `layout` is in the disk cache (a process building this model
    loads it; one serving it on the virtual machine swaps it in at its next lookup)."""
    return compilation_enabled() and _library_path(layout).exists()


T = TypeVar("T")

# The full-span functions of the meshes used (virtual machine only, `CompiledModel.full_span`).
_full_span: dict[Layout, ca.Function] = {}
_full_span_lock = threading.Lock()


class _BufferedCall:
    """Calls a CasADi Function through preallocated buffers (4x cheaper than f(x, p)).

    `__call__` returns copies of the outputs in C order. `collect` hands the buffers themselves
    (Fortran order, as CasADi writes them) to a reader that copies what it keeps: the coupled
    function's Jacobian blocks go straight into the Fortran-ordered matrices that LAPACK
    factorises without transposing them.
    """

    def __init__(self, function: ca.Function) -> None:
        self._lock = threading.Lock()
        self._x = np.zeros(function.nnz_in(0))
        self._p = np.zeros(function.nnz_in(1))
        self._outputs = [np.zeros(function.size_out(i), order="F") for i in range(function.n_out())]
        self._buffer, self._evaluate = function.buffer()
        self._buffer.set_arg(0, memoryview(self._x))  # type: ignore[call-arg, arg-type]
        self._buffer.set_arg(1, memoryview(self._p))  # type: ignore[call-arg, arg-type]
        for i, out in enumerate(self._outputs):
            # Dense outputs are written column-major; ravel("K") of an F-ordered array is a view.
            self._buffer.set_res(i, memoryview(out.ravel(order="K")))  # type: ignore[call-arg, arg-type]

    def __call__(self, x: np.ndarray, p: np.ndarray) -> list[np.ndarray]:
        with self._lock:
            self._evaluate_at(x, p)
            return [out.copy(order="C") for out in self._outputs]

    def collect(self, x: np.ndarray, p: np.ndarray, read: Callable[[list[np.ndarray]], T]) -> T:
        """`read(outputs)` on the output buffers themselves, under the lock: `read` copies what
        it keeps (the next call overwrites the buffers)."""
        with self._lock:
            self._evaluate_at(x, p)
            return read(self._outputs)

    def _evaluate_at(self, x: np.ndarray, p: np.ndarray) -> None:
        self._x[:] = x
        self._p[:] = p
        self._evaluate()


_Functions = tuple[ca.Function, ca.Function, ca.Function]


def _buffered_calls(functions: _Functions) -> list[_BufferedCall]:
    """One buffered call per function, in the order of `_Functions`."""
    return [_BufferedCall(function) for function in functions]


def _symbolic_functions(layout: Layout, flow: bool = False) -> _Functions:
    """The coupled (with Jacobians), residual-only and panel-loads functions, in that order
    (the flow model's with `flow`)."""
    return (
        build_coupled_function(layout, flow),
        build_residual_function(layout, flow),
        build_panel_loads_function(layout, flow),
    )


def _alpha_terms(outputs: list[np.ndarray]) -> AlphaTerms:
    """The coupled function's trim and design outputs (copies) as `AlphaTerms`."""
    r0_alpha, r1_alpha, lift, lift_x, lift_alpha, drag, drag_x = outputs
    return AlphaTerms(
        r0_alpha.ravel(),
        r1_alpha.ravel(),
        float(lift[0, 0]),
        lift_x.ravel(),
        float(lift_alpha[0, 0]),
        float(drag[0, 0]),
        drag_x.ravel(),
    )


class CompiledModel:
    """The numerical functions of one mesh; thread-safe.

    `compiled` says whether generated C code serves it (else CasADi's virtual machine); `flow`
    whether it is the mesh's flow model (`solver.model.residual`: its parameter vector is longer,
    and `evaluate_with_controls`, `residual_with_roll` and `full_span` are its own).
    """

    def __init__(self, layout: Layout, functions: _Functions, flow: bool = False) -> None:
        self.layout = layout
        self.flow = flow
        self._calls = _buffered_calls(functions)
        self.compiled = False
        self._compile_thread: threading.Thread | None = None

    @classmethod
    def from_library(cls, layout: Layout, library: Path, flow: bool = False) -> CompiledModel:
        """The model served by a compiled library: no symbolic build at all."""
        model = cls.__new__(cls)
        model.layout = layout
        model.flow = flow
        model._compile_thread = None
        model._use_library(library)
        return model

    def evaluate(self, x: np.ndarray, p: np.ndarray) -> Evaluation:
        """Residual parts and exact Jacobians at x (about 4x the cost of `residual`)."""
        return self._calls[0].collect(x, p, self._evaluation)

    def _evaluation(self, outputs: list[np.ndarray]) -> Evaluation:
        """r0, r1 and the full (n, n) Jacobians, Fortran-ordered, from the coupled function's
        outputs: J0's structure and tangency rows placed, J1's load rows placed among zeros."""
        r0, r1, structure, tangency, loads = outputs[:5]
        layout, n = self.layout, self.layout.n_unknowns
        j0 = np.empty((n, n), order="F")
        j0[layout.structure_rows] = structure
        j0[layout.tangency_rows] = tangency
        j1 = np.zeros((n, n), order="F")
        j1[layout.load_rows] = loads
        return Evaluation(r0.ravel().copy(), r1.ravel().copy(), j0, j1)

    def evaluate_with_alpha(self, x: np.ndarray, p: np.ndarray) -> tuple[Evaluation, AlphaTerms]:
        """`evaluate`, and what trim and design add (same evaluation, nothing recomputed)."""
        evaluation, alpha_outputs = self._calls[0].collect(
            x, p, lambda outputs: (self._evaluation(outputs), [a.copy() for a in outputs[5:12]])
        )
        return evaluation, _alpha_terms(alpha_outputs)

    def evaluate_with_controls(
        self, x: np.ndarray, p: np.ndarray
    ) -> tuple[Evaluation, AlphaTerms, ControlTerms]:
        """The flow model's `evaluate_with_alpha`, and what control surfaces and roll add (same
        evaluation)."""
        evaluation, alpha_outputs, control_outputs = self._calls[0].collect(
            x,
            p,
            lambda outputs: (
                self._evaluation(outputs),
                [a.copy() for a in outputs[5:12]],
                [c.copy() for c in outputs[12:]],
            ),
        )
        r0_c, r1_c, lift_c, roll, roll_x, roll_c, r0_p, r1_p, roll_p, *rates = control_outputs
        m, n = self.layout.n_panels, self.layout.n
        # The exact beam's two more load rows follow the six (`solver.model.exact_beam`).
        loads_along, loads_control, loads_rate = (r.reshape(-1, m)[:6] for r in rates[:3])
        center_along, center_control = (r.reshape(m, 3).T for r in rates[3:5])
        leading_edge_along, quarter_chord_along = (r.reshape(n, 3).T for r in rates[5:])
        controls = ControlTerms(
            r0_c.ravel(),
            r1_c.ravel(),
            float(lift_c[0, 0]),
            float(roll[0, 0]),
            roll_x.ravel(),
            float(roll_c[0, 0]),
            r0_p.ravel(),
            r1_p.ravel(),
            float(roll_p[0, 0]),
            loads_along,
            loads_control,
            loads_rate,
            center_along,
            center_control,
            leading_edge_along,
            quarter_chord_along,
        )
        return evaluation, _alpha_terms(alpha_outputs), controls

    def residual(self, x: np.ndarray, p: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(r0, r1) at x, without derivatives."""
        r0, r1, *_ = self._calls[1](x, p)
        return r0.ravel(), r1.ravel()

    def residual_with_lift(
        self, x: np.ndarray, p: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray, float]:
        """(r0, r1) at x, and the lift of both halves per unit q [m^2], without derivatives."""
        r0, r1, lift, *_ = self._calls[1](x, p)
        return r0.ravel(), r1.ravel(), float(lift[0, 0])

    def residual_with_roll(
        self, x: np.ndarray, p: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray, float]:
        """The flow model's (r0, r1) at x, and the rolling moment per unit q [m^3]
        (`ControlTerms.roll`), without derivatives."""
        r0, r1, _, roll = self._calls[1](x, p)
        return r0.ravel(), r1.ravel(), float(roll[0, 0])

    def full_span(self) -> ca.Function:
        """`solver.model.residual.build_full_span_function` of this mesh: the right half with a
        left half of its own (the flow model's parameters). Built on first use and served by
        the virtual machine: only tests call it."""
        with _full_span_lock:
            function = _full_span.get(self.layout)
            if function is None:
                function = build_full_span_function(self.layout)
                _full_span[self.layout] = function
            return function

    def panel_loads(self, x: np.ndarray, p: np.ndarray) -> list[np.ndarray]:
        """[force (3, M) per unit q, torque (1, M) per unit q about the undeformed elastic axis,
        center (3, M) force points, quarter_chord (3, N), and the flow model's leading_edge
        (3, N)]: the right half-wing's panels."""
        return self._calls[2](x, p)

    @property
    def compiling(self) -> bool:
        thread = self._compile_thread
        return thread is not None and thread.is_alive()

    def refresh(self) -> None:
        """Swap in the library on disk if one appeared since (another process compiled it)."""
        if not self.compiled and not self.compiling:
            library = _library_path(self.layout, self.flow)
            if library.exists():
                with contextlib.suppress(OSError, RuntimeError):
                    self._use_library(library)

    def wait_compiled(self, timeout: float | None = None) -> None:
        """Wait (up to `timeout` seconds, or for as long as it takes) for the compiled library,
        compiling it here if no process is doing so; returns on the virtual machine if
        compilation is disabled, fails or takes longer."""
        deadline = None if timeout is None else time.monotonic() + timeout
        thread = self._compile_thread
        if thread is not None:
            thread.join(timeout)
            if thread.is_alive():
                return  # still compiling here, past the timeout
        if self.compiled or not compilation_enabled():
            return
        if deadline is None:
            library = _compile_library(self.layout, None, wait=True, flow=self.flow)
            if library is not None:
                self._use_library(library)
            return
        # Another process holds the compile lock: look for its library until the deadline.
        # (Waiting on the lock itself would ignore the timeout.)
        while True:
            self.refresh()
            remaining = deadline - time.monotonic()
            if self.compiled or remaining <= 0:
                return
            time.sleep(min(_LIBRARY_POLL, remaining))

    def _use_library(self, library: Path) -> None:
        tag = model_tag(self.layout)
        kind = "flow_" if self.flow else ""
        coupled, residual, panel_loads = (
            ca.external(f"flexwing_{kind}{function}_{tag}", str(library))
            for function in ("coupled", "residual", "panel_loads")
        )
        calls = _buffered_calls((coupled, residual, panel_loads))
        self._calls = calls  # one assignment: a concurrent call sees either set, never a mix
        self.compiled = True

    def _start_compiling(self, functions: _Functions) -> None:
        launched = threading.Event()
        _handoffs.append(launched)
        self._compile_thread = threading.Thread(
            target=_background_compile,
            args=(self, functions, launched),
            daemon=True,
            name=f"flexwing-compile-{self.layout.n}-{self.layout.chordwise}"
            + ("-flow" if self.flow else ""),
        )
        self._compile_thread.start()


def build_model(layout: Layout, flow: bool = False) -> CompiledModel:
    """A model for `layout` (its flow model with `flow`): compiled if a library exists on disk,
    else the virtual machine, compiling in the background when compilation is enabled."""
    library = _library_path(layout, flow)
    if library.exists():
        with contextlib.suppress(OSError, RuntimeError):
            return CompiledModel.from_library(layout, library, flow)
    functions = _symbolic_functions(layout, flow)
    model = CompiledModel(layout, functions, flow)
    model.refresh()
    if not model.compiled and compilation_enabled():
        model._start_compiling(functions)
    return model


def _compile_library(
    layout: Layout,
    functions: _Functions | None,
    wait: bool = False,
    launched: threading.Event | None = None,
    flow: bool = False,
) -> Path | None:
    """Generate and compile the C library of `layout` (its flow model's with `flow`).

    If another process is compiling it, return None at once, or with `wait` block until it has.
    `launched` is set once the detached compiler runs.
    """
    library = _library_path(layout, flow)
    if library.exists():
        return library
    library.parent.mkdir(parents=True, exist_ok=True)
    lock_path = library.with_suffix(".lock")
    with open(lock_path, "w") as lock_file:
        try:
            fcntl.flock(lock_file, fcntl.LOCK_EX | (0 if wait else fcntl.LOCK_NB))
        except BlockingIOError:
            return None  # another process compiles it; `refresh` will find it
        if library.exists():
            return library
        with open(library.parent / "compiler.lock", "w") as compiler_slot:
            # One C compiler at a time per cache directory (per machine): each mesh a request
            # names may start a compile, and a large one takes minutes and gigabytes.
            try:
                fcntl.flock(compiler_slot, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except BlockingIOError:
                if launched is not None:
                    launched.set()  # nothing handed off yet: exiting need not wait for the queue
                fcntl.flock(compiler_slot, fcntl.LOCK_EX)
            if library.exists():
                return library
            return _generate_and_compile(layout, functions, library, launched, flow)
    return library


def _generate_and_compile(
    layout: Layout,
    functions: _Functions | None,
    library: Path,
    launched: threading.Event | None,
    flow: bool = False,
) -> Path:
    """Generate the C source of `layout` and compile it into `library` (locks held)."""
    if functions is None:
        functions = _symbolic_functions(layout, flow)
    work = Path(tempfile.mkdtemp(prefix="build-", dir=library.parent))
    kind = "flow_" if flow else ""
    source = work / f"flexwing_{kind}{layout.n}_{layout.chordwise}.c"
    generator = ca.CodeGenerator(source.name, {"with_header": False})
    for function in functions:
        generator.add(function)
    generator.generate(str(work) + os.sep)
    # The compiler runs in its own session and the shell finishes the job (atomic rename,
    # clean-up) even if this process exits first: a short-lived process still leaves the
    # library for the next one instead of a half-built directory.
    script = (
        f'"$0" {" ".join(_flags(_compiler()))} -fPIC -shared "$1" -o "$2/lib.so" '
        '&& mv -f "$2/lib.so" "$3"; status=$?; rm -rf "$2"; exit $status'
    )
    compiler = subprocess.Popen(
        ["sh", "-c", script, _compiler(), str(source), str(work), str(library)],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        start_new_session=True,
    )
    if launched is not None:
        launched.set()
    stdout, stderr = compiler.communicate()
    if compiler.returncode != 0 or not library.exists():
        raise subprocess.CalledProcessError(compiler.returncode, _compiler(), stdout, stderr)
    return library


# Interpreter exit waits until each background compile has handed its work to the detached
# compiler (code generation takes a fraction of a second), never for the compile itself.
_handoffs: list[threading.Event] = []
_HANDOFF_WAIT = 60.0  # [s]


@atexit.register
def _wait_for_handoffs() -> None:
    for launched in list(_handoffs):
        launched.wait(_HANDOFF_WAIT)


def _background_compile(
    model: CompiledModel, functions: _Functions, launched: threading.Event
) -> None:
    try:
        library = _compile_library(model.layout, functions, launched=launched, flow=model.flow)
    except (OSError, subprocess.CalledProcessError) as error:
        log.warning("compiling the %s model failed, staying on the VM: %s", model.layout, error)
        return
    finally:
        launched.set()  # nothing (more) to hand off
        with contextlib.suppress(ValueError):
            _handoffs.remove(launched)
    if library is not None:
        model._use_library(library)
        log.info("the %s model now runs compiled code from %s", model.layout, library)
