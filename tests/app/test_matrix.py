"""Every operation meets every option and every wing part: never a 5xx.

The cases are generated from the declarations (tests/app/matrix.py): the operations of
`solver.OPERATION_TABLE`, every modelled option value of each (aerodynamics, chordwise panels,
torque axis, the fold, flutter's and roll's choices, a design's objective...), every optional
part of the wing (spar, mass, control surfaces, camber, sweep, jig twist, ...) and every way of
giving the flight (at an alpha, trimmed to a lift or a weight), all pairs of them, on a small
wing. A new operation, option or wing part enters by its declaration, without an edit here.

Each case runs the service's own path in this process: the request model, the service's checks
and limits (`task_of`), the worker's `run` and the response's serialisation. Each answers 200,
an invalid-input 422 naming a field, or one of the domain answers its row of the table declares
(no equilibrium, not converged, infeasible design); any other exception is the 5xx this test
exists to find (issue 40: the induced-drag objective under strip theory divided by zero).
"""

from __future__ import annotations

import itertools
import json
from collections import Counter

import pytest
from pydantic import ValidationError

import solver
from app.execution import worker
from app.problems import Problem, problem_of
from app.schemas import REQUESTS, RESPONSES
from app.service import task_of
from app.settings import Settings
from tests.app.matrix import Case, _covering, cases

CASES = cases()
TABLE = {op.name: op for op in solver.OPERATION_TABLE}
SETTINGS = Settings()
_OUTCOMES: Counter[str] = Counter()


@pytest.mark.parametrize("case", CASES, ids=[case.id for case in CASES])
def test_every_combination_answers_or_refuses_with_a_type(case: Case) -> None:
    operation = TABLE[case.operation]
    try:
        request = REQUESTS[case.operation].model_validate(case.body)
        task = task_of(request, SETTINGS)
    except ValidationError:
        _OUTCOMES["invalid"] += 1
        return
    except Problem as problem:
        assert problem.type.slug == "invalid-input" and problem.extensions["errors"], problem.detail
        _OUTCOMES["invalid"] += 1
        return
    outcome = worker.run(task)  # an unexpected exception here is the 5xx
    if outcome.error is None:
        assert outcome.answer is not None
        body = json.loads(outcome.answer.body())
        RESPONSES[case.operation].model_validate(body)
        _OUTCOMES["answered"] += 1
        return
    problem = problem_of(outcome.error)
    assert 400 <= problem.type.status < 500
    if isinstance(outcome.error, solver.InvalidInput):
        assert outcome.error.field, "an invalid input names its field"
        _OUTCOMES["invalid"] += 1
    else:
        assert isinstance(outcome.error, operation.answers), (
            f"{case.operation} answered {type(outcome.error).__name__}, which its row of "
            "the table does not declare"
        )
        _OUTCOMES["domain"] += 1


def test_the_matrix_reaches_every_operation_and_mostly_answers() -> None:
    """The matrix is not a wall of refusals: every operation is in it, and most cases get
    past validation to an answer or a domain answer (measured: see the counts)."""
    assert {case.operation for case in CASES} == set(TABLE)
    ran = sum(_OUTCOMES.values())
    if ran < len(CASES):  # the cases ran in another process, or were deselected
        pytest.skip("the matrix's cases did not all run in this process")
    # Measured: 94 of 115 answered, 3 domain answers, 18 refused with a type (invalid input
    # naming the field).
    assert _OUTCOMES["answered"] + _OUTCOMES["domain"] >= 0.7 * ran, dict(_OUTCOMES)


def test_the_covering_array_meets_every_allowed_pair_and_no_forbidden_one() -> None:
    """Four factors of 2, 3, 2, 2 values with value 1 of factor 0 never beside values 0 and 2
    of factor 1 (as a wing's in-plane stiffness is never beside the linear beam): every other
    pair of values meets in some row, and no row forms a forbidden pair."""
    domains = [2, 3, 2, 2]
    forbidden = {((0, 1), (1, 0)), ((0, 1), (1, 2))}
    rows = _covering(domains, 2, forbidden)
    for (i, a), (j, b) in itertools.combinations(
        [(k, v) for k, d in enumerate(domains) for v in range(d)], 2
    ):
        if i == j:
            continue
        met = any(row[i] == a and row[j] == b for row in rows)
        assert met != (((i, a), (j, b)) in forbidden), ((i, a), (j, b))


def test_a_value_that_needs_another_meets_the_rest_beside_it() -> None:
    """The wing's in-plane stiffness is refused under the linear beam (the default structure),
    so it meets the other factors beside the geometrically exact beam, in cases the service
    lets through to a worker for every operation that takes lag (and for none that refuses
    it)."""
    takes_lag = {"solve", "sweep", "flutter", "controls", "roll", "loads"}
    for operation in TABLE:
        beside = [
            case
            for case in CASES
            if case.operation == operation
            and case.body["wing"].get("in_plane_bending_stiffness") is not None
            and (case.body.get("options") or {}).get("structure") == "geometrically_exact"
        ]
        reaching = [case for case in beside if _reaches_a_worker(case)]
        assert bool(reaching) == (operation in takes_lag), operation


def _reaches_a_worker(case: Case) -> bool:
    try:
        task_of(REQUESTS[case.operation].model_validate(case.body), SETTINGS)
    except (ValidationError, Problem):
        return False
    return True
