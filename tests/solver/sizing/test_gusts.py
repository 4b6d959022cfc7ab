"""solver.sizing.gusts: CS-23.341's gust load factor against a published worked example, against
the FAR's imperial form by hand, and CS-23.333(c)'s derived gust velocities."""

from __future__ import annotations

import math

import numpy as np
import pytest

from solver.sizing import gusts


def test_megsons_worked_gust_example():
    """Megson, Aircraft Structures for Engineering Students (section 8.6.3 of the 3rd edition,
    13.4.3 of the 5th): a civil aircraft of wing loading w = 2400 N/m^2, dC_L/dalpha = 5.0 /rad,
    gust alleviation factor F = 0.715, in a 15.25 m/s EAS gust: n = 1 + 0.0139 V_C (V_C EAS,
    m/s), with rho0 = 1.223 kg/m^3. Ours (rho0 = 1.225) is 0.013914 per m/s: the three digits
    printed."""
    per_speed = gusts.sharp_edged_gust_increment(2400.0, 1.0, 15.25, 5.0, alleviation=0.715)
    assert round(per_speed, 4) == 0.0139
    # With Megson's sea-level density the increment is his to 1e-15: the formula is his eq.
    assert per_speed * 1.223 / 1.225 == pytest.approx(0.5 * 1.223 * 5.0 * 0.715 * 15.25 / 2400)


def test_the_gust_load_factor_is_the_fars_imperial_formula_by_hand():
    """14 CFR 23.341(c) (Amdt. 23-48): n = 1 + K_g U_de V a / (498 (W/S)), U_de ft/s, V knots,
    W/S lb/ft^2, mu_g = 2 (W/S) / (rho c a g) in slugs and feet. A 3,000 lb airplane, 175 ft^2,
    mean chord 5 ft, a = 5.0 /rad, 140 kt EAS in a 50 ft/s gust at 10,000 ft (rho =
    0.0017556 slug/ft^3). 498 rounds 2 / (rho0 * 1 kt in ft/s) = 498.53: 0.11 %, the tolerance."""
    pounds, area, chord, slope, knots, gust_fps, rho_slug = (
        3000.0,
        175.0,
        5.0,
        5.0,
        140.0,
        50.0,
        0.0017556,
    )
    loading_psf = pounds / area
    mu = 2 * loading_psf / (rho_slug * chord * slope * 32.174)
    k_g = 0.88 * mu / (5.3 + mu)
    by_hand = 1 + k_g * gust_fps * knots * slope / (498 * loading_psf)

    psf, ft, kt = 47.880259, 0.3048, 1852 / 3600
    up, down = gusts.gust_load_factors(
        wing_loading=loading_psf * psf,
        airspeed=knots * kt,
        gust_velocity=gust_fps * ft,
        lift_slope=slope,
        mean_chord=chord * ft,
        density=rho_slug * 515.378818,  # slug/ft^3 to kg/m^3
    )
    assert up == pytest.approx(by_hand, rel=1.5e-3)
    assert up + down == pytest.approx(2.0, rel=1e-15)  # +- the same increment


def test_the_mass_ratio_is_nondimensional_and_the_alleviation_pratts_fit():
    """mu_g = 2 (W/S) / (rho c a g); K_g = 0.88 mu_g / (5.3 + mu_g): 0.44 at mu_g = 5.3, to 0.88
    for an aircraft heavy against the air, 0 for one as light as it."""
    mu = gusts.gust_mass_ratio(1000.0, 1.225, 1.5, 5.0)
    assert mu == pytest.approx(2 * 1000.0 / (1.225 * 1.5 * 5.0 * 9.80665), rel=1e-15)
    assert gusts.gust_alleviation_factor(5.3) == pytest.approx(0.44, rel=1e-15)
    assert gusts.gust_alleviation_factor(1e12) == pytest.approx(0.88, rel=1e-10)
    assert gusts.gust_alleviation_factor(0.0) == 0.0
    ratios = np.geomspace(0.1, 1000.0, 50)
    factors = [gusts.gust_alleviation_factor(m) for m in ratios]
    assert (np.diff(factors) > 0).all()


def test_thinner_air_alleviates_less_at_the_same_equivalent_airspeed():
    """At altitude the aircraft is heavier against the air (mu_g up), so K_g nears 0.88: the
    same EAS gust at the same EAS loads more (until U_de falls, above 6,096 m)."""
    sea, high = (
        gusts.gust_load_factors(1200.0, 80.0, 15.24, 5.0, 1.4, density)[0]
        for density in (1.225, 0.7364)
    )
    assert high > sea


@pytest.mark.parametrize(
    ("speed", "low", "high"),
    [
        # CS-23.333(c)(1)(i)-(iii), in ft/s: 50 -> 25 (V_C), 25 -> 12.5 (V_D), 66 -> 38 (V_B).
        pytest.param("cruise", 15.24, 7.62, id="at-v-c"),
        pytest.param("dive", 7.62, 3.81, id="at-v-d"),
        pytest.param("rough_air", 20.1168, 11.5824, id="at-v-b"),
    ],
)
def test_the_derived_gust_velocities_of_cs_23_333_c(speed, low, high):
    assert gusts.derived_gust_velocity(speed, 0.0) == pytest.approx(low, rel=1e-15)
    assert gusts.derived_gust_velocity(speed, 6096.0) == pytest.approx(low, rel=1e-15)
    assert gusts.derived_gust_velocity(speed, -1000.0) == pytest.approx(low, rel=1e-15)
    middle = (6096.0 + 15240.0) / 2
    assert gusts.derived_gust_velocity(speed, middle) == pytest.approx((low + high) / 2, rel=1e-14)
    assert gusts.derived_gust_velocity(speed, 15240.0) == pytest.approx(high, rel=1e-14)
    # Past 50,000 ft the rule stops: held at its value there.
    assert gusts.derived_gust_velocity(speed, 20_000.0) == pytest.approx(high, rel=1e-14)
    heights = np.array([0.0, middle, 15240.0])
    np.testing.assert_allclose(
        gusts.derived_gust_velocity(speed, heights), [low, (low + high) / 2, high], rtol=1e-14
    )


def test_the_gust_increment_grows_with_airspeed_and_falls_with_wing_loading():
    base = gusts.sharp_edged_gust_increment(1000.0, 50.0, 15.24, 5.0)
    assert gusts.sharp_edged_gust_increment(1000.0, 100.0, 15.24, 5.0) == pytest.approx(2 * base)
    assert gusts.sharp_edged_gust_increment(2000.0, 50.0, 15.24, 5.0) == pytest.approx(base / 2)
    assert base == pytest.approx(1.225 * 15.24 * 50.0 * 5.0 / 2000.0, rel=1e-15)
    assert math.isclose(gusts.sharp_edged_gust_increment(1000.0, 0.0, 15.24, 5.0), 0.0)
