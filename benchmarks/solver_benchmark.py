"""How fast the solver core is, against AeroSandbox on the same wing when it is available.

    python benchmarks/solver_benchmark.py [--stations 30 60 120] [--chordwise 4] [--repeat 50]
        [--aerosandbox-python PATH] [--aerosandbox-repeat 3] [--reuse-cache]

Prints medians for the design study's wing (tests/study.py, scaled to N stations), compiled
functions: one Jacobian evaluation, one residual, the stability eigenproblem included in every
answer, an equilibrium from the jig shape, a warm-started neighbour (10 -> 10.5 m/s and
10 -> 12 m/s, `solve(..., hint=)` from the answer at 10 m/s), and the study's 6-speed sweep
[6, 10, 12, 15, 18, 20]. The sweep is timed for a known wing (its jig, linear divergence and
branch from the jig cached by an earlier sweep) and for a new one (the stiffness scaled by
1 + 1e-9 i: every cache misses but the compiled model's, and the fold is traced by continuation
first). With k chordwise panels (--chordwise, at N = 30) the equilibrium from the jig is timed
too. It also measures, in a fresh process with an empty cache, the first solve of a never-seen N
(symbolic build + CasADi virtual machine, no C compiler), and the C compile time.

The targets of the project are printed next to the figures they judge (medians):

    warm solve, +0.5 m/s from a known answer (N = 30)    <= 1 ms
    6-speed sweep, known wing (N = 30)                   <= 8 ms
    6-speed sweep, new wing (N = 30)                     <= 15 ms
    equilibrium from the jig, N = 120                    <= 25 ms
    equilibrium from the jig, N = 30, k = 4              <= 15 ms
    AeroSandbox / flexwing, one equilibrium (N = 30)     >= 2000x
    AeroSandbox / flexwing, 6-speed sweep (N = 30)       >= 2500x

They are reported, never asserted: on a shared, loaded machine a figure can miss its target
without any change in the code (the load average is printed with the figures).

AeroSandbox runs in a separate interpreter (its casadi settings are global, and it is never a
dependency of flexwing), through the reference generator in tests/reference/, on the same case in
the same run: the interpreter is the current one if it can import aerosandbox, else
--aerosandbox-python, $FLEXWING_AEROSANDBOX_PYTHON or /work/venv-peers/bin/python; without one
its columns are skipped. Its times are IPOPT's own per equilibrium (the generator's solves,
without the import and the Opti build), wall and CPU time; the sweep's is the sum over the six
speeds, each warm-started from the last as the study does. Ratios are the median of
--aerosandbox-repeat runs over flexwing's medians, wall over wall (the target) and CPU over CPU:
one equilibrium against flexwing's from the jig, the sweep against flexwing's sweep of a new wing
(no cache helps it; the known wing's ratio is printed beside it).

On a loaded machine the wall-time medians count the time the process waited for a core: each
target is printed with the median CPU time of this process too (what the wall time would be on
an idle machine: the solver is single-threaded) and the fastest repeat.

Set OPENBLAS_NUM_THREADS=1 (done below when unset): on a shared 2-core machine threaded BLAS
makes small dense solves 100x slower.
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import argparse
import atexit
import json
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable, Sequence
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

# Compile into a private cache so the compile time is measured, unless told to reuse one. Only
# when run as a script: importing this module must not touch the environment.
if __name__ == "__main__" and "--reuse-cache" not in sys.argv:
    _private_cache = tempfile.mkdtemp(prefix="flexwing-bench-")
    os.environ["FLEXWING_CACHE_DIR"] = _private_cache
    atexit.register(shutil.rmtree, _private_cache, True)

import solver  # noqa: E402
from solver.numerics.stability import beam_response, divergence_pressure  # noqa: E402
from solver.statics.system import CoupledSystem  # noqa: E402
from tests.study import ALPHA, DENSITY, study_wing  # noqa: E402

STUDY_SWEEP = [6.0, 10.0, 12.0, 15.0, 18.0, 20.0]
PEERS_PYTHON = "/work/venv-peers/bin/python"

# (label, goal, "max": a time [ms] at most | "min": a ratio at least)
GOALS = {
    "warm": ("warm solve, +0.5 m/s from a known answer, N=30", 1.0, "max"),
    "sweep_known": ("6-speed sweep, known wing, N=30", 8.0, "max"),
    "sweep_new": ("6-speed sweep, new wing, N=30", 15.0, "max"),
    "cold_120": ("equilibrium from the jig, N=120", 25.0, "max"),
    "chordwise": ("equilibrium from the jig, N=30, k=4", 15.0, "max"),
    "asb_solve": ("AeroSandbox / flexwing, one equilibrium, N=30", 2000.0, "min"),
    "asb_sweep": ("AeroSandbox / flexwing, 6-speed sweep (new wing), N=30", 2500.0, "min"),
}


def load_average() -> str:
    one, five, fifteen = os.getloadavg()
    return f"load average {one:.2f}, {five:.2f}, {fifteen:.2f} on {os.cpu_count()} CPUs"


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


# For each named figure: the fastest repeat (wall) and the median CPU time of this process, both
# [ms]. The solver is single-threaded (one BLAS thread, no compile running while timing), so its
# CPU time is what the wall time would be on an idle machine; on a loaded one the median wall
# time also counts the time the process waited for a core. Printed beside the targets' medians.
BEST: dict[str, float] = {}
CPU: dict[str, float] = {}


def _timed(action: Callable[[], object]) -> tuple[float, float]:
    wall, cpu = time.perf_counter(), time.process_time()
    action()
    return time.perf_counter() - wall, time.process_time() - cpu


def _record(name: str | None, samples: list[tuple[float, float]]) -> float:
    if name is not None:
        BEST[name] = 1e3 * min(wall for wall, _ in samples)
        CPU[name] = 1e3 * statistics.median(cpu for _, cpu in samples)
    return 1e3 * statistics.median(wall for wall, _ in samples)


def median_ms(action: Callable[[], object], repeat: int, name: str | None = None) -> float:
    """Median wall time of `action()` over `repeat` calls, after one untimed call."""
    action()
    return _record(name, [_timed(action) for _ in range(repeat)])


def median_each_ms(
    action: Callable[[object], object], inputs: Sequence[object], name: str | None = None
) -> float:
    """Median wall time of `action(x)` over the inputs, each once (built beforehand, untimed)."""
    return _record(name, [_timed(lambda item=item: action(item)) for item in inputs])


_FIRST_SOLVE = """
import time, json, sys
started = time.perf_counter()
sys.path.insert(0, {root!r})
import solver
from tests.study import study_wing
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
        script = _FIRST_SOLVE.format(root=str(ROOT), n=n)
        output = subprocess.run(
            [sys.executable, "-c", script], env=env, capture_output=True, text=True, check=True
        )
    return json.loads(output.stdout.strip().splitlines()[-1])


