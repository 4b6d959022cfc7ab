"""Schema fuzzing (issue 5, part 1): schemathesis against the live server's OpenAPI document.

Every operation in /openapi.json gets generated requests, valid and invalid by the schema (the
schemathesis default: positive and negative generation modes). Every response must:

- not be a server error (no 5xx at all: the server here is idle, so 503/504 would be defects too);
- use a status code the document lists for the operation;
- use a documented media type and match the documented schema for that status;
- reject schema-invalid data with a 4xx (negative_data_rejection);
- if it is a 4xx, be an RFC 9457 problem (`application/problem+json` with `type`, `title`,
  `status` equal to the HTTP status, and `detail`).

Counts: CI generates at least `CASES_PER_BODY_OPERATION` requests for each of POST /solve and POST
/sweep (2,000 together, asserted by the last test); HYPOTHESIS_PROFILE=nightly multiplies that by
20 (tests/conftest.py). The GET operations have no parameters, so few distinct requests exist.
"""

from __future__ import annotations

from collections import Counter
from typing import Any

import pytest
import schemathesis
from hypothesis import settings
from schemathesis.checks import not_a_server_error
from schemathesis.specs.openapi.checks import (
    content_type_conformance,
    negative_data_rejection,
    response_schema_conformance,
    status_code_conformance,
)

from tests.app.conftest import Server
from tests.conftest import fuzz_examples

CASES_PER_BODY_OPERATION = 1000
REQUEST_TIMEOUT = 60.0  # [s] generous: the solve budget is 20 s

calls: Counter[str] = Counter()


def problem_json_for_every_4xx(ctx: Any, response: Any, case: Any) -> None:
    """A 4xx answer is an RFC 9457 problem whose `status` matches the response."""
    if not 400 <= response.status_code < 500:
        return
    media_type = response.headers.get("content-type", [""])
    media_type = media_type[0] if isinstance(media_type, list) else media_type
    assert media_type.split(";")[0].strip() == "application/problem+json", (
        f"{response.status_code} answered with {media_type!r}: {response.text[:300]}"
    )
    problem = response.json()
    assert isinstance(problem, dict), problem
    for member in ("type", "title", "detail"):
        assert isinstance(problem.get(member), str) and problem[member], (member, problem)
    assert problem["type"].startswith("/problems/"), problem
    assert problem.get("status") == response.status_code, problem


CHECKS = [
    not_a_server_error,
    status_code_conformance,
    content_type_conformance,
    response_schema_conformance,
    negative_data_rejection,
    problem_json_for_every_4xx,
]


@pytest.fixture(scope="module")
def api_schema(server: Server) -> schemathesis.BaseSchema:
    return schemathesis.openapi.from_url(server.base_url + "/openapi.json", timeout=30)


schema = schemathesis.pytest.from_fixture("api_schema")


@schema.parametrize()
@settings(max_examples=fuzz_examples(CASES_PER_BODY_OPERATION))
def test_every_response_conforms_and_every_4xx_is_a_problem(case: schemathesis.Case) -> None:
    calls[case.operation.label] += 1
    case.call_and_validate(checks=CHECKS, timeout=REQUEST_TIMEOUT)


def test_enough_cases_were_generated() -> None:
    if not calls:
        pytest.skip("the fuzzing test did not run in this session (deselected)")
    for label in ("POST /solve", "POST /sweep"):
        assert calls[label] >= fuzz_examples(CASES_PER_BODY_OPERATION), dict(calls)
    assert sum(calls.values()) >= 2 * fuzz_examples(CASES_PER_BODY_OPERATION), dict(calls)
