"""solver.inputs.atmosphere: the ICAO standard atmosphere against its published tables, exact at
sea level, continuous at its layers' boundaries, and equivalent and true airspeed converting to
the same dynamic pressure."""

from __future__ import annotations

import math

import numpy as np
import pytest

from solver import InvalidInput
from solver.inputs import atmosphere
from solver.inputs.flight import ISA_SEA_LEVEL_DENSITY

# Published standard-atmosphere values: (altitude kind, altitude [m], T [K], p [Pa],
# rho [kg/m^3], a [m/s], mu [Pa s]). Rows by geometric height Z are the standard's tables by
# geometric altitude; rows by geopotential altitude H, those by H (ICAO Doc 7488/3's own form).
# Transcribed from the U.S. Standard Atmosphere 1976 (NOAA-S/T 76-1562) / ICAO Doc 7488 tables
# as the `ambiance` package's test data gives them (airinnova/ambiance, tests/table_data.py),
# which agree with the ICAO gas constant (module docstring) within 2 units of their sixth digit;
# the 10 km rows are NASA-TM-X-74335's (the 1976 standard) as ADRpy's tests quote them
# (yaseen157/ADRpy, tests/test_atmospheres.py).
TABLE = [
    ("H", -5_000, 320.650, 1.77687e5, 1.93047, 358.972, 1.9421e-5),
    ("Z", -2_500, 304.406, 1.35205e5, 1.54731, 349.761, 1.8668e-5),
    ("Z", 1_000, 281.651, 8.98763e4, 1.11166, 336.435, 1.7579e-5),
    ("Z", 2_000, 275.154, 7.95014e4, 1.00655, 332.532, 1.7260e-5),
    ("H", 10_000, 223.150, 2.6436e4, 4.1271e-1, 299.463, None),
    ("Z", 10_000, 223.252, 2.64999e4, 4.13511e-1, 299.532, None),
    ("Z", 11_000, 216.774, 2.26999e4, 3.64801e-1, 295.154, 1.4223e-5),
    ("H", 11_000, 216.650, 2.26320e4, 3.63918e-1, 295.069, 1.4216e-5),
    ("Z", 15_000, 216.650, 1.21118e4, 1.94755e-1, 295.069, 1.4216e-5),
    ("Z", 20_000, 216.650, 5.52929e3, 8.89097e-2, 295.069, 1.4216e-5),
    ("H", 20_000, 216.650, 5.47487e3, 8.80345e-2, 295.069, 1.4216e-5),
    ("Z", 25_000, 221.552, 2.54921e3, 4.00837e-2, 298.389, 1.4484e-5),
    ("H", 32_000, 228.650, 8.68014e2, 1.32249e-2, 303.131, 1.4868e-5),
    ("H", 41_000, 253.850, 2.42394e2, 3.32646e-3, 319.399, 1.6189e-5),
    ("H", 47_000, 270.650, 1.10906e2, 1.42752e-3, 329.799, 1.7037e-5),
    ("H", 50_000, 270.650, 7.59443e1, 9.77519e-4, 329.799, 1.7037e-5),
    ("H", 51_000, 270.650, 6.69384e1, 8.61600e-4, 329.799, 1.7037e-5),
    ("H", 61_000, 242.650, 1.76605e1, 2.53548e-4, 312.274, 1.5610e-5),
    ("H", 71_000, 214.650, 3.95639e0, 6.42105e-5, 293.704, 1.4106e-5),
    ("H", 75_000, 206.650, 2.06790e0, 3.48604e-5, 288.179, 1.3661e-5),
    ("H", 80_000, 196.650, 8.86272e-1, 1.57004e-5, 281.120, 1.3095e-5),
]
QUANTITIES = {
    "temperature": atmosphere.temperature,
    "pressure": atmosphere.pressure,
    "density": atmosphere.density,
    "speed_of_sound": atmosphere.speed_of_sound,
    "dynamic_viscosity": atmosphere.dynamic_viscosity,
}


