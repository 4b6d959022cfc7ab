"""The single-point design's answers on six problems, as JSON, to compare two commits field by
field (the multipoint design left them unchanged to the last digit: docs/accuracy.md).

    python -m benchmarks.design_answers before.json          # at one commit
    python -m benchmarks.design_answers after.json before.json  # at another: compares

Wall times are left out; the members a later commit added (null: `case`, `cases`) are ignored.
"""

from __future__ import annotations

import dataclasses
import json
import sys
from typing import Any

import numpy as np

import solver
from app.schemas.responses import payload
from tests.study import study_wing

_CARBON = solver.Material(
    youngs_modulus=70e9, shear_modulus=27e9, density=1600.0, yield_stress=600e6
)


def _spar_wing(yield_stress: float, massive: bool = False) -> solver.Wing:
    base = study_wing()
    material = dataclasses.replace(_CARBON, yield_stress=yield_stress)
    spar = solver.SparDesign(solver.ThicknessFraction(0.8), 0.002, material)
    mass = solver.MassModel.create(30, np.linspace(3.0, 0.5, 30), 0.45, 0.01) if massive else None
    return solver.Wing.create(base.y, base.chord, 0.4, airfoil="naca0012", spar=spar, mass=mass)


def _problems() -> dict[str, tuple[solver.Wing, solver.DesignProblem, Any]]:
    lift = solver.DesignCondition(12.0, lift=300.0)
    sized = solver.Design(wall_thickness=solver.WallDesign(5e-4, 0.01))
    return {
        "study": (study_wing(), solver.DesignProblem(lift), None),
        "every": (
            study_wing(),
            solver.DesignProblem(
                solver.DesignCondition(12.0, lift=300.0, alpha=2.0),
                design=solver.Design(solver.TwistDesign(control_points=None)),
                smoothness_weight=0.05,
            ),
            None,
        ),
        "trefftz_heave": (
            study_wing(),
            solver.DesignProblem(
                solver.DesignCondition(12.0, weight=150.0, load_factor=2.0),
                objective="trefftz_drag",
                constraints=solver.DesignConstraints(max_tip_heave=0.5),
            ),
            None,
        ),
        "mass": (
            _spar_wing(30e6),
            solver.DesignProblem(
                solver.DesignCondition(14.0, lift=750.0), design=sized, objective="spar_mass"
            ),
            None,
        ),
        "drag_sized_massive": (
            _spar_wing(60e6, massive=True),
            solver.DesignProblem(solver.DesignCondition(14.0, lift=750.0), design=sized),
            None,
        ),
        "strip": (
            study_wing(),
            solver.DesignProblem(lift),
            solver.SolverOptions(aerodynamics="strip"),
        ),
    }


def _comparable(value: Any) -> Any:
    if isinstance(value, dict):
        return {
            k: _comparable(v)
            for k, v in value.items()
            if k != "seconds" and not (k in ("case", "cases") and v is None)
        }
    if isinstance(value, list):
        return [_comparable(v) for v in value]
    return value


def main() -> None:
    answers: dict[str, Any] = {}
    for name, (wing, problem, options) in _problems().items():
        try:
            answers[name] = _comparable(payload(solver.optimize(wing, problem, options)))
        except solver.SolverError as error:
            answers[name] = repr(error)
    with open(sys.argv[1], "w") as out:
        json.dump(answers, out, sort_keys=True)
    if len(sys.argv) > 2:
        with open(sys.argv[2]) as before_file:
            before = _comparable(json.load(before_file))
        for name, answer in answers.items():
            same = before.get(name) == answer
            print(f"{name:20} {'identical' if same else 'DIFFERENT'}")


if __name__ == "__main__":
    main()
