"""Design: flexwing's `optimize` against AeroSandbox's Opti on the same problem, in one run.

    /path/to/peers-venv/bin/python benchmarks/optimize_benchmark.py      (from the repository root)

The peers' environment needs aerosandbox, scipy and pytest (the reference generator's imports).
Problems, on the study's wing (N = 30) carrying 300 N at 12 m/s, alpha 0:

- the regularised sketch AeroSandbox solves (every station's jig twist, total-twist root slope
  zero, penalty 0.01 N/deg^2; tests/reference/generate_reference.py `generate_design`): flexwing
  and AeroSandbox on it, flexible and rigid, with the optimum's agreement;
- flexwing's default: 6 control points, no penalty (goal <= 1 s);
- spar sizing: a carbon tube in NACA 0012 sections, walls at every station and 6 twist control
  points, minimum spar mass at 2.5 g with the von Mises constraint (goal <= 5 s).

Each flexwing figure is the median of REPEATS runs, caches cleared before each (an optimisation
is a new wing at every iterate anyway). The load average is printed beside the figures.
"""

from __future__ import annotations

import contextlib
import io
import json
import os
import statistics
import sys
import time
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

import numpy as np  # noqa: E402

import solver  # noqa: E402
from tests.reference import load_reference  # noqa: E402
from tests.reference.generate_reference import generate  # noqa: E402

REPEATS = 3
CASE = ROOT / "tests" / "reference" / "data" / "case_design_study.json"
REFERENCE = ROOT / "tests" / "reference" / "data" / "ref_design_study.json"


def _timed(run) -> tuple[float, object]:
    times, result = [], None
    for _ in range(REPEATS):
        solver.clear_caches()
        started = time.perf_counter()
        result = run()
        times.append(time.perf_counter() - started)
    return statistics.median(times), result


def main() -> None:
    reference = load_reference(REFERENCE)
    wing, rho = reference.wing, reference.rho
    print(f"compiled model: {solver.warm_up(wing.n_stations, timeout=300)}")
    with contextlib.redirect_stderr(io.StringIO()), contextlib.redirect_stdout(io.StringIO()):
        theirs = generate(json.loads(CASE.read_text()))
    print(f"load average: {os.getloadavg()[0]:.1f} (2 cores)\n")

    sketch = solver.DesignProblem(
        solver.DesignCondition(12.0, lift=300.0, density=rho),
        design=solver.Design(solver.TwistDesign(control_points=None)),
        smoothness_weight=0.01,
    )
    seconds, ours = _timed(lambda: solver.optimize(wing, sketch))
    flexible, rigid = theirs["flexible"], theirs["rigid"]
    print("the regularised sketch (every station, penalty 0.01 N/deg^2)")
    columns = ("flexwing", "AeroSandbox", "ratio", "|objective|", "|twist|")
    widths = (12, 12, 7, 12, 9)
    print(f"{'':24}" + "".join(f" {c:>{w}}" for c, w in zip(columns, widths, strict=True)))
    asb_flexible = flexible["solve_s"]
    print(
        f"{'flexible + rigid [s]':24} {seconds:12.3f} {asb_flexible + rigid['solve_s']:12.2f}"
        f" {(asb_flexible + rigid['solve_s']) / seconds:6.0f}x"
        f" {abs(ours.objective_value - flexible['objective']) / flexible['objective']:12.1e}"
        f" {np.max(np.abs(ours.jig_twist - flexible['jig_twist_deg'])):9.1e}"
    )
    print(
        f"{'  flexible only [s]':24} {ours.optimizer.seconds:12.3f} {asb_flexible:12.2f}"
        f" {asb_flexible / ours.optimizer.seconds:6.0f}x   (IPOPT iterations: flexwing"
        f" {ours.optimizer.iterations}, AeroSandbox {flexible['iterations']})"
    )
    near, far = ours.span_efficiency, ours.trefftz_span_efficiency
    print(f"  span efficiency: near field {near:.4f}, Trefftz {far:.4f}")

    default = solver.DesignProblem(solver.DesignCondition(12.0, lift=300.0, density=rho))
    seconds, ours = _timed(lambda: solver.optimize(wing, default))
    print(
        f"\n6 control points, no penalty: {seconds:.3f} s with the rigid optimum "
        f"({ours.optimizer.seconds:.3f} s flexible alone; goal <= 1 s); "
        f"D = {ours.induced_drag:.5f} N, rigid {ours.rigid.induced_drag:.5f} N"
    )

    carbon = solver.Material(70e9, 27e9, 1600.0, 30e6)
    spar = solver.SparDesign(solver.ThicknessFraction(0.8), 0.002, carbon)
    spar_wing = solver.Wing.create(wing.y, wing.chord, 0.4, airfoil="naca0012", spar=spar)
    sizing = solver.DesignProblem(
        solver.DesignCondition(14.0, lift=750.0),
        design=solver.Design(wall_thickness=solver.WallDesign(5e-4, 0.01)),
        objective="spar_mass",
    )
    seconds, ours = _timed(lambda: solver.optimize(spar_wing, sizing))
    print(
        f"spar sizing (36 variables, 29 stress constraints): {seconds:.3f} s (goal <= 5 s); "
        f"mass {ours.spar_mass:.4f} kg, {ours.optimizer.iterations} IPOPT iterations"
    )


if __name__ == "__main__":
    main()
