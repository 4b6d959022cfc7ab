"""solver.deprecated: a renamed public name keeps working for a release, warning with its
replacement, and answers as the new name does."""

from __future__ import annotations

import pytest

import solver
from tests import study


@pytest.mark.parametrize(
    ("old", "new"),
    [
        ("SweepResult", solver.AirspeedSweep),
        ("SweepPoint", solver.AirspeedPoint),
        ("SweepInfo", solver.AirspeedSweepInfo),
    ],
    ids=["SweepResult", "SweepPoint", "SweepInfo"],
)
def test_a_renamed_type_is_the_new_one_with_a_warning(old: str, new: type) -> None:
    with pytest.warns(DeprecationWarning, match=new.__name__):
        assert getattr(solver, old) is new


def test_the_old_sweep_answers_as_airspeed_sweep_at_that_alpha() -> None:
    wing = study.study_wing()
    with pytest.warns(DeprecationWarning, match="airspeed_sweep"):
        old = solver.sweep(wing, [10.0, 12.0], 5.0, 1.225)
    new = solver.airspeed_sweep(wing, [10.0, 12.0], solver.FlightCondition(None, 5.0, 1.225))
    assert [e.totals.lift for e in old.equilibria] == [e.totals.lift for e in new.equilibria]


def test_the_old_trim_sweep_and_trim_condition_answer_as_a_trimmed_flight() -> None:
    wing = study.study_wing()
    with pytest.warns(DeprecationWarning, match="lift=lift"):
        old = solver.trim_sweep(wing, [12.0], 300.0, 1.225)
    with pytest.warns(DeprecationWarning, match="FlightCondition"):
        condition = solver.TrimCondition(12.0, 300.0)
    assert condition == solver.FlightCondition(velocity=12.0, lift=300.0)
    trimmed = solver.trim(wing, condition)
    assert old.equilibria[0].totals.alpha == trimmed.totals.alpha


def test_a_name_that_never_was_is_an_attribute_error() -> None:
    with pytest.raises(AttributeError, match="no_such_name"):
        solver.no_such_name  # noqa: B018
    assert "sweep" not in solver.__all__  # the aliases are not offered to new code
