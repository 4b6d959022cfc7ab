"""solver.sizing.regulations: the limit load factors and design speeds of CS-23.335/23.337 and
CS-25.335/25.337, checked against the rules' own text in their own units (pounds, lb/ft^2,
knots), computed here by hand."""

from __future__ import annotations

import math

import pytest

from solver.sizing import regulations

G0 = 9.80665
POUND_MASS = 0.45359237  # [kg], exact
KNOT = 1852.0 / 3600.0  # [m/s], exact
PSF = POUND_MASS * G0 / 0.3048**2  # [Pa] of 1 lb/ft^2


def newtons(pounds: float) -> float:
    return pounds * POUND_MASS * G0


@pytest.mark.parametrize(
    ("category", "pounds", "n_max", "n_min"),
    [
        # CS-23.337(a)(1): 2.1 + 24,000 / (W + 10,000), need not exceed 3.8 (W = 4,118 lb).
        pytest.param(
            "normal",
            12_500.0,
            2.1 + 24_000 / 22_500,
            -0.4 * (2.1 + 24_000 / 22_500),
            id="normal-12500lb",
        ),
        pytest.param("normal", 4_000.0, 3.8, -1.52, id="normal-capped-at-3.8"),
        pytest.param(
            "commuter",
            19_000.0,
            2.1 + 24_000 / 29_000,
            -0.4 * (2.1 + 24_000 / 29_000),
            id="commuter-19000lb",
        ),
        # (a)(2), (a)(3), (b): utility 4.4, aerobatic 6.0; n_min 0.4 (0.5 aerobatic) of n_max.
        pytest.param("utility", 2_000.0, 4.4, -1.76, id="utility"),
        pytest.param("aerobatic", 2_000.0, 6.0, -3.0, id="aerobatic"),
        # CS-25.337(b), (c): the same formula, at least 2.5, at most 3.8; -1.0.
        pytest.param("cs25", 100_000.0, 2.5, -1.0, id="cs25-heavy-at-2.5"),
        pytest.param("cs25", 30_000.0, 2.7, -1.0, id="cs25-30000lb"),
        pytest.param("cs25", 2_000.0, 3.8, -1.0, id="cs25-light-capped-at-3.8"),
    ],
)
def test_the_limit_load_factors_are_the_rules(category, pounds, n_max, n_min):
    computed = regulations.limit_load_factors(category, newtons(pounds))
    # The pound of the rule is the exact 0.45359237 kg weighing g0: equal to round-off.
    assert computed == pytest.approx((n_max, n_min), rel=1e-14)


def test_the_load_factor_cap_is_reached_at_4118_pounds():
    """2.1 + 24,000 / (W + 10,000) = 3.8 at W = 24,000 / 1.7 - 10,000 = 4,117.6 lb."""
    at_cap = 24_000 / 1.7 - 10_000
    assert regulations.limit_load_factors("normal", newtons(at_cap))[0] == pytest.approx(3.8)
    assert regulations.limit_load_factors("normal", newtons(at_cap * 0.9))[0] == 3.8
    assert regulations.limit_load_factors("normal", newtons(at_cap * 1.1))[0] < 3.8


def test_the_negative_limit_at_v_d_is_zero_or_minus_one():
    """CS-23.333(b)(3): 0 at V_D for normal and commuter, -1.0 for utility and aerobatic;
    CS-25.337(c)(2): 0."""
    assert [regulations.negative_limit_at_dive(c) for c in ("normal", "commuter", "cs25")] == [
        0,
        0,
        0,
    ]
    assert [regulations.negative_limit_at_dive(c) for c in ("utility", "aerobatic")] == [-1, -1]


@pytest.mark.parametrize(
    ("category", "psf", "knots"),
    [
        # CS-23.335(a)(1): 33 sqrt(W/S) (36 aerobatic) up to 20 lb/ft^2 ...
        pytest.param("normal", 15.0, 33 * math.sqrt(15.0), id="normal-15psf"),
        pytest.param("utility", 20.0, 33 * math.sqrt(20.0), id="utility-20psf"),
        pytest.param("aerobatic", 15.0, 36 * math.sqrt(15.0), id="aerobatic-15psf"),
        # ... (a)(2): decreased linearly to 28.6 at W/S = 100: halfway at 60 lb/ft^2.
        pytest.param("commuter", 60.0, (33 + 28.6) / 2 * math.sqrt(60.0), id="commuter-60psf"),
        pytest.param("aerobatic", 60.0, (36 + 28.6) / 2 * math.sqrt(60.0), id="aerobatic-60psf"),
        pytest.param("normal", 100.0, 28.6 * math.sqrt(100.0), id="normal-100psf"),
        pytest.param("normal", 150.0, 28.6 * math.sqrt(150.0), id="past-100psf-held"),
    ],
)
def test_the_minimum_cruise_speed_is_cs_23_335_a(category, psf, knots):
    computed = regulations.minimum_cruise_speed(category, psf * PSF)
    assert computed == pytest.approx(knots * KNOT, rel=1e-13)


