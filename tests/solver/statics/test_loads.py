"""solver.statics.loads: the reported loads are the outboard sums of the panel loads, rotated into
wind axes, and satisfy the beam equations the solver solved.

Tolerances: exact identities of the reported numbers to round-off (1e-12 relative); the loads
against the solved state (numpy against CasADi) to the Newton tolerance (1e-9, with a margin for
summation order).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import solver
from tests.study import flight, relative_difference, study_wing

ROUND_OFF = 1e-12
TWO_SOLVES = 1e-9


@pytest.fixture(scope="module")
def cruise() -> solver.Equilibrium:
    return solver.solve(study_wing(), flight(12.0))


def test_panels_are_ordered_root_to_tip_within_their_strips(cruise):
    """Panel j's load acts between stations j and j + 1, root first."""
    y, panel_y = cruise.stations.y, cruise.panels.y
    assert np.all(np.diff(panel_y) > 0)
    assert np.all((y[:-1] < panel_y) & (panel_y < y[1:]))


def test_internal_loads_are_the_outboard_sums_of_the_panel_loads(cruise):
    """S_i = sum_{j>=i} F_j, M_i = sum_{j>=i} F_j (y_j - y_i), T_i = sum_{j>=i} tau_j, written
    out panel by panel; in particular the root shear is the half-wing's lift force."""
    s, p = cruise.stations, cruise.panels
    y, force, arm, tau = s.y, p.lift, p.y, p.torque
    shear = [sum(force[j] for j in range(i, len(force))) for i in range(len(y))]
    moment = [sum(force[j] * (arm[j] - y[i]) for j in range(i, len(force))) for i in range(len(y))]
    torque = [sum(tau[j] for j in range(i, len(tau))) for i in range(len(y))]
    assert relative_difference(s.shear, shear) < ROUND_OFF
    assert relative_difference(s.bending_moment, moment) < ROUND_OFF
    assert relative_difference(s.torque, torque) < ROUND_OFF
    assert s.shear[0] == pytest.approx(np.sum(force), rel=ROUND_OFF)
    # Free tip: nothing is outboard of it.
    assert s.shear[-1] == s.bending_moment[-1] == s.torque[-1] == 0


def test_lift_is_the_vertical_force_rotated_into_wind_axes(cruise):
    """L = Fz cos a - Fx sin a and D = Fx cos a + Fz sin a, so Fz (both halves, twice the
    right half's panel forces) = L cos a + D sin a."""
    alpha = math.radians(cruise.flight.alpha)
    t = cruise.totals
    vertical = t.lift * math.cos(alpha) + t.induced_drag * math.sin(alpha)
    assert 2 * np.sum(cruise.panels.lift) == pytest.approx(vertical, rel=ROUND_OFF)


def test_lift_per_span_is_panel_lift_over_the_jig_strip_width(cruise):
    widths = np.diff(cruise.stations.y)
    p = cruise.panels
    assert relative_difference(p.lift_per_span * widths, p.lift) < ROUND_OFF


def test_coefficients_and_totals_restate_the_loads(cruise):
    t, q = cruise.totals, cruise.dynamic_pressure
    assert pytest.approx(t.lift / (q * t.reference_area), rel=ROUND_OFF) == t.CL
    assert t.CDi == pytest.approx(t.induced_drag / (q * t.reference_area), rel=ROUND_OFF)
    assert t.CL_deformed_area == pytest.approx(t.lift / (q * t.deformed_area), rel=ROUND_OFF)
    assert t.lift_amplification == pytest.approx(t.lift / t.rigid_lift, rel=ROUND_OFF)
    assert t.tip_twist == cruise.stations.twist[-1]
    assert t.root_bending_moment == cruise.stations.bending_moment[0]


def test_the_reported_loads_satisfy_the_beam_equations(cruise):
    """Trapezoidal EI u'' = M and GJ theta' = T, clamped root."""
    s, wing = cruise.stations, cruise.wing
    h = np.diff(s.y)

    def trapezoid(values):
        return h * (values[:-1] + values[1:]) / 2

    assert max(abs(s.heave[0]), abs(s.slope[0]), abs(s.twist[0])) <= 1e-10  # the clamps' rows
    assert np.max(np.abs(np.diff(s.heave) - trapezoid(s.slope))) < TWO_SOLVES
    curvature = s.bending_moment / wing.bending_stiffness
    assert np.max(np.abs(np.diff(s.slope) - trapezoid(curvature))) < TWO_SOLVES
    twist_rate = np.degrees(s.torque / wing.torsional_stiffness)
    assert np.max(np.abs(np.diff(s.twist) - trapezoid(twist_rate))) < TWO_SOLVES


def test_the_rigid_distribution_is_the_stiff_wings():
    """panels.rigid_lift_per_span: the jig's own lattice solution; a wing a million times
    stiffer deforms by ~1e-6 of the study wing's, so its lift per span matches to ~1e-6."""
    stiff = solver.solve(study_wing(stiffness_scale=1e6), flight(12.0))
    np.testing.assert_allclose(
        stiff.panels.lift_per_span, stiff.panels.rigid_lift_per_span, rtol=2e-6
    )
    cruise = solver.solve(study_wing(), flight(12.0))
    np.testing.assert_array_equal(
        cruise.panels.rigid_lift_per_span, stiff.panels.rigid_lift_per_span
    )
