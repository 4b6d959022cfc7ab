"""Per-mesh compiled model: built once per N, served by CasADi's virtual machine at once and by
generated C code as soon as it has been compiled.

The first solve of a never-seen N must not wait for a C compiler: `model_for(n)` returns
immediately with functions evaluated by CasADi's virtual machine and, if compilation is enabled,
starts a background thread that generates C code, compiles it with the system C compiler and
swaps the compiled library in. Libraries are cached on disk, keyed by N, the model version, the
CasADi version and the platform, so a process (or a worker in a pool) that finds one loads it in
milliseconds. A file lock stops several processes from compiling the same N at once.

Environment:
    FLEXWING_CACHE_DIR  where compiled libraries live (default: ~/.cache/flexwing)
    FLEXWING_COMPILE    "0" to never compile (virtual machine only); default "1"
    FLEXWING_CC         C compiler (default: "cc")
    FLEXWING_MODEL_CACHE_SIZE  mesh sizes whose models a process keeps (default 8, LRU)
"""

from __future__ import annotations

import atexit
import contextlib
import fcntl
import logging
import os
import platform
import shutil
import subprocess
import tempfile
import threading
from dataclasses import dataclass, field
from pathlib import Path

import casadi as ca
import numpy as np

from solver.model import (
    MODEL_VERSION,
    Layout,
    build_coupled_function,
    build_panel_loads_function,
    build_residual_function,
)

__all__ = ["CompiledModel", "Evaluation", "model_for", "compile_now", "cache_dir"]

log = logging.getLogger(__name__)

_OPTIMISATION = "-O2"  # -O3 gave no measurable gain and compiles slower; see benchmarks/


def cache_dir() -> Path:
    return Path(os.environ.get("FLEXWING_CACHE_DIR", Path.home() / ".cache" / "flexwing"))


def _compilation_enabled() -> bool:
    return os.environ.get("FLEXWING_COMPILE", "1") != "0" and shutil.which(_compiler()) is not None


def _compiler() -> str:
    return os.environ.get("FLEXWING_CC", "cc")


def _library_path(n: int) -> Path:
    casadi_version = ca.__version__  # type: ignore[attr-defined]
    tag = f"n{n}-model{MODEL_VERSION}-casadi{casadi_version}-{platform.machine()}-{_OPTIMISATION}"
    return cache_dir() / f"flexwing-{tag}.so"


@dataclass
class Evaluation:
    """r = r0 + q r1 and J = J0 + q J1 at one state; arrays owned by the caller."""

    r0: np.ndarray  # (4N-1,)
    r1: np.ndarray  # (4N-1,)
    jacobian0: np.ndarray  # (4N-1, 4N-1)
    jacobian1: np.ndarray  # (4N-1, 4N-1)

    def residual(self, q: float) -> np.ndarray:
        return self.r0 + q * self.r1

    def jacobian(self, q: float) -> np.ndarray:
        return self.jacobian0 + q * self.jacobian1


class _BufferedCall:
    """Calls a CasADi Function through preallocated buffers (4x cheaper than f(x, p))."""

    def __init__(self, function: ca.Function) -> None:
        self._function = function
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
            self._x[:] = x
            self._p[:] = p
            self._evaluate()
            return [out.copy(order="C") for out in self._outputs]


