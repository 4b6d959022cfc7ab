"""solver.inputs.envelope: a FlightEnvelope accepts what describes an aircraft's envelope and
rejects anything else, naming the field."""

from __future__ import annotations

import math

import pytest

from solver import InvalidInput
from solver.fields import spec_of
from solver.inputs.envelope import CATEGORIES, FlightEnvelope

VALID = {"weights": [10_787.0, 9_000.0], "cl_max": 1.6, "cl_min": -1.0}


def test_an_envelope_normalises_its_lists_to_tuples_of_floats():
    envelope = FlightEnvelope(**VALID, altitudes=[0, 3000])
    assert envelope.weights == (10_787.0, 9_000.0)
    assert envelope.altitudes == (0.0, 3000.0)
    assert all(type(h) is float for h in envelope.altitudes)
    assert envelope.category == "normal"
    assert envelope.design_weight == 10_787.0
    assert FlightEnvelope(**VALID, max_takeoff_weight=12_000.0).design_weight == 12_000.0


def test_an_envelope_is_hashable_and_equal_to_itself_rebuilt():
    """Frozen, its lists tuples: an envelope can key a cache (solver.fields.digest too)."""
    assert FlightEnvelope(**VALID) == FlightEnvelope(**VALID)
    assert hash(FlightEnvelope(**VALID)) == hash(FlightEnvelope(**VALID))


def test_the_categories_are_the_declared_choices():
    assert spec_of(FlightEnvelope, "category").choices == CATEGORIES
    for category in CATEGORIES:
        speeds = {"cruise_speed": 120.0} if category == "cs25" else {}
        assert FlightEnvelope(**VALID, category=category, **speeds).category == category


@pytest.mark.parametrize(
    ("changes", "field"),
    [
        pytest.param({"weights": []}, "weights", id="no-weights"),
        pytest.param({"weights": [1e4, -1.0]}, "weights", id="a-negative-weight"),
        pytest.param({"weights": [1e4, math.nan]}, "weights", id="a-nan-weight"),
        pytest.param({"weights": "10000"}, "weights", id="weights-as-text"),
        pytest.param({"weights": [1e4, 9e3, 1e4]}, "weights[2]", id="a-repeated-weight"),
        pytest.param({"altitudes": [0.0, 90_000.0]}, "altitudes", id="an-altitude-above-the-isa"),
        pytest.param({"altitudes": [0.0, 0.0]}, "altitudes[1]", id="a-repeated-altitude"),
        pytest.param({"category": "glider"}, "category", id="an-unknown-category"),
        pytest.param({"cl_max": 0.0}, "cl_max", id="no-positive-stall"),
        pytest.param({"cl_max": math.inf}, "cl_max", id="infinite-cl-max"),
        pytest.param({"cl_min": 0.5}, "cl_min", id="a-positive-cl-min"),
        pytest.param({"wing_area": 0.0}, "wing_area", id="no-wing-area"),
        pytest.param({"mean_chord": -1.0}, "mean_chord", id="a-negative-chord"),
        pytest.param({"lift_slope": 0.0}, "lift_slope", id="no-lift-slope"),
        pytest.param({"load_factor_max": 0.5}, "load_factor_max", id="n-max-below-level-flight"),
        pytest.param({"load_factor_min": 1.0}, "load_factor_min", id="a-positive-n-min"),
        pytest.param({"cruise_speed": 0.0}, "cruise_speed", id="a-zero-cruise-speed"),
        pytest.param({"max_takeoff_weight": 9_500.0}, "weights", id="a-weight-over-the-mtow"),
        pytest.param({"category": "cs25"}, "cruise_speed", id="cs25-without-a-cruise-speed"),
        pytest.param({"rough_air_speed": 60.0}, "rough_air_speed", id="v-b-outside-commuter"),
        pytest.param(
            {"cruise_speed": 80.0, "dive_speed": 80.0}, "dive_speed", id="v-d-not-above-v-c"
        ),
        pytest.param(
            {"manoeuvring_speed": 90.0, "dive_speed": 80.0},
            "manoeuvring_speed",
            id="v-a-above-v-d",
        ),
        pytest.param(
            {"category": "commuter", "rough_air_speed": 90.0, "cruise_speed": 80.0},
            "rough_air_speed",
            id="v-b-above-v-c",
        ),
    ],
)
def test_an_invalid_envelope_names_the_field(changes, field):
    with pytest.raises(InvalidInput) as raised:
        FlightEnvelope(**{**VALID, **changes})
    assert raised.value.field == field
