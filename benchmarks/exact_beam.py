"""How fast the geometrically exact beam is, against the linear one on the same wing.

    python benchmarks/exact_beam.py [--repeat 30]

The design study's wing at N = 30 (tests/study.py), compiled functions (C, in a private cache,
compiled before timing): an equilibrium from the jig shape at 18 m/s of a new wing (its caches
cold, the compiled model's warm), under each structure (`options.structure`), interleaved
repeat by repeat (the machine's drift hits both alike), and a
10-speed sweep through large deflection (a wing with a twentieth of the study's bending
stiffness, 2 to 11 m/s, its tip heave from 1 % to ~24 % of the semispan) under the exact beam,
for a known wing (caches warm) and a new one (the stiffness scaled by 1 + 1e-9 i: every cache
misses but the compiled model's), the new wings under the linear beam too. Targets (issue 38),
printed, never asserted:

    exact / linear, one equilibrium from the jig (N = 30)    < 5x
    10-speed sweep through large deflection (N = 30)         < 100 ms

Medians of wall and CPU time (this process; the solver is single-threaded) and the load average.
Set OPENBLAS_NUM_THREADS=1 (done below when unset).
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import argparse
import atexit
import dataclasses
import shutil
import statistics
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
if __name__ == "__main__":
    _cache = tempfile.mkdtemp(prefix="flexwing-bench-")
    os.environ["FLEXWING_CACHE_DIR"] = _cache
    os.environ["FLEXWING_COMPILE"] = "1"
    atexit.register(shutil.rmtree, _cache, True)

import solver  # noqa: E402
from solver.numerics.cache import model_for  # noqa: E402
from solver.statics.system import CoupledSystem  # noqa: E402
from tests.study import flight, study_arrays, study_wing  # noqa: E402

SPEEDS = [2.0 + i for i in range(10)]  # [m/s]


def _timed(action) -> tuple[float, float]:  # type: ignore[no-untyped-def]
    wall, cpu = time.perf_counter(), time.process_time()
    action()
    return time.perf_counter() - wall, time.process_time() - cpu


def _soft_wing(scale: float = 1.0) -> solver.Wing:
    arrays = study_arrays(30)
    arrays["bending_stiffness"] = 0.05 * arrays["bending_stiffness"] * scale
    return solver.Wing.create(**arrays)


def _lagging(wing: solver.Wing) -> solver.Wing:
    """`wing` bending in its plane too, 50 times stiffer there than in flap (a wing's chord is
    several times its thickness)."""
    return dataclasses.replace(wing, in_plane_bending_stiffness=50 * wing.bending_stiffness)


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--repeat", type=int, default=30)
    args = parser.parse_args()
    exact_options = solver.SolverOptions(structure="geometrically_exact")
    options = {
        "linear": solver.SolverOptions(),
        "geometrically_exact": exact_options,
        "exact with lag": exact_options,  # the wing bending in its plane too (_lagging)
    }
    wing = study_wing(30)
    for name, option in options.items():  # compile every model before timing
        given = _lagging(wing) if name == "exact with lag" else wing
        model_for(CoupledSystem.of(given, 5.0, option).layout).wait_compiled()
    times: dict[str, list[tuple[float, float]]] = {name: [] for name in options}
    for i in range(args.repeat):
        # A new wing each time (the stiffness scaled by 1 + 1e-9 i): every cache misses but the
        # compiled model's.
        arrays = study_arrays(30, 1.0 + 1e-9 * (i + 1))
        fresh = solver.Wing.create(**arrays)
        for name, option in options.items():
            given = _lagging(fresh) if name == "exact with lag" else fresh
            times[name].append(
                _timed(lambda o=option, w=given: solver.solve(w, flight(18.0), options=o))
            )
    exact = options["geometrically_exact"]
    soft = _soft_wing()
    answer = solver.airspeed_sweep(soft, SPEEDS, flight(None), exact)
    tips = [
        p.equilibrium.stations.heave[-1] / soft.semispan for p in answer.points if p.equilibrium
    ]
    linear = options["linear"]
    known, new, new_linear = [], [], []
    for i in range(args.repeat):
        known.append(_timed(lambda: solver.airspeed_sweep(soft, SPEEDS, flight(None), exact)))
        fresh = _soft_wing(1.0 + 1e-9 * (i + 1))
        new.append(_timed(lambda w=fresh: solver.airspeed_sweep(w, SPEEDS, flight(None), exact)))
        new_linear.append(
            _timed(lambda w=fresh: solver.airspeed_sweep(w, SPEEDS, flight(None), linear))
        )

    def median(samples: list[tuple[float, float]], part: int) -> float:
        return statistics.median(s[part] for s in samples) * 1e3

    print(f"load average {os.getloadavg()[0]:.2f}, {args.repeat} repeats, N = 30")
    for name in options:
        print(
            f"equilibrium from the jig, {name:20s} wall {median(times[name], 0):7.2f} ms "
            f"cpu {median(times[name], 1):7.2f} ms"
        )
    ratio = median(times["geometrically_exact"], 0) / median(times["linear"], 0)
    cpu_ratio = median(times["geometrically_exact"], 1) / median(times["linear"], 1)
    print(f"exact / linear: wall {ratio:.2f}x, cpu {cpu_ratio:.2f}x (target < 5x)")
    lag_ratio = median(times["exact with lag"], 0) / median(times["linear"], 0)
    print(f"exact with lag / linear: wall {lag_ratio:.2f}x")
    print(
        f"10-speed sweep 2..11 m/s, tip heave {100 * min(tips):.1f} to {100 * max(tips):.1f} % "
        f"of the semispan ({len(tips)} equilibria)"
    )
    print(
        f"  known wing: wall {median(known, 0):7.2f} ms cpu {median(known, 1):7.2f} ms; "
        f"new wing: wall {median(new, 0):7.2f} ms cpu {median(new, 1):7.2f} ms (target < 100 ms)"
    )
    print(
        f"  the same new wings under the linear beam: wall {median(new_linear, 0):7.2f} ms cpu "
        f"{median(new_linear, 1):7.2f} ms; exact / linear wall "
        f"{median(new, 0) / median(new_linear, 0):.2f}x"
    )


if __name__ == "__main__":
    main()
