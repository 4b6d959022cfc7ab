"""solver.sizing.vn: the V-n diagram's corners and gust points against CS-23.333 to 23.341 and
CS-25.333 to 25.337 worked by hand here (the rules' imperial units where they state them), and
its boundary."""

from __future__ import annotations

import math

import numpy as np
import pytest

from solver import InvalidInput
from solver.inputs.envelope import FlightEnvelope
from solver.sizing import vn
from tests.solver.sizing.aircraft import G0, LIGHT, RHO0, RHO_3000

KNOT = 1852.0 / 3600.0
PSF = 0.45359237 * G0 / 0.3048**2  # [Pa] of 1 lb/ft^2


def pratt(loading: float, speed: float, gust: float, slope: float, chord: float, rho: float):
    """CS-23.341(c) written out: 1 + K_g rho0 U_de V a / (2 W/S)."""
    mu = 2 * loading / (rho * chord * slope * G0)
    return 1 + 0.88 * mu / (5.3 + mu) * RHO0 * gust * speed * slope / (2 * loading)


def points(diagram: vn.VnDiagram) -> dict[str, tuple[float, float]]:
    return {p.name: (p.airspeed, p.load_factor) for p in diagram.points}


def test_the_normal_category_corners_are_cs_23_335_and_23_337_by_hand():
    diagram = vn.vn_diagram(FlightEnvelope(**LIGHT), 1100.0 * G0, 0.0)
    pounds = 1100.0 / 0.45359237
    loading_psf = pounds / (16.2 / 0.3048**2)
    # CS-23.337(a)(1): 2.1 + 24,000 / (2,425 + 10,000) = 4.03: capped at 3.8; (b)(1): -0.4 n.
    assert 2.1 + 24_000 / (pounds + 10_000) > 3.8
    n_max, n_min = 3.8, -0.4 * 3.8
    # CS-23.335(a)(1), (b)(2)(i): 13.9 lb/ft^2 < 20: V_C = 33 sqrt(W/S) kt, V_D = 1.40 V_C.
    v_c = 33 * math.sqrt(loading_psf) * KNOT
    v_d = 1.40 * v_c
    # 1 g stall at C_Lmax (1.6) and C_Lmin (-1.0), from sea-level air in slugs and feet.
    stall_fps = math.sqrt(2 * loading_psf / (0.0023769 * 1.6))
    inverted_fps = math.sqrt(2 * loading_psf / (0.0023769 * 1.0))
    v_s, v_s_inverted = stall_fps * 0.3048, inverted_fps * 0.3048
    v_a, v_g = v_s * math.sqrt(n_max), v_s_inverted * math.sqrt(-n_min)
    expected = {
        "A+": (v_a, n_max),
        "C+": (v_c, n_max),
        "D+": (v_d, n_max),
        "G-": (v_g, n_min),
        "C-": (v_c, n_min),
        "D-": (v_d, 0.0),  # CS-23.333(b)(3): linearly to 0 at V_D (normal)
    }
    found = points(diagram)
    # 2e-6: 0.0023769 slug/ft^3 is 1.225 kg/m^3 to 6 digits.
    for name, (speed, load_factor) in expected.items():
        assert found[name][0] == pytest.approx(speed, rel=2e-6), name
        assert found[name][1] == pytest.approx(load_factor, rel=1e-14, abs=1e-15), name
    assert v_a < v_c and v_g < v_c  # the corners this test means
    assert diagram.stall_speed == pytest.approx(v_s, rel=2e-6)
    assert diagram.load_factor_max == n_max and diagram.load_factor_min == n_min


@pytest.mark.parametrize("altitude", [0.0, 3000.0], ids=["sea-level", "3000m"])
def test_the_gust_points_are_cs_23_341_by_hand(altitude):
    diagram = vn.vn_diagram(FlightEnvelope(**LIGHT), 1100.0 * G0, altitude)
    loading = 1100.0 * G0 / 16.2
    rho = RHO0 if altitude == 0 else RHO_3000
    found = points(diagram)
    v_c, v_d = diagram.cruise_speed, diagram.dive_speed
    # CS-23.333(c): 50 and 25 ft/s at V_C and V_D below 20,000 ft.
    up_c = pratt(loading, v_c, 15.24, 5.0, 1.5, rho)
    up_d = pratt(loading, v_d, 7.62, 5.0, 1.5, rho)
    # 1e-5: the density at 3,000 m is the table's 5 digits (it enters through K_g, damped).
    assert found["gust C+"] == pytest.approx((v_c, up_c), rel=1e-5)
    assert found["gust C-"] == pytest.approx((v_c, 2 - up_c), rel=1e-5)
    assert found["gust D+"] == pytest.approx((v_d, up_d), rel=1e-5)
    assert found["gust D-"] == pytest.approx((v_d, 2 - up_d), rel=1e-5)
    assert "gust B+" not in found  # V_B: the commuter category's


