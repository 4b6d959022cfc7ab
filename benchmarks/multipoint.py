"""Multipoint design (`DesignProblem.load_cases`) against the single-point problem, in process.

A grid of 96 problems on the design study's wing (30 stations) with a carbon tube spar (its
outer diameter 80 % of the section's 12 % thickness): a yield stress of 30 or 60 MPa, without
and with the wing's own mass (3 to 0.5 kg/m, on the elastic axis), a design flight of 300 N at
12, 14 or 16 m/s, and as load cases a 2.5 g pull-up, a -1 g push-over, both, or both with a
1.5 g case at 1.3 times the speed; the objective the spar's mass (walls sized, the twist free)
or the design flight's induced drag (the spar kept, its stress held in every case).

Prints, per problem, the answer (the spar's mass or drag, or the typed failure), IPOPT's
iterations and the wall time against the single-point problem's (the design flight alone, same
wing, same objective); then the spar's mass with the design flight alone against with a 2.5 g
pull-up added, the cost ratios (median, range) and the failures.

    python -m benchmarks.multipoint            # the grid (about 3 minutes on one core)
    python -m benchmarks.multipoint --quick    # 12 problems
"""

from __future__ import annotations

import argparse
import dataclasses
import statistics
import time

import numpy as np

import solver
from tests.study import study_wing

_CARBON = solver.Material(
    youngs_modulus=70e9, shear_modulus=27e9, density=1600.0, yield_stress=600e6
)


def _wing(yield_stress: float, massive: bool) -> solver.Wing:
    base = study_wing()
    material = dataclasses.replace(_CARBON, yield_stress=yield_stress)
    spar = solver.SparDesign(solver.ThicknessFraction(0.8), 0.002, material)
    mass = (
        solver.MassModel.create(base.n_stations, np.linspace(3.0, 0.5, base.n_stations), 0.4, 0.01)
        if massive
        else None
    )
    return solver.Wing.create(base.y, base.chord, 0.4, airfoil="naca0012", spar=spar, mass=mass)


def _cases(velocity: float, which: str) -> tuple[solver.DesignLoadCase, ...]:
    def case(name: str, n: float, speed: float = velocity) -> solver.DesignLoadCase:
        return solver.DesignLoadCase(
            name, solver.FlightCondition(speed, weight=300.0, load_factor=n)
        )

    pull, push = case("pull-up", 2.5), case("push-over", -1.0)
    return {
        "pull": (pull,),
        "push": (push,),
        "pull+push": (pull, push),
        "pull+push+fast": (pull, push, case("fast", 1.5, 1.3 * velocity)),
    }[which]


def _problem(velocity: float, objective: str) -> solver.DesignProblem:
    if objective == "spar_mass":
        return solver.DesignProblem(
            solver.DesignCondition(velocity, weight=300.0),
            design=solver.Design(wall_thickness=solver.WallDesign(5e-4, 0.01)),
            objective="spar_mass",
        )
    return solver.DesignProblem(solver.DesignCondition(velocity, weight=300.0))


def _run(wing: solver.Wing, problem: solver.DesignProblem) -> tuple[str, float, int, float]:
    """(answer, its value or nan, IPOPT's iterations or -1, seconds)."""
    started = time.perf_counter()
    try:
        design = solver.optimize(wing, problem)
    except solver.SolverError as error:
        return type(error).__name__, float("nan"), -1, time.perf_counter() - started
    value = design.spar_mass if problem.objective == "spar_mass" else design.objective_value
    seconds = time.perf_counter() - started
    return "optimum", float(value or 0.0), design.optimizer.iterations, seconds


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="12 problems")
    quick = parser.parse_args().quick
    yields = [30e6] if quick else [30e6, 60e6]
    masses = [False] if quick else [False, True]
    speeds = [14.0] if quick else [12.0, 14.0, 16.0]
    sets = ["pull", "push", "pull+push", "pull+push+fast"]
    objectives = ["spar_mass", "induced_drag"]
    solver.optimize(_wing(30e6, False), _problem(14.0, "induced_drag"))  # compile, warm caches
    ratios, failures, sizing = [], [], []
    print("yield massive V objective cases | answer value iterations seconds | single ratio")
    for yield_stress in yields:
        for massive in masses:
            wing = _wing(yield_stress, massive)
            for velocity in speeds:
                for objective in objectives:
                    plain = _problem(velocity, objective)
                    # Twice, the faster: the first pays what a wing's first solve caches.
                    single = min(_run(wing, plain), _run(wing, plain), key=lambda run: run[3])
                    for which in sets:
                        problem = dataclasses.replace(plain, load_cases=_cases(velocity, which))
                        answer, value, iterations, seconds = _run(wing, problem)
                        ratio = seconds / single[3]
                        print(
                            f"{yield_stress / 1e6:4.0f} {massive!s:5} {velocity:4.0f} "
                            f"{objective:12} {which:14} | {answer:21} {value:9.5f} "
                            f"{iterations:4d} {seconds:6.2f} | {single[1]:9.5f} {ratio:5.2f}",
                            flush=True,
                        )
                        if answer == "optimum":
                            ratios.append(ratio)
                        else:
                            failures.append((yield_stress, massive, velocity, objective, which))
                        if objective == "spar_mass" and which == "pull" and answer == "optimum":
                            sizing.append((single[1], value))
    print(f"\n{len(ratios) + len(failures)} problems, {len(failures)} without an optimum")
    for failure in failures:
        print("  no optimum:", failure)
    if ratios:
        print(
            f"time / single point: median {statistics.median(ratios):.2f}, "
            f"range {min(ratios):.2f} - {max(ratios):.2f}"
        )
    for alone, pulled in sizing:
        print(
            f"spar mass: design flight alone {alone:.3f} kg, with the 2.5 g pull-up "
            f"{pulled:.3f} kg ({100 * (pulled / alone - 1):+.0f} %)"
        )


if __name__ == "__main__":
    main()
