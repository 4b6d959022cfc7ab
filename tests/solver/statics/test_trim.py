"""Trimmed flight (`solver.trim`): alpha solved for a lift, against AeroSandbox's trimmed Opti
(tests/reference/data: trim_study, trim_swept, k4_dae11_trim; CONVENTIONS.md item 14), against
the alpha solve at the trimmed alpha, and against what a held lift means physically.

Tolerances: fields as in test_reference_extended (1e-6 relative to the largest value); alpha
1e-6 deg absolute (AeroSandbox's IPOPT stops at 1e-10 in lift, ~1e-11 deg of alpha).
"""

from __future__ import annotations

import functools
import math

import numpy as np
import pytest

import solver
from solver.statics.trim import _trimmed_point
from tests.reference import Reference, extended_references
from tests.solver.test_reference_extended import QUANTITIES, RELATIVE_TOLERANCE
from tests.study import study_wing

ALPHA_TOLERANCE = 1e-6  # [deg]
RHO = solver.ISA_SEA_LEVEL_DENSITY
STUDY_WEIGHT = 300.0  # [N] the study's sailplane-model wing at its weight (the references')

TRIMMED = [r for r in extended_references() if r.trimmed_lift is not None]
POINTS = [
    pytest.param(reference, e["velocity"], id=f"{reference.name}-{e['velocity']:g}ms")
    for reference in TRIMMED
    for e in reference.equilibria
]
RIGID_POINTS = [
    pytest.param(
        reference, r["velocity"], r["alpha_deg"], id=f"{reference.name}-{r['velocity']:g}ms"
    )
    for reference in TRIMMED
    for r in reference.data["rigid_trim"]
]


@functools.cache
def _trimmed(reference: Reference, velocity: float) -> solver.Equilibrium:
    condition = solver.FlightCondition(velocity, density=reference.rho, lift=reference.trimmed_lift)
    return solver.trim(reference.wing, condition, reference.options)


def _relative(ours, theirs) -> float:
    ours, theirs = np.atleast_1d(ours), np.atleast_1d(theirs)
    return float(np.max(np.abs(ours - theirs)) / np.max(np.abs(theirs)))


def test_the_trimmed_references_are_the_ones_the_issue_names():
    names = {r.name for r in TRIMMED}
    assert {"trim_study", "trim_swept", "k4_dae11_trim"} <= names  # and combined: all at once
    assert all(r.trimmed_lift in (STUDY_WEIGHT, 400.0) for r in TRIMMED)


@pytest.mark.parametrize(("reference", "velocity"), POINTS)
def test_trimmed_alpha_matches_aerosandbox(reference: Reference, velocity: float):
    theirs = reference.equilibrium_at(velocity)["alpha_deg"]
    assert abs(_trimmed(reference, velocity).totals.alpha - theirs) <= ALPHA_TOLERANCE


@pytest.mark.parametrize("quantity", list(QUANTITIES))
@pytest.mark.parametrize(("reference", "velocity"), POINTS)
def test_trimmed_equilibrium_matches_aerosandbox(reference, velocity, quantity: str):
    ours_of, key = QUANTITIES[quantity]
    theirs = reference.equilibrium_at(velocity)[key]
    assert _relative(ours_of(_trimmed(reference, velocity)), theirs) <= RELATIVE_TOLERANCE


@pytest.mark.parametrize(("reference", "velocity", "alpha"), RIGID_POINTS)
def test_rigid_trim_matches_aerosandbox(reference, velocity, alpha):
    condition = solver.FlightCondition(velocity, density=reference.rho, lift=reference.trimmed_lift)
    assert abs(solver.rigid_trim_alpha(reference.wing, condition, reference.options) - alpha) <= (
        ALPHA_TOLERANCE
    )
    assert abs(_trimmed(reference, velocity).totals.rigid_alpha - alpha) <= ALPHA_TOLERANCE


