"""Flutter: the Goland wing's modes and a 50-speed V-g / V-f sweep at N = 30, in process.

    OPENBLAS_NUM_THREADS=1 python benchmarks/flutter_benchmark.py [--repeats 15]

Each case is a new wing (its stiffness changed by a part in 1e12), so nothing of the wing is
cached between repeats; the compiled model of the mesh is (it is built once per mesh and kept
on disk). Medians of CPU time (this is a shared 2-core machine: wall time drifts with the other
users' load, printed alongside) and, as baselines measured in the same run, one static
equilibrium of the same wing and the same sweep without the wake's lag (quasi-steady: one
eigenvalue solve per airspeed, no p-k iteration).

Cases:
- natural modes alone (`solver.dynamics.modes.natural_modes`)
- the sweep about the jig, strip theory (the issue's benchmark: target < 100 ms)
- the same with the lattice's circulation
- the same about the equilibrium at alpha 2 deg (a static sweep underneath)
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import argparse
import statistics
import sys
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import solver
from solver.dynamics.flutter import FlutterOptions, flutter
from solver.dynamics.modes import natural_modes
from solver.model.layout import Layout
from solver.numerics.cache import model_for
from tests.flutter_reference import SEA_LEVEL, goland_mass, goland_wing

N = 30
SPEEDS = np.linspace(5.0, 250.0, 50)  # [m/s]


def _timed(run: Callable[[int], object], repeats: int) -> tuple[float, float]:
    """Median (CPU, wall) seconds of run(i) over `repeats` calls, after one warm-up."""
    run(-1)
    cpu, wall = [], []
    for i in range(repeats):
        c0, w0 = time.process_time(), time.perf_counter()
        run(i)
        cpu.append(time.process_time() - c0)
        wall.append(time.perf_counter() - w0)
    return statistics.median(cpu), statistics.median(wall)


def _wing(i: int) -> solver.Wing:
    """A new wing per repeat: nothing of it is in the solver's cache."""
    return goland_wing(N, 1.0 + 1e-12 * (i + 2))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=15)
    repeats = parser.parse_args().repeats
    for aerodynamics in ("strip", "lattice"):
        model = model_for(Layout(N, 1, aerodynamics))  # type: ignore[arg-type]
        model.wait_compiled()
        print(f"N = {N} {aerodynamics} model compiled: {model.compiled}")
    print(f"load average {os.getloadavg()[0]:.2f} (2 cores, shared)")
    mass = goland_mass(N)
    strip = solver.SolverOptions(aerodynamics="strip")
    lattice = solver.SolverOptions(aerodynamics="lattice")
    flight = solver.FlightCondition(100.0, 2.0, SEA_LEVEL)
    quasi_steady = FlutterOptions(unsteady="quasi_steady")
    cases: dict[str, Callable[[int], object]] = {
        "static equilibrium, strip (baseline)": lambda i: solver.solve(
            _wing(i), flight, options=strip
        ),
        "natural modes": lambda i: natural_modes(_wing(i), mass, 6),
        "modes + 50-speed sweep, strip, about the jig": lambda i: flutter(
            _wing(i), mass, SPEEDS, SEA_LEVEL, options=strip
        ),
        "same, quasi-steady (baseline)": lambda i: flutter(
            _wing(i), mass, SPEEDS, SEA_LEVEL, options=strip, flutter_options=quasi_steady
        ),
        "modes + 50-speed sweep, lattice, about the jig": lambda i: flutter(
            _wing(i), mass, SPEEDS, SEA_LEVEL, options=lattice
        ),
        "modes + 50-speed sweep, strip, about alpha 2 deg": lambda i: flutter(
            _wing(i), mass, SPEEDS, SEA_LEVEL, alpha=2.0, options=strip
        ),
    }
    results = {name: _timed(run, repeats) for name, run in cases.items()}
    result = flutter(_wing(0), mass, SPEEDS, SEA_LEVEL, options=strip)
    onset = result.flutter
    assert onset is not None
    print(
        f"Goland, strip theory, sea level: flutter {onset.velocity:.3f} m/s at "
        f"{onset.frequency:.3f} rad/s (mode {onset.mode}), {result.solver.iterations} p-k solves"
    )
    baseline = results["static equilibrium, strip (baseline)"][0]
    steady = results["same, quasi-steady (baseline)"][0]
    print(f"{'case':50} {'CPU [ms]':>9} {'wall [ms]':>10} {'/ static':>9} {'/ quasi-st.':>12}")
    for name, (cpu, wall) in results.items():
        print(
            f"{name:50} {cpu * 1e3:9.1f} {wall * 1e3:10.1f} {cpu / baseline:9.2f} "
            f"{cpu / steady:12.2f}"
        )
    print(f"load average {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
