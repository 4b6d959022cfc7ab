"""A trimmed solve's cost against an alpha solve, and against AeroSandbox's trimmed Opti.

    /path/to/peers-venv/bin/python benchmarks/trim_benchmark.py      (from the repository root)

The peers' environment needs aerosandbox, scipy and this repository on the path (the script puts
the repository first). Three timings on the study's wing carrying 300 N at 8-18 m/s:

- flexwing `trim`: alpha solved for the lift, from the rigid jig (nothing cached but the wing's
  compiled model and its state at rest, as in a design loop that varies the flight);
- flexwing `solve` at an alpha it has not seen (the alpha solve a trimmed solve replaces; goal:
  trim <= 1.3 x this);
- AeroSandbox: the reference generator's Opti (tests/reference/generate_reference.py) with alpha
  a variable and `L == W`, warm-started from the previous speed as the study's sweep does.

Each figure is the median over REPEATS runs; the machine's load average is printed beside them
(timings on a shared 2-core machine move with it).
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

import solver  # noqa: E402 - after the path and the thread count
from tests.reference import load_reference  # noqa: E402
from tests.reference.generate_reference import generate  # noqa: E402

REPEATS = 7
CASE = ROOT / "tests" / "reference" / "data" / "case_trim_study.json"


def _median_ms(run, repeats: int = REPEATS) -> float:
    times = []
    for i in range(repeats):
        started = time.perf_counter()
        run(i)
        times.append(time.perf_counter() - started)
    return 1e3 * statistics.median(times)


def main() -> None:
    reference = load_reference(ROOT / "tests" / "reference" / "data" / "ref_trim_study.json")
    wing, rho, lift = reference.wing, reference.rho, reference.trimmed_lift
    velocities = [e["velocity"] for e in reference.equilibria]
    print(f"compiled model: {solver.warm_up(wing.n_stations, timeout=300)}")
    solver.trim(
        wing, solver.FlightCondition(velocities[0], density=rho, lift=lift)
    )  # the wing at rest

    case = json.loads(CASE.read_text())
    with contextlib.redirect_stderr(io.StringIO()):
        generated = [generate(case) for _ in range(3)]
    asb_ms = {
        e["velocity"]: 1e3 * statistics.median(g["equilibria"][i]["solve_s"] for g in generated)
        for i, e in enumerate(generated[0]["equilibria"])
    }

    print(f"load average: {os.getloadavg()[0]:.1f} (2 cores)")
    header = f"{'V [m/s]':>8} {'trim [ms]':>10} {'alpha solve [ms]':>17} {'ratio':>6}"
    print(header + f" {'AeroSandbox [ms]':>17} {'speed-up':>9} {'|alpha - ASB| [deg]':>20}")
    ratios, speedups = [], []
    for velocity in velocities:
        trimmed = solver.trim(wing, solver.FlightCondition(velocity, density=rho, lift=lift))
        alpha = trimmed.totals.alpha
        # Fresh speeds and alphas on every repeat: nothing of the request is cached.
        trim_ms = _median_ms(
            lambda i, v=velocity: solver.trim(
                wing, solver.FlightCondition(v + 1e-6 * i, density=rho, lift=lift)
            )
        )
        solve_ms = _median_ms(
            lambda i, v=velocity, a=alpha: solver.solve(
                wing, solver.FlightCondition(v, a + 1e-6 * (i + 1), rho)
            )
        )
        theirs = reference.equilibrium_at(velocity)["alpha_deg"]
        ratios.append(trim_ms / solve_ms)
        speedups.append(asb_ms[velocity] / trim_ms)
        print(
            f"{velocity:8g} {trim_ms:10.2f} {solve_ms:17.2f} {ratios[-1]:6.2f}"
            f" {asb_ms[velocity]:17.1f} {speedups[-1]:8.0f}x {abs(alpha - theirs):20.1e}"
        )
    print(
        f"median: trim / alpha solve = {statistics.median(ratios):.2f} (goal <= 1.3); "
        f"AeroSandbox / trim = {statistics.median(speedups):.0f}x"
    )


if __name__ == "__main__":
    main()
