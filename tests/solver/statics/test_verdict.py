"""solver.statics.verdict: a converged state becomes an answer with its loads, its stability verdict
and its findings."""

from __future__ import annotations

import time

import numpy as np
import pytest

import solver
from solver.numerics.stability import divergence_pressure
from solver.statics.jig import linear_pressure
from solver.statics.system import CoupledSystem
from solver.statics.verdict import judge, stability_of
from tests.study import flight, study_wing


@pytest.fixture(scope="module")
def answer() -> solver.Equilibrium:
    return solver.solve(study_wing(), flight(15.0))


def test_the_verdict_compares_q_with_the_local_divergence_pressure(answer):
    system = CoupledSystem(answer.wing, answer.flight.alpha)
    verdict = stability_of(system, answer.flight, answer.evaluation)
    local = divergence_pressure(answer.evaluation, system.layout)
    assert verdict.local_divergence_pressure == pytest.approx(local, rel=1e-12)
    assert verdict.margin == answer.dynamic_pressure / verdict.local_divergence_pressure
    assert verdict.stable and verdict.margin < 1 and verdict.branch == "jig"
    # The classical (linear, jig) divergence is reported beside it, at the flight's density.
    assert verdict.divergence_dynamic_pressure == linear_pressure(system)
    assert verdict.divergence_velocity == pytest.approx(
        np.sqrt(2 * linear_pressure(system) / answer.flight.density), rel=1e-15
    )
    assert verdict == answer.stability


def test_judging_the_same_state_again_gives_the_same_answer(answer):
    system = CoupledSystem(answer.wing, answer.flight.alpha)
    again = judge(
        system,
        answer.flight,
        answer.options,
        answer.state,
        answer.evaluation,
        iterations=answer.solver.iterations,
        residual_norm=answer.solver.residual_norm,
        warm_start=False,
        started=time.perf_counter(),
    )
    assert again.totals == answer.totals and again.stability == answer.stability
    np.testing.assert_array_equal(again.stations.bending_moment, answer.stations.bending_moment)
    assert [f.code for f in again.validity] == [f.code for f in answer.validity]
    assert again.solver.iterations == answer.solver.iterations and again.solver.seconds >= 0
