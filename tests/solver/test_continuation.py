"""solver.continuation: the branch from the jig, traced by pseudo-arclength continuation, is the
same however far and in what order it is asked for."""

from __future__ import annotations

import numpy as np
import pytest

from solver.branch import pressure_scale
from solver.continuation import BranchTracer
from solver.jig import jig
from solver.system import CoupledSystem
from tests.study import DENSITY, study_wing


def _tracer(system: CoupledSystem) -> BranchTracer:
    start = jig(system)
    return BranchTracer(
        system.evaluate,
        system.residual,
        np.array(start.state),
        system.scale(pressure_scale(system)),
    )


@pytest.fixture(scope="module")
def system() -> CoupledSystem:
    return CoupledSystem(study_wing(), 5.0)


def _same(a, b) -> None:
    assert len(a.points) == len(b.points)
    assert a.folded == b.folded and a.reason == b.reason and a.evaluations == b.evaluations
    for p, q in zip(a.points, b.points, strict=True):
        np.testing.assert_array_equal(p.state, q.state)
        np.testing.assert_array_equal(p.tangent, q.tangent)
        assert p.dynamic_pressure == q.dynamic_pressure and p.arclength == q.arclength


@pytest.mark.parametrize("first_limit", [20.0, 100.0, 250.0], ids=["20Pa", "100Pa", "250Pa"])
def test_a_branch_extended_later_is_the_branch_traced_at_once(system, first_limit):
    """The prefix property that makes cached branches harmless: a trace to 100 Pa later
    extended to the fold holds the same bits as one traced to the fold at once, and a view to
    100 Pa of the longer trace is the shorter trace."""
    at_once = _tracer(system)
    full = at_once.view(0.5 * DENSITY * 30.0**2)
    in_steps = _tracer(system)
    short = in_steps.view(first_limit)
    _same(short, at_once.view(first_limit))
    _same(in_steps.view(0.5 * DENSITY * 30.0**2), full)
    assert full.folded


def test_the_branch_rises_in_q_until_its_fold(system):
    branch = _tracer(system).view(0.5 * DENSITY * 30.0**2)
    pressures = [point.dynamic_pressure for point in branch.points]
    assert pressures[0] == 0.0
    assert np.all(np.diff(pressures) > 0)
    assert branch.fold is not None and branch.fold.dq_ds == pytest.approx(0.0, abs=1e-5)


def test_the_hermite_start_lies_within_one_newton_step_of_the_branch(system):
    branch = _tracer(system).view(0.5 * DENSITY * 25.0**2)
    q = 0.5 * DENSITY * 14.3**2
    start = branch.start_for(q)
    r0, r1 = system.residual(start)
    # O(ds^4) interpolation error: the residual there is small but not yet converged.
    assert np.max(np.abs(r0 + q * r1)) < 1e-3
