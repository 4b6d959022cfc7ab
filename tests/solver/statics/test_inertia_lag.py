"""solver.statics.inertia in lag layouts: the wing's weight about the deformed stations in three
dimensions (the lag beam's, `solver.model.lag_beam`), with its exact derivative."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import solver
from solver.inputs.mass import ConcentratedMass, MassModel
from solver.statics.inertia import GRAVITY, inertial_loads, lag_deformed_loads
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


def test_il3_a_wing_curved_in_its_plane_twists_under_its_weight_as_the_closed_form():
    """A wing curved into a circle in its own plane (psi = s / R, R = 6 m, L = 8 m, N = 33),
    0.75 kg/m and a 2 kg tip mass on its axis, straight in flap: every mass lies across the
    tangent of the stations inboard, so the weight twists them. Against the mass points' 3D
    cross products (the model's lumping, an independent sum): to 1e-12 of the largest torque
    (measured 8.5e-14 N m of 186); against the continuous closed form at the root,
    T(0) = -w R (L - R sin(L/R)) - m g R (1 - cos(L/R)) = -185.687 N m, the model's -185.724
    (2e-4: the lumping's O(h^2)); held to 1e-3. Nose down for a wing curved forward."""
    n, length, radius = 33, 8.0, 6.0
    store = ConcentratedMass.create(n - 1, mass=2.0, inertia=0.1, offset=0.0)
    wing = solver.Wing.create(
        np.linspace(0.0, length, n), 1.0, 0.5, 2e4, 1e4,
        mass=MassModel.create(n, 0.75, 0.5, 0.1, (store,)),
        in_plane_bending_stiffness=np.full(n, 4e5),
    )  # fmt: skip
    inertia = inertial_loads(wing, CoupledSystem.of(wing, 0.0, STRIP).layout)
    assert inertia is not None
    arc = np.asarray(wing.arc_length, dtype=float)
    psi = arc / radius
    _, torque, _ = lag_deformed_loads(inertia, wing, (np.zeros(n), np.zeros(n), psi))
    # The mass points in (e_s, n, e_c) and the stations' tangents, the weights down along n.
    line = np.stack([radius * np.sin(psi), np.zeros(n), -radius * (1 - np.cos(psi))], axis=1)
    tangent = np.stack([np.cos(psi), np.zeros(n), -np.sin(psi)], axis=1)
    weights = -GRAVITY * 0.75 * np.diff(arc)
    points = [((line[j] + line[j + 1]) / 2, weights[j], j) for j in range(n - 1)]
    points.append((line[-1], -GRAVITY * 2.0, n - 1))
    direct = np.array(
        [
            sum(np.cross(p - line[i], [0.0, f, 0.0]) @ tangent[i] for p, f, j in points if j >= i)
            for i in range(n)
        ]
    )
    assert np.abs(torque - direct).max() <= 1e-12 * np.abs(torque).max()
    closed = -0.75 * GRAVITY * radius * (length - radius * np.sin(length / radius)) - (
        2.0 * GRAVITY * radius * (1 - np.cos(length / radius))
    )
    assert closed == pytest.approx(-185.687, abs=1e-3)
    assert torque[0] == pytest.approx(closed, rel=1e-3)


def test_il4_the_answers_loads_carry_the_weight_the_rows_balance():
    """The loaded wing's equilibrium at 20 m/s and 3 deg, 1 g: the answer's inertial flap
    moment and torque are the one-g loads at its state times n cos(alpha), and its net loads
    (the lift's and the weight's, the in-plane moment's share included) balance its rows."""
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
    # The net loads (lift's and weight's) through the section's law and the trapezoid give the
    # answer's own rotations: the rows balance (measured 5e-14, 4e-11, 3e-13 of the largest
    # step in beta, psi, phi; held to 1e-8).
    assert st.lag_bending_moment is not None
    beta, psi, phi = rotations[0], rotations[2], np.radians(st.axis_twist)
    flap_s = np.cos(phi) * st.bending_moment - np.sin(phi) * st.lag_bending_moment
    lag_s = np.sin(phi) * st.bending_moment + np.cos(phi) * st.lag_bending_moment
    ei, gj = wing.bending_stiffness, wing.torsional_stiffness
    ei_lag = wing.in_plane_bending_stiffness
    assert ei_lag is not None
    beta_rate = np.cos(phi) * flap_s / ei + np.sin(phi) * lag_s / ei_lag
    psi_rate = (-np.sin(phi) * flap_s / ei + np.cos(phi) * lag_s / ei_lag) / np.cos(beta)
    twist_rate = st.torque / gj
    h = np.diff(np.asarray(wing.arc_length, dtype=float))

    def trapezoid(rate: np.ndarray) -> np.ndarray:
        return h / 2 * (rate[:-1] + rate[1:])

    mean_beta = (beta[:-1] + beta[1:]) / 2
    for residual, step in (
        (np.diff(beta) - trapezoid(beta_rate), np.diff(beta)),
        (np.diff(psi) - trapezoid(psi_rate), np.diff(psi)),
        (np.diff(phi) + np.sin(mean_beta) * np.diff(psi) - trapezoid(twist_rate), np.diff(phi)),
    ):
        assert np.abs(residual).max() <= 1e-8 * np.abs(step).max()
