"""app.jobs.models: the jobs API's models. POST /jobs' example (STUDY_BATCH) is a valid batch of
the study's solves; a batch holds one or more /solve bodies and nothing else; JobStatus
is what `app.jobs.views.job_view` shows of a job, in every state; a batch item is a result or a
problem."""

from __future__ import annotations

from typing import Any, get_args

import pytest
from pydantic import ValidationError

import solver
from app.jobs.models import (
    FINISHED_STATES,
    JOB_STATES,
    STUDY_BATCH,
    BatchItem,
    BatchRequest,
    JobState,
    JobStatus,
)
from app.jobs.operations import JOB_KINDS
from app.jobs.store import interrupted_problem
from app.jobs.views import job_view
from app.problems import Problem, problem_body
from app.schemas import SolveRequest
from app.schemas.examples import STUDY_SOLVE


def test_the_study_batch_validates_as_three_solves_of_the_study_wing() -> None:
    """STUDY_BATCH is /solve's example at 8, 10 and 12 m/s (alpha 5 deg, sea level)."""
    request = BatchRequest.model_validate(STUDY_BATCH)
    assert BatchRequest.model_json_schema()["examples"] == [STUDY_BATCH]
    tasks = [item.to_solver() for item in request.items]
    assert all(isinstance(task, solver.SolveInput) for task in tasks)
    assert [task.flight.velocity for task in tasks] == [8.0, 10.0, 12.0]
    assert {(task.flight.alpha, task.flight.density) for task in tasks} == {
        (5.0, solver.ISA_SEA_LEVEL_DENSITY)
    }
    study = SolveRequest.model_validate(STUDY_SOLVE).to_solver()
    assert all(solver.digest(task.wing) == solver.digest(study.wing) for task in tasks)


NOT_BATCHES = {
    "no items": {"items": []},
    "another member": STUDY_BATCH | {"priority": 1},
    "an item that is no solve": {"items": [{"velocities": [6.0]}]},
    "items as an object": {"items": {"0": STUDY_SOLVE}},
}


@pytest.mark.parametrize("body", list(NOT_BATCHES.values()), ids=list(NOT_BATCHES))
def test_a_batch_is_one_or_more_solve_bodies_and_nothing_else(body: dict[str, Any]) -> None:
    with pytest.raises(ValidationError):
        BatchRequest.model_validate(body)


def test_the_job_states_are_the_published_ones() -> None:
    assert get_args(JobState) == JOB_STATES
    assert set(JOB_STATES) - {"queued", "running"} == FINISHED_STATES


def _row(status: str, **changes: Any) -> dict[str, Any]:
    return {
        "id": "a-job-id",
        "operation": "sweep",
        "status": status,
        "principal": "",
        "created": 1_700_000_000.0,
        "started": None,
        "finished": None,
        "expires": None,
        "done": 0,
        "total": 6,
        "problems": 0,
        "problem": None,
    } | changes


ROWS = {
    "queued": _row("queued"),
    "running": _row("running", started=1_700_000_001.0, done=2),
    "succeeded": _row(
        "succeeded", started=1.7e9 + 1, finished=1.7e9 + 2, expires=1.7e9 + 9, done=6
    ),
    "failed": _row(
        "failed",
        started=1.7e9 + 1,
        finished=1.7e9 + 2,
        expires=1.7e9 + 9,
        done=2,
        problem=interrupted_problem("running", 2, 6),
    ),
    "cancelled": _row("cancelled", finished=1.7e9 + 2, expires=1.7e9 + 9),
}


@pytest.mark.parametrize("row", list(ROWS.values()), ids=list(ROWS))
def test_job_status_describes_the_view_of_a_job_in_every_state(row: dict[str, Any]) -> None:
    view = job_view(row, JOB_KINDS)
    status = JobStatus.model_validate(view)
    # Every member of the view is a field of the model and the other way round, but for the
    # result (GET /jobs/{id} only).
    assert set(view) == set(JobStatus.model_fields) - {"result"}
    assert status.model_dump(mode="json", exclude_unset=True) == view
    assert status.created_at.timestamp() == row["created"]


def test_a_batch_item_is_its_solve_response_or_its_problem() -> None:
    problem = problem_body(Problem("no-equilibrium", "beyond", extensions={"fold_velocity": 21.4}))
    item = BatchItem.model_validate({"index": 3, "status": "problem", "problem": problem})
    assert item.problem is not None and item.problem.fold_velocity == 21.4
    with pytest.raises(ValidationError):
        BatchItem.model_validate({"index": 3, "status": "done", "problem": problem})
