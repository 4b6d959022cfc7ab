"""app.jobs.views: how the API shows a job (GET /jobs/{id}, its events, the job list): its
database row (or a live job's) as the status document, its links, and its times as RFC 3339
timestamps in UTC."""

from __future__ import annotations

import json
import re
import time
from datetime import UTC, datetime, timedelta
from typing import Any

import pytest

from app.jobs.operations import JOB_KINDS
from app.jobs.views import job_links, job_view

# created, started and finished a quarter second, one and two and a half seconds apart; each
# exactly representable as a double, so its printed fraction is exact too.
ROW: dict[str, Any] = {
    "id": "Ab3_-x",
    "operation": "batch",
    "status": "failed",
    "principal": "",
    "created": 1_700_000_000.25,
    "started": 1_700_000_001.0,
    "finished": 1_700_000_002.5,
    "expires": 1_700_086_402.5,
    "done": 2,
    "total": 3,
    "problems": 1,
    "problem": json.dumps({"type": "/problems/job-interrupted", "status": 503}),
}
RFC_3339_UTC = re.compile(r"^\d{4}-\d\d-\d\dT\d\d:\d\d:\d\d(\.\d{1,6})?Z$")


def test_a_row_is_shown_with_its_progress_problem_and_links() -> None:
    view = job_view(ROW, JOB_KINDS)
    assert view == {
        "id": "Ab3_-x",
        "operation": "batch",
        "status": "failed",
        "progress": {"done": 2, "total": 3, "problems": 1},
        "created_at": "2023-11-14T22:13:20.250000Z",
        "started_at": "2023-11-14T22:13:21Z",
        "finished_at": "2023-11-14T22:13:22.500000Z",
        "expires_at": "2023-11-15T22:13:22.500000Z",
        "problem": {"type": "/problems/job-interrupted", "status": 503},
        "links": {
            "self": "/jobs/Ab3_-x",
            "events": "/jobs/Ab3_-x/events",
            "items": "/jobs/Ab3_-x/items.ndjson",
        },
    }
    assert "principal" not in view  # whose it is is not shown


@pytest.mark.parametrize("field", ["created", "started", "finished", "expires"])
def test_times_are_rfc_3339_in_utc_and_mean_the_rows_instant(field: str) -> None:
    shown = job_view(ROW, JOB_KINDS)[f"{field}_at"]
    assert RFC_3339_UTC.match(shown), shown
    parsed = datetime.fromisoformat(shown)
    assert parsed.utcoffset() == timedelta(0)
    assert parsed.timestamp() == ROW[field]  # every ROW time is exact to the microsecond


def test_the_epoch_and_a_time_not_yet_reached_are_shown_as_such() -> None:
    queued = ROW | {"created": 0.0, "started": None, "finished": None, "expires": None}
    view = job_view(queued, JOB_KINDS)
    assert view["created_at"] == "1970-01-01T00:00:00Z"
    assert (view["started_at"], view["finished_at"], view["expires_at"]) == (None, None, None)


@pytest.mark.parametrize(
    ("problem", "shown"),
    [
        (None, None),
        ('{"type": "/problems/not-converged"}', {"type": "/problems/not-converged"}),
        ({"type": "/problems/overloaded"}, {"type": "/problems/overloaded"}),
    ],
    ids=["none", "stored-json", "live-dict"],
)
def test_a_problem_is_shown_as_json_whether_stored_as_text_or_held_live(
    problem: Any, shown: Any
) -> None:
    assert job_view(ROW | {"problem": problem}, JOB_KINDS)["problem"] == shown


@pytest.mark.parametrize(
    ("operation", "items"),
    [("batch", True), ("solve", False), ("sweep", False), ("optimize", False), ("gone", False)],
    ids=["batch", "solve", "sweep", "optimize", "unregistered"],
)
def test_only_an_operation_with_items_links_to_them(operation: str, items: bool) -> None:
    links = job_view(ROW | {"operation": operation}, JOB_KINDS)["links"]
    assert links == job_links("Ab3_-x", items)
    assert (links["items"] is not None) is items
    assert links["self"] == "/jobs/Ab3_-x" and links["events"] == "/jobs/Ab3_-x/events"


def test_times_are_utc_whatever_the_local_zone(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("TZ", "America/Los_Angeles")
    time.tzset()
    try:
        shown = job_view(ROW, JOB_KINDS)["created_at"]
    finally:
        monkeypatch.undo()
        time.tzset()
    assert shown == datetime.fromtimestamp(ROW["created"], tz=UTC).isoformat()[:-6] + "Z"
    assert shown == "2023-11-14T22:13:20.250000Z"
