"""solver.fields: an input's limits, stated once, judge its values and say so in words."""

from __future__ import annotations

import math
import pickle

import numpy as np
import pytest

from solver.errors import InvalidInput
from solver.fields import Limits, Spec, digest, number, stations
from solver.inputs.airfoil import CamberLine
from solver.inputs.wing import Wing
from tests.study import study_wing

CHORD = Spec("m", "chord", Limits(ge=1e-3, le=100.0, why="1 mm to 100 m"), form="per_station")
SWEEP = Spec("deg", "sweep", Limits(gt=-60.0, lt=60.0))


@pytest.mark.parametrize(
    ("limits", "phrase"),
    [
        pytest.param(Limits(ge=0.01, le=1000.0), "from 0.01 to 1000", id="closed"),
        pytest.param(Limits(gt=-60.0, lt=60.0), "above -60 below 60", id="open"),
        pytest.param(Limits(gt=0.0), "positive", id="positive"),
        pytest.param(Limits(ge=1.0), "at least 1", id="lower-only"),
        pytest.param(Limits(le=0.0), "at most 0", id="upper-only"),
        pytest.param(Limits(), "", id="none"),
    ],
)
def test_a_range_is_said_in_words(limits: Limits, phrase: str):
    assert limits.phrase() == phrase


@pytest.mark.parametrize(
    ("value", "inside"),
    [(-60.0, False), (-59.999, True), (0.0, True), (59.999, True), (60.0, False)],
)
def test_exclusive_ends_are_outside(value: float, inside: bool):
    assert bool(SWEEP.limits.contains(np.asarray(value))) is inside


def test_a_number_in_range_is_a_float_and_minus_zero_is_zero():
    value = number("sweep", -0.0, SWEEP)
    assert value == 0.0 and math.copysign(1.0, value) == 1.0


@pytest.mark.parametrize(
    ("value", "reason"),
    [
        pytest.param("10", "must be a number", id="string"),
        pytest.param(True, "must be a number", id="bool"),
        pytest.param(math.nan, "must be a finite number", id="nan"),
        pytest.param(60.0, "must be above -60 below 60 deg", id="at-the-open-end"),
    ],
)
def test_a_bad_number_is_named_with_its_reason(value: object, reason: str):
    with pytest.raises(InvalidInput) as raised:
        number("wing.sweep", value, SWEEP)
    assert raised.value.field == "wing.sweep" and raised.value.reason == reason


def test_one_number_is_every_station_and_the_array_is_read_only():
    array = stations("chord", 0.5, 4, CHORD)
    assert array.tolist() == [0.5] * 4 and not array.flags.writeable


@pytest.mark.parametrize(
    ("value", "reason"),
    [
        pytest.param([1.0, 2.0], "has 2 values but y has 3 stations", id="length"),
        pytest.param([1.0, math.inf, 1.0], "must contain only finite numbers", id="infinite"),
        pytest.param([1.0, math.nan, 1.0], "must contain only finite numbers", id="nan"),
        pytest.param(
            [1.0, 1.0, 200.0],
            "must be from 0.001 to 100 m at every station (1 mm to 100 m)",
            id="out-of-range-at-the-top",
        ),
        pytest.param(
            [1.0, 0.0, 1.0],
            "must be from 0.001 to 100 m at every station (1 mm to 100 m)",
            id="out-of-range",
        ),
        pytest.param(["1", 1.0, 1.0], "must be a number or a list of numbers", id="string-item"),
    ],
)
def test_a_bad_station_array_is_named_with_its_reason(value: object, reason: str):
    with pytest.raises(InvalidInput) as raised:
        stations("wing.chord", value, 3, CHORD)
    assert raised.value.reason == reason


@pytest.mark.parametrize(
    ("plain", "general"),
    [
        (1.5, np.float64(1.5)),
        (2, np.int64(2)),
        (-0.0, np.float64(0.0)),
        (np.arange(3.0), np.arange(3)),  # float64 array (fast path) and an int array
        (np.array(4.0), np.float64(4.0)),  # a 0-d array and a numpy scalar
    ],
    ids=["float", "int", "minus-zero", "array", "0-d-array"],
)
def test_the_digest_of_a_value_does_not_depend_on_its_python_type(plain, general):
    """Plain floats, ints and float64 arrays are digested by a fast path: the same bytes as
    the general one, so a cache keyed by digest cannot tell them apart."""
    assert digest(plain) == digest(general)
    assert digest([plain]) == digest((general,))


def test_a_number_and_the_array_of_it_differ_from_other_numbers():
    assert digest(1.0) != digest(1.0 + 2**-52)
    assert digest(1.0) != digest(np.array([1.0, 1.0]))


@pytest.mark.parametrize("digested", [False, True], ids=["pickled-first", "digested-first"])
def test_a_wing_is_pickled_once_and_unpickles_as_an_equal_wing(digested: bool):
    """A wing (`pickled_once`) pickles its fields once and sends the same bytes after (the
    service hands one kept wing to its workers with every request); the copy is the same wing,
    whether its digest was kept before or not."""
    wing = study_wing(n=12)
    if digested:
        digest(wing)
    first = pickle.dumps(wing)
    state = wing.__dict__["_fields_pickle"]
    assert pickle.dumps(wing) == first and wing.__dict__["_fields_pickle"] is state
    copy = pickle.loads(first)
    assert type(copy) is Wing and copy is not wing
    assert digest(copy) == digest(study_wing(n=12))  # every field, canonically
    assert np.array_equal(copy.torsional_stiffness, wing.torsional_stiffness)
    assert "_fields_pickle" not in copy.__dict__  # its own state, should it be sent on


def test_a_wing_keeps_its_digest_and_cannot_change_under_it():
    """A wing (`digested_once`) is digested once for good, which is only right because nothing
    in it can change: its arrays, its camber lines' and its spar's are read-only."""
    wing = study_wing(n=12)
    first = digest(wing)
    assert wing.__dict__["_fields_digest"]  # kept
    assert digest(wing) == first == digest(study_wing(n=12))  # and equal to a fresh one's
    arrays = [wing.y, wing.chord, wing.bending_stiffness, wing.airfoil[0].x, wing.airfoil[0].camber]
    assert not any(a.flags.writeable for a in arrays)
    line = CamberLine(np.array([0.0, 0.5, 1.0]), np.array([0.0, 0.02, 0.0]))
    assert not line.x.flags.writeable and not line.camber.flags.writeable
