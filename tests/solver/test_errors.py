"""solver.errors: each way a solve ends without an answer says why, in fields and in words."""

from __future__ import annotations

import pickle

import pytest

from solver import (
    ConvergenceError,
    InfeasibleDesign,
    InvalidInput,
    NoEquilibrium,
    OptimizerNotConverged,
    SolverError,
)


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


def test_a_design_failure_names_its_case_and_crosses_processes_whole():
    """A worker sends the error itself: pickled and back, every field as it was."""
    infeasible = InfeasibleDesign("von_mises", "IPOPT stopped", 0.25, case="pull-up")
    assert "von_mises in case 'pull-up'" in str(infeasible)
    again = pickle.loads(pickle.dumps(infeasible))
    assert (again.constraint, again.violation, again.case) == ("von_mises", 0.25, "pull-up")
    assert InfeasibleDesign("lift", "no equilibrium").case is None  # a single-point problem's


def test_an_optimizer_stopped_at_its_limit_is_a_convergence_error_not_an_infeasible_design():
    stopped = OptimizerNotConverged(14.0, 500, 2e-3, "IPOPT stopped with its limit")
    assert isinstance(stopped, ConvergenceError) and not isinstance(stopped, InfeasibleDesign)
    assert str(stopped).startswith("the design optimizer did not converge")
    assert "after 500 iterations" in str(stopped) and "Newton" not in str(stopped)
    again = pickle.loads(pickle.dumps(stopped))
    assert type(again) is OptimizerNotConverged and str(again) == str(stopped)
