"""Fuzzing, the long forms: the solver over random wings, and schemathesis against the service.

    .venv/bin/python benchmarks/fuzz_benchmark.py [--wings 2000] [--seed 1] [--schemathesis]
        [--examples 150] [--seeds 1 2 3 4 5] [--schema] [--json results.json]

Solver (in this process, CasADi's VM, tests/strategies.py): --wings random wings and flights
(N = 3..40, speeds 0.05..2.5 x the linear divergence speed). Reported: outcome counts (stable,
flagged unstable, no equilibrium, not converged, and any untyped exception or NaN, which would be
defects), solve time p50/p99/max, and determinism: for every stable equilibrium, the same solve
warm-started from the equilibrium at 0.8 x the speed, with the largest relative difference over
heave, twist, loads and lift (max |warm - cold| / max |cold| per field), over the pairs whose
tip twist is at least 1e-3 deg (smaller deformations are resolved only to the absolute residual
tolerance, 1e-10 deg on twist), and the largest absolute twist difference over all pairs.

--schemathesis runs schemathesis' own command line (`schemathesis run`, its default checks and
phases but three whose assumptions this API's contract breaks on purpose, each said where it is
excluded) against a live server: `uvicorn app.main:app` on a free loopback port, 2 workers, the
default settings except FLEXWING_MAX_QUEUED_JOBS=100000 (the fuzzer outruns two workers; a full
queue's 503 is load shedding, measured by load_benchmark.py), FLEXWING_COMPILE=0 (libraries on
disk are used, no new one is compiled: random mesh sizes would start a C compilation per size in
every worker) and, unless
--default-budgets, solve and sweep budgets of 120 s and 600 s (a loaded machine must not turn
slow solves into 504s counted as failures). --examples test cases per operation (150), once per
seed (--seeds, five by default); it reports per seed the test cases generated, the failures by
check (with the operations) and errors, and schemathesis' warnings, and the totals. The goal is
0 failures, 0 errors and 0 warnings. Bounded: every request has a timeout (180 s, 60 s with the
default budgets), every seed 30 minutes.

--schema also runs tests/app/test_schema_fuzz.py with HYPOTHESIS_PROFILE=nightly (20 x the CI
counts: 40,000 generated requests and 1,000 physical wings) and reports its result and time.

Figures are reported, never asserted; the exit status is 1 only for a defect (an untyped
exception or a NaN from the solver, a schema failure, error or warning).
"""

from __future__ import annotations

import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
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
sys.path.insert(0, str(ROOT / "benchmarks"))

from load_benchmark import local_server_process  # noqa: E402

import solver  # noqa: E402
from tests.strategies import alphas, densities, ratios, speed_for, wings  # noqa: E402

SCHEMA_TESTS = "tests/app/test_schema_fuzz.py"
# (group, field) of `Equilibrium` compared between a warm-started and a cold solve.
FIELDS = (
    ("stations", "heave"),
    ("stations", "twist"),
    ("stations", "shear"),
    ("stations", "bending_moment"),
    ("stations", "torque"),
    ("panels", "lift"),
)
# ... and the other arrays that must be finite.
OTHER_ARRAYS = (
    ("stations", "slope"),
    ("stations", "axis_twist"),
    ("panels", "y"),
    ("panels", "torque"),
    ("panels", "lift_per_span"),
    ("panels", "rigid_lift_per_span"),
)


def _array(eq: solver.Equilibrium, group: str, name: str) -> np.ndarray:
    return np.asarray(getattr(getattr(eq, group), name))


def _relative(warm: solver.Equilibrium, cold: solver.Equilibrium) -> float:
    worst = abs(warm.lift - cold.lift) / max(abs(cold.lift), 1e-300)
    for group, name in FIELDS:
        a, b = _array(warm, group, name), _array(cold, group, name)
        scale = np.max(np.abs(b))
        if scale > 0:
            worst = max(worst, float(np.max(np.abs(a - b)) / scale))
    return worst


