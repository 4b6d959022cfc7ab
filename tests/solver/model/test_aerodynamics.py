"""solver.model.aerodynamics: the air's onset, the Kutta-Joukowski loads and their moments about
the elastic axis, and tangency, on the lattice of a wing read by name."""

from __future__ import annotations

import math

import casadi as ca
import numpy as np

import solver
from solver.model.aerodynamics import LOADS, ROLL, aero_function, lattice_function, onset
from solver.model.geometry import chordwise_nodes
from solver.model.layout import Layout

N, K = 4, 2


def test_a_roll_rate_adds_the_air_seen_from_the_rolling_wing():
    """p about x (right wing up) moves a point at (y, z) by p (0, -z, y): the air it sees is
    the freestream plus (p / V) (0, z, -y) per unit V."""
    points = ca.SX.sym("points", 3, 2)
    rate = ca.SX.sym("rate")
    function = ca.Function("onset", [points, rate], [onset(ca.SX(4.0), points, rate)])
    where = np.array([[0.1, 0.2], [1.0, 3.0], [0.05, -0.2]])
    air = np.array(function(where, 0.3))
    freestream = [math.cos(math.radians(4.0)), 0.0, math.sin(math.radians(4.0))]
    expected = np.array(freestream)[:, None] + 0.3 * np.vstack([[0, 0], where[2], -where[1]])
    np.testing.assert_allclose(air, expected, rtol=1e-15, atol=1e-16)


def _wing() -> solver.Wing:
    return solver.Wing.create(
        np.linspace(0, 3, N), [1.0, 0.9, 0.8, 0.7], 0.35, 1e4, 1e3, sweep=15.0, airfoil="naca2412"
    )


def _values(layout: Layout, flow: bool, roll_rate: float) -> np.ndarray:
    """The parameter vector of `_wing` at alpha 5 deg (the flow model's with `flow`)."""
    wing = _wing()
    camber = wing.camber_at(chordwise_nodes(K))
    values = layout.wing_values(wing) | {"camber": camber, "alpha": 5.0, "deformed_axis": 0.0}
    if not flow:
        return layout.pack(values)
    flows = {"image": 1.0, "image_jacobian": 1.0, "roll_rate": roll_rate}
    flows |= {"control": np.zeros((N, K + 1)), "direction": np.zeros(layout.n_unknowns)}
    return layout.pack(values | flows, flow=True)


def _glue(flow: bool, roll_rate: float = 0.2):
    """The aerodynamic glue's values at a deformed state of a swept, cambered wing: its
    tangency and loads, and the state, circulation and induced velocities they were taken at."""
    layout = Layout(N, K)
    rng = np.random.default_rng(5)
    z = np.concatenate([rng.uniform(0, 0.1, N), rng.uniform(0, 0.02, N), rng.uniform(-2, 2, N)])
    g = rng.uniform(0.0, 0.1, layout.n_panels)
    induced_t = rng.normal(scale=0.05, size=3 * layout.n_panels)
    induced_f = rng.normal(scale=0.05, size=3 * layout.n_panels)
    p = _values(layout, flow, roll_rate)
    tangency, loads = aero_function(layout, False, flow)(z, g, p, induced_t, induced_f)
    return np.array(tangency).ravel(), np.array(loads).ravel(), (z, g, induced_f)


def test_the_loads_are_kutta_joukowskis_and_their_moments_are_about_the_elastic_axis():
    """F = 2 (V_local x l) g per unit q is normal to the local air and to the bound leg; the
    arm and the torque are the force point's and the moment's components along e_s =
    (sin, cos, 0), the flow model's rolling moment its component along x. Round-off only."""
    layout = Layout(N, K)
    m = layout.n_panels
    _, loads, (z, g, induced_f) = _glue(flow=True)
    fx, fy, fz, moment_arm, torque, roll = (loads[i * m : (i + 1) * m] for i in range(6))
    assert ROLL == LOADS == 5 and loads.size == (LOADS + 1) * m
    lattice = lattice_function(layout)(z, _values(layout, False, 0.0))
    left, right, _, center = (np.array(v) for v in lattice[:4])
    force = np.vstack([fx, fy, fz])
    air = np.array(onset(ca.DM(5.0), ca.DM(center), ca.DM(0.2))) + induced_f.reshape(m, 3).T
    leg = right - left
    scale = np.abs(force).max() * np.abs(air).max()
    np.testing.assert_allclose(np.sum(force * air, axis=0), 0.0, atol=1e-14 * scale)
    np.testing.assert_allclose(np.sum(force * leg, axis=0), 0.0, atol=1e-14 * scale)
    np.testing.assert_allclose(force, 2 * np.cross(air.T, leg.T).T * g, rtol=1e-13, atol=1e-15)
    sweep = math.radians(_wing().sweep)
    e_s = np.array([math.sin(sweep), math.cos(sweep), 0.0])
    np.testing.assert_allclose(moment_arm, fz * (e_s @ center), rtol=1e-13)
    moments = np.cross(center.T, force.T)
    np.testing.assert_allclose(torque, moments @ e_s, rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(roll, moments[:, 0], rtol=1e-12, atol=1e-15)


def test_the_flow_models_glue_is_the_symmetric_ones_without_a_roll_rate():
    """The flow model's functions read their own slots by name: at zero roll rate its tangency
    and its first five loads are the symmetric model's, to the bit."""
    m = Layout(N, K).n_panels
    tangency, loads, _ = _glue(flow=False)
    flow_tangency, flow_loads, _ = _glue(flow=True, roll_rate=0.0)
    np.testing.assert_array_equal(flow_tangency, tangency)
    np.testing.assert_array_equal(flow_loads[: LOADS * m], loads)