@pytest.mark.parametrize("velocity", [8.0, 14.0, 20.0, 23.0], ids=lambda v: f"{v:g}ms")
def test_alpha_solve_at_the_trimmed_alpha_is_the_same_equilibrium(velocity: float):
    trimmed = solver.trim(study_wing(), solver.FlightCondition(velocity, lift=STUDY_WEIGHT))
    at_alpha = solver.solve(study_wing(), solver.FlightCondition(velocity, trimmed.totals.alpha))
    # Both converge to 1e-10 in the residual; the difference is that times the conditioning,
    # which grows as 1 / (1 - q/q_div) towards divergence (23 m/s: margin 0.91).
    scale = 1e-8 / (1.0 - trimmed.stability.margin)
    assert np.max(np.abs(trimmed.state - at_alpha.state)) <= scale
    assert at_alpha.totals.lift == pytest.approx(STUDY_WEIGHT, rel=scale)
    assert at_alpha.stability.stable and at_alpha.stability.branch == "jig"


@pytest.mark.parametrize("lift", [300.0, -150.0, 1e-3], ids=["weight", "negative", "tiny"])
def test_the_lift_is_held(lift: float):
    trimmed = solver.trim(study_wing(), solver.FlightCondition(12.0, lift=lift))
    assert trimmed.totals.lift == pytest.approx(lift, rel=1e-9)
    assert trimmed.totals.rigid_lift == pytest.approx(lift, rel=1e-9)
    assert trimmed.totals.lift_amplification == pytest.approx(1.0, rel=1e-9)
    assert np.sign(trimmed.totals.alpha) == np.sign(lift)


def test_twice_the_lift_needs_more_alpha_but_less_than_the_rigid_wing_and_twice_the_moment():
    wing, velocity = study_wing(), 12.0
    two_g = solver.trim(wing, solver.FlightCondition(velocity, lift=2 * STUDY_WEIGHT))
    one_g = solver.trim(wing, solver.FlightCondition(velocity, lift=STUDY_WEIGHT))
    # The flexible wing twists nose-up under the load, so it needs less alpha than the rigid one.
    assert two_g.totals.alpha > one_g.totals.alpha
    assert two_g.totals.alpha < two_g.totals.rigid_alpha
    # The root moment comes from the vertical force in the wing's axes, the trim holds the lift
    # across the freestream: they differ by the change of alpha (1.9886 here, and 1.9896 for a
    # wing 100 times stiffer), so the moment doubles to within 1 %, not exactly.
    assert two_g.totals.root_bending_moment == pytest.approx(
        2 * one_g.totals.root_bending_moment, rel=0.01
    )


def _lift_slope(wing, velocity: float, alpha: float, *, rigid: bool) -> float:
    """[N/deg] central difference of the lift in alpha (the rigid one from the jig)."""
    step = 1e-3

    def lift(a: float) -> float:
        flight = solver.FlightCondition(velocity, a)
        if rigid:
            return solver.solve(wing, flight).totals.rigid_lift
        return solver.solve(wing, flight).totals.lift

    return (lift(alpha + step) - lift(alpha - step)) / (2 * step)


@pytest.mark.parametrize("velocity", [10.0, 18.0], ids=lambda v: f"{v:g}ms")
def test_lift_effectiveness_is_the_ratio_of_lift_curve_slopes(velocity: float):
    wing = study_wing()
    trimmed = solver.trim(wing, solver.FlightCondition(velocity, lift=STUDY_WEIGHT))
    flexible = _lift_slope(wing, velocity, trimmed.totals.alpha, rigid=False)
    rigid = _lift_slope(wing, velocity, trimmed.totals.rigid_alpha, rigid=True)
    # Central differences over 1e-3 deg: truncation ~1e-7 relative, round-off ~1e-9 / 1e-3.
    assert trimmed.totals.lift_effectiveness == pytest.approx(flexible / rigid, rel=1e-5)
    # The study's wing twists nose-up under load (elastic axis aft of the quarter chord).
    assert trimmed.totals.lift_effectiveness > 1.0


def test_trimmed_divergence_limit_is_where_the_margin_reaches_one():
    wing = study_wing()
    limit = solver.trimmed_divergence_limit(wing, STUDY_WEIGHT, RHO)
    linear = solver.linear_divergence(wing, RHO)
    assert limit.kind == "trimmed_stability_limit" and limit.velocity is not None
    # Trimmed, alpha falls towards zero at the limit: the wing there is nearly the unloaded
    # one, so the limit lies just below the classical speed (within 1 %), far above the
    # fold of the 5 deg branch (21.4 m/s).
    assert 0.99 * linear.velocity < limit.velocity < linear.velocity
    below = solver.trim(wing, solver.FlightCondition(0.999 * limit.velocity, lift=STUDY_WEIGHT))
    assert below.stability.stable and below.stability.margin == pytest.approx(1.0, abs=0.01)
    with pytest.raises(solver.NoEquilibrium, match="statically unstable"):
        solver.trim(wing, solver.FlightCondition(1.001 * limit.velocity, lift=STUDY_WEIGHT))


