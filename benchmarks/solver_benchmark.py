"""How fast the solver core is, against AeroSandbox on the same wing when it is available.

    python benchmarks/solver_benchmark.py [--stations 30 60 120] [--repeat 50]
        [--aerosandbox-python PATH] [--reuse-cache]

Prints medians for the design study's wing (scaled to N stations), compiled functions:
one Jacobian evaluation, one residual, an equilibrium from the jig shape, a warm-started
neighbour (10 -> 10.5 m/s and 10 -> 12 m/s), the study's 6-speed sweep [6, 10, 12, 15, 18, 20],
and the stability eigenproblem included in each of those. The sweep is timed for a known wing
(its branch from the jig cached) and for a new one (the fold traced by continuation first). It
also measures, in a fresh process with an empty cache, the first solve of a never-seen N
(symbolic build + CasADi virtual machine, no C compiler), and the C compile time.

AeroSandbox runs in a separate interpreter (its casadi settings are global), through the
reference generator in tests/reference/, on the same case in the same run: the interpreter is
the current one if it can import aerosandbox, else --aerosandbox-python or
$FLEXWING_AEROSANDBOX_PYTHON; without one its columns are skipped.

Set OPENBLAS_NUM_THREADS=1 (done below when unset): on a shared 2-core machine threaded BLAS
makes small dense solves 100x slower.
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import argparse
import json
import statistics
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np

# Compile into a private cache so the compile time is measured, unless told to reuse one.
if "--reuse-cache" not in sys.argv:
    os.environ["FLEXWING_CACHE_DIR"] = tempfile.mkdtemp(prefix="flexwing-bench-")

import solver
from solver.compiled import compile_now, model_for
from solver.divergence import clear_branch_cache
from solver.stability import divergence_pressure

ROOT = Path(__file__).resolve().parents[1]
STUDY_SWEEP = [6.0, 10.0, 12.0, 15.0, 18.0, 20.0]
ALPHA = 5.0  # [deg]
RHO = 1.2249991558876672  # [kg/m^3] AeroSandbox's sea-level ISA density, as in the references


def study_case(n: int) -> dict:
    """The design study's wing with N stations (reference-file case format)."""
    chords = np.sqrt(np.linspace(2, 0.02, n))
    return {
        "name": f"study_n{n}",
        "span": 10.0,
        "chords": chords.tolist(),
        "x_ea_over_chord": 0.4,
        "EI": (2e4 * chords**3).tolist(),
        "GJ": (1e3 * chords**3).tolist(),
        "alpha_deg": ALPHA,
        "velocities": [10.0],
    }


def study_wing(n: int) -> solver.Wing:
    case = study_case(n)
    return solver.Wing.create(
        np.linspace(0, case["span"] / 2, n), case["chords"], 0.4, case["EI"], case["GJ"]
    )


def median_ms(action: Callable[[], object], repeat: int) -> float:
    action()
    samples = []
    for _ in range(repeat):
        started = time.perf_counter()
        action()
        samples.append(time.perf_counter() - started)
    return 1e3 * statistics.median(samples)


_FIRST_SOLVE = """
import time, json, sys
started = time.perf_counter()
sys.path.insert(0, {root!r})
sys.path.insert(0, {bench!r})
import solver
from solver_benchmark import study_wing
imported = time.perf_counter()
wing, flight = study_wing({n}), solver.FlightCondition(10.0, 5.0, 1.225)
equilibrium = solver.solve(wing, flight)
first = time.perf_counter() - imported
repeats = []
for _ in range(5):
    tick = time.perf_counter()
    solver.solve(wing, flight)
    repeats.append(time.perf_counter() - tick)
vm_solve = sorted(repeats)[2]
print(json.dumps({{"import_s": imported - started, "solve_s": first, "vm_solve_s": vm_solve}}))
"""


