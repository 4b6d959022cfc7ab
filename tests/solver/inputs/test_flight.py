"""solver.inputs.flight: FlightCondition accepts physical inputs and rejects anything else,
naming the offending field."""

from __future__ import annotations

import math

import pytest

import solver
from solver import InvalidInput


def test_a_valid_flight_condition_and_its_dynamic_pressure():
    flight = solver.FlightCondition(velocity=20.0, alpha=-4.0, density=0.9)
    assert flight.dynamic_pressure == pytest.approx(0.5 * 0.9 * 20.0**2, rel=1e-15)
    assert solver.FlightCondition.velocity_for(flight.dynamic_pressure, 0.9) == pytest.approx(20.0)
    assert flight.at_velocity(10.0) == solver.FlightCondition(10.0, -4.0, 0.9)


@pytest.mark.parametrize(
    ("velocity", "alpha", "density", "field"),
    [
        pytest.param(0.0, 5.0, 1.2, "velocity", id="zero-velocity"),
        pytest.param(-10.0, 5.0, 1.2, "velocity", id="negative-velocity"),
        pytest.param(math.nan, 5.0, 1.2, "velocity", id="nan-velocity"),
        pytest.param(math.inf, 5.0, 1.2, "velocity", id="infinite-velocity"),
        pytest.param(10.0, 90.0, 1.2, "alpha", id="alpha-90"),
        pytest.param(10.0, -95.0, 1.2, "alpha", id="alpha-below-minus-90"),
        pytest.param(10.0, math.nan, 1.2, "alpha", id="nan-alpha"),
        pytest.param(10.0, 5.0, 0.0, "density", id="zero-density"),
        pytest.param(10.0, 5.0, -1.2, "density", id="negative-density"),
        pytest.param(10.0, 5.0, math.inf, "density", id="infinite-density"),
        pytest.param(10.0, 5.0, 5e-324, "density", id="denormal-density"),
        pytest.param(1e200, 5.0, 1.2, "velocity", id="dynamic-pressure-overflows"),
    ],
)
def test_an_invalid_flight_condition_names_the_field(velocity, alpha, density, field):
    with pytest.raises(InvalidInput) as raised:
        solver.FlightCondition(velocity=velocity, alpha=alpha, density=density)
    assert raised.value.field == field
