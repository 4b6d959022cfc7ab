"""solver.inputs.wing: Wing.create accepts physical inputs and rejects anything else, naming
the offending field, before any numerics run."""

from __future__ import annotations

import math

import numpy as np
import pytest

import solver
from solver import InvalidInput

N = 5
GOOD = {
    "y": np.linspace(0.0, 4.0, N),
    "chord": np.linspace(1.0, 0.5, N),
    "elastic_axis": 0.35,
    "bending_stiffness": np.full(N, 5e3),
    "torsional_stiffness": np.full(N, 4e2),
}


def wing_with(**changes) -> solver.Wing:
    return solver.Wing.create(**{**GOOD, **changes})


def test_a_valid_wing_is_normalised_to_read_only_station_arrays():
    wing = wing_with()
    assert wing.n_stations == N
    assert wing.semispan == 4.0
    np.testing.assert_array_equal(wing.elastic_axis, np.full(N, 0.35))  # one number, broadcast
    for array in (wing.y, wing.chord, wing.elastic_axis, wing.bending_stiffness):
        assert array.shape == (N,)
        with pytest.raises(ValueError):
            array[0] = 1.0


def test_planform_area_of_a_trapezoidal_wing():
    """Both halves of a straight-tapered wing: span times the mean of root and tip chords."""
    wing = wing_with()
    assert wing.planform_area == pytest.approx(2 * 4.0 * (1.0 + 0.5) / 2, rel=1e-15)


@pytest.mark.parametrize(
    ("changes", "field"),
    [
        pytest.param({"y": [0.0, 1.0]}, "y", id="too-few-stations"),
        pytest.param({"y": [0.5, 1.0, 2.0, 3.0, 4.0]}, "y", id="root-not-at-zero"),
        pytest.param({"y": [0.0, 1.0, 1.0, 3.0, 4.0]}, "y", id="repeated-station"),
        pytest.param({"y": [0.0, 2.0, 1.0, 3.0, 4.0]}, "y", id="decreasing-stations"),
        pytest.param({"y": [0.0, 1e-5, 2.0, 3.0, 4.0]}, "y", id="stations-closer-than-1e-4"),
        pytest.param({"y": [[0.0, 1.0, 2.0]]}, "y", id="two-dimensional-y"),
        pytest.param({"y": [0.0, 1.0, math.nan, 3.0, 4.0]}, "y", id="nan-station"),
        pytest.param({"y": 4.0}, "y", id="scalar-y"),
        pytest.param({"chord": [1.0, 1.0, 1.0]}, "chord", id="chord-wrong-length"),
        pytest.param({"chord": [1.0, 1.0, 0.0, 1.0, 1.0]}, "chord", id="zero-chord"),
        pytest.param({"chord": [1.0, 1.0, -0.5, 1.0, 1.0]}, "chord", id="negative-chord"),
        pytest.param({"chord": [1.0, 1.0, math.inf, 1.0, 1.0]}, "chord", id="infinite-chord"),
        pytest.param({"elastic_axis": [0.3, 0.3]}, "elastic_axis", id="elastic-axis-length"),
        pytest.param({"elastic_axis": math.nan}, "elastic_axis", id="nan-elastic-axis"),
        pytest.param({"bending_stiffness": 0.0}, "bending_stiffness", id="zero-EI"),
        pytest.param(
            {"bending_stiffness": [5e3, 5e3, -1.0, 5e3, 5e3]}, "bending_stiffness", id="negative-EI"
        ),
        pytest.param({"bending_stiffness": np.ones(N + 1)}, "bending_stiffness", id="EI-length"),
        pytest.param({"torsional_stiffness": -4e2}, "torsional_stiffness", id="negative-GJ"),
        pytest.param(
            {"torsional_stiffness": [4e2, 4e2, 4e2, 4e2, math.nan]},
            "torsional_stiffness",
            id="nan-GJ",
        ),
    ],
)
def test_an_invalid_wing_names_the_field(changes: dict, field: str):
    with pytest.raises(InvalidInput) as raised:
        wing_with(**changes)
    assert raised.value.field == field
    assert str(raised.value).startswith(f"{field}: ")
    assert raised.value.reason


def test_invalid_input_is_a_value_error():
    """Callers that only know Python's conventions can still catch it."""
    with pytest.raises(ValueError):
        wing_with(chord=-1.0)


def test_the_wing_key_is_canonical():
    """One key per wing, whatever the spelling of equal numbers: the caches of the solver and
    the service depend on it."""
    key = wing_with().key
    assert wing_with(elastic_axis=[0.35] * N).key == key
    assert wing_with(y=[-0.0, *GOOD["y"][1:]]).key == key
    assert wing_with(bending_stiffness=5e3).key == key
    assert wing_with(elastic_axis=0.36).key != key
    assert wing_with(torsional_stiffness=4.01e2).key != key
