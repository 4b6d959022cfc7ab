"""Schema fuzzing: schemathesis against the live server's OpenAPI document.

Every operation in /openapi.json gets generated requests, valid and invalid by the schema (the
schemathesis default: positive and negative generation modes). Every response must:

- not be a server error: no 5xx at all (the server here is idle, so a 503 would be a defect too;
  a valid request that needs longer than its synchronous wait is answered 202 with its job);
- use a status code the document lists for the operation;
- use a documented media type and match the documented schema for that status;
- reject schema-invalid data with a 4xx (negative_data_rejection);
- if it is a 4xx, be an RFC 9457 problem (`application/problem+json` with `type`, `title`,
  `status` equal to the HTTP status, and `detail`).

Counts: CI generates at least `CASES_PER_BODY_OPERATION` requests for each of POST /solve and POST
/sweep (2,000 together, asserted by `test_enough_cases_were_generated`), half with each of two
seeds (`SEEDS`); HYPOTHESIS_PROFILE=nightly multiplies that by 20 (tests/conftest.py), and
benchmarks/schema_fuzz_benchmark.py runs schemathesis' own command line with more seeds and
counts its warnings. The GET operations have no parameters, so few distinct requests exist.
Schema-generated wings are rarely physical (y must start at 0 and increase), so the solver's
fuzzing wings (tests/strategies.py), within the API's limits, are also sent as bodies, on a
VM-only server: each must get a 200 or a 422 saying the solver found no answer, never
invalid-input.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Iterator
from typing import Any

import httpx
import numpy as np
import pytest
import schemathesis
from hypothesis import assume, given, seed, settings
from hypothesis import strategies as st
from schemathesis import GenerationMode
from schemathesis.checks import not_a_server_error
from schemathesis.specs.openapi.checks import (
    content_type_conformance,
    negative_data_rejection,
    response_schema_conformance,
    status_code_conformance,
)

import solver
from solver import ISA_SEA_LEVEL_DENSITY, Wing
from tests.app.conftest import Server
from tests.conftest import fuzz_examples
from tests.strategies import alphas, densities, ratios, speed_for, wings

CASES_PER_BODY_OPERATION = 1000
SEEDS = (0, 20261201)
# [s] past the synchronous wait (FLEXWING_SYNC_WAIT, 10 s), so that every case ends in the
# service's own answer (a result, a problem, or 202 with the job it became), however loaded the
# machine.
REQUEST_TIMEOUT = 60.0

calls: Counter[str] = Counter()
statuses: Counter[str] = Counter()


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
def api_schema(make_server: Any) -> schemathesis.BaseSchema:
    fuzzed = make_server("fuzz_server")
    return schemathesis.openapi.from_url(fuzzed.base_url + "/openapi.json", timeout=30)


# (schemathesis' own pytest integration, `schema.parametrize()`, fails under pytest 9 with
# "'Function' object has no attribute '_nodeid'"; its Hypothesis strategies work everywhere.)
OPERATIONS = [
    ("POST", "/solve"),
    ("POST", "/sweep"),
    # Design (issue 12): fewer cases; a generated request that is a physical wing runs an
    # optimisation.
    ("POST", "/optimize"),
    # Flutter: as few cases as a design; a physical wing with a mass model runs an analysis.
    ("POST", "/flutter"),
    # Controls: as few cases as a design; a physical wing with control surfaces rolls or
    # sweeps its effectiveness.
    ("POST", "/roll"),
    ("POST", "/controls"),
    # A wing's stations: validation and the solver's expansion only, no solve.
    ("POST", "/wing/stations"),
    ("GET", "/healthz"),
    ("GET", "/readyz"),
    # Jobs (issue 13): fewer cases; ids the fuzzer makes up are never a job's (404).
    ("POST", "/jobs"),
    ("GET", "/jobs"),
    ("GET", "/jobs/{job_id}"),
    ("DELETE", "/jobs/{job_id}"),
    ("GET", "/jobs/{job_id}/events"),
    ("GET", "/jobs/{job_id}/items.ndjson"),
]
POSITIVE, NEGATIVE = GenerationMode.POSITIVE, GenerationMode.NEGATIVE
# Parameterless GET operations have no invalid request to generate.
RUNS = [(m, p, POSITIVE, s) for m, p in OPERATIONS for s in SEEDS] + [
    ("POST", p, NEGATIVE, s)
    for p in (
        *("/solve", "/sweep", "/optimize", "/flutter", "/roll", "/controls", "/jobs"),
        "/wing/stations",
    )
    for s in SEEDS
]
# Per seed and mode.
CASES_PER_JOB_OPERATION = {"POST /jobs": 50, "GET /jobs": 15}
CASES_PER_DESIGN_OPERATION = 50


def test_the_document_lists_exactly_these_operations(api_schema: schemathesis.BaseSchema) -> None:
    listed = {(op.method.upper(), op.path) for op in _operations(api_schema)}
    assert listed == set(OPERATIONS)


def _operations(api_schema: schemathesis.BaseSchema) -> list[Any]:
    return [result.ok() for result in api_schema.get_all_operations()]


def _examples(method: str, path: str) -> int:
    """Per seed and mode; parameterless GET operations have a handful of distinct requests."""
    if path.startswith("/jobs"):
        return fuzz_examples(CASES_PER_JOB_OPERATION.get(f"{method} {path}", 5))
    if path in ("/optimize", "/flutter", "/roll", "/controls", "/wing/stations"):
        return fuzz_examples(CASES_PER_DESIGN_OPERATION)
    return fuzz_examples(CASES_PER_BODY_OPERATION // 4 if method == "POST" else 5)


@pytest.mark.parametrize(
    ("method", "path", "mode", "seed_value"),
    RUNS,
    ids=[f"{m} {p} {g} seed{s}" for m, p, g, s in RUNS],
)
def test_every_response_conforms_and_every_4xx_is_a_problem(
    api_schema: schemathesis.BaseSchema,
    method: str,
    path: str,
    mode: GenerationMode,
    seed_value: int,
) -> None:
    operation = api_schema[path][method]

    @seed(seed_value)
    @settings(max_examples=_examples(method, path), derandomize=False)
    @given(case=operation.as_strategy(generation_mode=mode))
    def fuzz(case: schemathesis.Case) -> None:
        calls[f"{method} {path}"] += 1
        response = case.call_and_validate(checks=CHECKS, timeout=REQUEST_TIMEOUT)
        statuses[f"{method} {path} {mode} -> {response.status_code}"] += 1

    fuzz()


# ------------------------------------------------- physically valid wings through the API


@pytest.fixture(scope="module")
def vm_server(make_server: Any) -> Server:
    """Random mesh sizes would start a C compilation per N in the workers: CasADi's VM only."""
    return make_server("vm_server", FLEXWING_COMPILE="0")


