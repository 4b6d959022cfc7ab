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

Counts: every operation the document lists gets the same number of generated requests
(`CASES_PER_OPERATION` per seed and mode; asserted by `test_enough_cases_were_generated`),
positive and negative for those that take parameters or a body, with two seeds (`SEEDS`); the
operations are read from the document, so a new one is fuzzed without an edit. Sequences along
the document's links (an accepted job: its state, cancellation, events and items) run as
schemathesis' state machine. HYPOTHESIS_PROFILE=nightly multiplies the counts by 20
(tests/conftest.py), and benchmarks/fuzz_benchmark.py runs schemathesis' own command line with
more seeds and counts its warnings.
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
from app.main import app as service
from solver import ISA_SEA_LEVEL_DENSITY, Wing
from tests.app.conftest import Server
from tests.conftest import fuzz_examples
from tests.strategies import alphas, densities, ratios, speed_for, wings

# Per operation, seed and mode (two seeds, two modes: four times this per operation that takes
# input): 120 requests for each operation the document lists that takes input, in the ~1 minute
# of one CI process this file can take (HYPOTHESIS_PROFILE=nightly: 20 times as many).
CASES_PER_OPERATION = 30
STATEFUL_SEQUENCES = 25
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


def no_server_error_but_shedding(ctx: Any, response: Any, case: Any) -> None:
    """No 5xx, but the one the document calls load shedding: POST /jobs answers 503
    `/problems/overloaded` when FLEXWING_MAX_QUEUED_JOBS jobs already wait (a fuzzer that
    submits jobs faster than two workers run them fills the queue)."""
    shedding = (
        case.method.upper() == "POST"
        and case.path == "/jobs"
        and response.status_code == 503
        and response.json().get("type") == "/problems/overloaded"
    )
    if not shedding:
        not_a_server_error(ctx, response, case)


CHECKS = [
    no_server_error_but_shedding,
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

# Every operation the document lists (read in this process at collection: the same document the
# server serves), each with the same number of generated requests per seed and mode: a new
# operation is fuzzed without an edit here. Operations without parameters or a body have no
# invalid request to generate, and few distinct valid ones (Hypothesis stops when it has them).
DOCUMENT = service.openapi()
OPERATIONS = [
    (method.upper(), path, bool(item.get("parameters") or item.get("requestBody")))
    for path, methods in DOCUMENT["paths"].items()
    for method, item in methods.items()
]
POSITIVE, NEGATIVE = GenerationMode.POSITIVE, GenerationMode.NEGATIVE
RUNS = [
    (method, path, mode, seed_value)
    for method, path, has_input in OPERATIONS
    for mode in ((POSITIVE, NEGATIVE) if has_input else (POSITIVE,))
    for seed_value in SEEDS
]


def test_every_operation_of_the_served_document_is_fuzzed(
    api_schema: schemathesis.BaseSchema,
) -> None:
    listed = {(op.method.upper(), op.path) for op in _operations(api_schema)}
    assert listed == {(method, path) for method, path, _ in OPERATIONS}


def _operations(api_schema: schemathesis.BaseSchema) -> list[Any]:
    return [result.ok() for result in api_schema.get_all_operations()]


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
    @settings(max_examples=fuzz_examples(CASES_PER_OPERATION), derandomize=False)
    @given(case=operation.as_strategy(generation_mode=mode))
    def fuzz(case: schemathesis.Case) -> None:
        calls[f"{method} {path}"] += 1
        response = case.call_and_validate(checks=CHECKS, timeout=REQUEST_TIMEOUT)
        statuses[f"{method} {path} {mode} -> {response.status_code}"] += 1

    fuzz()


def test_sequences_along_the_documents_links_conform(api_schema: schemathesis.BaseSchema) -> None:
    """Stateful: an accepted job's links (its state, cancellation, events, items) followed
    from the 202 of every operation that can answer with one, in generated sequences."""
    machine = api_schema.as_state_machine()

    class Checked(machine):  # type: ignore[misc,valid-type]
        def get_call_kwargs(self, case: schemathesis.Case) -> dict[str, Any]:
            return {"timeout": REQUEST_TIMEOUT}

        def validate_response(
            self, response: Any, case: schemathesis.Case, *args: Any, **kwargs: Any
        ) -> None:
            calls["stateful"] += 1
            statuses[f"{case.method} {case.path} (stateful) -> {response.status_code}"] += 1
            case.validate_response(response, checks=CHECKS)

    Checked.run(
        settings=settings(
            max_examples=fuzz_examples(STATEFUL_SEQUENCES),
            stateful_step_count=4,
            deadline=None,
            derandomize=True,
        )
    )


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
    """Every operation that takes input got its full count (those without input have only a
    handful of distinct requests), and the stateful sequences ran."""
    if not calls:
        pytest.skip("the fuzzing test did not run in this session (deselected)")
    for method, path, has_input in OPERATIONS:
        if has_input:
            expected = 2 * len(SEEDS) * fuzz_examples(CASES_PER_OPERATION)
            assert calls[f"{method} {path}"] >= expected, dict(calls)
    assert calls["stateful"] >= fuzz_examples(STATEFUL_SEQUENCES), dict(calls)
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
