"""solver.model.beam: the beam's rows, the outboard sums of the panel loads and the trapezoidal
rule along the swept elastic axis, against a point load worked by hand."""

from __future__ import annotations

import math

import casadi as ca
import numpy as np
import pytest

import solver
from solver.model.aerodynamics import LOADS
from solver.model.beam import DEG_PER_RAD, Beam, outboard_sum, structure_rows
from solver.model.layout import Layout

N = 5
Y = np.linspace(0.0, 2.0, N)
EI = np.linspace(4e3, 1e3, N)
GJ = np.linspace(5e2, 2e2, N)


def _rows(sweep: float, loads: np.ndarray, heave: np.ndarray, deformed: float) -> np.ndarray:
    """The beam's load rows of per-panel `loads` (LOADS M,) on a wing of `sweep` [deg]."""
    wing = solver.Wing.create(Y, 0.5, 0.4, EI, GJ, sweep=sweep)
    layout = Layout(N)
    p = ca.MX.sym("p", layout.n_parameters)
    load_symbol = ca.MX.sym("loads", LOADS * layout.n_panels)
    heave_symbol = ca.MX.sym("heave", N)
    beam = Beam(layout, layout.unpack(p))
    rows = beam.load_rows(load_symbol, heave_symbol, deformed)
    values = layout.wing_values(wing) | {"camber": np.zeros((N, 2)), "alpha": 0.0}
    parameters = layout.pack(values | {"deformed_axis": deformed})
    function = ca.Function("rows", [p, load_symbol, heave_symbol], [rows])
    return np.array(function(parameters, loads, heave)).ravel()


@pytest.mark.parametrize("sweep", [0.0, 25.0], ids=["straight", "swept"])
@pytest.mark.parametrize("deformed", [0.0, 1.0], ids=["undeformed_axis", "heaved_axis"])
def test_a_tip_panels_load_bends_and_twists_every_segment_as_worked_by_hand(sweep, deformed):
    """One force (Fx, Fy, Fz) on the tip strip's panel, at arm a along the axis, with torque tau
    about it: M_i = Fz (a - s_i), T_i = tau - d u_i (Fx cos - Fy sin), and the rows
    -h/2 (M_i/EI_i + M_{i+1}/EI_{i+1}) (bending) and -h/2 (180/pi)(T_i/GJ_i + ...) (torsion),
    h = diff(y) / cos(sweep). Round-off only."""
    layout = Layout(N)
    m = layout.n_panels
    fx, fy, fz, arm, tau = 3.0, -2.0, 40.0, 1.9, 7.0
    loads = np.zeros(LOADS * m)
    for part, value in enumerate((fx, fy, fz, fz * arm, tau)):
        loads[part * m + m - 1] = value
    heave = np.linspace(0.0, 0.1, N)
    ours = _rows(sweep, loads, heave, deformed)
    cos, sin = math.cos(math.radians(sweep)), math.sin(math.radians(sweep))
    s = Y / cos
    h = np.diff(s)
    moment = fz * (arm - s)
    moment[-1] = 0.0  # nothing outboard of the tip
    torque = tau - deformed * heave * (fx * cos - fy * sin)
    torque[-1] = 0.0
    bending = -h / 2 * (moment[:-1] / EI[:-1] + moment[1:] / EI[1:])
    torsion = -h / 2 * DEG_PER_RAD * (torque[:-1] / GJ[:-1] + torque[1:] / GJ[1:])
    np.testing.assert_allclose(ours, np.concatenate([bending, torsion]), rtol=1e-13, atol=1e-13)


def test_the_outboard_sum_runs_from_the_tip():
    strips = ca.MX.sym("strips", 3, 2)
    function = ca.Function("sum", [strips], [outboard_sum(strips)])
    values = np.array([[1.0, 10.0], [2.0, 20.0], [4.0, 40.0]])
    expected = [[7.0, 70.0], [6.0, 60.0], [4.0, 40.0], [0.0, 0.0]]
    np.testing.assert_array_equal(np.array(function(values)), expected)


def test_the_structure_rows_clamp_the_root_and_integrate_the_slope_by_trapezoids():
    layout = Layout(N)
    x = ca.MX.sym("x", layout.n_unknowns)
    h = ca.MX.sym("h", N - 1)
    function = ca.Function("rows", [x, h], [structure_rows(layout, x, h)])
    rng = np.random.default_rng(3)
    state, lengths = rng.normal(size=layout.n_unknowns), rng.uniform(0.1, 1.0, N - 1)
    rows = np.array(function(state, lengths)).ravel()
    heave, slope, twist = state[layout.heave], state[layout.slope], state[layout.twist]
    np.testing.assert_array_equal(rows[:3], [heave[0], slope[0], twist[0]])
    kinematics = np.diff(heave) - lengths * (slope[:-1] + slope[1:]) / 2
    np.testing.assert_allclose(rows[3 : 3 + N - 1], kinematics, rtol=1e-14, atol=1e-15)
    np.testing.assert_allclose(rows[layout.bending_rows], np.diff(slope), rtol=1e-14)
    np.testing.assert_allclose(rows[layout.torsion_rows], np.diff(twist), rtol=1e-14)