def _finite(eq: solver.Equilibrium) -> bool:
    arrays = [_array(eq, group, name) for group, name in (*FIELDS, *OTHER_ARRAYS)]
    totals = eq.totals
    scalars = [
        totals.lift,
        totals.induced_drag,
        totals.CL,
        totals.rigid_lift,
        totals.pitching_moment,
        eq.stability.margin,
    ]
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
                warm = solver.solve(case.wing, flight, hint=start)
            except solver.SolverError:
                return
            if warm.stability.stable:
                gap = np.abs(warm.stations.twist - eq.stations.twist)
                twist_gaps.append(float(np.max(gap)))
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


# The schemathesis server: 2 workers; CasADi's VM for every mesh size without a library on disk
# (random N would start a C compilation per size in every worker); budgets raised so that a solve
# slowed down by a loaded machine is not answered 504 (unless --default-budgets).
# The fuzzer submits jobs far faster than two workers run them: with the default queue (100)
# it measures the documented load shedding (503 overloaded, Retry-After), not conformance.
SCHEMATHESIS_SERVER = {
    "FLEXWING_WORKERS": "2",
    "FLEXWING_COMPILE": "0",
    "FLEXWING_MAX_QUEUED_JOBS": "100000",
}
GENEROUS_BUDGETS = {"FLEXWING_SOLVE_TIMEOUT": "120", "FLEXWING_SWEEP_TIMEOUT": "600"}


