"""How long control effectiveness, reversal and roll take next to a plain solve (issue 25).

    python benchmarks/controls_benchmark.py [--repeat 20]

The design study's wing (N = 30) at k = 4 chordwise panels with an aileron over 55-95 % of the
semispan (hinge at 75 % of the chord) and a flap over the inner 45 % (hinge at 50 %, 5 deg),
compiled functions (waits for the mesh's C libraries, the symmetric model's and the flow
model's). Every measurement is on a new wing (the
stiffness scaled by 1 + 1e-9 i), so that the jig, the linear divergence and every other cached
entry are computed afresh; only the compiled model is shared:

- a plain solve at 12 m/s, alpha 5 deg (the baseline);
- `control_effectiveness` at the same condition, of the wing with its aileron alone (the
  issue's target: within 3x the plain solve) and with both surfaces: each surface's rigid and
  elastic derivative, effectiveness, linear and local reversal (eigenvalues), divergence and
  hinge moment, the symmetric solve included;
- `roll` at the same condition (linearised: alpha 5 deg) and at alpha 0 (exact antisymmetric
  equilibrium), and the free roll;
- a 6-speed `control_sweep`.

Prints medians of wall and CPU time, and each one's ratio to the plain solve measured in the
same run. Never asserted (no timed assertions in tests).
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import argparse
import dataclasses
import itertools
import statistics
import sys
import time
from collections.abc import Callable
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import solver
from solver import FlightCondition, SolverOptions
from solver.model.layout import Layout
from solver.numerics.cache import model_for
from tests.study import DENSITY, study_arrays

OPTIONS = SolverOptions(chordwise_panels=4)
SURFACES = [
    {"name": "flap", "start": 0.0, "end": 0.45, "hinge": 0.5, "deflection": 5.0},
    {
        "name": "aileron",
        "start": 0.55,
        "end": 0.95,
        "hinge": 0.75,
        "deflection": 5.0,
        "kind": "aileron",
    },
]
_counter = itertools.count(1)


def new_wing() -> solver.Wing:
    """The study's wing with its surfaces, never seen before (no cached jig or divergence)."""
    scale = 1.0 + 1e-9 * next(_counter)
    return solver.Wing.create(**study_arrays(30, stiffness_scale=scale), control_surfaces=SURFACES)


def _aileron_only(wing: solver.Wing) -> solver.Wing:
    return dataclasses.replace(
        wing, control_surfaces=tuple(s for s in wing.control_surfaces if not s.symmetric)
    )


def load_average() -> str:
    one, five, fifteen = os.getloadavg()
    return f"load average {one:.2f}, {five:.2f}, {fifteen:.2f} on {os.cpu_count()} CPUs"


def median_ms(function: Callable[[solver.Wing], object], repeat: int) -> tuple[float, float]:
    """Medians [ms] of wall and CPU time of function(new wing)."""
    function(new_wing())
    walls, cpus = [], []
    for _ in range(repeat):
        wing = new_wing()
        started, cpu = time.perf_counter(), time.process_time()
        function(wing)
        walls.append(time.perf_counter() - started)
        cpus.append(time.process_time() - cpu)
    return 1e3 * statistics.median(walls), 1e3 * statistics.median(cpus)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--repeat", type=int, default=20)
    args = parser.parse_args()
    started = time.perf_counter()
    model_for(Layout(30, 4)).wait_compiled()
    model_for(Layout(30, 4), flow=True).wait_compiled()
    print(f"compiled libraries ready after {time.perf_counter() - started:.1f} s; {load_average()}")
    cruise = FlightCondition(12.0, 5.0, DENSITY)
    level = FlightCondition(12.0, 0.0, DENSITY)
    cases: list[tuple[str, Callable[[solver.Wing], object]]] = [
        ("plain solve, 12 m/s, alpha 5", lambda w: solver.solve(w, cruise, options=OPTIONS)),
        (
            "effectiveness and reversal, the aileron",
            lambda w: solver.control_effectiveness(_aileron_only(w), cruise, OPTIONS),
        ),
        (
            "effectiveness and reversal, both surfaces",
            lambda w: solver.control_effectiveness(w, cruise, OPTIONS),
        ),
        ("roll, alpha 5 (linearised)", lambda w: solver.roll(w, cruise, OPTIONS)),
        ("roll, alpha 0, no flap (exact)", lambda w: solver.roll(_no_flap(w), level, OPTIONS)),
        (
            "free roll, alpha 0, no flap (exact)",
            lambda w: solver.roll(_no_flap(w), level, OPTIONS, roll_rate=None),
        ),
        (
            "control sweep, 6 speeds",
            lambda w: solver.control_sweep(w, [6, 10, 12, 15, 18, 20], 5.0, DENSITY, OPTIONS),
        ),
    ]
    baseline = None
    print(f"study wing, N = 30, k = 4, {args.repeat} repeats, medians:")
    for name, function in cases:
        repeat = args.repeat if "sweep" not in name else max(3, args.repeat // 4)
        wall, cpu = median_ms(function, repeat)
        if baseline is None:
            baseline = (wall, cpu)
        print(
            f"  {name:42s} {wall:8.1f} ms wall ({wall / baseline[0]:4.2f}x)"
            f" {cpu:8.1f} ms CPU ({cpu / baseline[1]:4.2f}x)"
        )
    print(load_average())
    return 0


def _no_flap(wing: solver.Wing) -> solver.Wing:
    """The same wing with its flap neutral: the exact antisymmetric response needs it."""
    surfaces = tuple(
        dataclasses.replace(s, deflection=0.0) if s.symmetric else s for s in wing.control_surfaces
    )
    return dataclasses.replace(wing, control_surfaces=surfaces)


if __name__ == "__main__":
    sys.exit(main())
