"""OpenAPI descriptions of the error responses an operation's route can return (all
problem+json), from its row of `solver.OPERATION_TABLE`."""

from __future__ import annotations

from typing import Any

import solver
from app.problems import ProblemDetails

__all__ = ["errors_of"]


def _problem(description: str) -> dict[str, Any]:
    return {"model": ProblemDetails, "description": description}


def errors_of(operation: solver.Operation) -> dict[int | str, dict[str, Any]]:
    """413, 422 (invalid input, and the operation's own refusals), 503 and 504."""
    return {
        413: _problem("Request body too large (/problems/body-too-large)."),
        422: _problem(
            "Invalid input (/problems/invalid-input, `errors` names each bad field); "
            + operation.refusals
        ),
        503: _problem(
            "Overloaded, not ready, or the worker died (/problems/overloaded, "
            "/problems/not-ready, /problems/worker-lost); see Retry-After."
        ),
        504: _problem(
            f"The {operation.name} operation exceeded its time budget (/problems/solve-timeout)."
        ),
    }