@pytest.mark.parametrize(
    ("category", "n_max", "n_min", "at_dive", "v_c_knots_per_root", "dive_factor"),
    [
        pytest.param("utility", 4.4, -1.76, -1.0, 33, 1.50, id="utility"),
        pytest.param("aerobatic", 6.0, -3.0, -1.0, 36, 1.55, id="aerobatic"),
    ],
)
def test_utility_and_aerobatic_limits_reach_minus_one_at_v_d(
    category, n_max, n_min, at_dive, v_c_knots_per_root, dive_factor
):
    envelope = FlightEnvelope(**{**LIGHT, "category": category, "cl_min": -1.6})
    diagram = vn.vn_diagram(envelope, 1100.0 * G0, 0.0)
    loading_psf = 1100.0 * G0 / 16.2 / PSF
    v_c = v_c_knots_per_root * math.sqrt(loading_psf) * KNOT
    found = points(diagram)
    assert found["A+"][1] == found["D+"][1] == n_max
    assert found["C-"] == pytest.approx((v_c, n_min), rel=1e-13)
    assert found["D-"] == pytest.approx((dive_factor * v_c, at_dive), rel=1e-13)


def test_a_commuter_adds_the_rough_air_gust_at_v_b_of_cs_23_335_d():
    mass, area, chord, slope = 8600.0, 40.0, 2.0, 5.5
    envelope = FlightEnvelope(
        weights=[mass * G0],
        cl_max=1.5,
        cl_min=-0.9,
        category="commuter",
        wing_area=area,
        mean_chord=chord,
        lift_slope=slope,
    )
    diagram = vn.vn_diagram(envelope, mass * G0, 0.0)
    loading = mass * G0 / area
    loading_psf = loading / PSF
    # CS-23.335(a)(2), (b)(3): 44 lb/ft^2 > 20: 33 -> 28.6 and 1.40 -> 1.35 linearly to 100.
    fraction = (loading_psf - 20) / 80
    v_c = (33 - 4.4 * fraction) * math.sqrt(loading_psf) * KNOT
    assert diagram.cruise_speed == pytest.approx(v_c, rel=1e-13)
    assert diagram.dive_speed == pytest.approx((1.40 - 0.05 * fraction) * v_c, rel=1e-13)
    # CS-23.337(a)(1): 2.1 + 24,000 / (18,960 + 10,000).
    pounds = mass / 0.45359237
    assert diagram.load_factor_max == pytest.approx(2.1 + 24_000 / (pounds + 10_000), rel=1e-13)
    # CS-23.335(d)(1): the lesser of where the stall line meets the 66 ft/s gust line, and
    # V_S1 sqrt(n_g) with n_g the gust load factor at V_C; (d)(2): at most V_C.
    stall_per_v2 = RHO0 * 1.5 / (2 * loading)
    gust_per_v = pratt(loading, 1.0, 20.1168, slope, chord, RHO0) - 1
    meet = (gust_per_v + math.sqrt(gust_per_v**2 + 4 * stall_per_v2)) / (2 * stall_per_v2)
    n_g = pratt(loading, v_c, 15.24, slope, chord, RHO0)
    v_s = math.sqrt(1 / stall_per_v2)
    v_b = min(meet, v_s * math.sqrt(n_g), v_c)
    assert diagram.rough_air_speed == pytest.approx(v_b, rel=1e-13)
    found = points(diagram)
    assert found["gust B+"] == pytest.approx((v_b, 1 + gust_per_v * v_b), rel=1e-13)
    assert found["gust B-"] == pytest.approx((v_b, 1 - gust_per_v * v_b), rel=1e-13)
    assert v_b < meet  # here V_S sqrt(n_g) is the lesser: B+ lies past the stall line


