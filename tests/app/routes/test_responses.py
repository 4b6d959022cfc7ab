"""app.routes.responses: the error responses every operation's route documents. Every
problem type a description names (/problems/<slug>) is one the service has
(`app.problems.PROBLEM_TYPES`, served at that URI) with that response's status, and the
document serves each as application/problem+json."""

from __future__ import annotations

import re
from typing import Any

import httpx
import pytest

import app.main  # noqa: F401  (every module that adds problem types is imported)
import solver
from app.problems import PROBLEM_TYPES, ProblemDetails
from app.routes.responses import errors_of

DOCUMENTED = {f"/{op.name}": errors_of(op) for op in solver.OPERATION_TABLE}
NAMED = re.compile(r"/problems/([a-z-]+)")

CASES = [
    (path, status, response)
    for path, errors in DOCUMENTED.items()
    for status, response in errors.items()
]
IDS = [f"{path} {status}" for path, status, _ in CASES]


@pytest.mark.parametrize(("path", "status", "response"), CASES, ids=IDS)
def test_every_documented_problem_type_exists_with_that_status(
    path: str, status: int, response: dict[str, Any]
) -> None:
    assert response["model"] is ProblemDetails
    named = NAMED.findall(response["description"])
    assert named, f"{path} {status} names no problem type"
    for slug in named:
        assert slug in PROBLEM_TYPES, f"{path} {status}: /problems/{slug} does not exist"
        assert PROBLEM_TYPES[slug].status == status, f"/problems/{slug} is not a {status}"


def test_the_endpoints_document_the_failures_they_share() -> None:
    """Every operation can fail as a solve does (413, 503, 504), and each says what its 422
    means: its own refusals, from its row of the table."""
    solve = DOCUMENTED["/solve"]
    for path, errors in DOCUMENTED.items():
        assert set(errors) == {413, 422, 503, 504}, path
        assert errors[503] == solve[503] and errors[413] == solve[413], path
    assert "infeasible-design" in DOCUMENTED["/optimize"][422]["description"]
    assert "answered in its point" in DOCUMENTED["/sweep"][422]["description"]


@pytest.mark.parametrize(("path", "status", "response"), CASES, ids=IDS)
def test_the_document_serves_each_as_problem_json(
    in_process: httpx.Client, path: str, status: int, response: dict[str, Any]
) -> None:
    document = in_process.get("/openapi.json").json()
    documented = document["paths"][path]["post"]["responses"][str(status)]
    assert documented["description"] == response["description"]
    assert documented["content"] == {
        "application/problem+json": {"schema": {"$ref": "#/components/schemas/ProblemDetails"}}
    }


def test_every_problem_type_the_whole_document_names_exists_with_that_status(
    in_process: httpx.Client,
) -> None:
    """The jobs routes, the keys and the rate limits document theirs the same way."""
    document = in_process.get("/openapi.json").json()
    named = [
        (f"{method.upper()} {path} {status}", slug)
        for path, item in document["paths"].items()
        for method, operation in item.items()
        for status, response in operation["responses"].items()
        for slug in NAMED.findall(response.get("description", ""))
    ]
    assert {"job-conflict", "key-missing", "rate-limited"} <= {slug for _, slug in named}
    wrong = [
        (where, slug)
        for where, slug in named
        if slug not in PROBLEM_TYPES or str(PROBLEM_TYPES[slug].status) != where.split()[-1]
    ]
    assert wrong == []
