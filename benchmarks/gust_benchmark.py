"""Gust loads: the study wing (N = 30, compiled, a light mass: 1 kg/m, centre of gravity at
42 %, 0.02 kg m) at 12 m/s carrying 300 N, in process.

    OPENBLAS_NUM_THREADS=1 python benchmarks/gust_benchmark.py [--repeats 15]

Each repeat is a new wing (its stiffness changed by a part in 1e12): its trim, modes and
model are built anew. Medians of CPU and wall time (a shared 2-core machine). Cases:
- one static trimmed equilibrium of the same wing (the baseline);
- the gust model alone (trim, modes, the Jacobians, the state-space system);
- the tuned-gust search: the model and 20 gradients from 9 to 107 m (issue 37's target:
  < 200 ms), without turbulence;
- continuous turbulence's A-bar on a built model (issue 37's target: < 50 ms);
- the whole analysis (/gust's default: 20 gradients, turbulence, 4 modes);
- the same with the unsteady lattice (options.aerodynamics "unsteady_lattice": the
  frequency-domain model of `solver.gusts.lattice_model`, the tuned-gust search by FFT and
  A-bar, `solver.gusts.frequency_response`), against strip theory's state space in the run;
and the figures: the tuned gust, its load factor beside Pratt's, A-bar of the load factor.
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

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import solver
from solver.gusts.frequency_response import lattice_a_bar, top_frequency
from solver.gusts.lattice_model import lattice_gust_model
from solver.gusts.model import gust_model
from solver.gusts.turbulence import a_bar
from solver.model.layout import Layout
from solver.numerics.cache import model_for
from tests.study import DENSITY, study_arrays

N = 30
MASS = {"mass_per_length": 1.0, "center_of_gravity": 0.42, "inertia_per_length": 0.02}
FLIGHT = solver.FlightCondition(12.0, density=DENSITY, weight=300.0)


def _wing(i: int) -> solver.Wing:
    return solver.Wing.create(**study_arrays(N, 1.0 + 1e-12 * (i + 2)), mass=MASS)


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


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=15)
    repeats = parser.parse_args().repeats
    model = model_for(Layout(N, 1, "lattice"))
    model.wait_compiled()
    print(f"N = {N} lattice model compiled: {model.compiled}")
    print(f"load average {os.getloadavg()[0]:.2f} (2 cores, shared)")
    search = solver.GustSettings(turbulence=False)
    built = {i: gust_model(_wing(i), FLIGHT, None, 4) for i in range(-1, repeats)}
    unsteady = solver.SolverOptions(aerodynamics="unsteady_lattice")
    strip = solver.SolverOptions(aerodynamics="strip")
    top = top_frequency(12.0, 9.0)
    lattice_built = {
        i: lattice_gust_model(_wing(i), FLIGHT, unsteady, 4, top_frequency=top)
        for i in range(-1, repeats)
    }
    cases: dict[str, Callable[[int], object]] = {
        "static trimmed equilibrium (baseline)": lambda i: solver.solve(_wing(i), FLIGHT),
        "gust model (trim, modes, system)": lambda i: gust_model(_wing(i), FLIGHT, None, 4),
        "tuned-gust search, 20 gradients (target < 200 ms)": lambda i: solver.gust_analysis(
            _wing(i), FLIGHT, search
        ),
        "A-bar on a built model (target < 50 ms)": lambda i: a_bar(built[i]),
        "whole /gust analysis (20 gradients, turbulence)": lambda i: solver.gust_analysis(
            _wing(i), FLIGHT
        ),
        "strip: tuned-gust search, 20 gradients": lambda i: solver.gust_analysis(
            _wing(i), FLIGHT, search, strip
        ),
        "strip: whole /gust analysis": lambda i: solver.gust_analysis(
            _wing(i), FLIGHT, None, strip
        ),
        "unsteady lattice: model (trim, modes, 17 k)": lambda i: lattice_gust_model(
            _wing(i), FLIGHT, unsteady, 4, top_frequency=top
        ),
        "unsteady lattice: tuned-gust search, 20 gradients": lambda i: solver.gust_analysis(
            _wing(i), FLIGHT, search, unsteady
        ),
        "unsteady lattice: A-bar on a built model": lambda i: lattice_a_bar(lattice_built[i]),
        "unsteady lattice: whole /gust analysis": lambda i: solver.gust_analysis(
            _wing(i), FLIGHT, None, unsteady
        ),
    }
    base = None
    print(f"{'case':52s} {'CPU ms':>8s} {'wall ms':>8s} {'x baseline':>10s}")
    for name, run in cases.items():
        cpu, wall = _timed(run, repeats)
        base = base or cpu
        print(f"{name:52s} {1e3 * cpu:8.1f} {1e3 * wall:8.1f} {cpu / base:10.1f}")
    for label, options in (("lattice", None), ("strip", strip), ("unsteady lattice", unsteady)):
        _figures(label, solver.gust_analysis(_wing(0), FLIGHT, None, options))


def _figures(label: str, result: solver.GustResult) -> None:
    tuned = result.gusts[result.tuned_load_factor]
    print(label + ": ", end="")
    print(
        f"tuned gust H = {tuned.gradient:.3g} m: n = {tuned.max_load_factor:.4f}; Pratt "
        f"(mu_g = {result.mass_ratio:.3g}, K_g = {result.pratt_alleviation:.3f}): "
        f"n = {result.pratt_load_factor:.4f}; root bending 1 g {result.one_g_bending_moment[0]:.1f}"
        f" N m, envelope {result.envelope.max_bending_moment[0]:.1f} N m"
    )
    assert result.turbulence is not None
    print(
        f"A-bar: load factor {result.turbulence.load_factor:.4f} per m/s, root bending "
        f"{result.turbulence.bending_moment[0]:.2f} N m per m/s; U_sigma "
        f"{result.turbulence.intensity:.2f} m/s"
    )


if __name__ == "__main__":
    main()