def aerosandbox_python(explicit: str | None) -> str | None:
    candidates = [
        sys.executable,
        explicit,
        os.environ.get("FLEXWING_AEROSANDBOX_PYTHON"),
        PEERS_PYTHON,
    ]
    for python in candidates:
        if (
            python
            and Path(python).exists()
            and subprocess.run([python, "-c", "import aerosandbox"], capture_output=True).returncode
            == 0
        ):
            return python
    return None


# Runs the reference generator's `generate` in AeroSandbox's interpreter with its clock swapped:
# each solve's `solve_s` becomes the CPU time of the process (IPOPT and casadi included) and the
# wall time is kept beside it, so that the ratios can be taken both ways.
_AEROSANDBOX = """
import json, sys, time
sys.path.insert(0, {reference!r})
import generate_reference
walls = []
class _Clock:
    def __getattr__(self, name):
        return getattr(time, name)
    def perf_counter(self):
        walls.append(time.perf_counter())
        return time.process_time()
generate_reference.time = _Clock()
with open(sys.argv[1]) as case:
    result = generate_reference.generate(json.load(case))
cpu = [equilibrium["solve_s"] for equilibrium in result["equilibria"]]
wall = [b - a for a, b in zip(walls[0::2], walls[1::2])]
print(json.dumps({{"cpu_s": cpu, "wall_s": wall, "failures": len(result["failures"])}}))
"""


