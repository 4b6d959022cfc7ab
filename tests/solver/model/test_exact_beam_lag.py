"""solver.model.lag_beam: lag (in-plane) bending in the geometrically exact beam against the
elastica turned into the wing's plane (a pure in-plane end moment rolls the cantilever into a
circle; a dead in-plane tip load bends it as Bisshopp and Drucker's table), the constitutive
law in the twisted section's axes in closed form, the residual's Jacobian against central
differences, the small-deflection limit (today's exact beam), and the refusals (422 naming the
field) where lag is not taken.

The table: tests/solver/model/test_exact_beam.py (Bisshopp and Drucker, Q. Appl. Math. 3,
1945), the same elastica in the plane (e_s, e_c) instead of (e_s, n).
"""

from __future__ import annotations

import math

import casadi as ca
import numpy as np
import pytest

import solver
from solver.model.aerodynamics import LOADS
from solver.model.exact_beam import EXACT_LOADS
from solver.model.geometry import lag_reference_line
from solver.model.lag_beam import LagBeam, lag_structure_rows, section_moments
from solver.model.layout import Layout
from solver.statics.system import CoupledSystem
from tests.solver.model.test_exact_beam import BISSHOPP_DRUCKER

LENGTH, EI, GJ, EI_LAG = 2.0, 3.0e3, 1.0e3, 7.0e3
EXACT = solver.SolverOptions(structure="geometrically_exact")


def _scale(factors, matrix):  # type: ignore[no-untyped-def]
    return ca.repmat(factors, 1, matrix.size2()) * matrix


def _cantilever(n: int, ei_lag: float = EI_LAG, twist: float = 0.0):  # type: ignore[no-untyped-def]
    """A uniform straight cantilever's lag layout, numeric parameters, and its beam on symbols
    of its own: (layout, p, p_sym, z, beam)."""
    layout = Layout(n, beam="geometrically_exact", lag=True)
    wing = solver.Wing.create(
        np.linspace(0.0, LENGTH, n), 0.5, 0.4, EI, GJ, in_plane_bending_stiffness=ei_lag
    )
    values = layout.wing_values(wing) | {"camber": np.zeros((n, 2)), "alpha": 0.0}
    p = layout.pack(values | {"deformed_axis": 1.0})
    p_sym, z = ca.MX.sym("p", layout.n_parameters), ca.MX.sym("z", 5 * n)
    return layout, p, p_sym, z, LagBeam(layout, p_sym, z)


def _place(layout: Layout, rows: ca.MX) -> ca.MX:
    """The beam's 3(N-1) load rows at their places among the 5N structure rows."""
    strips = layout.n_strips
    return ca.vertcat(
        ca.MX(3 + strips, 1), rows[: 2 * strips], ca.MX(2 + strips, 1), rows[2 * strips :]
    )


def _solve(layout, p, p_sym, z, load_rows, steps: int = 1) -> np.ndarray:  # type: ignore[no-untyped-def]
    """z (5N,) where the structure rows plus the load rows vanish (Newton, CasADi's exact
    Jacobian), the load in `steps` equal increments."""
    n = layout.n
    scale = ca.MX.sym("scale")
    h = ca.DM(np.diff(np.linspace(0.0, LENGTH, n)))
    residual = lag_structure_rows(layout, z, h) + _place(layout, load_rows(scale))
    function = ca.Function("r", [z, p_sym, scale], [residual, ca.jacobian(residual, z)])
    state = np.zeros(5 * n)
    for step in range(1, steps + 1):
        for _ in range(50):
            r, jacobian = (np.array(v) for v in function(state, p, step / steps))
            state = state - np.linalg.solve(jacobian, r.ravel())
            if np.max(np.abs(r)) < 1e-13:
                break
    return state