def schemathesis_cli(examples: int, seeds: list[int], default_budgets: bool) -> dict[str, Any]:
    """`schemathesis run` against a live loopback server, once per seed (JSON reports)."""
    runs = []
    started = time.perf_counter()
    env = SCHEMATHESIS_SERVER | ({} if default_budgets else GENEROUS_BUDGETS)
    # Longer than any budget: a slow answer is the server's to give (a 504), not a client timeout.
    request_timeout = 60 if default_budgets else 180
    with (
        local_server_process(env) as (base_url, _),
        tempfile.TemporaryDirectory() as work,
    ):
        for seed in seeds:
            report = Path(work) / f"seed{seed}.json"
            tick = time.perf_counter()
            completed = subprocess.run(
                [
                    *(sys.executable, "-m", "schemathesis.cli", "run"),
                    f"{base_url}/openapi.json",
                    *("--max-examples", str(examples), "--seed", str(seed)),
                    *("--request-timeout", str(request_timeout), "--workers", "1"),
                    *("--report", "json", "--report-json-path", str(report)),
                    # A schema-valid request may have no equilibrium (past the fold: 422
                    # no-equilibrium, the domain's answer) or break a cross-field rule the
                    # schema cannot state (y increasing, one airfoil per station): those 422s
                    # are this API's contract, not a rejected valid request.
                    # DELETE /jobs/{id} cancels a job and keeps its record (issue 13: "cancels;
                    # the state says what was done", a batch's answered items stay readable), so
                    # the job is still there after a DELETE: not a use after free. Only a batch
                    # job has /items.ndjson: a sweep job's is 404, not a created resource lost.
                    *(
                        "--exclude-checks",
                        "positive_data_acceptance,use_after_free,ensure_resource_availability",
                    ),
                    "--no-color",
                ],
                cwd=work,
                capture_output=True,
                text=True,
                timeout=1800,
            )
            document = json.loads(report.read_text()) if report.exists() else {}
            failures = document.get("failures", [])
            errors = document.get("errors", [])
            # {warning kind: [operations]}: the kinds with no operation did not occur.
            warnings = {k: v for k, v in document.get("warnings", {}).items() if v}
            runs.append(
                {
                    "seed": seed,
                    "exit_code": completed.returncode,
                    "seconds": time.perf_counter() - tick,
                    "generated": document.get("test_cases", {}).get("generated"),
                    "failures": sum(group["count"] for group in failures),
                    "failure_groups": [
                        f"{g['title']} ({g['code']}) x{g['count']}: {', '.join(g['operations'])}"
                        for g in failures
                    ],
                    "errors": sum(group["count"] for group in errors),
                    "error_groups": [f"{g['title']} x{g['count']}" for g in errors],
                    "warnings": sum(len(operations) for operations in warnings.values()),
                    "warning_kinds": warnings,
                    "tail": completed.stdout.splitlines()[-3:] if not document else None,
                }
            )
            if failures or errors or warnings:
                # schemathesis' own account of each failure (reproducing curl commands included)
                text = completed.stdout
                starts = [i for i in (text.find("ERRORS"), text.find("FAILURES")) if i >= 0]
                print(text[min(starts, default=0) :][:12000], flush=True)
            print(
                f"schemathesis seed {seed}: {runs[-1]['generated']} test cases, "
                f"{runs[-1]['failures']} failures, {runs[-1]['errors']} errors, "
                f"{runs[-1]['warnings']} warnings, exit {completed.returncode}, "
                f"{runs[-1]['seconds']:.0f} s",
                flush=True,
            )
    return {
        "server": env,
        "examples_per_operation": examples,
        "seeds": seeds,
        "seconds": time.perf_counter() - started,
        "generated": sum(run["generated"] or 0 for run in runs),
        "failures": sum(run["failures"] for run in runs),
        "errors": sum(run["errors"] for run in runs),
        "warnings": sum(run["warnings"] for run in runs),
        "runs": runs,
    }


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--wings", type=int, default=2000)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--no-solver", action="store_true", help="skip the solver fuzzing")
    parser.add_argument("--schemathesis", action="store_true")
    parser.add_argument("--examples", type=int, default=150, help="per operation and seed")
    parser.add_argument("--seeds", type=int, nargs="+", default=[1, 2, 3, 4, 5])
    parser.add_argument(
        "--default-budgets", action="store_true", help="the service's own solve/sweep budgets"
    )
    parser.add_argument("--schema", action="store_true")
    parser.add_argument("--json", type=Path)
    args = parser.parse_args(argv)
    one, five, fifteen = os.getloadavg()
    print(f"load average {one:.2f}, {five:.2f}, {fifteen:.2f} on {os.cpu_count()} CPUs")
    results: dict[str, Any] = {}
    if not args.no_solver:
        results["solver"] = solver_fuzz(args.wings, args.seed)
        print(f"solver: {json.dumps(results['solver'], indent=1)}")
    if args.schemathesis:
        found = schemathesis_cli(args.examples, args.seeds, args.default_budgets)
        results["schemathesis"] = found
        print(f"schemathesis: {json.dumps(found, indent=1)}")
        print(
            f"schemathesis, {args.examples} examples x {len(args.seeds)} seeds: "
            f"{found['generated']} test cases, {found['failures']} failures (goal 0), "
            f"{found['errors']} errors (goal 0), {found['warnings']} warnings (goal 0)"
        )
    if args.schema:
        results["schema"] = schema_fuzz()
        print(f"schema: {json.dumps(results['schema'], indent=1)}")
    if args.json:
        args.json.write_text(json.dumps(results, indent=2) + "\n")
    one, five, fifteen = os.getloadavg()
    print(f"load average {one:.2f}, {five:.2f}, {fifteen:.2f} on {os.cpu_count()} CPUs")
    outcomes = results.get("solver", {}).get("outcomes", {})
    defects = [k for k in outcomes if k.startswith(("UNTYPED", "NaN"))]
    found = results.get("schemathesis", {})
    schema_defects = found.get("failures", 0) + found.get("errors", 0) + found.get("warnings", 0)
    return 1 if defects or schema_defects or results.get("schema", {}).get("exit_code") else 0


if __name__ == "__main__":
    sys.exit(main())
