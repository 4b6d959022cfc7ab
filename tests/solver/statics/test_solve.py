"""solver.statics.solve: the equilibrium on the branch from the jig shape, the same whatever start
or history, or a typed error.

Tolerances: answers of two independent paths (a hint against none) agree to the residual
tolerance times the problem's conditioning: 1e-9 relative here (lift amplification <= 2.5);
answers of one path repeated agree bit for bit.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import solver
from solver import ConvergenceError, FlightCondition, NoEquilibrium, SolverOptions, solve
from tests.reference import load_reference
from tests.study import (
    DENSITY,
    REFERENCE,
    SPAN,
    bistable_wing,
    flight,
    rect_public,
    relative_difference,
    study_wing,
    tapered_forward_ea,
)

TWO_SOLVES = 1e-9
WINGS = {"study": study_wing, "tapered_forward_ea": tapered_forward_ea}


# --- The design study's printed numbers (section 14.4) ------------------------------------------


def test_the_study_wing_at_cruise_prints_the_studys_numbers():
    """At the printed rounding; AeroSandbox's CL divides by the deformed wing's area."""
    e = solve(study_wing(), flight(10.0))
    t = e.totals
    amplification = t.CL_deformed_area / (t.rigid_lift / (e.dynamic_pressure * t.reference_area))
    assert f"Tip twist:  {t.tip_twist:+.2f} deg" == "Tip twist:  +1.71 deg"
    heave_percent = t.tip_heave / (SPAN / 2) * 100
    assert (
        f"Tip heave:  {t.tip_heave:.3f} m ({heave_percent:.1f}% of semispan)"
        == "Tip heave:  0.050 m (1.0% of semispan)"
    )
    assert (
        f"Lift:       {t.lift:.1f} N flexible vs. {t.rigid_lift:.1f} N rigid "
        f"({(amplification - 1) * 100:+.1f}%)"
        == "Lift:       304.1 N flexible vs. 259.4 N rigid (+17.3%)"
    )
    assert e.stability.stable and e.stability.branch == "jig"
    assert not e.solver.warm_start


# --- Limits and invariants ----------------------------------------------------------------------


def test_a_very_stiff_wing_gives_the_rigid_answer():
    """At 1e6 times the study's stiffness the lift is the rigid lift and the wing hardly moves:
    the flexible wing gains 17 % at 10 m/s, so the remaining gain must be ~1.7e-7."""
    e = solve(study_wing(stiffness_scale=1e6), flight(10.0))
    assert abs(e.totals.lift_amplification - 1) < 1e-6
    assert np.max(np.abs(e.stations.heave)) < 1e-6 * e.wing.semispan
    assert np.max(np.abs(e.stations.twist)) < 1e-5  # [deg]


def test_the_departure_from_rigid_falls_in_proportion_to_the_compliance():
    """Small-deformation limit: L/L_rigid - 1 is linear in 1/stiffness. Ten times stiffer, ten
    times less gain, up to the next order in the compliance (~1e-3 relative here)."""
    gain = {
        scale: solve(study_wing(stiffness_scale=scale), flight(10.0)).totals.lift_amplification - 1
        for scale in (1e3, 1e4)
    }
    assert gain[1e3] > 0
    assert gain[1e3] / gain[1e4] == pytest.approx(10.0, rel=1e-3)


def test_the_equilibrium_depends_on_airspeed_and_density_only_through_q():
    """The residual is r0 + q r1: (V, rho) and (V', rho') with one q give one equilibrium."""
    wing = study_wing()
    sea_level = solve(wing, flight(15.0, density=1.225))
    aloft = solve(wing, flight(15.0 * math.sqrt(1.225 / 0.8), density=0.8))
    assert aloft.dynamic_pressure == pytest.approx(sea_level.dynamic_pressure, rel=1e-12)
    for name in ("heave", "twist", "bending_moment", "torque"):
        a, b = getattr(aloft.stations, name), getattr(sea_level.stations, name)
        assert relative_difference(a, b) < TWO_SOLVES
    assert aloft.lift == pytest.approx(sea_level.lift, rel=TWO_SOLVES)


@pytest.mark.parametrize("wing_name", list(WINGS))
def test_negative_alpha_mirrors_every_load_and_deformation(wing_name: str):
    """Reflecting the problem in the x-y plane maps alpha to -alpha: heave, twist, lift and
    torques change sign; chordwise force and induced drag do not."""
    wing = WINGS[wing_name]()
    up, down = solve(wing, flight(14.0, alpha=4.0)), solve(wing, flight(14.0, alpha=-4.0))
    for name in ("heave", "slope", "twist", "shear", "bending_moment", "torque"):
        a, b = getattr(down.stations, name), getattr(up.stations, name)
        assert relative_difference(-a, b) < TWO_SOLVES, name
    assert -down.lift == pytest.approx(up.lift, rel=TWO_SOLVES)
    assert down.totals.induced_drag == pytest.approx(up.totals.induced_drag, rel=TWO_SOLVES)


def test_the_twist_sign_follows_the_elastic_axis():
    """Lift acts at the quarter chord: an elastic axis behind it twists the wing nose-up and
    adds lift (wash-in), one ahead of it nose-down and relieves lift (study, section 14.3)."""
    behind = solve(study_wing(elastic_axis=0.40), flight(8.0))
    ahead = solve(study_wing(elastic_axis=0.15), flight(8.0))
    assert np.all(behind.stations.twist[1:] > 0) and behind.lift > behind.totals.rigid_lift
    assert np.all(ahead.stations.twist[1:] < 0) and ahead.lift < ahead.totals.rigid_lift


# --- One answer per request ---------------------------------------------------------------------


def test_strip_theory_twists_a_uniform_wing_as_the_torsion_equation_says():
    """options.aerodynamics = "strip" through the whole solve: a uniform unswept wing obeys
    theta'' + lambda^2 theta = -lambda^2 alpha, lambda^2 = q e c a / GJ (a = 2 pi, e c the
    quarter chord's lead on the elastic axis), so theta(L) = alpha (sec(lambda L) - 1)
    (Bisplinghoff, Ashley and Halfman 1955, section 8-2). At half the divergence pressure and
    0.01 deg (linear) the discrete answer converges to it at O(h^2): -1.04e-3 at N = 21,
    -2.6e-4 at N = 41 (checked within 1.2x)."""
    length, chord, elastic_axis, torsional_stiffness = 10.0, 1.0, 0.4, 2e4
    lever_lift = (elastic_axis - 0.25) * chord * chord * 2 * math.pi  # [m^2] e c a
    q = 0.5 * (math.pi / 2) ** 2 * torsional_stiffness / (lever_lift * length**2)
    alpha = 0.01
    root = math.sqrt(q * lever_lift / torsional_stiffness) * length
    exact = alpha * (1 / math.cos(root) - 1)
    errors = {}
    for n in (21, 41):
        wing = solver.Wing.create(
            np.linspace(0, length, n), chord, elastic_axis, 2e5, torsional_stiffness
        )
        velocity = math.sqrt(2 * q / DENSITY)
        condition = FlightCondition(velocity=velocity, alpha=alpha, density=DENSITY)
        answer = solve(wing, condition, options=SolverOptions(aerodynamics="strip"))
        errors[n] = answer.totals.tip_twist / exact - 1
    assert -1.2 * 1.04e-3 < errors[21] < 0
    assert -1.2 * 2.6e-4 < errors[41] < 0
    assert errors[21] / errors[41] == pytest.approx(4.0, abs=0.2)


def test_a_request_repeated_gets_the_same_bits():
    wing = study_wing()
    first = solve(wing, flight(19.0))
    solver.clear_caches()
    second = solve(wing, flight(19.0))
    np.testing.assert_array_equal(first.state, second.state)
    assert first.totals == second.totals and first.stability == second.stability


@pytest.mark.parametrize(
    ("previous", "velocity"),
    [pytest.param(20.5, 21.0, id="20.5-to-21"), pytest.param(21.0, 21.3, id="21-to-21.3")],
)
def test_a_hint_saves_iterations_and_keeps_the_answer(previous: float, velocity: float):
    """Near the fold the path from the jig takes several steps; from a neighbour, one."""
    wing = study_wing()
    cold = solve(wing, flight(velocity))
    hinted = solve(wing, flight(velocity), hint=solve(wing, flight(previous)))
    assert hinted.solver.warm_start and not cold.solver.warm_start
    assert hinted.solver.iterations < cold.solver.iterations
    np.testing.assert_allclose(
        hinted.stations.twist, cold.stations.twist, rtol=TWO_SOLVES, atol=1e-10
    )
    assert hinted.lift == pytest.approx(cold.lift, rel=TWO_SOLVES)


def test_a_hint_from_the_answer_itself_needs_no_iteration():
    wing = study_wing()
    e = solve(wing, flight(15.0))
    again = solve(wing, flight(15.0), hint=e)
    assert again.solver.iterations == 0
    np.testing.assert_array_equal(again.state, e.state)


@pytest.mark.parametrize("first", [0.8, 0.95, 1.1], ids=["0.8mps", "0.95mps", "1.1mps"])
def test_a_hint_from_the_bistable_wings_branch_keeps_the_cold_answer(first: float):
    """Found by fuzzing: at 1 m/s (rho 1.038, alpha 0.5 deg) this wing has two stable
    equilibria, +69.93 deg tip twist on the branch from the jig and -70.48 deg on another.
    Newton from the branch's +33.6 deg equilibrium at 0.8 m/s used to land on -70.48 deg. The
    branch folds at 1.13 m/s; a hint from above 1 m/s follows it down."""
    wing = bistable_wing()
    condition = flight(1.0, 0.5, 1.038)
    cold = solve(wing, condition)
    assert cold.tip_twist == pytest.approx(69.93, abs=0.01) and cold.stability.stable
    hint = solve(wing, condition.at_velocity(first))
    hinted = solve(wing, condition, hint=hint)
    assert hinted.tip_twist == pytest.approx(cold.tip_twist, rel=1e-8)
    assert hinted.lift == pytest.approx(cold.lift, rel=1e-8)


def _never_diverging_in_practice() -> solver.Wing:
    y = np.linspace(0, 1, 8)
    chord = 1.7782794100389228 * (1 - (1 - 0.25) * y)
    return solver.Wing.create(y, chord, [0.25] * 4 + [0.05078125] * 4, 10.0, 1.0)


@pytest.mark.parametrize("hint_velocity", [30.0, 300.0], ids=["30mps", "300mps"])
def test_a_hint_does_not_change_the_outcome_at_the_fastest_airspeed(hint_velocity: float):
    """Found by fuzzing: this wing's divergence pressure is round-off (1.5e18 Pa before it was
    filtered); at 1.08e9 m/s the cold solve said NoEquilibrium and the solve hinted with an
    equilibrium at 5.4e8 m/s returned an answer. Such speeds are refused now (the lattice is
    incompressible: 1000 m/s at most); at the fastest accepted the hint changes nothing."""
    wing = _never_diverging_in_practice()
    with pytest.raises(solver.InvalidInput) as raised:
        FlightCondition(velocity=1081208826.6422322, alpha=1.0, density=1.225)
    assert raised.value.field == "velocity"
    condition = FlightCondition(velocity=1000.0, alpha=1.0, density=1.225)
    hint = solve(wing, condition.at_velocity(hint_velocity))
    assert hint.stability.stable
    cold, hinted = solve(wing, condition), solve(wing, condition, hint=hint)
    assert cold.stability.stable and hinted.stability.stable
    assert hinted.lift == pytest.approx(cold.lift, rel=TWO_SOLVES)


def test_a_hint_of_another_wing_or_off_the_branch_is_ignored():
    wing = study_wing()
    cold = solve(wing, flight(15.0))
    other = solve(study_wing(stiffness_scale=2.0), flight(15.0))
    ignored = solve(wing, flight(15.0), hint=other)
    assert not ignored.solver.warm_start
    np.testing.assert_array_equal(ignored.state, cold.state)


def test_a_hint_and_an_initial_guess_are_exclusive():
    wing = study_wing()
    e = solve(wing, flight(10.0))
    with pytest.raises(solver.InvalidInput, match="not both") as raised:
        solve(wing, flight(11.0), e.state, hint=e)
    assert raised.value.field == "initial_guess"


# --- A caller's initial guess ---------------------------------------------------------------------


def _nose_down_guess(wing: solver.Wing, alpha: float) -> np.ndarray:
    """A state like AeroSandbox's answers past the fold: the 10 m/s equilibrium with its heave
    and slope reversed and its twist turned nose-down eight times over."""
    state = solve(wing, flight(10.0, alpha)).state.copy()
    n = wing.n_stations
    state[: 2 * n] *= -1
    state[2 * n : 3 * n] *= -8
    return state


# AeroSandbox's "equilibria" of rect_public (shared/reference/ref_rect_public.json).
ASB_NOSE_DOWN_LIFT = {20: -520.442301323639, 25: -350.7935342461813}


@pytest.mark.parametrize("velocity", sorted(ASB_NOSE_DOWN_LIFT), ids=["20mps", "25mps"])
def test_a_callers_guess_on_the_nose_down_branch_is_returned_flagged(velocity):
    wing = rect_public()
    e = solve(wing, flight(float(velocity), 4.0), _nose_down_guess(wing, 4.0))
    # It is AeroSandbox's answer (same equations, same root) ...
    assert e.lift == pytest.approx(ASB_NOSE_DOWN_LIFT[velocity], rel=1e-6)
    # ... another branch than the jig's, and statically unstable.
    assert e.stability.branch == "other"
    assert not e.stability.stable and e.stability.margin > 1


def test_a_callers_guess_that_reaches_the_jig_branch_gets_the_cold_answer():
    wing = study_wing()
    cold = solve(wing, flight(14.0))
    near = solve(wing, flight(13.0)).state
    guessed = solve(wing, flight(14.0), near)
    assert guessed.stability.branch == "jig"
    np.testing.assert_array_equal(guessed.state, cold.state)


def test_a_callers_guess_can_find_the_bistable_wings_other_stable_equilibrium():
    wing = bistable_wing()
    condition = flight(1.0, 0.5, 1.038)
    cold = solve(wing, condition)
    mirrored = cold.state.copy()
    n = wing.n_stations
    mirrored[: 3 * n] *= -1  # heave, slope and twist reversed
    other = solve(wing, condition, mirrored)
    assert other.tip_twist == pytest.approx(-70.48, abs=0.01)
    assert other.stability.stable and other.stability.branch == "other"


@pytest.mark.parametrize(
    "guess",
    [
        pytest.param(np.zeros(4 * 30 - 2), id="wrong-length"),
        pytest.param(np.full(4 * 30 - 1, np.nan), id="not-finite"),
    ],
)
def test_a_malformed_initial_guess_is_invalid_input(guess: np.ndarray):
    with pytest.raises(solver.InvalidInput, match=r"shape \(119,\)") as raised:
        solve(study_wing(), flight(10.0), initial_guess=guess)
    assert raised.value.field == "initial_guess"


# --- Typed failures -----------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("options", "field"),
    [({"max_iterations": 0}, "max_iterations"), ({"tolerance": 1e-300}, "tolerance")],
    ids=["no-iterations", "below-round-off"],
)
def test_a_budget_no_solve_can_meet_is_refused_as_input(options: dict, field: str):
    """No iterations, or a tolerance below round-off (the residual bottoms out near 1e-15),
    can never give an equilibrium: they are refused before any numerics, as the API does."""
    with pytest.raises(solver.InvalidInput) as raised:
        SolverOptions(**options)
    assert raised.value.field == field


def test_the_tightest_tolerance_allowed_is_met():
    options = SolverOptions(tolerance=1e-14)
    e = solve(study_wing(), flight(15.0), options=options)
    assert e.solver.residual_norm <= 1e-14


@pytest.mark.parametrize("max_iterations", range(1, 6))
@pytest.mark.parametrize("velocity", [10.0, 20.0])
def test_only_converged_stable_states_are_returned(velocity: float, max_iterations: int):
    """Whatever the iteration budget: an equilibrium that meets the tolerance, or an error."""
    options = SolverOptions(max_iterations=max_iterations)
    try:
        e = solve(study_wing(), flight(velocity), options=options)
    except solver.SolverError:
        return
    r0, r1 = e.evaluation.r0, e.evaluation.r1
    assert np.max(np.abs(r0 + e.dynamic_pressure * r1)) <= options.tolerance
    assert e.solver.residual_norm <= options.tolerance
    assert e.stability.stable


def test_the_fold_is_reported_on_request():
    wing = study_wing()
    assert solve(wing, flight(10.0)).fold is None
    reported = solve(wing, flight(10.0), options=SolverOptions(find_fold=True)).fold
    assert reported is not None and reported.velocity == pytest.approx(21.4397, abs=1e-4)


def test_beyond_the_fold_is_no_equilibrium_naming_it():
    with pytest.raises(NoEquilibrium) as raised:
        solve(study_wing(), flight(23.0))
    assert raised.value.fold_velocity == pytest.approx(21.4397, abs=1e-4)
    assert raised.value.velocity == 23.0


def test_the_study_density_is_the_one_aerosandboxs_reference_used():
    assert load_reference(REFERENCE).rho == DENSITY


def test_a_degenerate_wing_ends_in_a_typed_error_not_a_crash():
    """Found by schema fuzzing: 131 stations over a 1e-5 m semispan under an 81 m chord made the
    rigid wing's system singular, and LinAlgError escaped (HTTP 500). Valid input whose numbers
    cannot be computed is a ConvergenceError. (Semispans under 1 cm are refused now; the
    shortest accepted, under the same chord, is solved.)"""
    wing = solver.Wing.create(np.linspace(0, 0.01, 31), 81.38702612179208, 0.778, 9.7e11, 5.7e11)
    try:
        solve(wing, FlightCondition(812.55, 25.43, 1.225))
    except solver.SolverError as error:
        assert isinstance(error, ConvergenceError | NoEquilibrium)
    (point,) = solver.airspeed_sweep(
        wing, [812.55], solver.FlightCondition(None, 25.43, 1.225)
    ).points  # no exception escapes
    if point.status == "equilibrium":
        assert point.equilibrium is not None and point.no_equilibrium is None
    else:
        assert point.equilibrium is None and point.no_equilibrium is not None
        assert isinstance(point.error, solver.SolverError)