@pytest.mark.parametrize(
    "angle", [1.0, math.pi, 1.9 * math.pi], ids=["one_radian", "half_circle", "nearly_closed"]
)
def test_a_pure_in_plane_end_moment_rolls_the_cantilever_into_a_circle_in_the_wings_plane(angle):
    """M0 n at every station (a couple about the wing's normal at the tip): psi = M0 s /
    EI_lag, the axis the circle r(s) = R sin(s/R) e_s - R (1 - cos(s/R)) e_c, R = EI_lag / M0
    (turned forward, toward -e_c, for M0 > 0); no flap, no twist. Each segment is the chord of
    its arc: the circle to round-off, at any N."""
    n = 9
    layout, p, p_sym, z, beam = _cantilever(n)
    moment = EI_LAG * angle / LENGTH
    zero = ca.MX(n, 1)

    def load_rows(scale: ca.MX) -> ca.MX:
        # The moment about the root, the forces nil: M_i = M0 n at each station.
        moments = section_moments(
            (zero, scale * moment * ca.DM.ones(n, 1), zero),
            (zero, zero, zero),
            lag_reference_line(z[n : 2 * n], z[4 * n :], ca.DM(np.diff(np.linspace(0, 2, n)))),
            z[n : 2 * n],
            z[4 * n :],
            _scale,
        )
        return beam.lag_rows(beam.rates_of(moments, z))

    state = _solve(layout, p, p_sym, z, load_rows)
    s, radius = np.linspace(0.0, LENGTH, n), EI_LAG / moment
    psi = state[4 * n :]
    along, heave, lag = lag_reference_line(state[n : 2 * n], psi, np.diff(s))
    np.testing.assert_allclose(psi, moment * s / EI_LAG, rtol=0, atol=1e-12)
    np.testing.assert_allclose(along, radius * np.sin(s / radius), rtol=0, atol=1e-12 * LENGTH)
    np.testing.assert_allclose(lag, -radius * (1 - np.cos(s / radius)), rtol=0, atol=1e-12)
    np.testing.assert_allclose(state[3 * n : 4 * n], lag, rtol=0, atol=1e-12)  # the unknowns v
    np.testing.assert_allclose(state[: 3 * n], 0.0, rtol=0, atol=1e-12)  # u, beta, phi
    np.testing.assert_allclose(heave, 0.0, rtol=0, atol=1e-12)


def _tip_under_in_plane_load(n: int, load_parameter: float) -> tuple[float, float]:
    """The tip's forward deflection and retreat along the jig axis over L under a dead tip
    load -P e_c (forward), P = load_parameter EI_lag / L^2, on the tip strip at the deformed
    tip: the elastica of the flap test in the wing's plane."""
    layout, p, p_sym, z, beam = _cantilever(n)
    m = layout.n_panels
    force = load_parameter * EI_LAG / LENGTH**2
    along, _, _ = lag_reference_line(
        z[n : 2 * n], z[4 * n :], ca.DM(np.diff(np.linspace(0.0, LENGTH, n)))
    )

    def load_rows(scale: ca.MX) -> ca.MX:
        loads = [ca.MX(m, 1) for _ in range(LOADS + EXACT_LOADS)]
        tip = ca.DM.zeros(m, 1)
        tip[m - 1] = 1.0
        # Zero sweep: e_s = y, n = z, e_c = x. F = (-P, 0, 0) at r = (v_tip, S_tip, 0):
        # r x F = (0, 0, S_tip P), about the normal.
        loads[0] = -scale * force * tip
        loads[LOADS + 1] = scale * force * along[-1] * tip
        return beam.load_rows(ca.vertcat(*loads), ca.MX(), ca.MX())

    state = _solve(layout, p, p_sym, z, load_rows, steps=10)
    h = np.diff(np.linspace(0, LENGTH, n))
    tip_along = float(lag_reference_line(state[n : 2 * n], state[4 * n :], h)[0][-1])
    assert np.max(np.abs(state[:n])) < 1e-12  # no heave
    return -state[4 * n - 1] / LENGTH, 1.0 - tip_along / LENGTH


# Three of the table's six loads, its ends and middle: the rows are the flap test's turned (which
# takes all six), and each point costs a 161-station continuation.
@pytest.mark.parametrize("load_parameter", [1.0, 3.0, 10.0], ids=lambda a: f"PL2_EI_{a:g}")
def test_a_dead_in_plane_tip_load_bends_the_cantilever_as_bisshopp_and_druckers_table(
    load_parameter,
):
    """At N = 161 the discretisation's error is 2e-5 of L at most (the flap test's, the same
    rows turned): the table's five digits to 5e-5."""
    forward, retreat = _tip_under_in_plane_load(161, load_parameter)
    expected_deflection, expected_retreat = BISSHOPP_DRUCKER[load_parameter]
    assert forward == pytest.approx(expected_deflection, abs=5e-5)
    assert retreat == pytest.approx(expected_retreat, abs=5e-5)


