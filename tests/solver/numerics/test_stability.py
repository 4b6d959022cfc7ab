"""solver.numerics.stability: the local divergence pressure, by power iteration when it can vouch
for its answer and by the full eigenvalue solve otherwise, and never a round-off value."""

from __future__ import annotations

import math

import numpy as np
import pytest

import solver
from solver.numerics import stability
from solver.statics.system import CoupledSystem
from tests.study import flight, rect_public, study_wing, tapered_forward_ea


def _full(evaluation, load_rows):
    """The reference: every eigenvalue mu of -K J0^-1 E, the largest positive real one."""
    n = evaluation.r0.size
    selector = np.zeros((n, load_rows.size))
    selector[load_rows, np.arange(load_rows.size)] = 1.0
    g = -evaluation.jacobian1[load_rows] @ np.linalg.solve(evaluation.jacobian0, selector)
    mu = np.linalg.eigvals(g)
    positive = mu[(np.abs(mu.imag) <= 1e-8 * np.linalg.norm(g)) & (mu.real > 0)].real
    return None if positive.size == 0 else 1.0 / positive.max()


CASES = [
    pytest.param(study_wing, 5.0, 10.0, id="study-10mps"),
    pytest.param(study_wing, 5.0, 21.0, id="study-21mps-near-fold"),
    pytest.param(rect_public, 4.0, 15.0, id="rect-public-15mps"),
    pytest.param(study_wing, -3.0, 12.0, id="study-negative-alpha"),
]


@pytest.mark.parametrize(("make_wing", "alpha", "velocity"), CASES)
def test_the_block_formula_and_power_iteration_agree_with_the_full_eigenvalue_solve(
    make_wing, alpha, velocity
):
    equilibrium = solver.solve(make_wing(), flight(velocity, alpha))
    layout = CoupledSystem(make_wing(), alpha).layout
    fast = stability.divergence_pressure(equilibrium.evaluation, layout)
    full = _full(equilibrium.evaluation, layout.load_rows)
    assert fast is not None and full is not None
    assert fast == pytest.approx(full, rel=1e-9)


def test_a_wing_that_cannot_diverge_has_no_divergence_pressure():
    """Elastic axis ahead of the quarter chord: every mu is negative (the full solve decides)."""
    equilibrium = solver.solve(tapered_forward_ea(), flight(20.0, 6.0))
    assert equilibrium.stability.local_divergence_pressure is None
    assert equilibrium.stability.margin == 0 and equilibrium.stability.stable


@pytest.mark.parametrize(
    "alpha", [1e-12, 1e-100, 1.3651542273090362e-160], ids=["1e-12", "1e-100", "1e-160"]
)
def test_a_wing_without_aerodynamic_torque_reports_no_divergence_pressure(alpha):
    """Found by fuzzing: with the elastic axis exactly at the quarter chord there is almost no
    aerodynamic torque, every mu is round-off (~1e-30), and 1/mu came out as 1e29 Pa or
    overflowed to inf. Round-off lies below NEGLIGIBLE ||G||: no divergence pressure."""
    wing = solver.Wing.create(np.linspace(0, 10, 30), 1.0, 0.25, 10.0, 100.0)
    point = solver.airspeed_sweep(
        wing, [12.02264434617413], solver.FlightCondition(None, alpha, 1.225)
    ).points[0]
    assert point.equilibrium is not None
    local = point.equilibrium.stability.local_divergence_pressure
    assert local is None


def test_the_margin_is_q_over_the_local_divergence_pressure():
    equilibrium = solver.solve(study_wing(), flight(15.0))
    s = equilibrium.stability
    assert s.local_divergence_pressure is not None and math.isfinite(s.local_divergence_pressure)
    assert s.margin == pytest.approx(equilibrium.dynamic_pressure / s.local_divergence_pressure)
    assert s.stable and 0 < s.margin < 1


def _swept_aft() -> solver.Wing:
    """A 25-deg aft-swept study wing, elastic axis at 30 % chord: its sweep's answers mostly
    need two Newton iterations, whose Jacobians lie one step from the answer."""
    wing = study_wing()
    return solver.Wing.create(
        wing.y, wing.chord, 0.3, wing.bending_stiffness, wing.torsional_stiffness, sweep=25.0
    )


@pytest.mark.parametrize(
    ("make_wing", "alpha"),
    [pytest.param(study_wing, 5.0, id="study"), pytest.param(_swept_aft, 5.0, id="swept-aft")],
)
def test_the_reported_divergence_pressure_is_that_of_the_converged_state(make_wing, alpha):
    """The verdict is computed on the Jacobians of Newton's last iterate, not re-evaluated at
    the converged state: the difference must stay at the linearisation's sensitivity times that
    last step (~1e-5 relative; 2e-4 at worst over 36 wings, and reading the Jacobians 1e-4 scaled
    away would already cost ~1e-3)."""
    wing = make_wing()
    system = CoupledSystem(wing, alpha)
    swept = solver.airspeed_sweep(
        wing, [6.0, 10.0, 12.0, 15.0, 18.0, 20.0], solver.FlightCondition(None, alpha, 1.225)
    )
    answers = [p.equilibrium for p in swept.points if p.equilibrium is not None]
    answers += [solver.solve(wing, e.flight) for e in answers]
    assert len(answers) >= 10
    for equilibrium in answers:
        reported = equilibrium.stability.local_divergence_pressure
        exact = stability.divergence_pressure(system.evaluate(equilibrium.state), system.layout)
        assert reported is not None and exact is not None
        assert reported == pytest.approx(exact, rel=1e-4)
