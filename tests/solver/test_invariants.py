"""Physical invariants and analytic limits every equilibrium must satisfy, reference data aside.

Tolerances: Newton stops when the largest residual is <= 1e-10 (heave rows in m, slope rows
dimensionless, twist rows in deg, tangency rows per unit airspeed). Quantities that are exact
identities of the reported numbers are checked to round-off (1e-12 relative); statements that
compare two independent solves, or the reported loads with the solved state, get 1e-9: the
solver tolerance times the problem's conditioning (lift amplification <= 2.5 here), with a
margin of ~10.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import solver
from solver import compiled

AEROSANDBOX_SEA_LEVEL_DENSITY = 1.2249991558876672  # [kg/m^3]
ROUND_OFF = 1e-12
TWO_SOLVES = 1e-9


def relative_difference(ours, theirs) -> float:
    ours, theirs = np.atleast_1d(ours), np.atleast_1d(theirs)
    return float(np.max(np.abs(ours - theirs)) / np.max(np.abs(theirs)))


def study_wing(stiffness_factor: float = 1.0, elastic_axis: float = 0.40) -> solver.Wing:
    """The design study's wing (N = 30), optionally stiffer or with the elastic axis moved."""
    n = 30
    chords = np.sqrt(np.linspace(2, 0.02, n))
    return solver.Wing.create(
        y=np.linspace(0, 5, n),
        chord=chords,
        elastic_axis=elastic_axis,
        bending_stiffness=stiffness_factor * 2e4 * chords**3,
        torsional_stiffness=stiffness_factor * 1e3 * chords**3,
    )


def tapered_odd_wing() -> solver.Wing:
    """N = 17, linear taper, elastic axis ahead of the quarter chord, EI ~ c^2, GJ ~ c."""
    n = 17
    chords = 1.0 - 0.6 * np.linspace(0, 1, n)
    return solver.Wing.create(np.linspace(0, 6, n), chords, 0.15, 2.5e4 * chords**2, 1.5e3 * chords)


def flight(velocity: float, alpha: float = 5.0, density: float = AEROSANDBOX_SEA_LEVEL_DENSITY):
    return solver.FlightCondition(velocity=velocity, alpha=alpha, density=density)


WINGS = {"study": study_wing, "tapered_forward_ea": tapered_odd_wing}


@pytest.fixture(scope="module")
def cruise() -> solver.Equilibrium:
    return solver.solve(study_wing(), flight(12.0))


# --- Limits -----------------------------------------------------------------------------------


def test_a_very_stiff_wing_gives_the_rigid_answer():
    """At 1e6 times the study's stiffness the lift is the rigid lift and the wing hardly moves:
    the flexible wing gains 17 % at 10 m/s, so the remaining gain must be ~1.7e-7."""
    e = solver.solve(study_wing(stiffness_factor=1e6), flight(10.0))
    assert abs(e.lift / e.rigid_lift - 1) < 1e-6
    assert np.max(np.abs(e.heave)) < 1e-6 * e.wing.semispan
    assert np.max(np.abs(e.twist)) < 1e-5  # [deg]


def test_the_departure_from_rigid_falls_in_proportion_to_the_compliance():
    """Small-deformation limit: L/L_rigid - 1 is linear in 1/stiffness. Ten times stiffer, ten
    times less gain, up to the next order in the compliance (~1e-3 relative here)."""
    gain = {
        factor: solver.solve(study_wing(factor), flight(10.0)).lift_amplification - 1
        for factor in (1e3, 1e4)
    }
    assert gain[1e3] > 0
    assert gain[1e3] / gain[1e4] == pytest.approx(10.0, rel=1e-3)


def test_at_zero_alpha_the_unloaded_jig_is_the_equilibrium():
    """Flat, symmetric sections at zero incidence carry no load, so nothing deforms."""
    e = solver.solve(study_wing(), flight(15.0, alpha=0.0))
    for values in (e.heave, e.slope, e.twist, e.panel_lift, e.bending_moment, e.torque):
        assert np.max(np.abs(values)) < 1e-12
    assert abs(e.lift) < 1e-9


# --- Scaling and symmetry ---------------------------------------------------------------------