@pytest.mark.parametrize("factor", [1.001, 1.5, 4.0, 30.0], ids=lambda f: f"{f:g}x")
def test_past_the_trimmed_limit_a_solve_and_a_sweep_name_the_limit(factor: float):
    """The answer beyond the limit is the same alone and in a sweep, whatever else the sweep
    asks, and names the limit (a sweep answers it without a trimmed solve)."""
    wing = study_wing()
    limit = solver.trimmed_divergence_limit(wing, STUDY_WEIGHT, RHO)
    assert limit.velocity is not None
    velocity = factor * limit.velocity
    with pytest.raises(solver.NoEquilibrium) as raised:
        solver.trim(wing, solver.FlightCondition(velocity, lift=STUDY_WEIGHT))
    assert raised.value.fold_velocity == limit.velocity
    assert "past the trimmed divergence limit" in str(raised.value)
    for others in ([], [10.0, 3 * velocity]):
        point = solver.airspeed_sweep(
            wing, [velocity, *others], solver.FlightCondition(None, density=RHO, lift=STUDY_WEIGHT)
        ).points[0]
        assert point.status == "no_equilibrium" and point.no_equilibrium is not None
        assert point.no_equilibrium.reason == str(raised.value)
        assert point.no_equilibrium.fold_velocity == limit.velocity


@pytest.mark.parametrize("factor", [1.001, 1.5, 4.0], ids=lambda f: f"{f:g}x")
def test_past_the_trimmed_limit_the_trimmed_wing_is_unstable_where_it_exists(factor: float):
    """What answering past the limit without a solve rests on: at a fixed lift the twist, and
    with it the trimmed wing's divergence pressure, hardly move with q, so q passes it once;
    every trimmed equilibrium beyond is unstable (or the trimmed path never reaches one)."""
    wing = study_wing()
    limit = solver.trimmed_divergence_limit(wing, STUDY_WEIGHT, RHO)
    assert limit.velocity is not None
    condition = solver.FlightCondition(factor * limit.velocity, lift=STUDY_WEIGHT)
    try:
        point = _trimmed_point(wing, condition, solver.SolverOptions())
    except solver.NoEquilibrium:
        return  # the trimmed branch turned back first
    local = point.local_divergence_pressure()
    assert local is not None and local < condition.dynamic_pressure


def test_trim_sweep_reports_divergence_at_a_fixed_lift():
    wing = study_wing()
    result = solver.airspeed_sweep(
        wing, [26.0, 8.0, 16.0, 22.0], solver.FlightCondition(None, density=RHO, lift=STUDY_WEIGHT)
    )
    statuses = [point.status for point in result.points]
    assert statuses == ["no_equilibrium", "equilibrium", "equilibrium", "equilibrium"]
    margins = [p.equilibrium.stability.margin for p in result.points[1:]]
    assert margins == sorted(margins) and margins[-1] < 1.0
    # For one torsion mode 1/lift effectiveness = 1 - q/q_div exactly; the study's wing is
    # nearly that, so the fit lands within 3 % of the classical divergence pressure.
    fit = result.divergence.fit
    assert fit.amplification == "lift_effectiveness"
    assert fit.dynamic_pressure == pytest.approx(
        result.divergence.linear.dynamic_pressure, rel=0.03
    )
    assert result.divergence.fold.kind == "trimmed_stability_limit"
    for point in result.points[1:]:
        alone = solver.trim(wing, solver.FlightCondition(point.velocity, lift=STUDY_WEIGHT))
        assert np.array_equal(alone.state, point.equilibrium.state)


