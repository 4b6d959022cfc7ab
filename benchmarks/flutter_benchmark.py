"""Flutter: the Goland wing's and the study wing's modes and 50-speed V-g / V-f sweeps at N = 30,
in process, under strip theory, the quasi-3D lattice and the unsteady vortex lattice.

    OPENBLAS_NUM_THREADS=1 python benchmarks/flutter_benchmark.py [--repeats 15]

Each case is a new wing (its stiffness changed by a part in 1e12), so nothing of the wing is
cached between repeats; the compiled model of the mesh is (it is built once per mesh and kept
on disk). Medians of CPU time (this is a shared 2-core machine: wall time drifts with the other
users' load, printed alongside) and, as baselines measured in the same run, one static
equilibrium of the same wing and the same sweep without the wake's lag (quasi-steady: one
eigenvalue solve per airspeed, no p-k iteration).

Cases:
- natural modes alone (`solver.dynamics.modes.natural_modes`)
- the sweep about the jig, strip theory (issue 26's benchmark: target < 100 ms)
- the same with the lattice's circulation
- the same about the equilibrium at alpha 2 deg (a static sweep underneath)
- the same about the jig with the unsteady lattice (its wake and matrices computed per wing)
- the study wing (tests/study.py, N = 30) with a light mass (1 kg/m, centre of gravity at 42 %,
  0.02 kg m: the service's `study_loaded` example), 50 speeds from 1 to 40 m/s about the jig,
  strip theory and the unsteady lattice (issue 42's benchmark: target < 500 ms, and its ratio
  to strip theory's time in the same run), and about its equilibrium at 5 deg to 21 m/s
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
from tests.study import DENSITY, study_wing

N = 30
SPEEDS = np.linspace(5.0, 250.0, 50)  # [m/s]
STUDY_SPEEDS = np.linspace(1.0, 40.0, 50)  # [m/s] the study wing diverges at 21-24 m/s
LOADED_STUDY_SPEEDS = np.linspace(1.0, 21.0, 50)  # [m/s] its fold at 5 deg is at 21.44 m/s
STUDY_MASS = solver.MassModel.create(N, 1.0, 0.42, 0.02)


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


def _study(i: int) -> solver.Wing:
    """A new study wing per repeat."""
    return study_wing(N, 1.0 + 1e-12 * (i + 2))


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
    unsteady = solver.SolverOptions(aerodynamics="unsteady_lattice")
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
        "modes + 50-speed sweep, unsteady lattice, about the jig": lambda i: flutter(
            _wing(i), mass, SPEEDS, SEA_LEVEL, options=unsteady
        ),
        "study wing: modes + 50 speeds, strip, about the jig": lambda i: flutter(
            _study(i), STUDY_MASS, STUDY_SPEEDS, DENSITY, options=strip
        ),
        "study wing: modes + 50 speeds, unsteady lattice, jig": lambda i: flutter(
            _study(i), STUDY_MASS, STUDY_SPEEDS, DENSITY, options=unsteady
        ),
        "study wing: the same about its equilibrium at 5 deg": lambda i: flutter(
            _study(i), STUDY_MASS, LOADED_STUDY_SPEEDS, DENSITY, alpha=5.0, options=unsteady
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
    print(f"{'case':56} {'CPU [ms]':>9} {'wall [ms]':>10} {'/ static':>9} {'/ quasi-st.':>12}")
    for name, (cpu, wall) in results.items():
        print(
            f"{name:56} {cpu * 1e3:9.1f} {wall * 1e3:10.1f} {cpu / baseline:9.2f} "
            f"{cpu / steady:12.2f}"
        )
    uvlm = flutter(_wing(0), mass, SPEEDS, SEA_LEVEL, options=unsteady).flutter
    assert uvlm is not None
    print(
        f"Goland, unsteady lattice (1 chordwise panel), sea level: flutter {uvlm.velocity:.3f} "
        f"m/s at {uvlm.frequency:.3f} rad/s (mode {uvlm.mode})"
    )
    answer = flutter(_study(0), STUDY_MASS, STUDY_SPEEDS, DENSITY, options=unsteady)
    divergence = answer.divergence.velocity if answer.divergence else float("nan")
    print(
        f"study wing, unsteady lattice: {answer.status} to {STUDY_SPEEDS[-1]:.0f} m/s, linear "
        f"divergence {divergence:.2f} m/s, {answer.solver.iterations} p-k solves"
    )
    study = results["study wing: modes + 50 speeds, unsteady lattice, jig"][0]
    study_strip = results["study wing: modes + 50 speeds, strip, about the jig"][0]
    print(
        f"issue 42: study wing, unsteady lattice, modes + 50 speeds about the jig: "
        f"{study * 1e3:.1f} ms CPU (target < 500 ms), {study / study_strip:.2f} x strip theory's"
    )
    print(f"load average {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