def test_a_transport_is_cs_25_333_to_25_337():
    mass = 70_000.0
    envelope = FlightEnvelope(
        weights=[mass * G0],
        cl_max=1.5,
        cl_min=-1.0,
        category="cs25",
        altitudes=[0.0, 10_000.0],
        cruise_speed=170.0,
        wing_area=122.6,
        mean_chord=4.2,
        lift_slope=6.0,
    )
    diagram = vn.vn_diagram(envelope, mass * G0, 10_000.0)
    # CS-25.337(b): 2.1 + 24,000 / (154,324 + 10,000) = 2.25, but at least 2.5; (c): -1.0 up
    # to V_C, 0 at V_D; CS-25.335(b): V_D = V_C / 0.8 when not given.
    found = points(diagram)
    assert found["C+"] == (170.0, 2.5)
    assert found["D+"] == (212.5, 2.5)
    assert found["C-"] == (170.0, -1.0)
    assert found["D-"] == (212.5, 0.0)
    # Gusts of CS-23.333(c) at 10,000 m: 50 ft/s falling to 25 from 20,000 to 50,000 ft.
    fraction = (10_000 - 6096) / (15240 - 6096)
    gust_d = 7.62 - 3.81 * fraction
    rho = 0.41271  # the standard atmosphere at 10,000 m (NASA-TM-X-74335), 5 digits
    loading = mass * G0 / 122.6
    assert found["gust D+"][1] == pytest.approx(
        pratt(loading, 212.5, gust_d, 6.0, 4.2, rho), rel=1e-5
    )
    assert {p.name for p in diagram.points if p.kind == "gust"} == {
        "gust C+",
        "gust C-",
        "gust D+",
        "gust D-",
    }


def test_given_design_speeds_and_load_factors_replace_the_rules():
    envelope = FlightEnvelope(
        **LIGHT,
        manoeuvring_speed=60.0,
        cruise_speed=70.0,
        dive_speed=95.0,
        load_factor_max=4.0,
        load_factor_min=-2.0,
    )
    diagram = vn.vn_diagram(envelope, 1100.0 * G0, 0.0)
    found = points(diagram)
    assert (diagram.manoeuvring_speed, diagram.cruise_speed, diagram.dive_speed) == (60, 70, 95)
    assert found["A+"] == (60.0, 4.0) and found["D+"] == (95.0, 4.0)
    assert found["C-"] == (70.0, -2.0) and found["D-"] == (95.0, 0.0)


def test_a_corner_past_v_d_is_the_stall_line_and_coinciding_corners_are_one_case():
    """V_S sqrt(n_max) past V_D: the stall line never reaches n_max; A+ falls on D+ (one case)
    and C+, below the corner, is on the stall line: n = (V_C / V_S)^2."""
    envelope = FlightEnvelope(**{**LIGHT, "cl_max": 0.7}, cruise_speed=55.0, dive_speed=70.0)
    diagram = vn.vn_diagram(envelope, 1100.0 * G0, 0.0)
    v_s = diagram.stall_speed
    assert v_s * math.sqrt(3.8) > 70.0
    found = points(diagram)
    assert "A+" in found and "D+" not in found
    assert found["A+"] == pytest.approx((70.0, (70.0 / v_s) ** 2), rel=1e-14)
    assert found["C+"] == pytest.approx((55.0, (55.0 / v_s) ** 2), rel=1e-14)


def test_the_negative_corner_on_the_sloped_limit_and_without_one():
    """Utility: n_min up to V_C, then linearly to -1 at V_D. A weak negative stall line meets
    the sloped part (V_G past V_C), or a weaker one never reaches the limit (no G-)."""
    sloped = vn.vn_diagram(
        FlightEnvelope(**{**LIGHT, "category": "utility", "cl_min": -0.35}), 1100.0 * G0, 0.0
    )
    v_c, v_d, v_g = sloped.cruise_speed, sloped.dive_speed, sloped.negative_manoeuvring_speed
    assert v_g is not None and v_c < v_g < v_d
    limit = -1.76 + (-1.0 + 1.76) * (v_g - v_c) / (v_d - v_c)
    stall = -RHO0 * v_g**2 * 0.35 / (2 * 1100.0 * G0 / 16.2)
    assert points(sloped)["G-"][1] == pytest.approx(limit, rel=1e-13)
    assert stall == pytest.approx(limit, rel=1e-12)
    assert points(sloped)["C-"][1] > -1.76  # on the stall line at V_C

    none = vn.vn_diagram(
        FlightEnvelope(**{**LIGHT, "category": "utility", "cl_min": -0.1}), 1100.0 * G0, 0.0
    )
    assert none.negative_manoeuvring_speed is None and "G-" not in points(none)
    loading = 1100.0 * G0 / 16.2
    assert points(none)["D-"][1] == pytest.approx(-RHO0 * none.dive_speed**2 * 0.1 / (2 * loading))


