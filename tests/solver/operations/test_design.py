"""solver.operations.design: `OptimizeInput` with load cases.

- `run()` answers what `solver.optimize` answers for the same multipoint problem (the same
  computation twice: 1e-12, as tests/solver/operations/test_inputs.py).
- The load cases are part of the input's identity: the same cases built apart have one key,
  another case another key (a cached answer is never another problem's).
- A problem with load cases that sizes a spar the wing has not is refused where it is built,
  naming the field.
"""

from __future__ import annotations

import dataclasses
import functools

import numpy as np
import pytest

import solver
from tests import study

SAME = 1e-12


@functools.cache
def _small_wing() -> solver.Wing:
    return study.study_wing(n=12)


def _pull_up(load_factor: float = 2.5) -> solver.DesignLoadCase:
    flight = solver.FlightCondition(12.0, weight=100.0, load_factor=load_factor)
    return solver.DesignLoadCase("pull-up", flight)


def _problem(*cases: solver.DesignLoadCase) -> solver.DesignProblem:
    return solver.DesignProblem(
        solver.DesignCondition(12.0, weight=100.0),
        solver.Design(solver.TwistDesign(control_points=4)),
        objective="trefftz_drag",
        constraints=solver.DesignConstraints(max_tip_heave=0.5),
        load_cases=cases,
    )


def test_an_optimize_input_with_load_cases_answers_what_optimize_answers() -> None:
    problem = _problem(_pull_up())
    ran = solver.OptimizeInput(_small_wing(), problem).run()
    plain = solver.optimize(_small_wing(), problem)
    assert np.max(np.abs(ran.jig_twist - plain.jig_twist)) <= SAME * np.max(np.abs(plain.jig_twist))
    assert ran.cases is not None and [case.name for case in ran.cases] == ["flight", "pull-up"]
    pulled = ran.cases[1].equilibrium.totals
    assert pulled.lift == pytest.approx(250.0, rel=1e-8)
    assert abs(pulled.tip_heave) <= 0.5 * (1 + 1e-8)  # the tip heave held in the case too


def test_the_load_cases_are_part_of_the_inputs_identity() -> None:
    def key(*cases: solver.DesignLoadCase) -> bytes:
        return solver.OptimizeInput(_small_wing(), _problem(*cases)).key

    assert key(_pull_up()) == key(_pull_up())
    assert key(_pull_up()) != key()
    assert key(_pull_up()) != key(_pull_up(2.0))
    renamed = dataclasses.replace(_pull_up(), name="manoeuvre")
    assert key(_pull_up()) != key(renamed)


def test_sizing_a_spar_the_wing_has_not_is_refused_with_load_cases_too() -> None:
    problem = dataclasses.replace(
        _problem(_pull_up()),
        design=solver.Design(wall_thickness=solver.WallDesign()),
    )
    with pytest.raises(solver.InvalidInput) as raised:
        solver.OptimizeInput(_small_wing(), problem)
    assert raised.value.field == "design.wall_thickness"
