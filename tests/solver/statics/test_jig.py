"""solver.statics.jig: the rigid wing's solution, its lift, and the linear divergence pressure."""

from __future__ import annotations

import numpy as np
import pytest

import solver
from solver.numerics.evaluation import Evaluation
from solver.statics.jig import at_rest, jig
from solver.statics.system import CoupledSystem
from tests.study import DENSITY, flight, study_wing


def test_the_rigid_jig_has_no_deformation_and_solves_the_unloaded_equations():
    start = jig(CoupledSystem(study_wing(), 5.0))
    layout = CoupledSystem(study_wing(), 5.0).layout
    assert np.all(start.state[layout.heave] == 0) and np.all(start.state[layout.twist] == 0)
    assert np.max(np.abs(start.evaluation.r0)) < 1e-14  # r = r0 at q = 0
    assert not start.unloaded


def test_the_study_wings_rigid_lift_and_cl():
    """Section 14.2.1: "Rigid wing: L = 259.4 N, CL = 0.445" at 10 m/s."""
    equilibrium = solver.solve(study_wing(), flight(10.0))
    t = equilibrium.totals
    rigid_cl = t.rigid_lift / (equilibrium.dynamic_pressure * t.reference_area)
    assert f"L = {t.rigid_lift:.1f} N, CL = {rigid_cl:.3f}" == "L = 259.4 N, CL = 0.445"


def test_rigid_lift_scales_with_rho_v_squared():
    """Linear aerodynamics: the jig's lift is its CL times q S at any airspeed and density."""
    wing = study_wing()
    base = solver.solve(wing, flight(10.0, density=1.225)).totals.rigid_lift
    for velocity, density in ((6.0, 1.225), (14.0, 1.225), (10.0, 0.7)):
        other = solver.solve(wing, flight(velocity, density=density)).totals.rigid_lift
        assert other == pytest.approx(base * density * velocity**2 / (1.225 * 100.0), rel=1e-12)


def test_at_zero_alpha_the_jig_is_unloaded():
    assert jig(CoupledSystem(study_wing(), 0.0)).unloaded


def test_the_study_wings_linear_divergence_matches_the_notes():
    """shared/notes: q = 359.3 Pa, V = 24.22 m/s at the unloaded jig."""
    q_div = solver.linear_divergence_pressure(study_wing())
    assert q_div == pytest.approx(359.26, abs=0.01)
    assert solver.FlightCondition.velocity_for(q_div, DENSITY) == pytest.approx(24.22, abs=0.005)


def test_what_the_cache_keeps_of_the_jig_cannot_be_written():
    """Every answer from the jig starts from these arrays, and an answer may carry them: a
    caller writing into one must not change the next answer."""
    system = CoupledSystem(study_wing(), 5.0)
    kept = [jig(system).state, *_arrays(jig(system).evaluation), at_rest(system).beam]
    kept += _arrays(at_rest(system).evaluation)
    for array in kept:
        with pytest.raises(ValueError, match="read-only"):
            array[0] = 1.0


def _arrays(evaluation: Evaluation) -> list[np.ndarray]:
    return [evaluation.r0, evaluation.r1, evaluation.jacobian0, evaluation.jacobian1]