@pytest.mark.parametrize("twist_deg", [-25.0, 10.0, 40.0], ids=lambda t: f"phi_{t:g}deg")
def test_a_twisted_section_under_a_moment_about_e_c_bends_in_both_planes_in_closed_form(twist_deg):
    """At beta = psi = 0 and a twist phi, a moment M about e_c: the section's axes see
    M cos(phi) about its chord and M sin(phi) about its normal, so beta' = M (cos^2(phi)/EI +
    sin^2(phi)/EI_lag) and psi' = -M sin(phi) cos(phi) (1/EI - 1/EI_lag); no twist rate. To
    round-off."""
    n = 4
    _layout, p, p_sym, z, beam = _cantilever(n)
    moment, phi = 250.0, math.radians(twist_deg)
    zero = ca.DM.zeros(n, 1)
    state = np.zeros(5 * n)
    state[2 * n : 3 * n] = twist_deg
    line = (zero, zero, zero)
    moments = section_moments(
        (zero, zero, moment * ca.DM.ones(n, 1)), (zero, zero, zero), line, zero, zero, _scale
    )
    rates = ca.Function("rates", [z, p_sym], list(beam.rates_of(moments, z)))
    beta_rate, twist_rate, psi_rate = (np.array(v).ravel() for v in rates(state, p))
    cos, sin = math.cos(phi), math.sin(phi)
    expected_beta = moment * (cos**2 / EI + sin**2 / EI_LAG)
    expected_psi = -moment * sin * cos * (1 / EI - 1 / EI_LAG)
    np.testing.assert_allclose(beta_rate, expected_beta, rtol=1e-14)
    np.testing.assert_allclose(psi_rate, expected_psi, rtol=1e-13, atol=1e-18)
    np.testing.assert_allclose(twist_rate, 0.0, rtol=0, atol=1e-18)


def _small_wing(**given) -> solver.Wing:  # type: ignore[no-untyped-def]
    from tests.study import study_arrays

    arrays = study_arrays(6, 1.0)
    return solver.Wing.create(**arrays, **given)


@pytest.mark.parametrize(
    ("aerodynamics", "chordwise", "sweep"),
    [("lattice", 1, 0.0), ("lattice", 2, 20.0), ("strip", 1, -15.0)],
    ids=["lattice", "lattice_k2_swept", "strip_swept_forward"],
)
def test_the_residuals_jacobian_is_its_derivative_at_large_rotations_in_both_planes(
    aerodynamics, chordwise, sweep
):
    """J0 + q J1 against central differences of r0 + q r1 (step 1e-6, truncation ~1e-12 of
    the entries) at flap and lag rotations up to 0.6 rad, twists up to 10 deg, lag
    displacements and circulations of their order: every entry to 1e-7 of the largest."""
    wing = _small_wing(sweep=sweep, in_plane_bending_stiffness=4e5, bending_torsion_coupling=5.0)
    options = solver.SolverOptions(
        structure="geometrically_exact", aerodynamics=aerodynamics, chordwise_panels=chordwise
    )
    system = CoupledSystem.of(wing, 4.0, options)
    layout = system.layout
    assert layout.lag and layout.n_unknowns == 5 * layout.n + layout.n_panels
    rng = np.random.default_rng(7)
    x = np.zeros(layout.n_unknowns)
    n = layout.n
    x[layout.heave] = rng.uniform(-0.5, 0.5, n)
    x[layout.slope] = rng.uniform(-0.6, 0.6, n)
    x[layout.twist] = rng.uniform(-10.0, 10.0, n)
    x[layout.lag_displacement] = rng.uniform(-0.3, 0.3, n)
    x[layout.lag_rotation] = rng.uniform(-0.6, 0.6, n)
    x[layout.circulation] = rng.uniform(-0.3, 0.3, layout.n_panels)
    q, step = 250.0, 1e-6
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
    # J1 lives in the load rows only: bending, torsion and lag bending.
    others = np.delete(np.arange(layout.n_unknowns), layout.load_rows)
    assert not np.any(evaluation.jacobian1[others])