def test_rigid_lift_scales_with_rho_v_squared():
    """Linear aerodynamics: the jig's lift is its CL times q S at any airspeed and density."""
    wing = study_wing()
    base = solver.solve(wing, flight(10.0, density=1.225))
    for velocity, density in ((6.0, 1.225), (14.0, 1.225), (10.0, 0.7)):
        other = solver.solve(wing, flight(velocity, density=density))
        expected = base.rigid_lift * (density * velocity**2) / (1.225 * 10.0**2)
        assert other.rigid_lift == pytest.approx(expected, rel=ROUND_OFF)


def test_the_equilibrium_depends_on_airspeed_and_density_only_through_q():
    """The residual is r0 + q r1: (V, rho) and (V', rho') with one q give one equilibrium."""
    wing = study_wing()
    sea_level = solver.solve(wing, flight(15.0, density=1.225))
    velocity_aloft = 15.0 * math.sqrt(1.225 / 0.8)
    aloft = solver.solve(wing, flight(velocity_aloft, density=0.8))
    assert aloft.dynamic_pressure == pytest.approx(sea_level.dynamic_pressure, rel=ROUND_OFF)
    for name in ("heave", "twist", "bending_moment", "torque", "panel_lift"):
        assert relative_difference(getattr(aloft, name), getattr(sea_level, name)) < TWO_SOLVES
    assert aloft.lift == pytest.approx(sea_level.lift, rel=TWO_SOLVES)


@pytest.mark.parametrize("wing_name", list(WINGS))
def test_negative_alpha_mirrors_every_load_and_deformation(wing_name: str):
    """Reflecting the problem in the x-y plane maps alpha to -alpha: heave, twist, lift and
    torques change sign; chordwise force and induced drag do not."""
    wing = WINGS[wing_name]()
    up = solver.solve(wing, flight(14.0, alpha=4.0))
    down = solver.solve(wing, flight(14.0, alpha=-4.0))
    for name in ("heave", "slope", "twist", "shear", "bending_moment", "torque", "panel_lift"):
        assert relative_difference(-getattr(down, name), getattr(up, name)) < TWO_SOLVES, name
    assert -down.lift == pytest.approx(up.lift, rel=TWO_SOLVES)
    assert down.induced_drag == pytest.approx(up.induced_drag, rel=TWO_SOLVES)
    assert -down.rigid_lift == pytest.approx(up.rigid_lift, rel=ROUND_OFF)


def test_the_twist_sign_follows_the_elastic_axis():
    """Lift acts at the quarter chord: an elastic axis behind it twists the wing nose-up and
    adds lift (wash-in), one ahead of it nose-down and relieves lift (study, section 14.3)."""
    behind = solver.solve(study_wing(elastic_axis=0.40), flight(8.0))
    ahead = solver.solve(study_wing(elastic_axis=0.15), flight(8.0))
    assert np.all(behind.twist[1:] > 0) and behind.lift > behind.rigid_lift
    assert np.all(ahead.twist[1:] < 0) and ahead.lift < ahead.rigid_lift


# --- Consistency of the reported equilibrium --------------------------------------------------


def test_panels_are_ordered_root_to_tip_within_their_strips(cruise):
    """Panel j's load acts between stations j and j + 1, root first."""
    y = cruise.y
    assert np.all(np.diff(cruise.panel_y) > 0)
    assert np.all((y[:-1] < cruise.panel_y) & (cruise.panel_y < y[1:]))


def test_internal_loads_are_the_outboard_sums_of_the_panel_loads(cruise):
    """S_i = sum_{j>=i} F_j, M_i = sum_{j>=i} F_j (y_j - y_i), T_i = sum_{j>=i} tau_j, written
    out panel by panel; in particular the root shear is the half-wing's lift force."""
    y, force, arm, tau = cruise.y, cruise.panel_lift, cruise.panel_y, cruise.panel_torque
    shear = [sum(force[j] for j in range(i, len(force))) for i in range(len(y))]
    moment = [sum(force[j] * (arm[j] - y[i]) for j in range(i, len(force))) for i in range(len(y))]
    torque = [sum(tau[j] for j in range(i, len(tau))) for i in range(len(y))]
    assert relative_difference(cruise.shear, shear) < ROUND_OFF
    assert relative_difference(cruise.bending_moment, moment) < ROUND_OFF
    assert relative_difference(cruise.torque, torque) < ROUND_OFF
    assert cruise.shear[0] == pytest.approx(np.sum(force), rel=ROUND_OFF)
    # Free tip: nothing is outboard of it.
    assert cruise.shear[-1] == cruise.bending_moment[-1] == cruise.torque[-1] == 0


