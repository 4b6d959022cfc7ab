"""The 1-cos gust response in time: a rigid clamped wing follows Kuessner's function (a
Duhamel integral computed here independently), a rigid aircraft in plunge reproduces Pratt's
K_g, a very long gust on a clamped flexible wing gives the static model's increment, the free
aircraft rides a long gust out, the response is linear, a swept wing's outer strips meet the
gust later, and the sampled peaks stand against four times more samples."""

from __future__ import annotations

import math

import numpy as np
import pytest

import solver
from solver.gusts.discrete import (
    discrete_response,
    kuessner_lagged_gust,
    peaks,
    profile_response,
)
from solver.gusts.indicial import KUESSNER
from solver.gusts.model import gust_model
from tests.solver.gusts.wings import (
    LIGHT_MASS,
    RHO,
    STRIP,
    STUDY_FLIGHT,
    rectangle,
    study,
    weight_for_mass_ratio,
)
from tests.study import DENSITY, study_arrays

V = 100.0  # [m/s]


def _duhamel_kuessner(
    time: np.ndarray, gradient: float, amplitude: float, semichord: float
) -> np.ndarray:
    """(T,) the Kuessner-lagged gust angle by the Duhamel integral of psi against dU/dt / V,
    on a fine grid (trapezoids): an independent path to `kuessner_lagged_gust`."""
    fine = np.linspace(0.0, time[-1], 20001)
    rate = np.where(
        fine <= 2 * gradient / V,
        amplitude / 2 * math.pi * V / gradient * np.sin(math.pi * V * fine / gradient),
        0.0,
    )
    lagged = np.empty(time.size)
    for i, t in enumerate(time):
        inside = fine <= t
        lagged[i] = (
            np.trapezoid(KUESSNER(V * (t - fine[inside]) / semichord) * rate[inside], fine[inside])
            / V
        )
    return lagged


def test_a_rigid_clamped_wing_lifts_as_kuessners_function_says() -> None:
    wing = rectangle()
    model = gust_model(wing, solver.FlightCondition(V, density=RHO, weight=1e5), STRIP, 2, True)
    gradient, amplitude = 5.0, 1.0
    response = discrete_response(model, gradient, amplitude)
    lagged = _duhamel_kuessner(response.time[::4], gradient, amplitude, 0.5)
    q = 0.5 * RHO * V**2
    # The section's slope at the trimmed alpha (2 pi cos alpha: 0.2 % below 2 pi here).
    assert model.lift_slope == pytest.approx(2 * math.pi, rel=0.005)
    expected = q * model.lift_slope * model.area * lagged
    shear = response.outputs[0, ::4]
    # Trapezoids on 20,000 intervals: 1e-3 of the peak.
    assert np.abs(shear - expected).max() < 2e-3 * np.abs(expected).max()
    direct = kuessner_lagged_gust(model, response.time, np.array([gradient]), np.array([amplitude]))
    assert np.allclose(direct[0, ::4, 0], lagged, atol=1e-3 * lagged.max())


@pytest.mark.parametrize("mu", [10.0, 20.0, 50.0, 100.0, 200.0], ids=lambda mu: f"mu={mu:g}")
def test_a_rigid_aircraft_in_plunge_reproduces_pratts_alleviation_factor(mu: float) -> None:
    # Pratt (NACA TN 2964, 1953; Pratt and Walker, NACA Report 1206, 1954) solved the rigid
    # airplane's plunge in a 1-cos gust 25 chords long with the unsteady-lift functions, and
    # fitted K_g = 0.88 mu / (5.3 + mu) to it. The same plunge here, strip theory (2D lift, as
    # a very high aspect ratio: 40), meets it within 3 % (measured +0.6 to +2.6 %).
    wing = rectangle()
    weight = weight_for_mass_ratio(mu, wing)
    model = gust_model(wing, solver.FlightCondition(V, density=RHO, weight=weight), STRIP, 2)
    model.check_stable()
    response = discrete_response(model, 12.5 * wing.mean_chord, 1.0)
    increment = peaks(response.outputs[model.output_slices["load_factor"]])[0]
    loading = weight / wing.planform_area
    mass_ratio = 2 * loading / (RHO * wing.mean_chord * model.lift_slope * 9.80665)
    sharp = RHO * 1.0 * V * model.lift_slope / (2 * loading)
    k_g = 0.88 * mass_ratio / (5.3 + mass_ratio)
    assert increment / sharp == pytest.approx(k_g, rel=0.03)


