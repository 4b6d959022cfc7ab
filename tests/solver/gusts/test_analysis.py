"""One flight's gust loads: the 1-cos gusts' design velocities, the tuned gusts, the total
loads (1 g plus gust, up and down), turbulence's design loads, Pratt beside the model, and
the findings of gusts outside the regulation."""

from __future__ import annotations

import math

import numpy as np
import pytest

import solver
from solver.gusts.profiles import design_gust_velocity
from tests.solver.gusts.wings import STUDY_FLIGHT, study

SETTINGS = solver.GustSettings(gradients=8, modes=3)


@pytest.fixture(scope="module")
def result() -> solver.GustResult:
    return solver.gust_analysis(study(), STUDY_FLIGHT, SETTINGS)


def test_each_gust_has_the_regulations_velocity(result: solver.GustResult) -> None:
    to_true = math.sqrt(1.225 / STUDY_FLIGHT.density)
    for case in result.gusts:
        expected = design_gust_velocity(case.gradient, 17.07, 1.0) * to_true
        assert case.gust_velocity == pytest.approx(expected, rel=1e-12)
    assert [c.gradient for c in result.gusts] == pytest.approx(np.linspace(9, 107, 8).tolist())


def test_the_tuned_gusts_give_the_largest_loads(result: solver.GustResult) -> None:
    factors = [case.max_load_factor for case in result.gusts]
    assert result.gusts[result.tuned_load_factor].max_load_factor == max(factors)
    moments = [case.max_bending_moment[0] for case in result.gusts]
    assert result.gusts[result.tuned_bending_moment].max_bending_moment[0] == max(moments)


def test_the_total_loads_are_one_g_plus_and_minus_the_worst_gust(
    result: solver.GustResult,
) -> None:
    envelope = result.envelope
    worst = np.max(
        [np.maximum(c.max_bending_moment, -c.min_bending_moment) for c in result.gusts], axis=0
    )
    assert envelope.max_bending_moment == pytest.approx(result.one_g_bending_moment + worst)
    assert envelope.min_bending_moment == pytest.approx(result.one_g_bending_moment - worst)
    assert np.all(envelope.max_shear >= result.one_g_shear)
    assert np.all(envelope.min_torque <= result.one_g_torque)


def test_turbulence_design_loads_are_one_g_plus_and_minus_u_sigma_a_bar(
    result: solver.GustResult,
) -> None:
    t = result.turbulence
    assert t is not None and t.intensity == pytest.approx(27.43)
    assert t.max_bending_moment == pytest.approx(
        result.one_g_bending_moment + 27.43 * t.bending_moment
    )


def test_pratts_load_factor_stands_beside_the_models(result: solver.GustResult) -> None:
    # A light, slow aircraft (mu_g ~ 1): Pratt's fit was made for mu_g from about 10 up;
    # here it is stated, not held to the model.
    assert result.pratt_alleviation == pytest.approx(
        0.88 * result.mass_ratio / (5.3 + result.mass_ratio)
    )
    assert result.pratt_load_factor > 1


def test_gusts_outside_the_regulation_are_answered_and_said_so() -> None:
    settings = solver.GustSettings(
        min_gradient=2.0, max_gradient=20.0, gradients=2, modes=2, turbulence=False
    )
    answer = solver.gust_analysis(study(), STUDY_FLIGHT, settings)
    assert len(answer.gusts) == 2 and answer.turbulence is None
    assert any("outside the regulation" in finding for finding in answer.findings)


def test_the_load_cases_include_the_one_g_load(result: solver.GustResult) -> None:
    cases = solver.gust_load_cases(study(), STUDY_FLIGHT, SETTINGS)
    assert len(cases) == 2
    for case in cases:
        assert np.all(case.max_bending_moment >= result.one_g_bending_moment - 1e-9)
        assert np.all(case.min_bending_moment <= result.one_g_bending_moment + 1e-9)


def test_a_given_profile_joins_the_envelope_as_given() -> None:
    settings = solver.GustSettings(
        gradients=2,
        modes=2,
        turbulence=False,
        profile_time=(0.0, 1.0, 2.0),
        profile_velocity=(0.0, -20.0, 0.0),
    )
    answer = solver.gust_analysis(study(), STUDY_FLIGHT, settings)
    assert answer.profile is not None and answer.profile.gust_velocity == 20.0
    assert answer.profile.min_bending_moment[0] < 0
    assert np.all(
        answer.envelope.min_bending_moment
        <= answer.one_g_bending_moment + answer.profile.min_bending_moment + 1e-9
    )


@pytest.mark.parametrize(
    ("given", "field"),
    [
        ({"profile_time": (0.0, 1.0)}, "profile_velocity"),
        ({"profile_time": (0.0, 1.0, 1.0), "profile_velocity": (0.0, 1.0, 0.0)}, "profile_time"),
        ({"profile_time": (0.0, 1.0), "profile_velocity": (0.0, 1.0, 0.0)}, "profile_velocity"),
        ({"min_gradient": 50.0, "max_gradient": 20.0}, "max_gradient"),
    ],
    ids=["time-alone", "not-increasing", "lengths-differ", "gradients-reversed"],
)
def test_settings_that_mean_nothing_are_refused_naming_the_field(given: dict, field: str) -> None:
    with pytest.raises(solver.InvalidInput) as caught:
        solver.GustSettings(**given)
    assert caught.value.field == field


def test_the_alleviation_factor_follows_from_the_aircrafts_weights() -> None:
    settings = solver.GustSettings(
        gradients=1, modes=2, turbulence=False, weights=(1000.0, 900.0, 800.0), max_altitude=12000.0
    )
    answer = solver.gust_analysis(study(), STUDY_FLIGHT, settings)
    f_gm = math.sqrt(0.8 * math.tan(math.pi * 0.9 / 4))
    expected = 0.5 * (1 - 12000 / 76200 + f_gm)
    assert answer.alleviation == pytest.approx(expected, rel=1e-12)
    to_true = math.sqrt(1.225 / STUDY_FLIGHT.density)
    assert answer.gusts[0].gust_velocity == pytest.approx(
        design_gust_velocity(9.0, 17.07, expected) * to_true
    )
