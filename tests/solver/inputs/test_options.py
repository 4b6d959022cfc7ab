"""solver.inputs.options: SolverOptions rejects anything out of its limits, naming the field."""

from __future__ import annotations

import math

import pytest

import solver
from solver import InvalidInput


@pytest.mark.parametrize(
    ("changes", "field"),
    [
        pytest.param({"tolerance": 0.0}, "tolerance", id="zero-tolerance"),
        pytest.param({"tolerance": math.nan}, "tolerance", id="nan-tolerance"),
        pytest.param({"max_iterations": -1}, "max_iterations", id="negative-iterations"),
        pytest.param({"aerodynamics": "doublet"}, "aerodynamics", id="unknown-aerodynamics"),
    ],
)
def test_invalid_solver_options_name_the_field(changes: dict, field: str):
    with pytest.raises(InvalidInput) as raised:
        solver.SolverOptions(**changes)
    assert raised.value.field == field
