"""solver.model.beam: the beam's rows, the outboard sums of the panel loads and the trapezoidal
rule along the swept elastic axis, against a point load worked by hand."""

from __future__ import annotations

import math

import casadi as ca
import numpy as np
import pytest

import solver
from solver.model.aerodynamics import LOADS
from solver.model.beam import DEG_PER_RAD, Beam, coupled_trapezoid, outboard_sum, structure_rows
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


# --- Bending-torsion coupling ---------------------------------------------------------------


def _beam_rows_function(layout: Layout) -> ca.Function:
    """(p, M (N,), T (N,)) -> the load terms of the bending and torsion rows (2(N-1),)."""
    p = ca.MX.sym("p", layout.n_parameters)
    moment, torque = ca.MX.sym("M", layout.n), ca.MX.sym("T", layout.n)
    beam = Beam(layout, layout.unpack(p))
    return ca.Function("rows", [p, moment, torque], [beam.rows(moment, torque)])


def _parameters(layout: Layout, wing: solver.Wing) -> np.ndarray:
    values = layout.wing_values(wing) | {"camber": np.zeros((layout.n, 2)), "alpha": 0.0}
    return layout.pack(values | {"deformed_axis": 0.0})


def _deformation(wing: solver.Wing, moment: np.ndarray, torque: np.ndarray) -> np.ndarray:
    """z = (u, u', phi [deg]) (3N,) of the cantilever under internal loads M, T (N,) [N m]:
    the structure rows solved with the beam's load terms."""
    n = wing.n_stations
    layout = Layout(n)
    x = ca.MX.sym("x", layout.n_unknowns)
    h = np.diff(wing.arc_length)
    structure = ca.Function("s", [x], [structure_rows(layout, x, ca.DM(h))])
    jacobian = ca.Function("j", [x], [ca.jacobian(structure(x), x)])
    matrix = np.array(jacobian(np.zeros(layout.n_unknowns)))[:, layout.structure]
    rows = np.zeros(3 * n)
    load_terms = np.array(_beam_rows_function(layout)(_parameters(layout, wing), moment, torque))
    rows[layout.bending_rows.start : layout.torsion_rows.stop] = load_terms.ravel()
    return np.linalg.solve(matrix, -rows)


@pytest.mark.parametrize(
    ("force", "moment", "torque"),
    [(30.0, 0.0, 0.0), (0.0, 50.0, 0.0), (0.0, 0.0, 20.0), (-25.0, 40.0, 15.0)],
    ids=["tip_force", "tip_moment", "tip_torque", "all_three"],
)
@pytest.mark.parametrize(
    "coupling", [0.0, 600.0, -600.0], ids=["uncoupled", "positive", "negative"]
)
def test_a_coupled_cantilever_deforms_as_the_closed_form_of_its_two_by_two_stiffness(
    force, moment, torque, coupling
):
    """A uniform cantilever of length L, [M; T] = [[EI, K], [K, GJ]] [u''; phi'], under a tip
    force P, a tip moment M0 and a tip torque T0: M(s) = P (L - s) + M0, T(s) = T0, so with
    D = EI GJ - K^2, u'' = (GJ M - K T)/D and phi' = (EI T - K M)/D, and
        u'(L) = (GJ (P L^2/2 + M0 L) - K T0 L)/D,   phi(L) = (EI T0 L - K (P L^2/2 + M0 L))/D,
        u(L) = (GJ (P L^3/3 + M0 L^2/2) - K T0 L^2/2)/D.
    The trapezoidal rule integrates the linear u'' and the constant phi' exactly (round-off);
    u(L) integrates the quadratic u' by trapezoids: exact without the force, and with it off by
    the trapezoidal rule's own error, -GJ P L h^2 / (12 D) exactly (a quadratic's)."""
    n, length, ei, gj = 21, 2.0, 4e3, 5e2
    wing = solver.Wing.create(
        np.linspace(0.0, length, n), 0.5, 0.4, ei, gj, bending_torsion_coupling=coupling
    )
    s = wing.arc_length
    z = _deformation(wing, force * (length - s) + moment, np.full(n, torque))
    det = ei * gj - coupling**2
    bend = force * length**2 / 2 + moment * length
    slope = (gj * bend - coupling * torque * length) / det
    twist = (ei * torque * length - coupling * bend) / det
    heave = (
        gj * (force * length**3 / 3 + moment * length**2 / 2) - coupling * torque * length**2 / 2
    ) / det
    scale = abs(slope) + abs(twist) + 1e-300
    assert abs(z[n - 1 + n] - slope) < 1e-12 * scale
    assert abs(math.radians(z[3 * n - 1]) - twist) < 1e-12 * scale
    h = length / (n - 1)
    # Trapezoids of u' = c (L s - s^2/2) + ...: h^2/12 (u''(L) - u''(0)) = -c L h^2/12, exactly.
    trapezoid_error = -gj * force * length * h**2 / 12 / det
    assert abs(z[n - 1] - heave - trapezoid_error) <= 1e-12 * (abs(heave) + abs(slope) + 1e-300)


