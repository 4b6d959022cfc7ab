"""Where an answer leaves the model's validity (`solver.statics.validity`, issue 15).

Every finding is checked against the limits computed here by hand from the answer's own arrays
(the documented formulas, nothing shared with the module): the design study's wing at 10, 15,
18 and 20 m/s, a stiff wing over its whole range below divergence, per-station cl_max, trimmed
answers and sweeps. A property test shows that judging validity never changes a number of the
answer.
"""

from __future__ import annotations

import dataclasses
import functools
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import solver
from solver import Equilibrium, InvalidInput, SolverOptions, ValidityLimits
from solver.statics.system import CoupledSystem
from tests.conftest import fuzz_examples
from tests.study import DENSITY, flight, study_arrays, study_wing

DEFAULTS = ValidityLimits()
STUDY_WEIGHT = 300.0  # [N]
# A wing stiff for its divergence: the study's planform with the elastic axis at 30 % chord
# (0.05 c behind the quarter chord), EI x 100 and GJ x 10, at 2 deg: linear divergence at
# 132.6 m/s, the branch from the jig folds at 118.3 m/s.
STIFF_ALPHA = 2.0
STIFF_SPEEDS = [10.0, 30.0, 50.0, 70.0, 85.0, 95.0, 100.0, 105.0, 110.0, 115.0]


def stiff_wing() -> solver.Wing:
    a = study_arrays()
    return solver.Wing.create(
        a["y"], a["chord"], 0.3, 100 * a["bending_stiffness"], 10 * a["torsional_stiffness"]
    )


@functools.cache
def _study(velocity: float, limits: ValidityLimits = DEFAULTS) -> Equilibrium:
    return solver.solve(study_wing(), flight(velocity), options=SolverOptions(validity=limits))


@functools.cache
def _stiff_sweep() -> solver.AirspeedSweep:
    return solver.airspeed_sweep(
        stiff_wing(), STIFF_SPEEDS, solver.FlightCondition(None, STIFF_ALPHA, DENSITY)
    )


# ------------------------------------------------------------------------------ by hand


def section_cl(eq: Equilibrium) -> np.ndarray:
    """Each strip's lift per unit span over q and its mean chord."""
    chord = eq.wing.chord
    return eq.panels.lift_per_span / (eq.dynamic_pressure * (chord[1:] + chord[:-1]) / 2)


def by_hand(eq: Equilibrium, limits: ValidityLimits = DEFAULTS) -> list[tuple]:
    """(code, measure, indices, value, limit) of every finding the documented limits give."""
    wing, stations = eq.wing, eq.stations
    found = []

    def judge(code, measure, values, bound):
        bound = np.broadcast_to(np.asarray(bound, dtype=float), values.shape)
        over = [i for i in range(values.size) if abs(values[i]) > bound[i]]
        if over:
            worst = max(over, key=lambda i: abs(values[i]) / bound[i])
            found.append((code, measure, over, float(values[worst]), float(bound[worst])))

    heave_fraction = stations.heave / wing.semispan
    judge("large_deflection", "heave_fraction", heave_fraction, limits.heave_fraction)
    judge("large_deflection", "slope", stations.slope, limits.slope)
    judge("large_twist", "twist", stations.axis_twist, limits.twist)
    cl_max = limits.cl_max if wing.cl_max is None else (wing.cl_max[1:] + wing.cl_max[:-1]) / 2
    judge("section_stall", "section_cl", section_cl(eq), cl_max)
    if eq.stability.margin > limits.divergence_margin:
        found.append(
            ("near_divergence", "margin", [], eq.stability.margin, limits.divergence_margin)
        )
    return found


def reported(eq: Equilibrium) -> list[tuple]:
    return [(f.code, f.measure, f.indices, f.value, f.limit) for f in eq.validity]


