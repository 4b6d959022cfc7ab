"""How the cost of an equilibrium grows with chordwise panels, against AeroSandbox on each.

    python benchmarks/chordwise_benchmark.py [--chordwise 1 2 3 4] [--repeat 30]
        [--aerosandbox-python PATH] [--aerosandbox-repeat 1]

The design study's wing (N = 30, alpha 5 deg, 10 m/s) with k chordwise panels per strip (issue
10: "k = 4 on the study's wing (116 panels): from the jig <= 15 ms compiled; report how cost
grows with N and k, and the ratio to AeroSandbox on the same case in the same run"; the growth
with N is solver_benchmark.py's). For each k: the median wall and CPU time of an equilibrium from
the jig (stability verdict included), whether compiled code served it, and AeroSandbox's IPOPT
time on the same case in the same run (tests/reference/generate_reference.py, one equilibrium,
wall and CPU). Libraries come from $FLEXWING_CACHE_DIR: a k without one is timed on CasADi's
virtual machine and says so (compile first with `solver.warm_up(30, chordwise_panels=k)`;
k = 4 takes 3-4 minutes of one core). Figures are reported, never asserted.
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import argparse
import statistics
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from solver_benchmark import (
    CPU,
    aerosandbox_python,
    aerosandbox_seconds,
    load_average,
    median_ms,
)

import solver
from tests.study import ALPHA, DENSITY, study_wing

STATIONS = 30
VELOCITY = 10.0  # [m/s]
GOAL_K4_MS = 15.0


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--chordwise", type=int, nargs="+", default=[1, 2, 3, 4])
    parser.add_argument("--repeat", type=int, default=30)
    parser.add_argument("--aerosandbox-python", default=None)
    parser.add_argument("--aerosandbox-repeat", type=int, default=1)
    args = parser.parse_args()
    print(f"study wing, N = {STATIONS}, {VELOCITY} m/s, alpha {ALPHA} deg; {load_average()}")
    python = aerosandbox_python(args.aerosandbox_python)
    wing = study_wing(STATIONS)
    flight = solver.FlightCondition(VELOCITY, ALPHA, DENSITY)
    print(
        f"{'k':>2} {'panels':>6} {'unknowns':>8} {'code':>8} {'from jig [ms]':>13} "
        f"{'CPU [ms]':>9} {'ASB wall [ms]':>13} {'ASB CPU [ms]':>12} {'ratio':>6} {'CPU ratio':>9}"
    )
    rows = []
    for k in args.chordwise:
        options = solver.SolverOptions(chordwise_panels=k)
        compiled = solver.warm_up(STATIONS, timeout=0.0, chordwise_panels=k)
        equilibrium = solver.solve(wing, flight, options=options)
        wall = median_ms(lambda o=options: solver.solve(wing, flight, options=o), args.repeat, "k")
        cpu = CPU["k"]
        asb_wall = asb_cpu = float("nan")
        if python is not None:
            runs = [
                aerosandbox_seconds(python, STATIONS, [VELOCITY], k)
                for _ in range(args.aerosandbox_repeat)
            ]
            asb_wall = 1e3 * statistics.median(r["solve_s"][0] for r in runs)
            asb_cpu = 1e3 * statistics.median(r["cpu_s"][0] for r in runs)
        rows.append((k, wall, cpu))
        print(
            f"{k:>2} {STATIONS * k - k:>6} {equilibrium.state.size:>8} "
            f"{'C' if compiled else 'VM':>8} {wall:>13.2f} {cpu:>9.2f} {asb_wall:>13.0f} "
            f"{asb_cpu:>12.0f} {asb_wall / wall:>5.0f}x {asb_cpu / cpu:>8.0f}x"
        )
    if len(rows) > 1:
        (k0, wall0, cpu0), (k1, wall1, cpu1) = rows[0], rows[-1]
        print(
            f"cost grows like k^{np.log(wall1 / wall0) / np.log(k1 / k0):.2f} (wall), "
            f"k^{np.log(cpu1 / cpu0) / np.log(k1 / k0):.2f} (CPU) from k = {k0} to {k1}"
        )
    for k, wall, cpu in rows:
        if k == 4:
            met = "met" if wall <= GOAL_K4_MS else "NOT MET"
            print(
                f"goal: k = 4 from the jig <= {GOAL_K4_MS:g} ms: {wall:.2f} ms ({met}), "
                f"CPU {cpu:.2f} ms"
            )
    print(load_average())


if __name__ == "__main__":
    main()
