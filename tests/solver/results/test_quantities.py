"""solver.results.quantities: the result types, defined once; every reported quantity
states its unit and what it is (the service's response models and the OpenAPI document are
derived from them)."""

from __future__ import annotations

import dataclasses
import importlib
import inspect
import pkgutil

import pytest

import solver
import solver.results
from tests.study import flight, study_wing

# Every result type of every module of solver.results, a new one included without an edit.
RESULT_TYPES = [
    cls
    for module in (
        importlib.import_module(f"solver.results.{info.name}")
        for info in pkgutil.iter_modules(solver.results.__path__)
    )
    for _, cls in inspect.getmembers(module, inspect.isclass)
    if dataclasses.is_dataclass(cls) and cls.__module__ == module.__name__
]


@pytest.mark.parametrize("cls", RESULT_TYPES, ids=lambda cls: cls.__name__)
def test_every_field_states_its_unit_and_meaning_or_is_python_only(cls: type) -> None:
    for field in dataclasses.fields(cls):
        if field.metadata.get("internal"):
            continue
        assert "unit" in field.metadata, f"{cls.__name__}.{field.name} has no unit"
        assert field.metadata["description"], f"{cls.__name__}.{field.name} is not described"


def test_an_equilibriums_shorthands_are_its_totals_and_flight() -> None:
    equilibrium = solver.solve(study_wing(), flight(10.0))
    assert equilibrium.lift == equilibrium.totals.lift
    assert equilibrium.tip_twist == equilibrium.totals.tip_twist
    assert equilibrium.tip_heave == equilibrium.totals.tip_heave
    q = 0.5 * flight(10.0).density * 10.0**2
    assert equilibrium.dynamic_pressure == pytest.approx(q, rel=1e-15)  # rounding order only
