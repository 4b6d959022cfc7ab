"""How fast flexwing finds where a wing diverges (issue 3).

    python benchmarks/divergence_benchmark.py [--repeat 50]

Prints medians, compiled functions (waits for the C library of each N), for the design study's
wing (N = 30, alpha 5 deg) and rect_public (N = 24, alpha 4 deg):
- linear divergence: the eigenvalue at the unloaded jig, including its one model evaluation
  (uncached), and the cached lookup every equilibrium's stability report makes;
- the fold by pseudo-arclength continuation from the jig shape for a new wing (the stiffness
  scaled by 1 + 1e-9 i, so that the jig, the linear divergence and the branch are all computed
  afresh; only the compiled model is cached), with its model evaluations and branch points;
- the study's 6-speed sweep [6, 10, 12, 15, 18, 20] with its divergence summary (a new wing:
  fold uncached; then the same wing again: fold cached, as in a repeated request);
- solve() past the fold: the NoEquilibrium answer (the path fails, the cached fold decides).

Set OPENBLAS_NUM_THREADS=1 (done below when unset): threaded BLAS makes small dense solves slow
on a shared 2-core machine. Figures are reported, never asserted: the median wall time and the
median CPU time of this process (on a loaded machine the first also counts waiting for a core),
with the load average.
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import argparse
import itertools
import statistics
import sys
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import solver
from solver import FlightCondition, NoEquilibrium, SolverOptions, Wing
from solver.numerics.stability import divergence_pressure
from solver.statics.branch import branch, search_velocity_limit
from solver.statics.system import CoupledSystem
from tests.study import DENSITY as RHO
from tests.study import study_wing as _study_wing

STUDY_SWEEP = [6.0, 10.0, 12.0, 15.0, 18.0, 20.0]


def study_wing(scale: float = 1.0) -> Wing:
    return _study_wing(30, stiffness_scale=scale)


def rect_public(scale: float = 1.0) -> Wing:
    """shared/reference/case_rect_public.json, stiffness scaled."""
    return Wing.create(np.linspace(0, 4, 24), 0.8, 0.35, 5000.0 * scale, 400.0 * scale)


def load_average() -> str:
    one, five, fifteen = os.getloadavg()
    return f"load average {one:.2f}, {five:.2f}, {fifteen:.2f} on {os.cpu_count()} CPUs"


def median_ms(function: Callable[[], object], repeat: int) -> tuple[float, float]:
    """Medians [ms] of the wall time and of this process's CPU time (single-threaded: what the
    wall time would be on an idle machine)."""
    function()  # warm: caches of other kinds, branch prediction, allocator
    walls, cpus = [], []
    for _ in range(repeat):
        started, cpu = time.perf_counter(), time.process_time()
        function()
        walls.append(time.perf_counter() - started)
        cpus.append(time.process_time() - cpu)
    return 1e3 * statistics.median(walls), 1e3 * statistics.median(cpus)


def beyond_fold(wing: Wing, alpha: float, velocity: float) -> None:
    try:
        solver.solve(wing, FlightCondition(velocity, alpha, RHO))
    except NoEquilibrium:
        return
    raise RuntimeError("expected NoEquilibrium")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=50)
    repeat = parser.parse_args().repeat
    print(f"solver from {Path(solver.__file__).parent}; {load_average()}")
    fresh = itertools.count(1)  # stiffness scale 1 + 1e-9 i: a wing no cache has seen

    def new(make: Callable[[float], Wing]) -> Wing:
        return make(1 + 1e-9 * next(fresh))

    for name, make, alpha in (("study", study_wing, 5.0), ("rect_public", rect_public, 4.0)):
        wing = make(1.0)
        if not solver.warm_up(wing.n_stations):
            print(f"[{name}] warning: no compiled library, timings are the CasADi VM's")
        system = CoupledSystem.of(wing, alpha, SolverOptions())
        at_rest = system.at_alpha(0.0)
        jig = np.zeros(system.layout.n_unknowns)
        limit = search_velocity_limit(system, RHO, 20.0)
        fold = solver.find_fold(wing, alpha, RHO, limit)
        traced = branch(system, 0.5 * RHO * limit**2)
        q_linear = solver.linear_divergence_pressure(wing)
        if q_linear is None or fold.velocity is None:
            raise RuntimeError(f"{name}: expected a linear divergence and a fold")
        print(f"{name} (N = {wing.n_stations}, alpha {alpha:g} deg, rho {RHO:.6f} kg/m^3)")
        print(
            f"  linear divergence  q = {q_linear:8.3f} Pa  "
            f"V = {FlightCondition.velocity_for(q_linear, RHO):.4f} m/s"
        )
        print(
            f"  fold               q = {fold.dynamic_pressure:8.3f} Pa  V = {fold.velocity:.6f} m/s"
            f"  tip twist {fold.tip_twist:.3f} deg  lift {fold.lift:.1f} N"
        )
        reached = FlightCondition.velocity_for(traced.reached_pressure, RHO)
        print(
            f"  continuation: {fold.evaluations} model evaluations to the fold, "
            f"{len(traced.points)} branch points to {reached:.2f} m/s"
        )
        rows: list[tuple[str, Callable[[], object]]] = [
            (
                "linear divergence, eigenvalue at the jig (uncached)",
                lambda at_rest=at_rest, jig=jig: divergence_pressure(
                    at_rest.evaluate(jig), at_rest.layout
                ),
            ),
            (
                "linear divergence, cached lookup",
                lambda wing=wing: solver.linear_divergence_pressure(wing),
            ),
            (
                "fold by continuation, new wing (uncached)",
                lambda make=make, alpha=alpha, limit=limit: solver.find_fold(
                    new(make), alpha, RHO, limit
                ),
            ),
            (
                "solve() beyond the fold -> NoEquilibrium (fold cached)",
                lambda wing=wing, alpha=alpha, v=1.2 * fold.velocity: beyond_fold(wing, alpha, v),
            ),
        ]
        if name == "study":
            rows += [
                (
                    "6-speed sweep + divergence summary, new wing (fold uncached)",
                    lambda make=make: solver.airspeed_sweep(
                        new(make), STUDY_SWEEP, solver.FlightCondition(None, 5.0, RHO)
                    ),
                ),
                (
                    "6-speed sweep + divergence summary (fold cached)",
                    lambda wing=wing: solver.airspeed_sweep(
                        wing, STUDY_SWEEP, solver.FlightCondition(None, 5.0, RHO)
                    ),
                ),
            ]
        print(f"  {'median of ' + str(repeat) + ' repeats':62s} {'wall':>11} {'CPU':>11}")
        for label, function in rows:
            wall, cpu = median_ms(function, repeat)
            print(f"  {label:62s} {wall:8.3f} ms {cpu:8.3f} ms")
    print(load_average())


if __name__ == "__main__":
    main()
