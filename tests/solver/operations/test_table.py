"""solver.operations.table: every operation listed once, its row whole (a result type, a known
tag and budget, a progress its input can count), and the public OPERATIONS mapping derived
from it."""

from __future__ import annotations

import dataclasses
import typing
from functools import cached_property

import pytest

import solver
from solver.operations.table import TAGS, Budget

ROWS = solver.OPERATION_TABLE
IDS = [op.name for op in ROWS]


def test_every_operation_is_listed_once_and_operations_is_the_tables() -> None:
    names = [op.name for op in ROWS]
    assert len(names) == len(set(names))
    assert {op.name: op.input for op in ROWS} == solver.OPERATIONS
    assert {op.tag for op in ROWS} <= set(TAGS)


@pytest.mark.parametrize("operation", ROWS, ids=IDS)
def test_a_rows_input_answers_with_its_result_type(operation: solver.Operation) -> None:
    """The service derives the response model from the result: a dataclass of the results
    package, returned by `run` (its annotation)."""
    assert dataclasses.is_dataclass(operation.result)
    assert operation.result.__module__.startswith("solver.results.")
    hints = typing.get_type_hints(operation.input.run)
    assert set(hints) == {"progress", "return"}


@pytest.mark.parametrize("operation", ROWS, ids=IDS)
def test_a_rows_text_and_budget_are_what_the_service_reads(operation: solver.Operation) -> None:
    assert operation.summary and "\n" not in operation.summary
    assert len(operation.description.split()) > 20
    assert operation.refusals.endswith(".")
    assert operation.budget in typing.get_args(Budget)
    assert all(issubclass(error, solver.SolverError) for error in operation.answers)


@pytest.mark.parametrize("operation", [op for op in ROWS if op.parts], ids=lambda op: op.name)
def test_a_rows_parts_are_its_inputs_to_count(operation: solver.Operation) -> None:
    """Progress counts the input's `parts` attribute (a sweep's airspeeds, a loads question's
    case count): it exists as a property of the input."""
    assert operation.parts is not None
    assert isinstance(getattr(operation.input, operation.parts), property | cached_property)


@pytest.mark.parametrize("operation", [op for op in ROWS if op.spread], ids=lambda op: op.name)
def test_a_spread_rows_input_plans_its_parts_and_assembles_its_result(
    operation: solver.Operation,
) -> None:
    """What the service runs apart: `plan` (a property), each part an input that `run`s, and
    `assemble` returning the row's result type from their answers."""
    assert isinstance(operation.input.plan, property | cached_property)  # type: ignore[attr-defined]
    assemble = typing.get_type_hints(operation.input.assemble)  # type: ignore[attr-defined]
    assert assemble["return"] is operation.result