@pytest.fixture(scope="module")
def _no_compilation_here() -> Iterator[None]:
    """`speed_for` builds the model of each N in this process too."""
    with pytest.MonkeyPatch.context() as patch:
        patch.setenv("FLEXWING_COMPILE", "0")
        yield


SOLVER_FAILURES = {"/problems/no-equilibrium", "/problems/not-converged"}


def _within_limits(wing: Wing, velocity: float) -> bool:
    """The inputs' own limits (solver.fields), which the API publishes: the strategies keep
    to them, so every generated case is one a client may send."""
    stiffness = solver.spec_of(solver.Wing, "bending_stiffness").limits
    speed = solver.spec_of(solver.FlightCondition, "velocity").limits
    arrays = (wing.bending_stiffness, wing.torsional_stiffness)
    return bool(speed.contains(np.asarray(velocity))) and all(
        bool(np.all(stiffness.contains(a))) for a in arrays
    )


def _physical_checks(response: Any) -> None:
    """A valid wing is never invalid input: 200, or 422 saying the solver found no answer."""
    if response.status_code == 422:
        assert response.json()["type"] in SOLVER_FAILURES, response.text
    else:
        assert response.status_code == 200, response.text


@pytest.mark.usefixtures("_no_compilation_here")
@settings(max_examples=fuzz_examples(40))
@given(case=wings(), alpha=alphas, ratio=ratios, density=densities)
def test_a_physically_valid_wing_gets_an_equilibrium_or_a_solver_problem(
    api_schema: schemathesis.BaseSchema, vm_server: Server, case, alpha, ratio, density
) -> None:
    velocity = speed_for(case.wing, ratio, density)
    assume(_within_limits(case.wing, velocity))
    body = {
        "wing": case.json(),
        "flight": {"velocity": velocity, "alpha": alpha, "density": density},
    }
    request = api_schema["/solve"]["POST"].Case(body=body)
    response = request.call_and_validate(
        base_url=vm_server.base_url, checks=CHECKS, timeout=REQUEST_TIMEOUT
    )
    calls["POST /solve (physical)"] += 1
    _physical_checks(response)


@pytest.mark.usefixtures("_no_compilation_here")
@settings(max_examples=fuzz_examples(10))
@given(
    case=wings(max_stations=30),
    alpha=alphas,
    speeds=st.lists(ratios, min_size=1, max_size=6),
)
def test_a_physically_valid_sweep_answers_every_point(
    api_schema: schemathesis.BaseSchema, vm_server: Server, case, alpha, speeds
) -> None:
    density = ISA_SEA_LEVEL_DENSITY
    velocities = [speed_for(case.wing, ratio, density) for ratio in speeds]
    assume(all(_within_limits(case.wing, velocity) for velocity in velocities))
    body = {"wing": case.json(), "flight": {"alpha": alpha}, "velocities": velocities}
    request = api_schema["/sweep"]["POST"].Case(body=body)
    response = request.call_and_validate(
        base_url=vm_server.base_url, checks=CHECKS, timeout=REQUEST_TIMEOUT
    )
    calls["POST /sweep (physical)"] += 1
    assert response.status_code == 200, response.text
    points = response.json()["points"]
    assert [p["velocity"] for p in points] == velocities
    for point in points:
        assert (point["equilibrium"] is None) == (point["status"] != "equilibrium"), point


def test_enough_cases_were_generated() -> None:
    if not calls:
        pytest.skip("the fuzzing test did not run in this session (deselected)")
    for label in ("POST /solve", "POST /sweep"):
        assert calls[label] >= fuzz_examples(CASES_PER_BODY_OPERATION), dict(calls)
    assert sum(calls.values()) >= 2 * fuzz_examples(CASES_PER_BODY_OPERATION), dict(calls)
    print("\nschema fuzzing, responses:", dict(sorted(statuses.items())))


# ------------------------------------------------------------------ cases found by fuzzing


@pytest.mark.parametrize("path", ["/solve", "/sweep"])
def test_a_body_that_is_not_utf8_is_invalid_input(
    api_schema: schemathesis.BaseSchema, server: Server, path: str
) -> None:
    """Found by this fuzzing before commit ccb0876: the single byte 0xff as a body got 400
    /problems/http-error, a status the document does not list for /solve and /sweep."""
    response = httpx.post(
        server.base_url + path,
        content=b"\xff",
        headers={"content-type": "application/json"},
        timeout=REQUEST_TIMEOUT,
    )
    assert response.status_code == 422
    assert response.headers["content-type"] == "application/problem+json"
    assert response.json()["type"] == "/problems/invalid-input"
    assert "422" in api_schema[path]["POST"].responses.status_codes