@dataclass
class CompiledModel:
    """The numerical functions of one mesh size; thread-safe."""

    n: int
    layout: Layout
    _coupled: _BufferedCall
    _residual: _BufferedCall
    _panel_loads: _BufferedCall
    compiled: bool = False
    _swap_lock: threading.Lock = field(default_factory=threading.Lock)

    def evaluate(self, x: np.ndarray, p: np.ndarray) -> Evaluation:
        """Residual parts and exact Jacobians at x (about 4x the cost of `residual`)."""
        r0, r1, j0, j1 = self._coupled(x, p)
        return Evaluation(r0.ravel(), r1.ravel(), j0, j1)

    def residual(self, x: np.ndarray, p: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(r0, r1) at x, without derivatives."""
        r0, r1 = self._residual(x, p)
        return r0.ravel(), r1.ravel()

    def panel_loads(self, x: np.ndarray, p: np.ndarray) -> list[np.ndarray]:
        """[force (3, N-1) per unit q, torque (1, N-1) per unit q, vortex_center, vortex_vertex]."""
        return self._panel_loads(x, p)

    def _use_library(self, library: Path) -> None:
        coupled = ca.external(f"flexwing_coupled_{self.n}", str(library))
        residual = ca.external(f"flexwing_residual_{self.n}", str(library))
        loads = ca.external(f"flexwing_panel_loads_{self.n}", str(library))
        with self._swap_lock:
            self._coupled = _BufferedCall(coupled)
            self._residual = _BufferedCall(residual)
            self._panel_loads = _BufferedCall(loads)
            self.compiled = True


# Models kept per process, least recently used first: each holds CasADi graphs of 10-60 MB, so
# a service asked for many mesh sizes must not keep them all. An evicted size is rebuilt (or its
# library reloaded from disk) in milliseconds to a second when asked for again.
_models: dict[int, CompiledModel] = {}


def _model_cache_size() -> int:
    return max(1, int(os.environ.get("FLEXWING_MODEL_CACHE_SIZE", "8")))


def _remember(n: int, model: CompiledModel) -> None:
    """Insert or refresh N as the most recently used model; evict beyond the cache size."""
    _models.pop(n, None)
    _models[n] = model
    while len(_models) > _model_cache_size():
        _models.pop(next(iter(_models)))


_models_lock = threading.Lock()
_compile_threads: dict[int, threading.Thread] = {}


_Functions = tuple[ca.Function, ca.Function, ca.Function]


def _symbolic_functions(n: int) -> _Functions:
    """The coupled (with Jacobians), residual-only and panel-loads functions, in that order."""
    return build_coupled_function(n), build_residual_function(n), build_panel_loads_function(n)


def _compile_library(
    n: int,
    functions: _Functions | None,
    wait: bool = False,
    launched: threading.Event | None = None,
) -> Path | None:
    """Generate and compile the C library for N.

    If another process is compiling it, return None at once, or with `wait` block until it has.
    `launched` is set once the detached compiler runs.
    """
    library = _library_path(n)
    if library.exists():
        return library
    library.parent.mkdir(parents=True, exist_ok=True)
    lock_path = library.with_suffix(".lock")
    with open(lock_path, "w") as lock_file:
        try:
            fcntl.flock(lock_file, fcntl.LOCK_EX | (0 if wait else fcntl.LOCK_NB))
        except BlockingIOError:
            return None  # another process compiles it; a later model_for() will find it
        if library.exists():
            return library
        if functions is None:
            functions = _symbolic_functions(n)
        work = Path(tempfile.mkdtemp(prefix="build-", dir=library.parent))
        source = work / f"flexwing_{n}.c"
        generator = ca.CodeGenerator(source.name, {"with_header": False})
        for function in functions:
            generator.add(function)
        generator.generate(str(work) + os.sep)
        # The compiler runs in its own session and the shell finishes the job (atomic rename,
        # clean-up) even if this process exits first: a short-lived process still leaves the
        # library for the next one instead of a half-built directory.
        script = (
            f'"$0" {_OPTIMISATION} -fPIC -shared "$1" -o "$2/lib.so" '
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
        library = _compile_library(model.n, functions, launched=launched)
    except (OSError, subprocess.CalledProcessError) as error:
        log.warning("compiling the N=%d model failed, staying on the VM: %s", model.n, error)
        return
    finally:
        launched.set()  # nothing (more) to hand off
    if library is not None:
        model._use_library(library)
        log.info("N=%d model now runs compiled code from %s", model.n, library)


def model_for(n: int) -> CompiledModel:
    """The cached model for N stations: compiled if a library exists, else the VM (compiling)."""
    with _models_lock:
        model = _models.get(n)
        if model is not None:
            _remember(n, model)
    if model is not None:
        if not model.compiled and n not in _compile_threads and _library_path(n).exists():
            with contextlib.suppress(OSError, RuntimeError):
                model._use_library(_library_path(n))
        return model
    with _models_lock:
        model = _models.get(n)
        if model is not None:
            return model
        functions = _symbolic_functions(n)
        coupled, residual, panel_loads = (_BufferedCall(function) for function in functions)
        model = CompiledModel(n, Layout(n), coupled, residual, panel_loads)
        library = _library_path(n)
        if library.exists():
            with contextlib.suppress(OSError, RuntimeError):
                model._use_library(library)
        if not model.compiled and _compilation_enabled():
            launched = threading.Event()
            _handoffs.append(launched)
            thread = threading.Thread(
                target=_background_compile,
                args=(model, functions, launched),
                daemon=True,
                name=f"flexwing-compile-{n}",
            )
            _compile_threads[n] = thread
            thread.start()
        _remember(n, model)
        return model


def compile_now(n: int, timeout: float | None = None) -> CompiledModel:
    """The model for N, waiting (up to `timeout` seconds) for its compiled library.

    Used to warm worker pools and by benchmarks; returns the VM model if compilation is disabled,
    fails, or takes longer than the timeout.
    """
    model = model_for(n)
    thread = _compile_threads.get(n)
    if thread is not None:
        thread.join(timeout)
        _compile_threads.pop(n, None)
    if not model.compiled and _compilation_enabled():
        # Another process held the compile lock: wait for its library.
        library = _compile_library(n, None, wait=True)
        if library is not None:
            model._use_library(library)
    return model