def assert_as_by_hand(eq: Equilibrium, limits: ValidityLimits = DEFAULTS) -> None:
    assert reported(eq) == by_hand(eq, limits)
    for finding in eq.validity:
        where = {"stations": eq.stations.y, "panels": eq.panels.y}.get(finding.where)
        assert finding.y == ([] if where is None else [float(where[i]) for i in finding.indices])
        assert finding.message and finding.unit in ("-", "deg")


# ---------------------------------------------------------------------------- the study


def test_the_study_wing_at_10_ms_is_within_every_limit():
    eq = _study(10.0)
    assert eq.validity == []
    # The numbers: largest section lift coefficient 0.63, tip heave 1 % of the semispan.
    assert float(np.max(section_cl(eq))) == pytest.approx(0.63, abs=0.005)
    assert eq.tip_heave / eq.wing.semispan == pytest.approx(0.01, abs=0.0005)


@pytest.mark.parametrize(
    ("velocity", "codes"),
    [
        (10.0, []),
        (15.0, []),
        (18.0, ["section_stall"]),
        (20.0, ["large_deflection", "large_twist", "section_stall", "near_divergence"]),
    ],
)
def test_the_study_wings_findings_are_the_limits_computed_by_hand(velocity, codes):
    eq = _study(velocity)
    assert [f.code for f in eq.validity] == codes
    assert_as_by_hand(eq)


def test_the_study_wing_at_20_mps_stalls_bends_twists_and_nears_divergence():
    eq = _study(20.0)
    found = {f.measure: f for f in eq.validity}
    # Section lift coefficients reach 1.70 near the tip, past the thin airfoil's 1.2 on the
    # outer half (strips 15 to 28).
    stall = found["section_cl"]
    assert stall.value == pytest.approx(1.70, abs=0.005) and stall.limit == 1.2
    assert stall.indices == list(range(15, 29)) and stall.where == "panels"
    assert "1.70" in stall.message
    # Tip heave 9.6 % of the semispan: within the 10 %, but the slope reaches 0.148 > 0.1.
    assert eq.tip_heave / eq.wing.semispan == pytest.approx(0.096, abs=0.0005)
    assert "heave_fraction" not in found
    assert found["slope"].value == pytest.approx(0.148, abs=0.0005)
    assert found["slope"].indices[-1] == 29
    # Tip twist 13.7 deg (13.66 at the station before the tip) past 10 deg.
    assert eq.tip_twist == pytest.approx(13.65, abs=0.005)
    assert found["twist"].value == pytest.approx(13.66, abs=0.005)
    assert found["twist"].unit == "deg"
    # Near divergence: 58 % of the local divergence pressure, the lift 6 times as sensitive
    # to q as the rigid wing's (one torsion mode would say 1 / (1 - 0.584)^2 = 5.8).
    near = found["margin"]
    assert near.value == eq.stability.margin == pytest.approx(0.584, abs=0.0005)
    assert near.sensitivity == pytest.approx(1 / (1 - near.value) ** 2, rel=0.05)
    assert near.where == "wing" and near.indices == [] and near.y == []


def test_the_sensitivity_is_the_lift_slope_in_q_over_the_rigid_wings():
    """d(lift)/d(q) from the tangent against a central difference of two solves."""
    eq = _study(20.0)
    q = eq.dynamic_pressure
    dq = 1e-4 * q
    lifts = [
        solver.solve(study_wing(), flight(math.sqrt(2 * (q + s * dq) / DENSITY))).lift
        for s in (-1, 1)
    ]
    slope = (lifts[1] - lifts[0]) / (2 * dq)
    near = eq.validity[-1]
    assert near.code == "near_divergence"
    assert near.sensitivity == pytest.approx(slope / (eq.totals.rigid_lift / q), rel=1e-5)