def _half_unit_in_digit(value: float, digits: int) -> float:
    """Half a unit in the `digits`-th significant digit of `value`: two numbers this close agree
    to that many digits."""
    return 0.5 * 10.0 ** (math.floor(math.log10(abs(value))) - digits + 1)


def _geopotential(kind: str, altitude: float) -> float:
    return float(atmosphere.geopotential_altitude(altitude)) if kind == "Z" else altitude


@pytest.mark.parametrize(
    ("kind", "altitude", "published"),
    [(row[0], row[1], dict(zip(QUANTITIES, row[2:], strict=True))) for row in TABLE],
    ids=[f"{row[0]}={row[1]}m" for row in TABLE],
)
def test_the_atmosphere_agrees_with_the_published_table_to_five_digits(kind, altitude, published):
    """Five significant digits, each quantity within half a unit of its fifth digit: every layer
    from -5 km to 80 km, by geopotential and (through the conversion) geometric altitude."""
    h = _geopotential(kind, float(altitude))
    for name, value in published.items():
        if value is None:
            continue
        computed = QUANTITIES[name](h)
        assert abs(computed - value) <= _half_unit_in_digit(value, 5), (name, computed, value)


def test_sea_level_is_the_standards_values_exactly():
    assert atmosphere.temperature(0.0) == 288.15
    assert atmosphere.pressure(0.0) == 101_325.0
    assert atmosphere.density(0.0) == 1.225 == ISA_SEA_LEVEL_DENSITY
    # ICAO Doc 7488's a0 = 340.294 m/s and mu0 = 1.7894e-5 Pa s, to the digits it prints.
    assert abs(atmosphere.speed_of_sound(0.0) - 340.294) <= 5e-4
    assert atmosphere.speed_of_sound(0.0) == atmosphere.SEA_LEVEL_SPEED_OF_SOUND
    assert abs(atmosphere.dynamic_viscosity(0.0) - 1.7894e-5) <= 5e-10


# Each layer's base (H [m], T [K], p [Pa]) as the 1976 standard (NOAA-S/T 76-1562, Table 4)
# prints it. ICAO's gas constant is 7e-7 smaller: the pressures part by up to 8e-6 at 71 km.
LAYER_BASES_1976 = [
    (11_000.0, 216.65, 22_632.06),
    (20_000.0, 216.65, 5_474.889),
    (32_000.0, 228.65, 868.0187),
    (47_000.0, 270.65, 110.9063),
    (51_000.0, 270.65, 66.93887),
    (71_000.0, 214.65, 3.956420),
]


@pytest.mark.parametrize(
    ("base", "temperature", "pressure"),
    LAYER_BASES_1976,
    ids=[f"{b[0]:.0f}m" for b in LAYER_BASES_1976],
)
def test_each_layer_starts_at_the_standards_base_values(base, temperature, pressure):
    assert atmosphere.temperature(base) == pytest.approx(temperature, rel=1e-14)
    # 1e-5: the two standards' gas constants (above); their tables' 5 digits hold either way.
    assert atmosphere.pressure(base) == pytest.approx(pressure, rel=1e-5)


@pytest.mark.parametrize("base", [b[0] for b in LAYER_BASES_1976], ids=lambda b: f"{b:.0f}m")
@pytest.mark.parametrize("quantity", ["temperature", "pressure", "density"])
def test_the_atmosphere_is_continuous_across_a_layer_boundary(base, quantity):
    """One float below and above the boundary: a jump would show at 1e-12; the layers' formulas
    meet to round-off (their base values are the layer below's top values)."""
    below, above = np.nextafter(base, -np.inf), np.nextafter(base, np.inf)
    values = [float(QUANTITIES[quantity](h)) for h in (below, base, above)]
    assert values[0] == pytest.approx(values[1], rel=1e-12)
    assert values[2] == pytest.approx(values[1], rel=1e-12)


def test_an_array_of_altitudes_answers_in_its_shape_as_each_altitude_alone():
    heights = np.array([[-4000.0, 0.0, 5000.0], [11_000.0, 36_000.0, 79_999.0]])
    for name, quantity in QUANTITIES.items():
        values = quantity(heights)
        assert isinstance(values, np.ndarray) and values.shape == heights.shape, name
        alone = [quantity(float(h)) for h in heights.ravel()]
        assert all(isinstance(value, float) for value in alone), name
        np.testing.assert_array_equal(values.ravel(), alone, err_msg=name)


