"""Fuzzing, the long forms: the solver over random wings, and schemathesis against the service.

    .venv/bin/python benchmarks/fuzz_benchmark.py [--wings 2000] [--seed 1] [--schema]
        [--json results.json]

Solver (in this process, CasADi's VM, tests/strategies.py): --wings random wings and flights
(N = 3..40, speeds 0.05..2.5 x the linear divergence speed). Reported: outcome counts (stable,
flagged unstable, no equilibrium, not converged, and any untyped exception or NaN, which would be
defects), solve time p50/p99/max, and determinism: for every stable equilibrium, the same solve
warm-started from the equilibrium at 0.8 x the speed, with the largest relative difference over
heave, twist, loads and lift (max |warm - cold| / max |cold| per field), over the pairs whose
tip twist is at least 1e-3 deg (smaller deformations are resolved only to the absolute residual
tolerance, 1e-10 deg on twist), and the largest absolute twist difference over all pairs.

--schema also runs tests/app/test_schema_fuzz.py with HYPOTHESIS_PROFILE=nightly (20 x the CI
counts: 40,000 generated requests and 1,000 physical wings) and reports its result and time.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import subprocess
import sys
import time
from collections import Counter
from pathlib import Path
from typing import Any

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ["FLEXWING_COMPILE"] = "0"  # forty mesh sizes: no background compilations

import hypothesis
import numpy as np
from hypothesis import HealthCheck, given, settings

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

import solver  # noqa: E402
from tests.strategies import alphas, densities, ratios, speed_for, wings  # noqa: E402

SCHEMA_TESTS = "tests/app/test_schema_fuzz.py"
FIELDS = ("heave", "twist", "shear", "bending_moment", "torque", "panel_lift")


def _relative(warm: solver.Equilibrium, cold: solver.Equilibrium) -> float:
    worst = abs(warm.lift - cold.lift) / max(abs(cold.lift), 1e-300)
    for name in FIELDS:
        a, b = getattr(warm, name), getattr(cold, name)
        scale = np.max(np.abs(b))
        if scale > 0:
            worst = max(worst, float(np.max(np.abs(a - b)) / scale))
    return worst


def _finite(eq: solver.Equilibrium) -> bool:
    arrays = [getattr(eq, name) for name in (*FIELDS, "slope", "panel_y", "panel_torque")]
    scalars = [eq.lift, eq.induced_drag, eq.CL, eq.rigid_lift, eq.stability.margin]
    return all(np.all(np.isfinite(a)) for a in arrays) and all(map(math.isfinite, scalars))


def solver_fuzz(count: int, seed: int) -> dict[str, Any]:
    outcomes: Counter[str] = Counter()
    times: list[float] = []
    differences: list[float] = []
    twist_gaps: list[float] = []
    worst: list[tuple[float, str]] = []
    untyped: list[str] = []

    @hypothesis.seed(seed)
    @settings(
        max_examples=count,
        deadline=None,
        database=None,
        suppress_health_check=list(HealthCheck),
    )
    @given(case=wings(), alpha=alphas, ratio=ratios, density=densities)
    def run(case: Any, alpha: float, ratio: float, density: float) -> None:
        flight = solver.FlightCondition(speed_for(case.wing, ratio, density), alpha, density)
        started = time.perf_counter()
        try:
            eq = solver.solve(case.wing, flight)
        except solver.NoEquilibrium:
            outcomes["no equilibrium"] += 1
            return
        except solver.ConvergenceError:
            outcomes["not converged"] += 1
            return
        except Exception as error:  # a defect: recorded with its wing, not raised
            outcomes[f"UNTYPED {type(error).__name__}"] += 1
            untyped.append(f"{error!r}: {case!r} alpha={alpha} V={flight.velocity}")
            return
        finally:
            times.append(time.perf_counter() - started)
        outcomes["stable" if eq.stability.stable else "flagged unstable"] += 1
        if not _finite(eq):
            outcomes["NaN in a field"] += 1
        if eq.stability.stable:
            slower = flight.at_velocity(0.8 * flight.velocity)
            try:
                start = solver.solve(case.wing, slower)
                warm = solver.solve(case.wing, flight, start)
            except solver.SolverError:
                return
            if warm.stability.stable:
                twist_gaps.append(float(np.max(np.abs(warm.twist - eq.twist))))
                if abs(eq.tip_twist) >= 1e-3:
                    differences.append(_relative(warm, eq))
                    worst.append((differences[-1], f"{case!r} {flight}"))

    started = time.perf_counter()
    run()
    elapsed = time.perf_counter() - started
    p50, p99 = np.percentile(times, [50, 99])
    return {
        "cases": sum(outcomes.values()),
        "seconds": elapsed,
        "outcomes": dict(outcomes),
        "solve_ms": {"p50": 1e3 * p50, "p99": 1e3 * p99, "max": 1e3 * max(times)},
        "warm_vs_cold": {
            "pairs": len(twist_gaps),
            "pairs_tip_twist_over_1e-3_deg": len(differences),
            "max_relative": max(differences, default=None),
            "p99_relative": float(np.percentile(differences, 99)) if differences else None,
            "max_twist_difference_deg": max(twist_gaps, default=None),
            "worst_case": max(worst, default=(None, None))[1],
        },
        "untyped": untyped[:10],
    }


def schema_fuzz() -> dict[str, Any]:
    started = time.perf_counter()
    completed = subprocess.run(
        [sys.executable, "-m", "pytest", "-q", "-s", "-p", "no:cacheprovider", SCHEMA_TESTS],
        cwd=ROOT,
        env=os.environ | {"HYPOTHESIS_PROFILE": "nightly"},
        capture_output=True,
        text=True,
        timeout=3 * 3600,
    )
    lines = completed.stdout.splitlines()
    return {
        "exit_code": completed.returncode,
        "seconds": time.perf_counter() - started,
        "responses": next((ln for ln in lines if "schema fuzzing, responses" in ln), None),
        "summary": lines[-1] if lines else None,
    }


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--wings", type=int, default=2000)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--schema", action="store_true")
    parser.add_argument("--json", type=Path)
    args = parser.parse_args(argv)
    results = {"solver": solver_fuzz(args.wings, args.seed)}
    print(f"solver: {json.dumps(results['solver'], indent=1)}")
    if args.schema:
        results["schema"] = schema_fuzz()
        print(f"schema: {json.dumps(results['schema'], indent=1)}")
    if args.json:
        args.json.write_text(json.dumps(results, indent=2) + "\n")
    defects = [k for k in results["solver"]["outcomes"] if k.startswith(("UNTYPED", "NaN"))]
    return 1 if defects or results.get("schema", {}).get("exit_code") else 0


if __name__ == "__main__":
    sys.exit(main())