def test_the_minimum_cruise_speed_in_si_is_2_4534_sqrt_wing_loading():
    """The SI form the module states: 33 kt per sqrt(lb/ft^2) is 2.4534 m/s per sqrt(Pa)."""
    assert regulations.minimum_cruise_speed("normal", 900.0) == pytest.approx(
        2.4534 * math.sqrt(900.0), rel=2e-5
    )


@pytest.mark.parametrize(
    ("category", "psf", "factor"),
    [
        # CS-23.335(b)(2): 1.40, 1.50, 1.55 V_C,min up to 20 lb/ft^2; (b)(3) to 1.35 at 100.
        pytest.param("normal", 15.0, 1.40, id="normal"),
        pytest.param("commuter", 15.0, 1.40, id="commuter"),
        pytest.param("utility", 15.0, 1.50, id="utility"),
        pytest.param("aerobatic", 15.0, 1.55, id="aerobatic"),
        pytest.param("normal", 60.0, (1.40 + 1.35) / 2, id="normal-60psf"),
        pytest.param("aerobatic", 60.0, (1.55 + 1.35) / 2, id="aerobatic-60psf"),
        pytest.param("utility", 100.0, 1.35, id="utility-100psf"),
    ],
)
def test_the_minimum_dive_speed_at_the_minimum_cruise_speed_is_cs_23_335_b2(category, psf, factor):
    loading = psf * PSF
    cruise = regulations.minimum_cruise_speed(category, loading)
    assert regulations.minimum_dive_speed(category, loading, cruise) == pytest.approx(
        factor * cruise, rel=1e-13
    )


def test_a_faster_cruise_speed_sets_the_dive_speed_by_cs_23_335_b1():
    """V_D >= 1.25 V_C (b)(1) wins once V_C passes 1.40 / 1.25 = 1.12 V_C,min (normal)."""
    loading = 15.0 * PSF
    slowest = regulations.minimum_cruise_speed("normal", loading)
    assert regulations.minimum_dive_speed("normal", loading, 1.3 * slowest) == pytest.approx(
        1.25 * 1.3 * slowest, rel=1e-14
    )
    assert regulations.minimum_dive_speed("normal", loading, 1.1 * slowest) == pytest.approx(
        1.40 * slowest, rel=1e-14
    )


def test_cs25_takes_v_d_as_v_c_over_0_8_and_derives_no_cruise_speed():
    assert regulations.minimum_dive_speed("cs25", 5000.0, 150.0) == 150.0 / 0.8
    with pytest.raises(ValueError, match="CS-25"):
        regulations.minimum_cruise_speed("cs25", 5000.0)


def test_the_stall_and_manoeuvring_speeds():
    """V_S = sqrt(2 W / (rho0 S C_Lmax)), 1 g at C_Lmax; V_A >= V_S sqrt(n) (CS-23.335(c))."""
    stall = regulations.stall_speed(10_000.0, 16.0, 1.5)
    assert stall == pytest.approx(math.sqrt(2 * 10_000.0 / (1.225 * 16.0 * 1.5)), rel=1e-15)
    assert 0.5 * 1.225 * stall**2 * 16.0 * 1.5 == pytest.approx(10_000.0, rel=1e-14)
    assert regulations.stall_speed(10_000.0, 16.0, -1.5) == stall
    assert regulations.minimum_manoeuvring_speed(stall, 3.8) == pytest.approx(
        stall * math.sqrt(3.8)
    )
    # At altitude, the same lift at the air's density: the true stall speed.
    assert regulations.stall_speed(10_000.0, 16.0, 1.5, density=0.6125) == pytest.approx(
        stall * math.sqrt(2.0), rel=1e-15
    )