def test_in_the_small_deflection_limit_lag_is_todays_exact_beam():
    """The study wing 1e4 times stiffer (tip heave 4e-6 of the semispan at 10 m/s) with
    EI_lag = 200 EI: the lag model differs from the planar exact beam at second order (the
    twist times the flap curvature, the drag's in-plane bending times the deflection), so the
    answers agree to 1e-6 of their largest values."""
    from tests.study import flight, study_wing

    planar = study_wing(30, 1e4)
    lag = solver.Wing.create(
        planar.y,
        planar.chord,
        planar.elastic_axis,
        planar.bending_stiffness,
        planar.torsional_stiffness,
        jig_twist=planar.jig_twist,
        in_plane_bending_stiffness=200 * planar.bending_stiffness,
    )
    ours = solver.solve(lag, flight(10.0), options=EXACT)
    theirs = solver.solve(planar, flight(10.0), options=EXACT)
    assert theirs.stations.lag is None and ours.stations.lag is not None
    for name in ("heave", "twist", "bending_moment", "torque"):
        a, b = getattr(ours.stations, name), getattr(theirs.stations, name)
        assert np.max(np.abs(a - b)) <= 1e-6 * np.max(np.abs(b)), name
    for name in ("axis_x", "axis_y", "axis_z"):  # axis_x is 0 without lag: of the semispan
        a, b = getattr(ours.stations, name), getattr(theirs.stations, name)
        assert np.max(np.abs(a - b)) <= 1e-6 * planar.semispan, name
    assert ours.totals.lift == pytest.approx(theirs.totals.lift, rel=1e-6)
    # The in-plane load in the wing's axes is forward (the lift tilted by alpha, -L sin(alpha),
    # outweighs the induced drag): it bends the stiff wing forward in its plane, a little.
    assert ours.stations.lag_bending_moment[0] > 0
    assert ours.stations.lag[-1] < 0 and ours.stations.lag_rotation[-1] > 0


def test_a_twisted_wing_soft_in_its_plane_bends_aft_along_its_sections_normal():
    """The study wing at 18 m/s with EI_lag = 2 EI, twisted 10 deg nose up at the tip: each
    section bends up along its own normal, tilted aft by the twist, more than the forward
    in-plane load bends it forward (the root's lag bending moment > 0), so the tip moves aft
    (v > 0, psi < 0; psi' = -M_f sin(phi) cos(phi) (1/EI - 1/EI_lag) / cos(beta) at first
    order). The answer's internal loads are those its rows balance: the rates of the
    constitutive law integrated by the trapezoid reproduce the answered beta and psi (to the
    solver's tolerance)."""
    from tests.study import flight, study_wing

    planar = study_wing(30)
    wing = solver.Wing.create(
        planar.y,
        planar.chord,
        planar.elastic_axis,
        planar.bending_stiffness,
        planar.torsional_stiffness,
        jig_twist=planar.jig_twist,
        in_plane_bending_stiffness=2 * planar.bending_stiffness,
    )
    answer = solver.solve(wing, flight(18.0), options=EXACT)
    st = answer.stations
    assert st.axis_twist[-1] > 9.0
    assert st.lag[-1] > 0 and st.lag_rotation[-1] < 0 and st.lag_bending_moment[0] > 0
    beta, psi, phi = (
        np.radians(st.bending_rotation),
        np.radians(st.lag_rotation),
        np.radians(st.axis_twist),
    )
    flap, lag = st.bending_moment, st.lag_bending_moment
    ei, _gj, ei_lag = (
        wing.bending_stiffness,
        wing.torsional_stiffness,
        wing.in_plane_bending_stiffness,
    )
    flap_s = np.cos(phi) * flap - np.sin(phi) * lag
    lag_s = np.sin(phi) * flap + np.cos(phi) * lag
    psi_rate = (-np.sin(phi) * flap_s / ei + np.cos(phi) * lag_s / ei_lag) / np.cos(beta)
    beta_rate = np.cos(phi) * flap_s / ei + np.sin(phi) * lag_s / ei_lag
    h = np.diff(wing.arc_length)
    integrated_psi = np.concatenate([[0.0], np.cumsum(h / 2 * (psi_rate[:-1] + psi_rate[1:]))])
    integrated_beta = np.concatenate([[0.0], np.cumsum(h / 2 * (beta_rate[:-1] + beta_rate[1:]))])
    np.testing.assert_allclose(integrated_psi, psi, rtol=0, atol=1e-9 * np.max(np.abs(psi)))
    np.testing.assert_allclose(integrated_beta, beta, rtol=0, atol=1e-9 * np.max(np.abs(beta)))


# --- Without the field: today's answers --------------------------------------------

