"""solver.statics.inertia in lag layouts: the wing's weight about the deformed stations in three
dimensions (the lag beam's, `solver.model.lag_beam`), with its exact derivative."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import solver
from solver.inputs.mass import ConcentratedMass, MassModel
from solver.statics.inertia import inertial_loads, lag_deformed_loads
from solver.statics.system import CoupledSystem
from tests.solver.model.test_hale_wing import hale_wing

STRIP = solver.SolverOptions(structure="geometrically_exact", aerodynamics="strip")
HANGING = solver.FlightCondition(1.0, 0.0, 0.0889, load_factor=1.0)


def _lagging(wing: solver.Wing, stiffness: float = 4e6) -> solver.Wing:
    return dataclasses.replace(wing, in_plane_bending_stiffness=np.full(wing.n_stations, stiffness))


def test_il1_a_hanging_wing_with_its_centre_of_gravity_on_its_axis_droops_as_the_planar_beam():
    """The HALE wing at 1 g without lift (tests/solver/model/test_exact_beam.py: the elastica
    of its weight, 2.93123 m; the planar exact beam 2.931213 m at N = 17): nothing bends it in
    its plane or twists it, so the lag beam hangs as the planar one to round-off (measured
    1 ulp), its lag and lag moment zero."""
    planar = solver.solve(hale_wing(17), HANGING, options=STRIP)
    lagging = solver.solve(_lagging(hale_wing(17)), HANGING, options=STRIP)
    assert lagging.stations.axis_z[-1] == pytest.approx(planar.stations.axis_z[-1], rel=1e-12)
    assert lagging.stations.bending_moment[0] == pytest.approx(
        planar.stations.bending_moment[0], rel=1e-12
    )
    assert lagging.stations.lag is not None and lagging.stations.lag_bending_moment is not None
    assert np.all(lagging.stations.lag == 0.0)
    assert np.all(lagging.stations.lag_bending_moment == 0.0)


def _loaded_wing() -> solver.Wing:
    """A small HALE-like wing with its centre of gravity aft of the axis and a tip store
    offset aft: the weight twists it."""
    mass = MassModel.create(
        9, 0.75, 0.6, 0.1, (ConcentratedMass.create(8, mass=2.0, inertia=0.1, offset=0.2),)
    )
    wing = solver.Wing.create(np.linspace(0.0, 8.0, 9), 1.0, 0.5, 2e4, 1e4, mass=mass)
    return _lagging(wing, 4e5)


def test_il2_the_residuals_jacobian_with_the_weight_is_its_derivative():
    """J0 + q J1 of a lag layout carrying its weight at load factor 2.5 against central
    differences of r0 + q r1 (step 1e-6) at flap and lag rotations up to 0.6 rad, twists up to
    10 deg: every entry to 1e-7 of the largest (as the lag beam's own test)."""
    wing = _loaded_wing()
    q = 20.0
    system = CoupledSystem.of(wing, 3.0, STRIP).with_inertia(2.5, q)
    layout = system.layout
    assert layout.lag and system.inertia is not None
    rng = np.random.default_rng(11)
    n = layout.n
    x = np.zeros(layout.n_unknowns)
    x[layout.heave] = rng.uniform(-0.5, 0.5, n)
    x[layout.slope] = rng.uniform(-0.6, 0.6, n)
    x[layout.twist] = rng.uniform(-10.0, 10.0, n)
    x[layout.lag_displacement] = rng.uniform(-0.3, 0.3, n)
    x[layout.lag_rotation] = rng.uniform(-0.6, 0.6, n)
    x[layout.circulation] = rng.uniform(-0.3, 0.3, layout.n_panels)
    step = 1e-6
    evaluation = system.evaluate(x)
    jacobian = evaluation.jacobian0 + q * evaluation.jacobian1
    numeric = np.empty_like(jacobian)
    for j in range(x.size):
        dx = np.zeros_like(x)
        dx[j] = step
        r0_plus, r1_plus = system.residual(x + dx)
        r0_minus, r1_minus = system.residual(x - dx)
        numeric[:, j] = (r0_plus - r0_minus + q * (r1_plus - r1_minus)) / (2 * step)
    assert np.max(np.abs(jacobian - numeric)) <= 1e-7 * np.max(np.abs(jacobian))


def test_il3_a_lagged_wings_weight_twists_it_through_the_lag():
    """A straight cantilever (beta = phi = 0) turned in its plane by a uniform psi: its stations
    lie at S_i = cos(psi) s_i, v_i = -sin(psi) s_i (s the arc length), and the weight's moment
    about each station, -sum_p F_p (v_p - v_i) e_s + sum_p F_p (S_p - S_i) e_c plus the static
    moments' T_jig e_s, projected on the turned tangent and flap axis, is the torque
    cos(psi) M_s - sin(psi) M_c and the flap moment sin(psi) M_s + cos(psi) M_c, to
    round-off; the lag's arm is what twists it (its part of M_s is tens of N m here)."""
    wing = _loaded_wing()
    layout = CoupledSystem.of(wing, 0.0, STRIP).layout
    inertia = inertial_loads(wing, layout)
    assert inertia is not None
    n = wing.n_stations
    psi = 0.2
    arc = np.asarray(wing.arc_length, dtype=float)
    along, lag = np.cos(psi) * arc, -np.sin(psi) * arc
    flap, torque, lag_moment = lag_deformed_loads(
        inertia, wing, (np.zeros(n), np.zeros(n), np.full(n, psi))
    )
    about_s = -inertia.station_weights @ lag + inertia.torque
    about_c = inertia.station_weights @ along
    np.testing.assert_allclose(
        torque, np.cos(psi) * about_s - np.sin(psi) * about_c, rtol=0, atol=1e-12 * 1e3
    )
    np.testing.assert_allclose(
        flap, np.sin(psi) * about_s + np.cos(psi) * about_c, rtol=0, atol=1e-12 * 1e3
    )
    assert np.all(lag_moment == 0.0)  # beta = 0: the weight has no moment about the normal
    # The lag's own share of the torque: the weight's arm across the jig axis.
    assert np.max(np.abs(inertia.station_weights @ lag)) > 10.0


def test_il4_the_answers_loads_carry_the_weight_the_rows_balance():
    """The loaded wing's equilibrium at 20 m/s and 3 deg, 1 g: the answer's inertial flap
    moment and torque are the one-g loads at its state times n cos(alpha), and its net loads
    the lift's and these."""
    wing = _loaded_wing()
    flight = solver.FlightCondition(20.0, 3.0, 0.0889, load_factor=1.0)
    answer = solver.solve(wing, flight, options=STRIP)
    st = answer.stations
    assert st.lag is not None and abs(st.lag[-1]) > 1e-4 and abs(st.twist[-1]) > 0.5
    layout = CoupledSystem.of(wing, 3.0, STRIP).layout
    inertia = inertial_loads(wing, layout)
    assert inertia is not None
    rotations = (
        np.radians(st.bending_rotation),
        st.axis_twist,
        np.radians(st.lag_rotation),
    )
    flap, torque, _ = lag_deformed_loads(inertia, wing, rotations)
    normal = np.cos(np.radians(3.0))
    np.testing.assert_allclose(st.inertial_bending_moment, normal * flap, rtol=1e-10, atol=1e-9)
    np.testing.assert_allclose(st.inertial_torque, normal * torque, rtol=1e-10, atol=1e-9)
