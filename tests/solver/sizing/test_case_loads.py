"""solver.sizing.case_loads: one load case is one equilibrium of the flexible wing, its loads the
structure's (the lift's less the wing's own weight under the load factor); a rolling pull-out
loads its two wings apart; a case that cannot be flown says why, in its place."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import solver
from solver.sizing.case_loads import case_loads
from tests.solver.sizing import loads_wings
from tests.study import DENSITY

OPTIONS = solver.SolverOptions()


def test_a_trimmed_case_is_the_flexible_wings_equilibrium_with_its_weight() -> None:
    """Its loads are /solve's of the same flight (the same solve: equal to the last digit),
    the wing's mass relieving the lift's bending."""
    wing = loads_wings.wing()
    flight = loads_wings.case("pull-up", 12.0, 2.5).flight
    loads = case_loads(wing, "pull-up", "given", flight, OPTIONS, weight=300.0)
    equilibrium = solver.solve(wing, flight)
    assert loads.status == "equilibrium" and loads.reason is None
    np.testing.assert_array_equal(loads.bending_moment, equilibrium.stations.bending_moment)
    np.testing.assert_array_equal(loads.torque, equilibrium.stations.torque)
    np.testing.assert_array_equal(loads.shear, equilibrium.stations.shear)
    assert loads.alpha == equilibrium.totals.alpha
    assert equilibrium.stations.inertial_bending_moment[0] < 0.0  # the weight relieves
    assert (loads.load_factor, loads.weight, loads.velocity) == (2.5, 300.0, 12.0)
    assert loads.equivalent_airspeed == pytest.approx(12.0 * (DENSITY / 1.225) ** 0.5, rel=1e-12)


def test_a_case_past_divergence_is_answered_no_equilibrium_with_the_reason() -> None:
    """The study's wing diverges near 21 m/s: 30 m/s has no equilibrium to fly."""
    flight = loads_wings.case("too fast", 30.0, 1.0).flight
    loads = case_loads(loads_wings.wing(), "too fast", "given", flight, OPTIONS, weight=300.0)
    assert loads.status == "no_equilibrium"
    assert loads.reason and loads.bending_moment is None and loads.alpha is None


def test_an_aileron_on_a_wing_without_one_is_an_invalid_case_not_an_error() -> None:
    flight = loads_wings.case("roll", 12.0, 2.0).flight
    loads = case_loads(
        loads_wings.wing(), "roll", "given", flight, OPTIONS, weight=300.0, aileron=5.0
    )
    assert loads.status == "invalid" and loads.reason is not None and "aileron" in loads.reason


def _rolled(
    wing: solver.Wing, flight: solver.FlightCondition, options: solver.SolverOptions
) -> solver.RollResponse:
    """/roll's answer with every aileron at 5 deg, rolling at 0.2 rad/s, linearised."""
    surfaces = tuple(dataclasses.replace(s, deflection=5.0) for s in wing.control_surfaces)
    deflected = dataclasses.replace(wing, control_surfaces=surfaces)
    return solver.roll(deflected, flight, options, roll_rate=0.2, method="linearised")


def test_a_rolling_pull_out_loads_its_wings_apart_as_roll_answers_them() -> None:
    """Both wings' loads are /roll's (linearised about the trimmed symmetric equilibrium) with
    every aileron at the case's deflection and its roll rate; the wing whose aileron goes down
    carries more."""
    wing = loads_wings.wing(control_surfaces=[loads_wings.AILERON])
    flight = loads_wings.case("rolling", 12.0, 2.0).flight
    options = solver.SolverOptions(chordwise_panels=3)
    loads = case_loads(
        wing, "rolling", "given", flight, options, weight=300.0, aileron=5.0, roll_rate=0.2
    )
    rolled = _rolled(wing, flight, options)
    assert loads.status == "equilibrium"
    np.testing.assert_allclose(loads.bending_moment, rolled.right.bending_moment, rtol=1e-9)
    np.testing.assert_allclose(loads.left_bending_moment, rolled.left.bending_moment, rtol=1e-9)
    np.testing.assert_allclose(loads.left_torque, rolled.left.torque, rtol=1e-9)
    assert loads.bending_moment[0] != pytest.approx(loads.left_bending_moment[0], rel=1e-3)


def test_a_case_with_neither_aileron_nor_roll_rate_has_one_wings_loads() -> None:
    flight = loads_wings.case("cruise", 14.0, 1.0).flight
    loads = case_loads(loads_wings.wing(), "cruise", "given", flight, OPTIONS, weight=300.0)
    assert loads.left_bending_moment is None and loads.solve_time > 0.0


def test_with_lag_a_case_carries_the_in_plane_moment_as_solve_and_roll_answer_it() -> None:
    """Under the exact beam, the wing twice as stiff in its plane as in flap: a symmetric case's
    in-plane moment is /solve's, a rolling pull-out's each wing's /roll's (the aileron-down
    wing's differing), and without lag there is none."""
    wing = loads_wings.wing(control_surfaces=[loads_wings.AILERON])
    lag = dataclasses.replace(wing, in_plane_bending_stiffness=2 * wing.bending_stiffness)
    options = solver.SolverOptions(chordwise_panels=3, structure="geometrically_exact")
    flight = loads_wings.case("pull-up", 12.0, 2.5).flight
    loads = case_loads(lag, "pull-up", "given", flight, options, weight=300.0)
    stations = solver.solve(lag, flight, options=options).stations
    assert stations.lag_bending_moment is not None
    np.testing.assert_array_equal(loads.lag_bending_moment, stations.lag_bending_moment)
    rolling = case_loads(
        lag, "rolling", "given", flight, options, weight=300.0, aileron=5.0, roll_rate=0.2
    )
    rolled = _rolled(lag, flight, options)
    assert rolled.right.lag_bending_moment is not None
    np.testing.assert_allclose(
        rolling.lag_bending_moment, rolled.right.lag_bending_moment, rtol=1e-9
    )
    np.testing.assert_allclose(
        rolling.left_lag_bending_moment, rolled.left.lag_bending_moment, rtol=1e-9
    )
    assert rolling.lag_bending_moment[0] != pytest.approx(
        rolling.left_lag_bending_moment[0], rel=1e-3
    )
    planar = case_loads(wing, "pull-up", "given", flight, options, weight=300.0)
    assert planar.lag_bending_moment is None and planar.left_lag_bending_moment is None
