"""solver.errors: each way a solve ends without an answer says why, in fields and in words."""

from __future__ import annotations

import pytest

from solver import ConvergenceError, InfeasibleDesign, InvalidInput, NoEquilibrium, SolverError


def test_invalid_input_is_a_value_error_naming_field_and_reason():
    error = InvalidInput("chord", "must be positive")
    assert isinstance(error, ValueError) and not isinstance(error, SolverError)
    assert (error.field, error.reason, str(error)) == (
        "chord",
        "must be positive",
        "chord: must be positive",
    )


def test_no_equilibrium_names_the_fold_or_says_there_is_none():
    beyond = NoEquilibrium(23.0, 21.4397)
    assert beyond.fold_velocity == 21.4397
    assert "beyond the fold of the equilibrium branch at 21.4397 m/s" in str(beyond)
    unstable = NoEquilibrium(23.0, None, detail="margin 1.2")
    assert "has no stable equilibrium there (margin 1.2)" in str(unstable)
    trimmed = NoEquilibrium(5.0, None, where="the rigid wing cannot carry this lift")
    assert str(trimmed).endswith("the rigid wing cannot carry this lift")


def test_convergence_and_design_failures_carry_what_stopped_them():
    stalled = ConvergenceError(12.0, 8, 3.5e-4, "path stalled")
    assert (stalled.velocity, stalled.iterations, stalled.residual_norm) == (12.0, 8, 3.5e-4)
    assert "path stalled after 8 Newton iterations (residual 0.00035)" in str(stalled)
    infeasible = InfeasibleDesign("von_mises", "IPOPT stopped")
    assert infeasible.constraint == "von_mises" and str(infeasible).startswith("no feasible")


@pytest.mark.parametrize("error", [ConvergenceError, NoEquilibrium, InfeasibleDesign])
def test_every_failure_of_a_valid_solve_is_a_solver_error(error: type[Exception]):
    assert issubclass(error, SolverError)