def test_the_boundary_is_closed_and_bounded_by_the_limits():
    diagram = vn.vn_diagram(FlightEnvelope(**LIGHT), 1100.0 * G0, 0.0)
    v, n = diagram.boundary_airspeed, diagram.boundary_load_factor
    assert (v[0], n[0]) == (0.0, 0.0) == (v[-1], n[-1])
    assert n.max() == 3.8 and n.min() == pytest.approx(-1.52, rel=1e-15)
    assert v.max() == diagram.dive_speed
    # Every manoeuvre corner is a vertex of the boundary.
    vertices = set(zip(v.tolist(), n.tolist(), strict=True))
    for point in diagram.points:
        if point.kind == "manoeuvre" and point.name != "C+":  # C+ lies on the n_max edge
            assert (point.airspeed, point.load_factor) in vertices, point.name
    # The stall curves: n = rho0 V^2 S C_L / (2 W) where the boundary is below n_max.
    loading = 1100.0 * G0 / 16.2
    on_stall = (n > 0) & (n < 3.8)
    np.testing.assert_allclose(
        n[on_stall], RHO0 * v[on_stall] ** 2 * 1.6 / (2 * loading), rtol=1e-12
    )
    assert not v.flags.writeable


def test_the_wing_gives_what_the_envelope_leaves_out():
    bare = {k: v for k, v in LIGHT.items() if k not in ("wing_area", "mean_chord", "lift_slope")}
    envelope = FlightEnvelope(**bare)
    with pytest.raises(InvalidInput) as raised:
        vn.vn_diagrams(envelope, mean_chord=1.5, lift_slope=5.0)
    assert raised.value.field == "wing_area"

    def drawn(diagrams: tuple[vn.VnDiagram, ...]) -> list[tuple[vn.VnPoint, ...]]:
        return [diagram.points for diagram in diagrams]

    from_wing = vn.vn_diagrams(envelope, wing_area=16.2, mean_chord=1.5, lift_slope=5.0)
    assert drawn(from_wing) == drawn(vn.vn_diagrams(FlightEnvelope(**LIGHT)))
    # The envelope's own value wins over the wing's.
    assert drawn(vn.vn_diagrams(FlightEnvelope(**LIGHT), wing_area=99.0)) == drawn(from_wing)
    with pytest.raises(InvalidInput) as raised:
        vn.vn_diagrams(envelope, wing_area=16.2, mean_chord=-1.0, lift_slope=5.0)
    assert raised.value.field == "mean_chord"


@pytest.mark.parametrize(
    ("changes", "field"),
    [
        # V_S (C_Lmax 0.25: 65.9 m/s) above the derived V_C (63.3 m/s): no manoeuvre envelope.
        pytest.param({"cl_max": 0.25}, "cl_max", id="stall-above-the-derived-v-c"),
        pytest.param({"cruise_speed": 25.0}, "cruise_speed", id="stall-above-the-given-v-c"),
        pytest.param({"manoeuvring_speed": 40.0}, "manoeuvring_speed", id="v-a-below-v-s-root-n"),
        pytest.param({"dive_speed": 50.0}, "dive_speed", id="v-d-below-the-derived-v-c"),
        pytest.param(
            {"manoeuvring_speed": 90.0}, "manoeuvring_speed", id="v-a-above-the-derived-v-d"
        ),
    ],
)
def test_an_envelope_the_rules_cannot_draw_names_the_field(changes, field):
    with pytest.raises(InvalidInput) as raised:
        vn.vn_diagrams(FlightEnvelope(**{**LIGHT, **changes}))
    assert raised.value.field == field


def test_a_diagram_at_a_weight_or_altitude_out_of_range_names_it():
    with pytest.raises(InvalidInput) as raised:
        vn.vn_diagram(FlightEnvelope(**LIGHT), -1.0, 0.0)
    assert raised.value.field == "weight"
    with pytest.raises(InvalidInput) as raised:
        vn.vn_diagram(FlightEnvelope(**LIGHT), 1e4, 1e6)
    assert raised.value.field == "altitude"
