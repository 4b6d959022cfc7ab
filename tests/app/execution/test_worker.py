"""app.execution.worker: what runs in a worker process answers with plain data: its response
body, or the solver's own typed error (which pickles), a refused input included."""

from __future__ import annotations

import json
import pickle

import numpy as np

from app.execution import worker
from app.problems import problem_of
from solver import (
    FlightCondition,
    InvalidInput,
    NoEquilibrium,
    SolveInput,
    SolverOptions,
    solve,
)
from tests.study import ALPHA, DENSITY, study_wing


def test_an_equilibrium_is_a_payload_and_beyond_the_fold_a_typed_error() -> None:
    wing = study_wing()
    ok = worker.run(SolveInput(wing, FlightCondition(10.0, ALPHA, DENSITY)))
    assert ok.error is None and ok.answer is not None
    assert json.loads(ok.answer.body())["totals"]["lift"] > 0
    beyond = worker.run(SolveInput(wing, FlightCondition(23.0, ALPHA, DENSITY)))
    assert beyond.answer is None and isinstance(beyond.error, NoEquilibrium)
    assert 21.43 < (beyond.error.fold_velocity or 0.0) < 21.45
    again = pickle.loads(pickle.dumps(beyond))  # what crosses the process boundary
    assert str(again.error) == str(beyond.error)
    assert again.error.fold_velocity == beyond.error.fold_velocity


class _Refused:
    """An operation input the solver refuses when it runs."""

    def run(self, progress: object = None) -> None:
        solve(study_wing(), FlightCondition(10.0, ALPHA, DENSITY), np.zeros(7), SolverOptions())


def test_an_input_the_solver_refuses_is_a_422_naming_it_not_a_server_error() -> None:
    """The service validates every input first; should a check be missing there, the solver's
    own refusal still reaches the client as the input's problem."""
    outcome = worker.run(_Refused())
    assert outcome.answer is None and isinstance(outcome.error, InvalidInput)
    assert outcome.error.field == "initial_guess"
    problem = problem_of(outcome.error)
    assert problem.status == 422 and problem.type.slug == "invalid-input"
    assert problem.extensions["errors"] == [
        {"field": "initial_guess", "reason": "must be a finite state of shape (119,)"}
    ]