# The study wing's answers (tip heave, tip twist, lift, root bending moment, root torque, the
# sums of the heaves and twists) measured before lag existed (main at 1436ccb, CasADi 3.8.2,
# x86_64, OPENBLAS_NUM_THREADS=1). On that machine they were equal to the bit after the change
# (measured at the merge: the layout, rows, parameter table and code path of a wing without
# `in_plane_bending_stiffness` are today's; a dihedral wing's too, the lag slot existing in lag
# layouts only). Held here to 1e-10 relative, not to the bit: another CPU, BLAS or ISA level
# moves a Newton solution's last digits, while any change of the model's rows, parameters or
# path moves these answers by far more (the lag model's own small-deflection difference is
# 1e-8 to 1e-3).
ROUND_OFF = 1e-10
TODAYS_ANSWERS = {
    ("linear", 12.0): [0.07931061606171763, 2.6748024556331536, 474.15620376188303,
                       515.026361153292, 36.04691422487433, 0.8950998402514708,
                       47.07874150925206],
    ("linear", 18.0): [0.2953155368968787, 8.892281468939444, 1601.5370786414644,
                       1852.4926298096823, 114.87118911086526, 3.3119548839385287,
                       157.00690411745944],
    ("geometrically_exact", 12.0): [0.07981974989852333, 2.77277696678651,
                                    476.0423634351732, 517.8339463157519,
                                    36.16331696530183, 0.9006649211871209,
                                    48.16338687756153],
    ("geometrically_exact", 18.0): [0.3140890614406038, 10.37870440223784,
                                    1672.8977642039677, 1957.8805005945057,
                                    119.16866137857913, 3.5181106930268298,
                                    174.638155940298],
}  # fmt: skip
DIHEDRAL_EXACT_18 = [0.3126800931844119, 10.342348164212913, 1656.282715527276]


@pytest.mark.parametrize(("structure", "velocity"), list(TODAYS_ANSWERS), ids=str)
def test_without_the_field_the_study_wings_answers_are_todays(structure, velocity):
    from tests.study import flight, study_wing

    answer = solver.solve(
        study_wing(30), flight(velocity), options=solver.SolverOptions(structure=structure)
    )
    st, totals = answer.stations, answer.totals
    assert st.lag is None and st.lag_rotation is None and st.lag_bending_moment is None
    numbers = [
        st.heave[-1],
        st.twist[-1],
        totals.lift,
        st.bending_moment[0],
        st.torque[0],
        float(sum(st.heave)),
        float(sum(st.twist)),
    ]
    assert numbers == pytest.approx(TODAYS_ANSWERS[(structure, velocity)], rel=ROUND_OFF)


def test_without_the_field_a_dihedral_wings_exact_answer_is_todays():
    from tests.study import flight, study_arrays

    wing = solver.Wing.create(**study_arrays(30), dihedral=5.0)
    answer = solver.solve(wing, flight(18.0), options=EXACT)
    numbers = [answer.stations.heave[-1], answer.stations.twist[-1], answer.totals.lift]
    assert numbers == pytest.approx(DIHEDRAL_EXACT_18, rel=ROUND_OFF)


# --- Refusals: a 422 naming the field ---------------------------------------------------------

LAG_FIELD = "wing.in_plane_bending_stiffness"


def test_with_the_linear_beam_the_in_plane_stiffness_is_refused_naming_it():
    from tests.study import flight

    wing = _small_wing(in_plane_bending_stiffness=4e5)
    with pytest.raises(solver.InvalidInput) as refused:
        solver.SolveInput(wing, flight(10.0))
    assert refused.value.field == LAG_FIELD
    assert "needs options.structure = geometrically_exact" in str(refused.value)
    with pytest.raises(solver.InvalidInput) as refused:
        solver.solve(wing, flight(10.0))
    assert refused.value.field == LAG_FIELD


def test_gust_loads_do_not_take_lag_yet_and_refuse_it_naming_the_field():
    """Gust loads' Python entry refuses lag (the service's operations too, before any work:
    tests/app/test_matrix.py meets the field with every operation)."""
    wing = _small_wing(in_plane_bending_stiffness=4e5)
    with pytest.raises(solver.InvalidInput) as refused:
        solver.gust_analysis(wing, solver.FlightCondition(10.0, weight=100.0), options=EXACT)
    assert refused.value.field == LAG_FIELD
    assert "does not take it yet" in str(refused.value)
