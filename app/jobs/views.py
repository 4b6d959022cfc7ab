"""How the API shows a job: its status document (GET /jobs/{id}), timestamps in RFC 3339, and
the links to its events and items."""

from __future__ import annotations

import json
from collections.abc import Mapping
from datetime import UTC, datetime
from typing import Any

from app.jobs.operations import JobKind

__all__ = ["job_links", "job_view"]


def job_links(job_id: str, has_items: bool) -> dict[str, str | None]:
    """The job's own URL, its events' and (a batch's) its items'."""
    return {
        "self": f"/jobs/{job_id}",
        "events": f"/jobs/{job_id}/events",
        "items": f"/jobs/{job_id}/items.ndjson" if has_items else None,
    }


def _iso(seconds: float | None) -> str | None:
    """[s since the epoch] -> RFC 3339 in UTC."""
    if seconds is None:
        return None
    return datetime.fromtimestamp(seconds, tz=UTC).isoformat().replace("+00:00", "Z")


def job_view(row: Mapping[str, Any], operations: Mapping[str, JobKind]) -> dict[str, Any]:
    """A job (a database row or `LiveJob.row()`) as the API shows it, without its result."""
    job_id = row["id"]
    problem = row.get("problem")
    operation = operations.get(row["operation"])
    items = operation is not None and operation.has_items
    return {
        "id": job_id,
        "operation": row["operation"],
        "status": row["status"],
        "progress": {"done": row["done"], "total": row["total"], "problems": row["problems"]},
        "created_at": _iso(row["created"]),
        "started_at": _iso(row["started"]),
        "finished_at": _iso(row["finished"]),
        "expires_at": _iso(row["expires"]),
        "problem": json.loads(problem) if isinstance(problem, str) else problem,
        "links": job_links(job_id, items),
    }