def test_a_very_long_gust_on_a_clamped_wing_gives_the_static_increment() -> None:
    # Every mode kept (strip theory), a gust 6 km long at 12 m/s: the wing follows it
    # quasi-statically, its loads the static model's at alpha + U / V (central difference).
    wing = solver.Wing.create(**study_arrays(n=9), mass=LIGHT_MASS)
    model = gust_model(wing, STUDY_FLIGHT, STRIP, None, True)
    model.check_stable()
    amplitude = 0.01
    high = peaks(discrete_response(model, 3000.0, amplitude).outputs)[0]
    alpha = model.equilibrium.totals.alpha
    turn = math.degrees(amplitude / 12.0)
    up, down = (
        solver.solve(wing, solver.FlightCondition(12.0, alpha + s * turn, DENSITY), options=STRIP)
        for s in (1, -1)
    )
    n = wing.n_stations
    # The static pair is linearised about alpha without the trim's inertia relief, the model
    # about the trimmed state: 1.1 % apart (measured), within 2 %.
    assert high[n] == pytest.approx(
        (up.stations.bending_moment[0] - down.stations.bending_moment[0]) / 2, rel=0.02
    )
    assert high[0] == pytest.approx((up.stations.shear[0] - down.stations.shear[0]) / 2, rel=0.02)
    assert high[3 * n + 1] == pytest.approx(
        (up.totals.tip_heave - down.totals.tip_heave) / 2, rel=0.02
    )


def test_the_free_aircraft_rides_a_long_gust_out_and_a_clamped_wing_does_not() -> None:
    wing = study()
    free = gust_model(wing, STUDY_FLIGHT, None, 2)
    clamped = gust_model(wing, STUDY_FLIGHT, None, 2, clamped=True)
    n = wing.n_stations
    for gradient in (9.0, 50.0, 500.0):
        free_peak = peaks(discrete_response(free, gradient, 1.0).outputs)[0][n]
        clamped_peak = peaks(discrete_response(clamped, gradient, 1.0).outputs)[0][n]
        assert 0 < free_peak < clamped_peak
    long_free = peaks(discrete_response(free, 500.0, 1.0).outputs)[0][n]
    long_clamped = peaks(discrete_response(clamped, 500.0, 1.0).outputs)[0][n]
    assert long_free < 0.2 * long_clamped


def test_the_response_is_linear_in_the_gust_velocity() -> None:
    model = gust_model(study(), STUDY_FLIGHT, None, 2)
    one = discrete_response(model, 30.0, 1.0).outputs
    three = discrete_response(model, 30.0, 3.0).outputs
    assert np.allclose(three, 3 * one, rtol=1e-9, atol=1e-12 * np.abs(three).max())


def test_an_up_gust_lifts_the_aircraft_and_bends_the_wing_up() -> None:
    model = gust_model(study(), STUDY_FLIGHT, None, 2)
    high, low = peaks(discrete_response(model, 30.0, 5.0).outputs)
    s = model.output_slices
    assert high[s["load_factor"]] > 0 and high[model.wing.n_stations] > 0
    # The rebound after it (the aircraft still rising) is a down load, smaller than the peak.
    assert 0 < -low[s["load_factor"]] < 1.05 * high[s["load_factor"]]


def test_a_swept_wings_outer_strips_meet_the_gust_later() -> None:
    sweep = 30.0
    wing = rectangle(sweep=sweep)
    model = gust_model(wing, solver.FlightCondition(V, density=RHO, weight=1e5), STRIP, 2, True)
    midpoints = (wing.y[1:] + wing.y[:-1]) / 2
    assert model.delay == pytest.approx(
        (midpoints - midpoints[0]) * math.tan(math.radians(sweep)) / V
    )
    response = discrete_response(model, 5.0, 1.0)
    # The shear at the last inner station: the tip strip's alone, but for the equivalent strip
    # loads of the inner strips' bending couples on a swept beam (1e-4 of the peak, measured).
    tip_strip = wing.n_stations - 2
    before = response.time < model.delay[-1]
    assert (
        np.abs(response.outputs[tip_strip, before]).max()
        < 1e-3 * np.abs(response.outputs[tip_strip]).max()
    )


def test_the_sampled_peaks_stand_against_four_times_more_samples() -> None:
    model = gust_model(study(), STUDY_FLIGHT, None, 4)
    for gradient in (9.0, 40.0, 107.0):
        coarse = peaks(discrete_response(model, gradient, 1.0).outputs)[0]
        fine = peaks(discrete_response(model, gradient, 1.0, refine=4.0).outputs)[0]
        scale = np.abs(fine).max()
        # Measured 0.06 %: within 0.5 %.
        assert np.abs(coarse - fine).max() < 0.005 * scale


def test_a_given_profile_shaped_as_a_1_cos_gust_answers_as_that_gust() -> None:
    # Two paths: Kuessner's states in closed form on the 1-cos, and the same states filtering
    # the profile's 400 linear pieces on the grid.
    model = gust_model(study(), STUDY_FLIGHT, None, 3)
    gradient, amplitude = 20.0, 2.0
    times = np.linspace(0.0, 2 * gradient / STUDY_FLIGHT.velocity, 401)
    velocity = amplitude / 2 * (1 - np.cos(np.pi * STUDY_FLIGHT.velocity * times / gradient))
    given = peaks(profile_response(model, times, velocity).outputs)
    exact = peaks(discrete_response(model, gradient, amplitude).outputs)
    for ours, theirs in zip(given, exact, strict=True):
        assert np.abs(ours - theirs).max() < 2e-3 * np.abs(theirs).max()