@pytest.mark.parametrize("velocity", [20.0, 21.0], ids=["20mps", "21mps"])
def test_the_sensitivitys_lift_derivative_is_the_exact_gradients_to_1e_9(velocity: float):
    """The lift's derivative along dx/dq is differenced from two residual evaluations; the
    exact gradient of the coupled evaluation (CasADi's, one Jacobian's cost) along the same
    dx/dq agrees to ~1e-11, far inside the 1e-9 asked here."""
    eq = _study(velocity)
    system = CoupledSystem.of(eq.wing, eq.flight.alpha, eq.options)
    q = eq.dynamic_pressure
    rate = np.linalg.solve(eq.evaluation.jacobian(q), -eq.evaluation.r1)
    _, terms = system.evaluate_with_alpha(eq.state)
    exact = (terms.lift + q * float(terms.lift_x @ rate)) / (eq.totals.rigid_lift / q)
    (near,) = [finding for finding in eq.validity if finding.code == "near_divergence"]
    assert near.sensitivity == pytest.approx(exact, rel=1e-9)


def test_a_stiff_wing_has_no_finding_below_its_divergence():
    """Nothing leaves the model's validity until q nears divergence: no finding at any speed
    where the margin is below 0.5, near_divergence exactly where it is above. Deflection and
    stall never appear; the twist, which grows without bound towards the fold at any alpha,
    passes 10 deg only in its last 3 % of airspeed (115 m/s, fold at 118.3 m/s)."""
    result = _stiff_sweep()
    assert result.divergence.fold.velocity == pytest.approx(118.3, abs=0.05)
    margins = []
    for point in result.points:
        eq = point.equilibrium
        assert eq is not None
        assert_as_by_hand(eq)
        codes = [f.code for f in eq.validity]
        if eq.stability.margin <= 0.5:
            assert codes == []
        elif point.velocity < 115.0:
            assert codes == ["near_divergence"]
        else:
            assert codes == ["large_twist", "near_divergence"]
        margins.append(eq.stability.margin)
    assert min(margins) < 0.5 < max(margins)  # both sides of the limit are seen
    first = min(p.velocity for p in result.points if p.equilibrium.stability.margin > 0.5)
    assert [(o.code, o.velocity) for o in result.validity] == [
        ("large_twist", 115.0),
        ("near_divergence", first),
    ]


def test_options_move_every_limit():
    limits = ValidityLimits(
        heave_fraction=0.02, slope=0.3, twist=4.0, cl_max=0.8, divergence_margin=0.3
    )
    eq = _study(15.0, limits)
    assert [f.measure for f in eq.validity] == ["heave_fraction", "twist", "section_cl", "margin"]
    assert_as_by_hand(eq, limits)
    assert all(
        f.limit == getattr(limits, name)
        for f, name in zip(
            eq.validity, ["heave_fraction", "twist", "cl_max", "divergence_margin"], strict=True
        )
    )


def test_the_wings_own_cl_max_per_station_decides_stall():
    # 2.0 at the root falling to 0.6 at the tip: stall only where the section's own limit is
    # passed, judged at each strip against the mean of its stations'.
    cl_max = np.linspace(2.0, 0.6, 30)
    wing = solver.Wing.create(**study_arrays(), cl_max=cl_max)
    eq = solver.solve(wing, flight(15.0))
    assert_as_by_hand(eq)
    stall = eq.validity[0]
    assert stall.code == "section_stall" and "wing.cl_max" in stall.message
    assert stall.indices == list(range(24, 29))
    assert stall.limit == pytest.approx((cl_max[28] + cl_max[29]) / 2)  # the tip strip's
    # The numbers are the study wing's: cl_max says nothing to the lattice.
    plain = _study(15.0)
    assert np.array_equal(eq.state, plain.state) and plain.validity == []
    # A high cl_max everywhere: no stall at 20 m/s.
    high = solver.solve(solver.Wing.create(**study_arrays(), cl_max=2.0), flight(20.0))
    assert "section_stall" not in [f.code for f in high.validity]
    assert np.array_equal(high.state, _study(20.0).state)


