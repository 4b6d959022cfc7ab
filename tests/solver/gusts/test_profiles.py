"""CS-25.341's gust definitions: U_ref and U_sigma against altitude, U_ds, F_g, and the von
Karman spectrum's unit variance."""

from __future__ import annotations

import math

import numpy as np
import pytest
import scipy.integrate

from solver.gusts.profiles import (
    design_gust_velocity,
    flight_profile_alleviation,
    one_minus_cosine,
    reference_gust_velocity,
    turbulence_intensity,
    von_karman,
)


@pytest.mark.parametrize(
    ("altitude", "expected"),
    [(0.0, 17.07), (4572.0, 13.41), (18288.0, 6.36), (2286.0, (17.07 + 13.41) / 2)],
    ids=["sea-level", "15000ft", "60000ft", "half-way"],
)
def test_reference_gust_velocity_follows_cs_25_341_a_5(altitude: float, expected: float) -> None:
    assert reference_gust_velocity(altitude) == pytest.approx(expected, rel=1e-12)
    assert reference_gust_velocity(altitude, dive=True) == pytest.approx(expected / 2, rel=1e-12)


def test_turbulence_intensity_follows_cs_25_341_b_3() -> None:
    assert turbulence_intensity(0.0) == pytest.approx(27.43)
    assert turbulence_intensity(7315.0) == pytest.approx(24.08)
    assert turbulence_intensity(12000.0) == pytest.approx(24.08)


def test_the_design_gust_grows_as_the_sixth_root_of_its_gradient() -> None:
    assert design_gust_velocity(107.0, 17.07, 1.0) == pytest.approx(17.07)
    ratio = design_gust_velocity(9.0, 17.07, 1.0) / 17.07
    assert ratio == pytest.approx((9.0 / 107.0) ** (1 / 6), rel=1e-12)


def test_flight_profile_alleviation_is_the_mean_at_sea_level_and_one_at_z_mo() -> None:
    # R1 = R2 = 1, Z_mo = 0 + ... : F_gm = sqrt(tan(pi/4)) = 1; F_gz = 1 - 12000/76200.
    at_sea_level = flight_profile_alleviation(1.0, 1.0, 1.0, 12000.0, 0.0)
    assert at_sea_level == pytest.approx(0.5 * (1 + 1 - 12000 / 76200))
    assert flight_profile_alleviation(1.0, 0.8, 0.7, 12000.0, 12000.0) == pytest.approx(1.0)


def test_the_one_minus_cosine_gust_peaks_at_its_gradient_and_vanishes_outside() -> None:
    s = np.array([-1.0, 0.0, 30.0, 60.0, 61.0])
    assert one_minus_cosine(s, 30.0, 10.0) == pytest.approx([0, 0, 10, 0, 0], abs=1e-12)


def test_the_von_karman_spectrum_has_unit_variance() -> None:
    # Integrated analytically in x = 1.339 L Omega: the tail falls as x^(-5/3).
    velocity = 50.0
    total, _ = scipy.integrate.quad(
        lambda w: von_karman(np.array(w), velocity), 0, math.inf, limit=500
    )
    assert total == pytest.approx(1.0, rel=1e-4)