def aerosandbox_seconds(
    python: str, n: int, velocities: list[float], chordwise_panels: int = 1
) -> dict:
    """AeroSandbox on the study's wing with k = `chordwise_panels` (one process: import, Opti
    build, solves in the order given, each warm-started from the last): wall time of the whole
    process, and wall and CPU time of IPOPT per solve [s]."""
    case = dict(study_case(n), velocities=velocities, chordwise_resolution=chordwise_panels)
    with tempfile.TemporaryDirectory() as work:
        case_path = Path(work) / "case.json"
        case_path.write_text(json.dumps(case))
        script = _AEROSANDBOX.format(reference=str(ROOT / "tests" / "reference"))
        started = time.perf_counter()
        completed = subprocess.run(
            [python, "-c", script, str(case_path)],
            check=True,
            capture_output=True,
            text=True,
            env=dict(os.environ, OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1"),
        )
        total = time.perf_counter() - started
    found = json.loads(completed.stdout.strip().splitlines()[-1])
    if found["failures"] or len(found["cpu_s"]) != len(velocities):
        raise RuntimeError(f"AeroSandbox solved {len(found['cpu_s'])} of {len(velocities)} speeds")
    return {"total_s": total, "solve_s": found["wall_s"], "cpu_s": found["cpu_s"]}


def compile_seconds(n: int, chordwise: int = 1) -> tuple[float, bool]:
    """Wall time to build, generate and compile (or load) the library of a mesh, nothing else
    running, and whether compiled code serves it afterwards."""
    started = time.perf_counter()
    compiled = solver.warm_up(n, chordwise_panels=chordwise)
    return time.perf_counter() - started, compiled


def new_wings(n: int, count: int, offset: int) -> list[solver.Wing]:
    """The study's wing with its stiffness scaled by 1 + 1e-9 i: distinct cache keys, the same
    numbers to 1e-9 (the same work)."""
    return [study_wing(n, stiffness_scale=1 + 1e-9 * (offset + i + 1)) for i in range(count)]


def benchmark(n: int, repeat: int, compile_s: float, compiled: bool) -> dict:
    wing = study_wing(n)
    options = solver.SolverOptions()
    system = CoupledSystem.of(wing, ALPHA, options)
    model, p, layout = system.model, system.parameters, system.layout
    if not compiled or not model.compiled:
        print(f"N={n}: no compiled library (compiler missing or disabled); timing the VM")
    cruise = solver.FlightCondition(10.0, ALPHA, DENSITY)
    equilibrium = solver.solve(wing, cruise)
    beam = beam_response(equilibrium.evaluation, layout)
    neighbour = solver.FlightCondition(10.5, ALPHA, DENSITY)
    farther = solver.FlightCondition(12.0, ALPHA, DENSITY)
    sweeps = max(5, repeat // 5)
    solver.airspeed_sweep(
        wing, STUDY_SWEEP, solver.FlightCondition(None, ALPHA, DENSITY)
    )  # the known wing: its branch cached
    return {
        "n": n,
        "unknowns": layout.n_unknowns,
        "compile_s": compile_s,
        "jacobian_ms": median_ms(lambda: model.evaluate(equilibrium.state, p), repeat),
        "residual_ms": median_ms(lambda: model.residual(equilibrium.state, p), repeat),
        "stability_ms": median_ms(
            lambda: divergence_pressure(equilibrium.evaluation, layout, beam), repeat
        ),
        "cold_ms": median_ms(lambda: solver.solve(wing, cruise), repeat, f"cold_{n}"),
        "cold_iterations": equilibrium.solver.iterations,
        "warm_near_ms": median_ms(
            lambda: solver.solve(wing, neighbour, hint=equilibrium), repeat, f"warm_{n}"
        ),
        "warm_far_ms": median_ms(lambda: solver.solve(wing, farther, hint=equilibrium), repeat),
        "sweep_ms": median_ms(
            lambda: solver.airspeed_sweep(
                wing, STUDY_SWEEP, solver.FlightCondition(None, ALPHA, DENSITY)
            ),
            sweeps,
            f"sweep_known_{n}",
        ),
        "sweep_new_ms": median_each_ms(
            lambda new: solver.airspeed_sweep(
                new, STUDY_SWEEP, solver.FlightCondition(None, ALPHA, DENSITY)
            ),
            new_wings(n, sweeps, offset=0),
            f"sweep_new_{n}",
        ),
    }


def chordwise_ms(k: int, repeat: int) -> tuple[float, int]:
    """An equilibrium from the jig of the study's wing (N = 30) with k chordwise panels."""
    wing = study_wing(30)
    options = solver.SolverOptions(chordwise_panels=k)
    cruise = solver.FlightCondition(10.0, ALPHA, DENSITY)
    iterations = solver.solve(wing, cruise, options=options).solver.iterations
    timed = median_ms(lambda: solver.solve(wing, cruise, options=options), repeat, "chordwise")
    return timed, iterations


def verdict(key: str, value: float | None, cpu: float | None, best: float | None) -> str:
    """One target: the median (wall) against its goal, then the median CPU time and the fastest
    repeat (for a ratio: the ratios with flexwing's median CPU time and fastest repeat)."""
    label, goal, kind = GOALS[key]
    sign = "<=" if kind == "max" else ">="
    unit = "ms" if kind == "max" else "x"
    if value is None:
        return f"  {label:<52} {'n/a':>9} {unit:<2}  goal {sign} {goal:g} {unit}"
    met = value <= goal if kind == "max" else value >= goal

    def shown(v: float | None) -> str:
        return "n/a" if v is None else f"{v:.2f}" if kind == "max" else f"{v:.0f}"

    return (
        f"  {label:<52} {shown(value):>9} {unit:<2}  goal {sign} {goal:g} {unit:<2}  "
        f"{'met' if met else 'NOT MET':<7}  CPU {shown(cpu):>8} {unit:<2}  "
        f"best {shown(best):>8} {unit}"
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--stations", type=int, nargs="+", default=[30, 60, 120])
    parser.add_argument("--chordwise", type=int, default=4, help="k for the N = 30 row")
    parser.add_argument("--repeat", type=int, default=50)
    parser.add_argument("--aerosandbox-python", default=None)
    parser.add_argument("--aerosandbox-repeat", type=int, default=3)
    parser.add_argument("--no-first-solve", action="store_true", help="skip the VM processes")
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
    print(f"solver from {Path(solver.__file__).parent}; {load_average()}")
    # Compile every mesh to the end, one at a time, before timing anything: a background compile
    # would share the two cores with the solves being timed.
    compile_times = {n: compile_seconds(n) for n in args.stations}
    chordwise_compile = compile_seconds(30, args.chordwise)
    rows = [benchmark(n, args.repeat, *compile_times[n]) for n in args.stations]
    k_ms, k_iterations = chordwise_ms(args.chordwise, args.repeat)

    print(f"\nflexwing solver, study wing, compiled, medians [ms]; {load_average()}")
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
    print(
        f"N=30, k={args.chordwise} chordwise panels: from the jig {k_ms:.2f} ms "
        f"({k_iterations} Newton iterations), compile {chordwise_compile[0]:.1f} s"
    )
    if len(rows) > 1:
        first, last = rows[0], rows[-1]
        growth = np.log(last["cold_ms"] / first["cold_ms"]) / np.log(last["n"] / first["n"])
        print(f"cost of an equilibrium from the jig grows like N^{growth:.2f} here")

    if not args.no_first_solve:
        print("\nfirst solve of a never-seen N (fresh process, empty cache, CasADi VM):")
        for row in rows:
            first = first_solve_seconds(row["n"])
            vm_ms = 1e3 * first["vm_solve_s"]
            saved_ms = vm_ms - row["cold_ms"]
            pays = (
                f"the {row['compile_s']:.0f} s compile pays for itself after "
                f"~{1e3 * row['compile_s'] / max(saved_ms, 1e-9):.0f} solves"
                if row["compile_s"] >= 1
                else "the library came from the cache (--reuse-cache): no compile time measured"
            )
            print(
                f"  N={row['n']}: import {first['import_s']:.2f} s, build + first solve "
                f"{first['solve_s']:.3f} s; then {vm_ms:.1f} ms per solve on the VM vs "
                f"{row['cold_ms']:.2f} ms compiled: {pays}"
            )

    by_n = {row["n"]: row for row in rows}
    ratios: dict[str, float | None] = {"asb_solve": None, "asb_sweep": None}
    python = aerosandbox_python(args.aerosandbox_python)
    if python is None:
        print("\nAeroSandbox not available: no peer comparison (see --aerosandbox-python)")
    else:
        print(f"\nAeroSandbox (Opti + IPOPT) via {python}, same wing, same run:")
        for n in args.aerosandbox_stations:
            ones = [aerosandbox_seconds(python, n, [10.0]) for _ in range(args.aerosandbox_repeat)]
            swept = [
                aerosandbox_seconds(python, n, STUDY_SWEEP) for _ in range(args.aerosandbox_repeat)
            ]
            one_ms = 1e3 * statistics.median(o["solve_s"][0] for o in ones)
            one_cpu = 1e3 * statistics.median(o["cpu_s"][0] for o in ones)
            sweep_ms = 1e3 * statistics.median(sum(s["solve_s"]) for s in swept)
            sweep_cpu = 1e3 * statistics.median(sum(s["cpu_s"]) for s in swept)
            wall_ms = 1e3 * statistics.median(s["total_s"] for s in swept)
            print(
                f"  N={n}: one equilibrium {one_ms:.0f} ms wall, {one_cpu:.0f} ms CPU (IPOPT); "
                f"6-sweep {sweep_ms:.0f} ms wall, {sweep_cpu:.0f} ms CPU (IPOPT, summed); "
                f"{wall_ms:.0f} ms for the whole process (import and build included); "
                f"medians of {args.aerosandbox_repeat}"
            )
            row = by_n.get(n)
            if row is None:
                continue
            solve_ratio = one_ms / row["cold_ms"]
            sweep_ratio = sweep_ms / row["sweep_new_ms"]
            print(
                f"  flexwing is {solve_ratio:.0f}x faster per equilibrium (from the jig), "
                f"{sweep_ratio:.0f}x per sweep of a new wing, "
                f"{sweep_ms / row['sweep_ms']:.0f}x per sweep of a known wing (wall / wall); "
                f"CPU / CPU: {one_cpu / CPU[f'cold_{n}']:.0f}x, "
                f"{sweep_cpu / CPU[f'sweep_new_{n}']:.0f}x, "
                f"{sweep_cpu / CPU[f'sweep_known_{n}']:.0f}x"
            )
            if n == 30:
                ratios = {
                    "asb_solve": solve_ratio,
                    "asb_sweep": sweep_ratio,
                    "asb_solve_cpu": one_cpu / CPU["cold_30"],
                    "asb_sweep_cpu": sweep_cpu / CPU["sweep_new_30"],
                }

    n30, n120 = by_n.get(30), by_n.get(120)
    print(
        f"\ntargets: median wall time against the goal; median CPU time and fastest repeat "
        f"beside it ({load_average()}):"
    )
    for key, value, name in (
        ("warm", n30 and n30["warm_near_ms"], "warm_30"),
        ("sweep_known", n30 and n30["sweep_ms"], "sweep_known_30"),
        ("sweep_new", n30 and n30["sweep_new_ms"], "sweep_new_30"),
        ("cold_120", n120 and n120["cold_ms"], "cold_120"),
        ("chordwise", k_ms if args.chordwise == 4 else None, "chordwise"),
    ):
        print(verdict(key, value, CPU.get(name), BEST.get(name)))
    for key in ("asb_solve", "asb_sweep"):
        print(verdict(key, ratios[key], ratios.get(f"{key}_cpu"), None))


if __name__ == "__main__":
    main()
