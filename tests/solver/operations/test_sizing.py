"""solver.operations.sizing: a loads question's plan (the cases given, then those its envelope
derives), its answer the same whether the cases run together or apart, the V-n diagrams the
cases came from, and what it refuses before any work."""

from __future__ import annotations

import dataclasses
import functools
import math

import numpy as np
import pytest

import solver
from solver.inputs.envelope import FlightEnvelope
from tests.solver.sizing import loads_wings
from tests.study import DENSITY, study_arrays

# The study's wing as a light aircraft of the CS-23 normal category: 250 and 300 N.
ENVELOPE = {
    "weights": [250.0, 300.0],
    "altitudes": [0.0],
    "category": "normal",
    "cl_max": 1.2,
    "cl_min": -0.6,
    "cruise_speed": 12.0,
    "dive_speed": 16.0,
}


def _loads(**changes: object) -> solver.LoadsInput:
    given: dict[str, object] = {
        "wing": loads_wings.wing(),
        "cases": loads_wings.CASES[:2],
        "envelope": FlightEnvelope(**ENVELOPE),  # type: ignore[arg-type]
    }
    return solver.LoadsInput(**(given | changes))  # type: ignore[arg-type]


@functools.cache
def _answer() -> solver.LoadsEnvelope:
    return _loads().run()


def test_the_plan_is_the_cases_given_then_every_vn_point_at_every_weight() -> None:
    task = _loads()
    names = [part.name for part in task.plan]
    assert names[:2] == ["cruise", "pull-up"]
    assert [part.kind for part in task.plan[:2]] == ["given", "given"]
    derived = task.plan[2:]
    assert {part.kind for part in derived} == {"manoeuvre", "gust"}
    assert "A+ at V_A, 25 kg, 0 m" in names and "gust D- at V_D, 31 kg, 0 m" in names
    assert len(set(names)) == len(names) == task.case_count


@pytest.mark.parametrize("category", ["normal", "utility", "aerobatic", "commuter", "cs25"])
@pytest.mark.parametrize("lift_slope", [None, 2.0, 9.0])
def test_the_case_count_is_the_plans_for_every_category_and_lift_slope(
    category: str, lift_slope: float | None
) -> None:
    """Counted without deriving the cases (the service's limit is checked before any work):
    which points a diagram has does not depend on where its gust lines put them."""
    envelope = FlightEnvelope(**ENVELOPE | {"category": category, "lift_slope": lift_slope})
    task = _loads(envelope=envelope, cases=())
    assert task.case_count == len(task.plan)


def test_the_answer_is_the_same_whether_the_cases_run_together_or_apart() -> None:
    """What the service does: each case run on its own (here in reverse order, as on other
    workers), the envelope assembled from their answers; each case depends on itself only."""
    task = _loads()
    apart = [part.run() for part in reversed(task.plan)][::-1]
    assembled = task.assemble(apart)
    together = _answer()
    assert [c.name for c in assembled.cases] == [c.name for c in together.cases]
    for ours, theirs in zip(assembled.cases, together.cases, strict=True):
        assert ours.status == theirs.status
        np.testing.assert_allclose(ours.bending_moment, theirs.bending_moment, rtol=1e-9)
    assert together.envelope is not None and assembled.envelope is not None
    np.testing.assert_allclose(
        assembled.envelope.max_torque, together.envelope.max_torque, rtol=1e-9
    )
    assert assembled.envelope.max_torque_case == together.envelope.max_torque_case


def test_every_derived_case_is_a_point_of_its_vn_diagram() -> None:
    answer = _answer()
    assert len(answer.vn) == 2  # two weights at one altitude
    points = {
        (diagram.weight, name): (v, n)
        for diagram in answer.vn
        for name, v, n in zip(
            diagram.points, diagram.point_airspeed, diagram.point_load_factor, strict=True
        )
    }
    for case in answer.cases[2:]:
        point = case.name.split(" at ")[0]
        v, n = points[(case.weight, point)]
        assert case.equivalent_airspeed == pytest.approx(v, rel=1e-12)
        assert case.load_factor == pytest.approx(n, rel=1e-12)
    assert answer.info.cases == len(answer.cases) and answer.info.answered <= answer.info.cases


def test_a_case_the_wing_cannot_fly_is_marked_and_the_others_answered() -> None:
    """CS-23's 3.8 g at the dive speed asks the study's wing for more than it carries before
    its trimmed limit: that case says so, every other keeps its loads."""
    answer = _answer()
    failed = [case for case in answer.cases if not case.answered]
    assert all(case.reason for case in failed)
    assert answer.info.answered == len(answer.cases) - len(failed) > 0
    assert answer.envelope is not None


def test_the_lift_slope_is_the_rigid_wings() -> None:
    """Pratt's a, where the envelope gives none: the lattice's dC_L/dalpha at alpha 0, both
    halves over the planform area, against a central difference of a very stiff wing's lift
    (its deformation 1e-6 of the soft wing's; the difference's error (h^2) under 1e-6)."""
    stiff = solver.Wing.create(**study_arrays(loads_wings.N, stiffness_scale=1e6))
    h = 0.01  # [deg]
    lifts = [
        solver.solve(stiff, solver.FlightCondition(12.0, alpha, DENSITY)).totals.lift
        for alpha in (-h, h)
    ]
    q = 0.5 * DENSITY * 12.0**2
    slope = (lifts[1] - lifts[0]) / math.radians(2 * h) / (q * stiff.planform_area)
    task = _loads(wing=stiff)
    assert task.lift_slope == pytest.approx(slope, rel=1e-5)