def first_solve_seconds(n: int) -> dict:
    """A fresh process, empty library cache: import, symbolic build and VM solves.

    Compilation is disabled there so that the repeated solves stay on the virtual machine.
    """
    with tempfile.TemporaryDirectory() as cache:
        env = dict(os.environ, FLEXWING_CACHE_DIR=cache, FLEXWING_COMPILE="0")
        script = _FIRST_SOLVE.format(root=str(ROOT), bench=str(ROOT / "benchmarks"), n=n)
        output = subprocess.run(
            [sys.executable, "-c", script], env=env, capture_output=True, text=True, check=True
        )
    return json.loads(output.stdout.strip().splitlines()[-1])


def aerosandbox_python(explicit: str | None) -> str | None:
    candidates = [sys.executable, explicit, os.environ.get("FLEXWING_AEROSANDBOX_PYTHON")]
    for python in candidates:
        if (
            python
            and subprocess.run([python, "-c", "import aerosandbox"], capture_output=True).returncode
            == 0
        ):
            return python
    return None


def aerosandbox_seconds(python: str, n: int, velocities: list[float]) -> dict:
    """Wall time of AeroSandbox's build + solves, and its IPOPT time per solve."""
    case = dict(study_case(n), velocities=velocities)
    with tempfile.TemporaryDirectory() as work:
        case_path, out_path = Path(work) / "case.json", Path(work) / "ref.json"
        case_path.write_text(json.dumps(case))
        started = time.perf_counter()
        subprocess.run(
            [python, str(ROOT / "tests/reference/generate_reference.py"), case_path, out_path],
            check=True,
            capture_output=True,
        )
        total = time.perf_counter() - started
        reference = json.loads(out_path.read_text())
    solves = [equilibrium["solve_s"] for equilibrium in reference["equilibria"]]
    return {"total_s": total, "solve_s": solves}


def compile_seconds(n: int) -> float:
    """Wall time to generate and compile (or load) the library for N, nothing else running."""
    started = time.perf_counter()
    compile_now(n)
    return time.perf_counter() - started