def test_a_trimmed_limit_whose_secant_leaves_positive_pressures_says_so():
    # A millimetre chord, a near-zero stiffness, -60 deg of sweep and 30 deg of jig twist (the
    # service's fuzzing found it): the secant's next q is negative, which no airspeed has.
    wing = solver.Wing.create(
        np.linspace(0.0, 5.0, 8), 0.001, 0.0, 0.001, 0.001, sweep=-59.999, jig_twist=30.0
    )
    limit = solver.trimmed_divergence_limit(wing, 1e-6, 1e-4)
    assert limit.velocity is None and "positive dynamic pressures" in limit.reason
    assert limit.searched_to_velocity > 0
    result = solver.airspeed_sweep(
        wing, [10.0], solver.FlightCondition(None, density=1e-4, lift=1e-6)
    )
    assert result.divergence.fold == limit


def test_a_trimmed_answer_does_not_depend_on_history():
    wing, condition = study_wing(), solver.FlightCondition(15.0, lift=STUDY_WEIGHT)
    solver.clear_caches()
    fresh = solver.trim(wing, condition)
    for velocity in (9.0, 21.0, 15.5):
        solver.trim(wing, solver.FlightCondition(velocity, lift=2 * STUDY_WEIGHT))
        solver.solve(wing, solver.FlightCondition(velocity, 3.0))
    again = solver.trim(wing, condition)
    assert np.array_equal(fresh.state, again.state)
    assert fresh.totals.alpha == again.totals.alpha


@pytest.mark.parametrize(
    ("velocity", "lift", "match"),
    [
        (4.5, 300.0, r"needs alpha = 31.2. deg for this lift, beyond \+-30 deg"),
        (3.0, 300.0, "cannot carry this lift at any angle of attack"),
    ],
    ids=["too_slow", "too_heavy"],
)
def test_a_lift_the_wing_cannot_carry_is_no_equilibrium(velocity, lift, match):
    with pytest.raises(solver.NoEquilibrium, match=match):
        solver.trim(study_wing(), solver.FlightCondition(velocity, lift=lift))


@pytest.mark.parametrize(
    ("fields", "field"),
    [
        ({"velocity": 10.0, "lift": 0.0}, "lift"),
        ({"velocity": 10.0, "lift": math.nan}, "lift"),
        ({"velocity": -1.0, "lift": 300.0}, "velocity"),
        ({"velocity": 10.0, "lift": 300.0, "density": 0.0}, "density"),
    ],
    ids=["zero_lift", "nan_lift", "negative_speed", "no_air"],
)
def test_a_trim_condition_rejects_what_cannot_be_flown(fields, field):
    with pytest.raises(solver.InvalidInput) as raised:
        solver.FlightCondition(**fields)
    assert raised.value.field == field


def test_a_trimmed_limit_past_the_fastest_airspeed_is_no_limit_with_the_reason():
    """Found by the operation x option matrix: a wing stiff enough that its trimmed limit lies
    past 1000 m/s (the fastest airspeed a flight condition takes) was a 422 naming a
    `velocity` the request never had; it is a limit not found, as far as the model reaches."""
    wing = study_wing()
    stiff = solver.Wing.create(wing.y, wing.chord, 0.4, 1e9, 1e9)
    limit = solver.trimmed_divergence_limit(stiff, STUDY_WEIGHT, RHO)
    assert limit.velocity is None and limit.kind == "trimmed_stability_limit"
    assert limit.reason is not None and "1000 m/s" in limit.reason
    assert limit.searched_to_velocity == 1000.0
    answered = solver.solve(
        stiff,
        solver.FlightCondition(12.0, lift=STUDY_WEIGHT),
        options=solver.SolverOptions(find_fold=True),
    )
    assert answered.fold is not None and answered.fold.velocity is None


def test_the_trimmed_limit_of_strip_theory_is_its_own_whatever_was_asked_before():
    """The limit is kept in the solver's cache: strip theory's and the lattice's are two
    answers, each the same asked first or after the other (its key holds the aerodynamics)."""
    strip = solver.SolverOptions(aerodynamics="strip")
    solver.clear_caches()
    strip_first = solver.trimmed_divergence_limit(study_wing(), STUDY_WEIGHT, RHO, strip)
    lattice = solver.trimmed_divergence_limit(study_wing(), STUDY_WEIGHT, RHO)
    strip_after = solver.trimmed_divergence_limit(study_wing(), STUDY_WEIGHT, RHO, strip)
    assert strip_first.velocity is not None and lattice.velocity is not None
    assert strip_after.velocity == strip_first.velocity
    # Strip theory has no tip loss: it diverges well before the lattice (measured ~15 %).
    assert strip_first.velocity < 0.95 * lattice.velocity