def test_a_zero_load_factor_case_flies_at_the_rigid_wings_zero_lift_alpha() -> None:
    """CS-23.333(b)'s zero at V_D (normal category): no lift to trim to, so the case flies
    where the rigid wing lifts nothing; a washed-out wing's is above zero."""
    arrays = study_arrays(loads_wings.N)
    twisted = solver.Wing.create(
        **arrays, jig_twist=-3.0 * arrays["y"] / 5.0, mass=loads_wings.MASS
    )
    task = _loads(wing=twisted, cases=())
    (zero, *_) = [part for part in task.plan if not part.flight.trimmed]
    assert zero.name.startswith("D- at V_D")
    flown = zero.run()
    assert flown.status == "equilibrium" and flown.load_factor == 0.0
    alpha = flown.alpha
    assert alpha is not None and alpha > 0.0
    stiff = solver.Wing.create(
        **study_arrays(loads_wings.N, stiffness_scale=1e6), jig_twist=-3.0 * arrays["y"] / 5.0
    )
    at = [
        solver.solve(stiff, solver.FlightCondition(12.0, a, DENSITY)).totals.lift
        for a in (alpha, alpha + 1.0)
    ]
    assert abs(at[0]) < 1e-6 * at[1]


@pytest.mark.parametrize(
    ("changes", "field"),
    [
        ({"cases": (), "envelope": None}, "cases"),
        ({"cases": (loads_wings.CASES[0], loads_wings.CASES[0])}, "cases[1].name"),
        ({"stations": (0, loads_wings.N)}, "stations[1]"),
        ({"envelope": FlightEnvelope(**ENVELOPE | {"manoeuvring_speed": 3.0})}, None),
    ],
    ids=["nothing to fly", "two cases one name", "a station past the tip", "V_A below V_S"],
)
def test_what_cannot_be_asked_is_refused_before_any_work(
    changes: dict[str, object], field: str | None
) -> None:
    with pytest.raises(solver.InvalidInput) as refused:
        _loads(**changes)
    if field is not None:
        assert refused.value.field == field


_GUSTS = (
    solver.GustCondition(
        "V_C gusts",
        solver.FlightCondition(12.0, density=DENSITY, weight=300.0),
        solver.GustSettings(gradients=5, modes=2, turbulence=False),
    ),
)


def test_gust_conditions_join_the_envelope_and_leave_the_other_cases_alone() -> None:
    without = _loads(envelope=None)
    with_gusts = _loads(envelope=None, gusts=_GUSTS)
    assert without.key != with_gusts.key and with_gusts.case_count == without.case_count + 2
    assert [part.name for part in with_gusts.plan[-2:]] == ["V_C gusts up", "V_C gusts down"]
    plain, joined = without.run(), with_gusts.run()
    for before, after in zip(plain.cases, joined.cases, strict=False):
        assert np.array_equal(before.bending_moment, after.bending_moment)
        assert np.array_equal(before.torque, after.torque)
    up, down = joined.cases[-2:]
    assert up.kind == down.kind == "gust_dynamic" and up.answered and down.answered
    gusts = solver.gust_analysis(loads_wings.wing(), _GUSTS[0].flight, _GUSTS[0].gust)
    assert up.bending_moment == pytest.approx(gusts.envelope.max_bending_moment, rel=1e-9)
    assert down.shear == pytest.approx(gusts.envelope.min_shear, rel=1e-9)
    envelope = joined.envelope
    assert envelope is not None
    for name in ("shear", "bending_moment", "torque"):
        table = np.vstack([getattr(case, name) for case in joined.cases if case.answered])
        assert np.array_equal(getattr(envelope, f"max_{name}"), table.max(axis=0))
        assert np.array_equal(getattr(envelope, f"min_{name}"), table.min(axis=0))


def test_gust_conditions_need_the_wings_mass() -> None:
    with pytest.raises(solver.InvalidInput) as caught:
        _loads(wing=solver.Wing.create(**study_arrays(16)), gusts=_GUSTS)
    assert caught.value.field == "wing.mass"


def test_gust_conditions_refuse_a_wing_bending_in_its_plane_naming_it() -> None:
    """Lag bending is taken in the load cases, not yet in the gust model (a 422 naming the
    field before any work)."""
    wing = loads_wings.wing()
    lag = dataclasses.replace(wing, in_plane_bending_stiffness=2 * wing.bending_stiffness)
    exact = solver.SolverOptions(structure="geometrically_exact")
    assert _loads(wing=lag, options=exact).case_count > 0
    with pytest.raises(solver.InvalidInput) as refused:
        _loads(wing=lag, options=exact, envelope=None, gusts=_GUSTS)
    assert refused.value.field == "wing.in_plane_bending_stiffness"
    assert "gust" in refused.value.reason


def test_a_gust_condition_past_flutter_is_answered_in_its_place() -> None:
    # The study's light wing trimmed at 40 m/s: past its divergence; the case says why.
    fast = solver.GustCondition(
        "fast", solver.FlightCondition(40.0, density=DENSITY, weight=300.0), _GUSTS[0].gust
    )
    answer = _loads(envelope=None, gusts=(fast,)).run()
    assert [case.status for case in answer.cases[-2:]] != ["equilibrium", "equilibrium"]
    assert all(case.reason for case in answer.cases[-2:])
    assert answer.cases[0].answered