def benchmark(n: int, repeat: int, compile_s: float) -> dict:
    wing = study_wing(n)
    model = model_for(n)
    if not model.compiled:
        print(f"N={n}: no compiled library (compiler missing or disabled); timing the VM")
    cruise = solver.FlightCondition(10.0, ALPHA, RHO)
    equilibrium = solver.solve(wing, cruise)
    p = wing.parameters(ALPHA)
    neighbour = solver.FlightCondition(10.5, ALPHA, RHO)
    farther = solver.FlightCondition(12.0, ALPHA, RHO)
    return {
        "n": n,
        "unknowns": model.layout.n_unknowns,
        "compile_s": compile_s,
        "jacobian_ms": median_ms(lambda: model.evaluate(equilibrium.state, p), repeat),
        "residual_ms": median_ms(lambda: model.residual(equilibrium.state, p), repeat),
        "stability_ms": median_ms(
            lambda: divergence_pressure(equilibrium.evaluation, model.layout), repeat
        ),
        "cold_ms": median_ms(lambda: solver.solve(wing, cruise), repeat),
        "cold_iterations": equilibrium.iterations,
        "warm_near_ms": median_ms(lambda: solver.solve(wing, neighbour, equilibrium), repeat),
        "warm_far_ms": median_ms(lambda: solver.solve(wing, farther, equilibrium), repeat),
        # A known wing: its branch (and fold) is cached from the sweeps before.
        "sweep_ms": median_ms(
            lambda: solver.sweep(wing, STUDY_SWEEP, ALPHA, RHO), max(5, repeat // 5)
        ),
        # A new wing: the fold is traced by continuation first.
        "sweep_new_ms": median_ms(
            lambda: (clear_branch_cache(), solver.sweep(wing, STUDY_SWEEP, ALPHA, RHO)),
            max(5, repeat // 5),
        ),
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--stations", type=int, nargs="+", default=[30, 60, 120])
    parser.add_argument("--repeat", type=int, default=50)
    parser.add_argument("--aerosandbox-python", default=None)
    parser.add_argument(
        "--reuse-cache",
        action="store_true",
        help="use $FLEXWING_CACHE_DIR's compiled libraries (compile times then read ~0)",
    )
    parser.add_argument(
        "--aerosandbox-stations",
        type=int,
        nargs="+",
        default=[30],
        help="N at which to run AeroSandbox (it needs ~90 s per equilibrium at N = 120)",
    )
    args = parser.parse_args()
    # Compile every N to the end, one at a time, before timing anything: a background compile
    # would share the two cores with the solves being timed.
    compile_times = {n: compile_seconds(n) for n in args.stations}
    rows = [benchmark(n, args.repeat, compile_times[n]) for n in args.stations]

    print("\nflexwing solver, study wing, compiled, medians [ms]")
    header = (
        f"{'N':>4} {'unknowns':>8} {'Jacobian':>9} {'residual':>9} {'stability':>9} "
        f"{'from jig':>9} {'warm +0.5':>9} {'warm +2':>8} {'6-sweep':>8} {'new wing':>8} "
        f"{'compile [s]':>11}"
    )
    print(header)
    for row in rows:
        print(
            f"{row['n']:>4} {row['unknowns']:>8} {row['jacobian_ms']:>9.3f} "
            f"{row['residual_ms']:>9.3f} {row['stability_ms']:>9.3f} {row['cold_ms']:>9.2f} "
            f"{row['warm_near_ms']:>9.2f} {row['warm_far_ms']:>8.2f} {row['sweep_ms']:>8.2f} "
            f"{row['sweep_new_ms']:>8.2f} {row['compile_s']:>11.1f}"
        )
    if len(rows) > 1:
        first, last = rows[0], rows[-1]
        growth = np.log(last["cold_ms"] / first["cold_ms"]) / np.log(last["n"] / first["n"])
        print(f"cost of an equilibrium from the jig grows like N^{growth:.2f} here")

    print("\nfirst solve of a never-seen N (fresh process, empty cache, CasADi VM, no compiler):")
    for row in rows:
        first = first_solve_seconds(row["n"])
        vm_ms = 1e3 * first["vm_solve_s"]
        saved_ms = vm_ms - row["cold_ms"]
        print(
            f"  N={row['n']}: import {first['import_s']:.2f} s, build + first solve "
            f"{first['solve_s']:.3f} s; then {vm_ms:.1f} ms per solve on the VM vs "
            f"{row['cold_ms']:.2f} ms compiled: the {row['compile_s']:.0f} s compile pays "
            f"for itself after ~{1e3 * row['compile_s'] / max(saved_ms, 1e-9):.0f} solves"
        )

    python = aerosandbox_python(args.aerosandbox_python)
    if python is None:
        print("\nAeroSandbox not available: no peer comparison (see --aerosandbox-python)")
        return
    print(f"\nAeroSandbox 4.2 (Opti + IPOPT) via {python}, same wing:")
    for n in args.aerosandbox_stations:
        row = next((r for r in rows if r["n"] == n), None)
        one = aerosandbox_seconds(python, n, [10.0])
        swept = aerosandbox_seconds(python, n, STUDY_SWEEP)
        one_ms, sweep_ms = 1e3 * one["solve_s"][0], 1e3 * swept["total_s"]
        print(
            f"  N={n}: one equilibrium {one_ms:.0f} ms (IPOPT), build + 6-sweep "
            f"{sweep_ms:.0f} ms (wall, incl. import)"
        )
        if row is not None:
            print(
                f"  flexwing is {one_ms / row['cold_ms']:.0f}x faster per equilibrium and "
                f"{sweep_ms / row['sweep_ms']:.0f}x faster per sweep"
            )


if __name__ == "__main__":
    main()
