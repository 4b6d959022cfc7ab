"""How fast flexwing finds where a wing diverges (issue 3).

    python benchmarks/divergence_benchmark.py [--repeat 50]

Prints medians, compiled functions (waits for the C library of each N), for the design study's
wing (N = 30, alpha 5 deg) and rect_public (N = 24, alpha 4 deg):
- linear divergence: the eigenvalue at the unloaded jig, including its one model evaluation
  (uncached), and the cached lookup every equilibrium's stability report makes;
- the fold by pseudo-arclength continuation from the jig shape (uncached), with its model
  evaluations and branch points;
- the study's 6-speed sweep [6, 10, 12, 15, 18, 20] with its divergence summary (fold uncached,
  then cached as in a repeated request);
- solve() past the fold: the NoEquilibrium answer (Newton fails, the cached fold decides).

Set OPENBLAS_NUM_THREADS=1 (done below when unset): threaded BLAS makes small dense solves slow
on a shared 2-core machine.
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import argparse
import statistics
import time
from collections.abc import Callable

import numpy as np

from solver import FlightCondition, NoEquilibrium, Wing, find_fold, solve, sweep
from solver.compiled import compile_now
from solver.divergence import clear_branch_cache, equilibrium_branch, search_velocity_limit
from solver.equilibrium import linear_divergence_pressure
from solver.stability import divergence_pressure

RHO = 1.2249991558876672  # [kg/m^3] AeroSandbox's sea-level ISA density
STUDY_SWEEP = [6.0, 10.0, 12.0, 15.0, 18.0, 20.0]


def study_wing() -> Wing:
    chord = np.sqrt(np.linspace(2, 0.02, 30))
    return Wing.create(np.linspace(0, 5, 30), chord, 0.40, 2e4 * chord**3, 1e3 * chord**3)


def rect_public() -> Wing:
    return Wing.create(np.linspace(0, 4, 24), np.full(24, 0.8), 0.35, 5000.0, 400.0)


def median_ms(function: Callable[[], object], repeat: int) -> float:
    function()  # warm: caches of other kinds, branch prediction, allocator
    times = []
    for _ in range(repeat):
        started = time.perf_counter()
        function()
        times.append(time.perf_counter() - started)
    return 1e3 * statistics.median(times)


def uncached_fold(wing: Wing, alpha: float, limit: float) -> None:
    clear_branch_cache()
    find_fold(wing, alpha, RHO, limit)


def beyond_fold(wing: Wing, alpha: float, velocity: float) -> None:
    try:
        solve(wing, FlightCondition(velocity, alpha, RHO))
    except NoEquilibrium:
        return
    raise AssertionError("expected NoEquilibrium")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=50)
    repeat = parser.parse_args().repeat
    for name, wing, alpha in (("study", study_wing(), 5.0), ("rect_public", rect_public(), 4.0)):
        model = compile_now(wing.n_stations)
        if not model.compiled:
            print(f"[{name}] warning: no compiled library, timings are the CasADi VM's")
        layout = model.layout
        jig = np.zeros(layout.n_unknowns)
        p0 = wing.parameters(0.0)
        limit = search_velocity_limit(wing, RHO, 20.0)
        fold = find_fold(wing, alpha, RHO, limit)
        branch = equilibrium_branch(wing, alpha, 0.5 * RHO * limit**2)
        q_linear = linear_divergence_pressure(wing)
        assert q_linear is not None and fold.velocity is not None
        print(f"{name} (N = {wing.n_stations}, alpha {alpha:g} deg, rho {RHO:.6f} kg/m^3)")
        print(
            f"  linear divergence  q = {q_linear:8.3f} Pa  "
            f"V = {FlightCondition.velocity_for(q_linear, RHO):.4f} m/s"
        )
        print(
            f"  fold               q = {fold.dynamic_pressure:8.3f} Pa  V = {fold.velocity:.6f} m/s"
            f"  tip twist {fold.tip_twist:.3f} deg  lift {fold.lift:.1f} N"
        )
        print(
            f"  continuation: {branch.evaluations} model evaluations, "
            f"{len(branch.points)} branch points"
        )
        rows = [
            (
                "linear divergence, eigenvalue at the jig (uncached)",
                lambda p0=p0, jig=jig, model=model: divergence_pressure(
                    model.evaluate(jig, p0), model.layout
                ),
            ),
            (
                "linear divergence, cached lookup",
                lambda wing=wing: linear_divergence_pressure(wing),
            ),
            (
                "fold by continuation (uncached)",
                lambda wing=wing, alpha=alpha, limit=limit: uncached_fold(wing, alpha, limit),
            ),
            (
                "solve() beyond the fold -> NoEquilibrium (fold cached)",
                lambda wing=wing, alpha=alpha, v=1.2 * fold.velocity: beyond_fold(wing, alpha, v),
            ),
        ]
        if name == "study":
            rows += [
                (
                    "6-speed sweep + divergence summary (fold uncached)",
                    lambda wing=wing: (clear_branch_cache(), sweep(wing, STUDY_SWEEP, 5.0, RHO)),
                ),
                (
                    "6-speed sweep + divergence summary (fold cached)",
                    lambda wing=wing: sweep(wing, STUDY_SWEEP, 5.0, RHO),
                ),
            ]
        for label, function in rows:
            print(f"  {label:58s} {median_ms(function, repeat):8.3f} ms")


if __name__ == "__main__":
    main()