def test_cl_max_is_part_of_the_wings_identity_and_validated():
    plain = study_wing()
    given_ = solver.Wing.create(**study_arrays(), cl_max=1.2)
    assert given_.key != plain.key  # what is said about an answer is cached with it
    assert solver.Wing.create(**study_arrays(), cl_max=[1.2] * 30).key == given_.key
    with pytest.raises(InvalidInput, match="cl_max"):
        solver.Wing.create(**study_arrays(), cl_max=-1.0)
    with pytest.raises(InvalidInput, match="cl_max"):
        solver.Wing.create(**study_arrays(), cl_max=[1.2] * 29)


@pytest.mark.parametrize(
    ("name", "value"),
    [
        ("heave_fraction", 0.0),
        ("slope", -1.0),
        ("twist", math.inf),
        ("cl_max", math.nan),
        ("divergence_margin", 1.5),
        ("divergence_margin", 0.0),
    ],
)
def test_invalid_limits_are_refused(name, value):
    with pytest.raises(InvalidInput) as raised:
        ValidityLimits(**{name: value})
    assert raised.value.field == name


# -------------------------------------------------------------------------------- sweeps


def test_a_sweep_says_from_which_airspeed_on_each_finding_appears():
    # In any order, with one speed past the fold (no equilibrium there, nothing to say).
    result = solver.airspeed_sweep(
        study_wing(),
        [20.0, 6.0, 23.0, 18.0, 10.0, 15.0],
        solver.FlightCondition(None, 5.0, DENSITY),
    )
    for point in result.points:
        if point.equilibrium is not None:
            assert_as_by_hand(point.equilibrium)
    onsets = {o.code: o for o in result.validity}
    assert list(onsets) == ["large_deflection", "large_twist", "section_stall", "near_divergence"]
    assert onsets["section_stall"].velocity == 18.0
    assert onsets["section_stall"].velocities == [18.0, 20.0]
    assert "from 18 m/s on" in onsets["section_stall"].message
    for code in ("large_deflection", "large_twist", "near_divergence"):
        assert onsets[code].velocity == 20.0 and onsets[code].velocities == [20.0]
    # The sweep's points say what single solves say (their numbers agree to the tolerance;
    # the margin, from Jacobians up to one Newton step away, to 1e-5).
    swept, single = reported(result.points[0].equilibrium), reported(_study(20.0))
    assert [f[:3] for f in swept] == [f[:3] for f in single]
    assert [f[3] for f in swept] == pytest.approx([f[3] for f in single], rel=1e-5)


def test_trimmed_answers_carry_their_findings():
    result = solver.airspeed_sweep(
        study_wing(),
        [8.0, 14.0, 20.0],
        solver.FlightCondition(None, density=DENSITY, lift=STUDY_WEIGHT),
    )
    for point in result.points:
        assert point.equilibrium is not None
        assert_as_by_hand(point.equilibrium)
    fast = result.points[-1].equilibrium
    assert [f.code for f in fast.validity] == ["near_divergence"]
    assert fast.validity[0].sensitivity > 1
    assert [(o.code, o.velocity) for o in result.validity] == [("near_divergence", 20.0)]
    single = solver.trim(
        study_wing(), solver.FlightCondition(20.0, density=DENSITY, lift=STUDY_WEIGHT)
    )
    assert [f[:3] for f in reported(single)] == [f[:3] for f in reported(fast)]


# ------------------------------------------------------------------------------ property


def _plain(value: object) -> object:
    """A result as plain data (its reported fields, arrays as lists)."""
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        return {
            f.name: _plain(getattr(value, f.name))
            for f in dataclasses.fields(value)
            if not f.metadata.get("internal")
        }
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, list | tuple):
        return [_plain(v) for v in value]
    return value


def _numbers(eq: Equilibrium) -> dict:
    """The answer's reported numbers, less what is said about it and the time it took."""
    data = _plain(eq)
    assert isinstance(data, dict)
    data.pop("validity")
    data["solver"].pop("seconds")
    return data