def test_positive_coupling_twists_a_section_bent_up_nose_down():
    """The sign convention: a pure bending moment bending the tip up (M > 0, T = 0) twists a
    positively coupled section nose down (washout), a negatively coupled one nose up."""
    n = 5
    y = np.linspace(0.0, 1.0, n)
    twists = []
    for coupling in (300.0, -300.0):
        wing = solver.Wing.create(y, 0.5, 0.4, 4e3, 5e2, bending_torsion_coupling=coupling)
        z = _deformation(wing, np.full(n, 100.0), np.zeros(n))
        assert z[n - 1] > 0  # the tip bends up
        twists.append(z[3 * n - 1])
    assert twists[0] < 0 < twists[1]


def test_without_coupling_the_rows_are_the_uncoupled_ones_to_the_last_digit():
    """K = 0 (the default): -h/2 (M_i/EI_i + M_{i+1}/EI_{i+1}) and the same of degrees(T/GJ),
    evaluated as the uncoupled model wrote them, bit for bit (the coupling adds signed zeros)."""
    layout = Layout(N)
    wing = solver.Wing.create(Y, 0.5, 0.4, EI, GJ, sweep=20.0)
    rng = np.random.default_rng(11)
    moment, torque = rng.normal(size=N) * 100.0, rng.normal(size=N) * 10.0
    ours = np.array(_beam_rows_function(layout)(_parameters(layout, wing), moment, torque)).ravel()
    h = ca.MX.sym("h", N - 1)
    m_sym, t_sym = ca.MX.sym("M", N), ca.MX.sym("T", N)
    ei_sym, gj_sym = ca.MX.sym("EI", N), ca.MX.sym("GJ", N)

    def trapezoid(values: ca.MX, stiffness: ca.MX, scale: float) -> ca.MX:
        inner = -scale * h / (2 * stiffness[:-1])
        outer = -scale * h / (2 * stiffness[1:])
        return inner * values[:-1] + outer * values[1:]

    uncoupled = ca.Function(
        "u",
        [h, m_sym, t_sym, ei_sym, gj_sym],
        [ca.vertcat(trapezoid(m_sym, ei_sym, 1.0), trapezoid(t_sym, gj_sym, DEG_PER_RAD))],
    )
    expected = np.array(uncoupled(np.diff(wing.arc_length), moment, torque, EI, GJ)).ravel()
    np.testing.assert_array_equal(ours, expected)


def test_the_numeric_rows_without_coupling_are_the_uncoupled_ones_to_the_last_digit():
    """`coupled_trapezoid` (inertia relief, the modes) at K = 0: -scale h/2 (f_i + f_{i+1}) of
    f = load / stiffness, bit for bit."""
    rng = np.random.default_rng(5)
    h = np.diff(Y)
    moment, torque = rng.normal(size=(N, 3)), rng.normal(size=(N, 3))
    bending, torsion = coupled_trapezoid(h, moment, torque, (EI, GJ, np.zeros(N)))
    per_m, per_t = moment / EI[:, None], torque / GJ[:, None]
    np.testing.assert_array_equal(bending, -1.0 * h[:, None] / 2 * (per_m[:-1] + per_m[1:]))
    np.testing.assert_array_equal(torsion, -DEG_PER_RAD * h[:, None] / 2 * (per_t[:-1] + per_t[1:]))


@pytest.mark.parametrize("coupling", [math.sqrt(4e3 * 5e2), -80.0e3], ids=["singular", "beyond"])
def test_a_section_whose_stiffness_is_not_positive_definite_is_refused_naming_its_station(
    coupling,
):
    ks = np.zeros(N)
    ks[-1] = coupling  # EI GJ = 1e3 * 2e2 at the tip
    with pytest.raises(solver.InvalidInput) as error:
        solver.Wing.create(Y, 0.5, 0.4, EI, GJ, bending_torsion_coupling=ks)
    assert error.value.field == f"bending_torsion_coupling[{N - 1}]"


@pytest.mark.parametrize("velocity", [8.0, 13.0], ids=["slow", "fast"])
def test_positive_coupling_washes_the_study_wing_out_and_negative_washes_it_in(velocity):
    """The study's wing (its lift bends it up) with K = +-0.3 sqrt(EI GJ) at every station:
    positive K twists the bent sections nose down, so its tip twist and its lift fall below
    the uncoupled wing's; negative K raises both."""
    from tests.study import flight, study_arrays

    arrays = study_arrays(20)
    root = np.sqrt(arrays["bending_stiffness"] * arrays["torsional_stiffness"])
    answers = {}
    for sign in (1.0, 0.0, -1.0):
        wing = solver.Wing.create(**arrays, bending_torsion_coupling=0.3 * sign * root)
        answers[sign] = solver.solve(wing, flight(velocity))
    tips = [answers[sign].stations.twist[-1] for sign in (1.0, 0.0, -1.0)]
    lifts = [answers[sign].totals.lift for sign in (1.0, 0.0, -1.0)]
    assert tips[0] < tips[1] < tips[2]
    assert lifts[0] < lifts[1] < lifts[2]