def test_geometric_and_geopotential_altitude_convert_both_ways():
    # Z = 10,000 m is H = 9,984.3 m (NASA-TM-X-74335, as ADRpy's tests quote it).
    assert atmosphere.geopotential_altitude(10_000.0) == pytest.approx(9_984.3, abs=0.05)
    heights = np.linspace(-5_000.0, 80_000.0, 9)
    back = atmosphere.geometric_altitude(atmosphere.geopotential_altitude(heights))
    np.testing.assert_allclose(back, heights, rtol=1e-14, atol=1e-9)
    assert atmosphere.geopotential_altitude(0.0) == 0.0


@pytest.mark.parametrize("altitude", [-5_000.0, 0.0, 3_000.0, 11_000.0, 20_000.0, 80_000.0])
def test_equivalent_and_true_airspeed_carry_the_same_dynamic_pressure(altitude):
    equivalent = np.array([10.0, 55.5, 250.0])
    true = atmosphere.true_airspeed(equivalent, altitude)
    rho = atmosphere.density(altitude)
    # q = rho V_TAS^2 / 2 = rho0 V_EAS^2 / 2: a few roundings apart.
    np.testing.assert_allclose(0.5 * rho * true**2, 0.5 * 1.225 * equivalent**2, rtol=1e-14)
    np.testing.assert_allclose(
        atmosphere.equivalent_airspeed(true, altitude), equivalent, rtol=1e-14
    )
    assert (true > equivalent).all() == (altitude > 0.0)


def test_at_sea_level_true_airspeed_is_equivalent_airspeed_exactly():
    assert atmosphere.true_airspeed(123.4, 0.0) == 123.4
    assert atmosphere.equivalent_airspeed(123.4, 0.0) == 123.4


def test_a_number_of_speeds_and_an_array_of_altitudes_answer_an_array():
    speeds = atmosphere.true_airspeed(50.0, np.array([0.0, 10_000.0]))
    assert isinstance(speeds, np.ndarray) and speeds.shape == (2,)
    assert speeds[0] == 50.0 and speeds[1] == pytest.approx(
        50.0 * math.sqrt(1.225 / 0.41271), rel=1e-4
    )


@pytest.mark.parametrize(
    "altitude",
    [
        pytest.param(-5_001.0, id="below-the-range"),
        pytest.param(80_001.0, id="above-the-range"),
        pytest.param(math.nan, id="nan"),
        pytest.param(math.inf, id="infinite"),
        pytest.param("1000", id="a-string"),
        pytest.param(True, id="a-flag"),
        pytest.param(np.array([0.0, 1e6]), id="one-of-an-array"),
    ],
)
def test_an_altitude_outside_the_standard_atmosphere_is_invalid_input(altitude):
    with pytest.raises(InvalidInput) as raised:
        atmosphere.density(altitude)
    assert raised.value.field == "altitude"


@pytest.mark.parametrize("speed", [-1.0, math.nan, math.inf], ids=["negative", "nan", "infinite"])
def test_an_airspeed_that_is_not_one_is_invalid_input(speed):
    with pytest.raises(InvalidInput) as raised:
        atmosphere.true_airspeed(speed, 0.0)
    assert raised.value.field == "equivalent_airspeed"
    with pytest.raises(InvalidInput) as raised:
        atmosphere.equivalent_airspeed(speed, 0.0)
    assert raised.value.field == "true_airspeed"


def test_the_standard_atmosphere_at_once_is_each_quantity_alone():
    for altitude in (7_500.0, np.array([0.0, 30_000.0])):
        air = atmosphere.standard_atmosphere(altitude)
        np.testing.assert_array_equal(air.altitude, altitude)
        for name, quantity in QUANTITIES.items():
            np.testing.assert_array_equal(getattr(air, name), quantity(altitude), err_msg=name)
            assert type(getattr(air, name)) is type(quantity(altitude)), name
