"""app.worker: what runs in a worker process answers with plain data, a refused input included."""

from __future__ import annotations

import numpy as np

from app import worker
from app.service import _failure_problem
from solver import FlightCondition, SolverOptions
from tests.study import ALPHA, DENSITY, study_wing


def test_an_equilibrium_is_a_payload_and_beyond_the_fold_a_typed_failure() -> None:
    wing, options = study_wing(), SolverOptions()
    ok = worker.run_solve(worker.SolveJob(wing, FlightCondition(10.0, ALPHA, DENSITY), options))
    assert ok.failure is None and ok.payload is not None
    assert ok.payload["totals"]["lift"] > 0
    beyond = worker.run_solve(worker.SolveJob(wing, FlightCondition(23.0, ALPHA, DENSITY), options))
    assert beyond.payload is None and beyond.failure is not None
    assert beyond.failure.kind == "no_equilibrium"
    assert 21.43 < (beyond.failure.fold_velocity or 0.0) < 21.45


def test_an_input_the_solver_refuses_is_a_422_naming_it_not_a_server_error() -> None:
    """The service validates every input first; should a check be missing there, the solver's
    own refusal still reaches the client as the input's problem."""
    job = worker.SolveJob(
        study_wing(), FlightCondition(10.0, ALPHA, DENSITY), SolverOptions(), np.zeros(7)
    )
    outcome = worker.run_solve(job)
    assert outcome.payload is None and outcome.failure is not None
    assert (outcome.failure.kind, outcome.failure.field) == ("invalid_input", "initial_guess")
    problem = _failure_problem(outcome.failure)
    assert problem.status == 422 and problem.type.slug == "invalid-input"
    assert problem.extensions["errors"] == [
        {"field": "initial_guess", "reason": "must be a finite state of shape (119,)"}
    ]
