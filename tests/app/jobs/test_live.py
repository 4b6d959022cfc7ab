"""app.jobs.live: a claimed job taken up here starts from what the store recorded: a batch's
progress is its items answered so far (not the progress column, written every 0.5 s), and an
operation this replica does not know is a stand-in that is never run."""

from __future__ import annotations

from typing import Any

from app.jobs.live import LiveJob
from app.jobs.operations import JOB_KINDS

CLAIM: dict[str, Any] = {
    "id": "job-1",
    "operation": "batch",
    "created": 1_700_000_000.0,
    "started": 1_700_000_001.0,
    "total": 5,
    "done": 1,  # written before the last two items were answered
    "problems": 0,
    "principal": "alice",
    "answers": 3,
    "answered": {4: True, 0: False, 2: True},
    "cancel_requested": 0,
}


def test_a_batch_taken_up_counts_the_items_answered_before() -> None:
    job = LiveJob.claimed(CLAIM, JOB_KINDS["batch"], None)
    assert (job.done, job.problems, job.answers) == (3, 1, 3)
    assert job.answered == {0, 2, 4} and job.status == "running"
    row = job.row()
    assert (row["principal"], row["started"], row["total"]) == ("alice", 1_700_000_001.0, 5)


def test_a_job_of_an_unknown_operation_keeps_its_name() -> None:
    claim = CLAIM | {"operation": "design-2030", "answered": {}, "answers": 0}
    job = LiveJob.claimed(claim, None, None)
    assert job.row()["operation"] == "design-2030"
    assert (job.done, job.problems) == (1, 0)