def test_lift_is_the_vertical_force_rotated_into_wind_axes(cruise):
    """L = Fz cos a - Fx sin a and D = Fx cos a + Fz sin a, so Fz (both halves, twice the
    right half's panel forces) = L cos a + D sin a."""
    alpha = math.radians(cruise.flight.alpha)
    vertical = cruise.lift * math.cos(alpha) + cruise.induced_drag * math.sin(alpha)
    assert 2 * np.sum(cruise.panel_lift) == pytest.approx(vertical, rel=ROUND_OFF)


def test_lift_per_span_is_panel_lift_over_the_jig_strip_width(cruise):
    widths = np.diff(cruise.y)
    assert relative_difference(cruise.panel_lift_per_span * widths, cruise.panel_lift) < ROUND_OFF


def test_the_reported_loads_satisfy_the_beam_equations(cruise):
    """Trapezoidal EI u'' = M and GJ theta' = T, clamped root: the loads computed from the
    panel forces (numpy) and the state Newton solved (CasADi residual) belong together, to the
    Newton tolerance (1e-10 in the equations' units, 1e-9 here for summation order)."""
    e, wing = cruise, cruise.wing
    h = np.diff(e.y)

    def trapezoid(values):
        return h * (values[:-1] + values[1:]) / 2

    assert max(abs(e.heave[0]), abs(e.slope[0]), abs(e.twist[0])) <= 1e-10  # the clamps' rows
    assert np.max(np.abs(np.diff(e.heave) - trapezoid(e.slope))) < TWO_SOLVES
    curvature = e.bending_moment / wing.bending_stiffness
    assert np.max(np.abs(np.diff(e.slope) - trapezoid(curvature))) < TWO_SOLVES
    twist_rate = np.degrees(e.torque / wing.torsional_stiffness)
    assert np.max(np.abs(np.diff(e.twist) - trapezoid(twist_rate))) < TWO_SOLVES


# --- The exact Jacobian ---------------------------------------------------------------------


def test_the_exact_jacobian_matches_central_finite_differences():
    """J0 and J1 against central differences at a random, moderately deformed state.

    Step 1e-5: truncation ~h^2 and round-off ~1e-16/h are both ~1e-11 relative (observed
    5e-11 row-wise). 1e-7 leaves a margin of 1000 and still catches any missing chain-rule
    path, whose terms are 1e-3 to 1 of a row's largest entry.
    """
    wing = tapered_odd_wing()
    model = compiled.model_for(wing.n_stations)
    layout = model.layout
    p = wing.parameters(6.0)
    rng = np.random.default_rng(20240611)
    x = np.zeros(layout.n_unknowns)
    x[layout.heave] = rng.uniform(-0.2, 0.2, wing.n_stations)  # [m]
    x[layout.slope] = rng.uniform(-0.05, 0.05, wing.n_stations)  # [-]
    x[layout.twist] = rng.uniform(-5.0, 5.0, wing.n_stations)  # [deg]
    x[layout.circulation] = rng.uniform(0.0, 0.1, wing.n_stations - 1)  # [m]
    exact = model.evaluate(x, p)

    step = 1e-5
    fd0 = np.zeros_like(exact.jacobian0)
    fd1 = np.zeros_like(exact.jacobian1)
    for k in range(layout.n_unknowns):
        dx = np.zeros_like(x)
        dx[k] = step
        plus, minus = model.evaluate(x + dx, p), model.evaluate(x - dx, p)
        fd0[:, k] = (plus.r0 - minus.r0) / (2 * step)
        fd1[:, k] = (plus.r1 - minus.r1) / (2 * step)

    for jacobian, finite_difference in ((exact.jacobian0, fd0), (exact.jacobian1, fd1)):
        row_scale = np.max(np.abs(jacobian), axis=1, keepdims=True)
        loaded = row_scale[:, 0] > 0
        error = np.abs(jacobian - finite_difference)
        assert np.max(error[loaded] / row_scale[loaded]) < 1e-7
        assert np.max(np.abs(finite_difference[~loaded]), initial=0.0) < 1e-9