limits = st.builds(
    ValidityLimits,
    heave_fraction=st.floats(1e-4, 1.0),
    slope=st.floats(1e-4, 1.0),
    twist=st.floats(0.01, 90.0),
    cl_max=st.floats(0.1, 3.0),
    divergence_margin=st.floats(0.01, 1.0),
)


@settings(max_examples=fuzz_examples(12), deadline=None)
@given(
    limits=limits,
    velocity=st.sampled_from([6.0, 12.0, 18.0, 20.0, 21.0]),
    trimmed=st.booleans(),
)
def test_judging_validity_never_changes_a_number_of_the_answer(limits, velocity, trimmed):
    options = SolverOptions(validity=limits)
    if trimmed:
        condition = solver.FlightCondition(velocity, density=DENSITY, lift=STUDY_WEIGHT)
        plain = solver.trim(study_wing(), condition)
        judged = solver.trim(study_wing(), condition, options)
    else:
        plain = _study(velocity)
        judged = solver.solve(study_wing(), flight(velocity), options=options)
    assert np.array_equal(judged.state, plain.state)
    assert _numbers(judged) == _numbers(plain)
    assert_as_by_hand(judged, limits)
    assert dataclasses.replace(judged, validity=[]).totals == plain.totals


# ------------------------------------------------------------------------ control surfaces


@pytest.mark.parametrize(("deflection", "found"), [(10.0, False), (-10.5, True), (15.0, True)])
def test_a_flap_deflected_past_the_linear_range_is_a_finding(deflection, found):
    """control_deflection at |deflection| > 10 deg (validity.CONTROL_DEFLECTION), with the
    surface's index and the middle of its extent; an aileron, which a symmetric answer does
    not deflect, is never one there."""
    surfaces = [
        {"name": "flap", "start": 0.0, "end": 0.4, "hinge": 0.75, "deflection": deflection},
        {
            "name": "ail",
            "start": 0.5,
            "end": 0.9,
            "hinge": 0.75,
            "deflection": 20.0,
            "kind": "aileron",
        },
    ]
    wing = solver.Wing.create(**study_arrays(13), control_surfaces=surfaces)
    answer = solver.solve(wing, flight(8.0, 0.0), options=SolverOptions(chordwise_panels=3))
    findings = [f for f in answer.validity if f.code == "control_deflection"]
    if not found:
        assert findings == []
        return
    (finding,) = findings
    assert finding.where == "control_surfaces" and finding.indices == [0]
    assert finding.value == deflection and finding.limit == 10.0 and finding.unit == "deg"
    assert finding.y == [pytest.approx(1.0)]
    assert finding.half is None


def test_a_roll_answer_is_judged_on_both_wings():
    """A 15 deg aileron at 8 m/s on the study's wing with cl_max 0.4: the right wing's aileron
    strips pass +0.4 and the left wing's -0.4 (its trailing edge up), each found on its own
    wing, in the order of the codes, the deflection once; the findings never change the
    answer's numbers."""
    surface = {
        "name": "ail",
        "start": 0.5,
        "end": 0.9,
        "hinge": 0.75,
        "deflection": 15.0,
        "kind": "aileron",
    }
    wing = solver.Wing.create(**study_arrays(13), control_surfaces=[surface], cl_max=0.4)
    options = SolverOptions(chordwise_panels=3)
    answer = solver.roll(wing, flight(8.0, 0.0), options)
    stalls = [f for f in answer.validity if f.code == "section_stall"]
    assert {f.half for f in stalls} == {"right", "left"}
    assert all(f.message.startswith(f"On the {f.half} wing") for f in stalls)
    assert [f.code for f in answer.validity][-1] == "control_deflection"
    relaxed = solver.roll(
        wing, flight(8.0, 0.0), dataclasses.replace(options, validity=ValidityLimits(cl_max=5.0))
    )
    assert relaxed.rolling_moment == answer.rolling_moment
