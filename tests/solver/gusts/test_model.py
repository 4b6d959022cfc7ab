"""The gust model's system: stable below the Goland wing's flutter speed and unstable past it
at its flutter frequency (Wagner's states in place of Theodorsen's C(k)), the lattice's 3D
lift slope, the clamped option, the mass it needs."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

import solver
from solver.gusts.discrete import discrete_response, peaks
from solver.gusts.model import gust_model
from tests.flutter_reference import goland_mass, goland_wing
from tests.solver.gusts.wings import RHO, STRIP, STUDY_FLIGHT, rectangle, study


@pytest.mark.parametrize("clamped", [True, False], ids=["clamped", "free"])
def test_the_goland_wing_is_stable_below_its_flutter_speed_and_flutters_past_it(
    clamped: bool,
) -> None:
    # Goland (1945), strip theory at sea level: flutter at ~137 m/s and ~70 rad/s (the flutter
    # tests hold the p-k answer to it). Jones' two lags for C(k): the onset lies between 130
    # and 145 m/s, at the flutter frequency within 5 %.
    wing = dataclasses.replace(goland_wing(), mass=goland_mass())
    below = gust_model(
        wing, solver.FlightCondition(130.0, density=RHO, weight=2e4), STRIP, 4, clamped
    )
    below.check_stable()
    above = gust_model(
        wing, solver.FlightCondition(145.0, density=RHO, weight=2e4), STRIP, 4, clamped
    )
    with pytest.raises(solver.DynamicInstability) as caught:
        above.check_stable()
    assert caught.value.growth_rate > 0
    assert caught.value.frequency == pytest.approx(70.7, rel=0.05)


def test_the_gust_lift_slope_is_the_static_models() -> None:
    # The quasi-steady lift of a uniform gust angle is the static model's lift slope: strip
    # theory's 2 pi, the lattice's 3D one (aspect ratio 8: below 2 pi A / (A + 2)), the latter
    # from two static solves 1 deg apart (0.5 %: the trim's alpha against alpha 0).
    wing = rectangle(semispan=4.0, stations=17)
    flight = solver.FlightCondition(100.0, density=RHO, weight=1e4)
    strip = gust_model(wing, flight, STRIP, 2).lift_slope
    lattice = gust_model(wing, flight, None, 2).lift_slope
    up, level = (solver.solve(wing, solver.FlightCondition(100.0, a, RHO)) for a in (1.0, 0.0))
    static = (up.totals.lift - level.totals.lift) / (0.5 * RHO * 100.0**2) / wing.planform_area
    assert strip == pytest.approx(2 * math.pi, rel=0.005)
    assert lattice == pytest.approx(static / math.radians(1.0), rel=0.005)
    assert lattice < 2 * math.pi * 8 / 10


def test_a_clamped_model_has_no_plunge_state() -> None:
    free = gust_model(study(), STUDY_FLIGHT, None, 3)
    clamped = gust_model(study(), STUDY_FLIGHT, None, 3, clamped=True)
    assert free.a.shape[0] == clamped.a.shape[0] + 1
    assert np.all(np.linalg.eigvals(free.a).real < 0)


def test_a_wing_without_mass_or_a_flight_without_weight_is_refused_naming_it() -> None:
    with pytest.raises(solver.InvalidInput) as caught:
        gust_model(rectangle().__class__.create([0, 1, 2], 1.0, 0.3, 1e4, 1e4), STUDY_FLIGHT)
    assert caught.value.field == "wing.mass"
    with pytest.raises(solver.InvalidInput) as caught:
        gust_model(study(), solver.FlightCondition(12.0, 5.0, RHO))
    assert caught.value.field == "flight.weight"


def test_a_rigid_aircrafts_load_factor_does_not_depend_on_where_its_mass_sits() -> None:
    # The weight's mass plunges as one when the wing does not bend: a store at the tip (part
    # of the same weight) changes the wing's root bending (it relieves it), not the load factor.
    flight = solver.FlightCondition(100.0, density=RHO, weight=2e5)
    plain = rectangle()
    store = solver.ConcentratedMass(
        station=plain.n_stations - 1, mass=500.0, inertia=1.0, offset=0.0
    )
    stored = dataclasses.replace(plain, mass=dataclasses.replace(plain.mass, concentrated=(store,)))
    answers = []
    for wing in (plain, stored):
        model = gust_model(wing, flight, STRIP, 2)
        answers.append((model, peaks(discrete_response(model, 10.0, 1.0).outputs)[0]))
    (model, without), (_, with_store) = answers
    s = model.output_slices
    assert with_store[s["load_factor"]] == pytest.approx(without[s["load_factor"]], rel=1e-3)
    n = plain.n_stations
    # The store's inertia under the load factor: about n g m y_tip off the root bending.
    relief = without[s["load_factor"]] * 9.80665 * 500.0 * plain.y[-1]
    assert without[n] - with_store[n] == pytest.approx(relief, rel=0.05)
