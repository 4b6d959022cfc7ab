"""solver.statics.airspeed_sweep: every point the branch's equilibrium at its airspeed, in the order
asked, the same whatever the order, and the study's printed sweep."""

from __future__ import annotations

import numpy as np
import pytest

import solver
from tests.study import DENSITY, SPAN, SWEEP, study_wing


@pytest.fixture(scope="module")
def study_sweep() -> dict[float, solver.Equilibrium]:
    result = solver.airspeed_sweep(
        study_wing(), list(SWEEP), solver.FlightCondition(None, 5.0, DENSITY)
    )
    assert all(point.status == "equilibrium" for point in result.points)
    return {point.velocity: point.equilibrium for point in result.points}


@pytest.mark.parametrize(
    ("velocity", "printed"),
    [
        pytest.param(6, "V =  6 m/s: CL = 0.470, tip twist =  0.55 deg", id="6ms"),
        pytest.param(12, "V = 12 m/s: CL = 0.565, tip twist =  2.67 deg", id="12ms"),
        pytest.param(15, "V = 15 m/s: CL = 0.666, tip twist =  4.93 deg", id="15ms"),
        pytest.param(18, "V = 18 m/s: CL = 0.847, tip twist =  8.89 deg", id="18ms"),
        pytest.param(20, "V = 20 m/s: CL = 1.070, tip twist = 13.65 deg", id="20ms"),
    ],
)
def test_the_studys_sweep_prints_its_numbers(study_sweep, velocity: int, printed: str):
    """Section 14.6, at the printed rounding (CL on the deformed area, as AeroSandbox's)."""
    e = study_sweep[velocity]
    line = (
        f"V = {velocity:2d} m/s: CL = {e.totals.CL_deformed_area:.3f}, "
        f"tip twist = {e.tip_twist:5.2f} deg"
    )
    assert line == printed


def test_the_top_of_the_sweep_prints_the_studys_numbers(study_sweep):
    top, cruise = study_sweep[20], study_sweep[10]
    rigid_cl = cruise.totals.rigid_lift / (cruise.dynamic_pressure * cruise.totals.reference_area)
    amplification = top.totals.CL_deformed_area / rigid_cl  # the study's amp_arr
    printed = (
        f"At 20 m/s: tip twist = {top.tip_twist:.1f} deg, "
        f"tip heave = {top.tip_heave:.2f} m ({top.tip_heave / (SPAN / 2) * 100:.0f}% of semispan), "
        f"lift amplification = {amplification:.2f}"
    )
    assert printed == (
        "At 20 m/s: tip twist = 13.7 deg, tip heave = 0.48 m (10% of semispan), "
        "lift amplification = 2.40"
    )


def test_every_point_of_the_studys_sweep_is_stable_wash_in(study_sweep):
    """Section 14.3's prediction: elastic axis behind the quarter chord twists the wing nose-up
    and raises its lift; all the study's points lie below divergence."""
    for e in study_sweep.values():
        assert e.stability.stable
        assert np.all(e.stations.twist[1:] > 0)
        assert e.lift > e.totals.rigid_lift


def test_a_sweep_point_is_the_solve_at_that_airspeed(study_sweep):
    """Two paths to one branch point: equal to the residual tolerance times the conditioning."""
    for velocity, point in study_sweep.items():
        alone = solver.solve(study_wing(), point.flight)
        assert point.lift == pytest.approx(alone.lift, rel=1e-9), velocity
        np.testing.assert_allclose(
            point.stations.twist, alone.stations.twist, rtol=1e-9, atol=1e-10
        )


def test_the_order_of_the_airspeeds_changes_nothing():
    wing = study_wing()
    forward = solver.airspeed_sweep(
        wing, [6.0, 12.0, 18.0, 23.0], solver.FlightCondition(None, 5.0, DENSITY)
    )
    solver.clear_caches()
    backward = solver.airspeed_sweep(
        wing, [23.0, 18.0, 12.0, 6.0], solver.FlightCondition(None, 5.0, DENSITY)
    )
    by_speed = {p.velocity: p for p in backward.points}
    for point in forward.points:
        other = by_speed[point.velocity]
        assert point.status == other.status
        if point.equilibrium is not None:
            np.testing.assert_array_equal(point.equilibrium.state, other.equilibrium.state)
    assert forward.divergence == backward.divergence


def test_points_beyond_the_fold_say_why():
    result = solver.airspeed_sweep(
        study_wing(), [20.0, 22.0], solver.FlightCondition(None, 5.0, DENSITY)
    )
    answered, beyond = result.points
    assert answered.status == "equilibrium" and answered.no_equilibrium is None
    assert beyond.status == "no_equilibrium" and beyond.equilibrium is None
    assert beyond.no_equilibrium.fold_velocity == pytest.approx(21.4397, abs=1e-4)
    assert "beyond the fold" in beyond.no_equilibrium.reason


@pytest.mark.parametrize(
    "flight",
    [solver.FlightCondition(None, 5.0, DENSITY), solver.FlightCondition(None, lift=300.0)],
    ids=["alpha", "trimmed"],
)
def test_a_sweep_reports_each_airspeed_as_it_is_answered(flight: solver.FlightCondition):
    """What a sweep job shows: one report per airspeed, in order, the last when all are in."""
    reports: list[tuple[int, int]] = []
    speeds = [8.0, 23.0, 12.0, 40.0]
    result = solver.airspeed_sweep(
        study_wing(), speeds, flight, progress=lambda *r: reports.append(r)
    )
    assert reports == [(done, 4) for done in range(1, 5)]
    assert [p.velocity for p in result.points] == speeds
