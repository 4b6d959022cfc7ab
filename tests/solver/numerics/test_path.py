"""solver.numerics.path: natural-parameter steps in q stay on the branch they start from."""

from __future__ import annotations

import numpy as np
import pytest

import solver
from solver.numerics.path import PathSettings, follow
from solver.statics.branch import pressure_scale
from solver.statics.jig import jig
from solver.statics.system import CoupledSystem
from tests.study import DENSITY, bistable_wing, flight, study_wing


def _follow(system, start, start_q, evaluation, q, **settings):
    return follow(
        system.evaluate,
        system.residual,
        start,
        start_q,
        evaluation,
        q,
        system.scale(pressure_scale(system)),
        1e-10,
        PathSettings(**settings),
    )


def test_one_step_reaches_cruise_from_the_jig():
    system = CoupledSystem(study_wing(), 5.0)
    start = jig(system)
    q = 0.5 * DENSITY * 10.0**2
    result = _follow(system, start.state, 0.0, start.evaluation, q)
    # How many steps and iterations it takes is the machine's round-off's to decide; that it
    # arrives, at an equilibrium of the requested q, is the path's promise.
    assert result.reached and result.dynamic_pressure == q
    r0, r1 = system.residual(result.x)
    assert np.max(np.abs(r0 + q * r1)) <= 1e-10


def test_the_path_to_the_bistable_wings_far_end_stays_on_the_jig_branch():
    """Found by fuzzing: the bistable wing at q = 0.519 Pa has a +70 deg (the jig's branch) and a
    -70 deg stable equilibrium. Plain Newton from the +34 deg equilibrium at 0.8 m/s jumped to
    -70 deg; the path's steps do not."""
    wing = bistable_wing()
    system = CoupledSystem(wing, 0.5)
    start = solver.solve(wing, flight(0.8, 0.5, 1.038))
    assert start.tip_twist == pytest.approx(33.6, abs=0.1)
    result = _follow(
        system, start.state, start.dynamic_pressure, start.evaluation, 0.5 * 1.038 * 1.0**2
    )
    assert result.reached
    assert result.x[system.layout.twist][-1] == pytest.approx(69.93, abs=0.01)


def test_a_path_that_cannot_pass_the_fold_stalls_below_it():
    system = CoupledSystem(study_wing(), 5.0)
    start = jig(system)
    result = _follow(system, start.state, 0.0, start.evaluation, 0.5 * DENSITY * 23.0**2)
    assert not result.reached
    assert "stalled" in result.reason or "steps" in result.reason
    assert result.dynamic_pressure < 0.5 * DENSITY * 21.44**2
    r0, r1 = system.residual(result.x)
    assert np.max(np.abs(r0 + result.dynamic_pressure * r1)) <= 1e-10  # an equilibrium still
