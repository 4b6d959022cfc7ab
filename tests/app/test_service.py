"""One request, one answer: the same numbers however, and after whatever, it is served.

- Result cache: a repeated request is answered from the cache with bit-identical numbers (every
  float of the JSON body equal, which for JSON's round-trip float repr means the same double),
  for /solve, /sweep and a cached no-equilibrium problem alike.
- History: with no result cache at all, a request answered first and the same request answered
  after any other requests for that wing (other speeds, sweeps, guesses) get bit-identical
  bodies: the service keeps no solver state between requests, and the solver's answer is a
  function of the request (its caches hold only what recomputes to the same bits).
- Different paths to one equilibrium (a sweep point and the /solve of the same speed) agree to
  TWO_PATHS relative, field by field (max |a - b| / max |b|): Newton stops at a residual of
  1e-10, and the conditioning near the fold multiplies it by up to ~1e2.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Iterator
from typing import Any

import httpx
import numpy as np
import pytest

from tests import study
from tests.app.conftest import Server

TWO_PATHS = 1e-8
STATION_FIELDS = ("heave", "slope", "twist", "shear", "bending_moment", "torque")
PANEL_FIELDS = ("y", "lift", "lift_per_span", "torque")
TOTALS = ("lift", "induced_drag", "CL", "rigid_lift", "tip_heave", "tip_twist", "root_torque")
SPEEDS = [6.0, 12.0, 18.0, 21.0]  # the study's wing folds at 21.44 m/s

_unique = itertools.count(1)


def fresh_wing(kind: str = "study") -> dict[str, Any]:
    """A wing no request has used yet (stiffness changed in the 13th digit): its solves start
    cold. 'study' is the design study's wing, 'tapered' a linear taper with the elastic axis
    ahead of the quarter chord (it washes out and never diverges)."""
    scale = 1.0 + 1e-12 * next(_unique)
    if kind == "study":
        return study.wing_json(stiffness_scale=scale)
    n = 17
    chord = 1.0 - 0.6 * np.linspace(0, 1, n)
    return {
        "y": np.linspace(0, 6, n).tolist(),
        "chord": chord.tolist(),
        "elastic_axis": 0.15,
        "bending_stiffness": (2.5e4 * chord**2 * scale).tolist(),
        "torsional_stiffness": (1.5e3 * chord * scale).tolist(),
    }


def solve_body(wing: dict[str, Any], velocity: float, **extra: Any) -> dict[str, Any]:
    return {"wing": wing, "flight": {"velocity": velocity, "alpha": 5.0}} | extra


def post(client: httpx.Client, path: str, body: dict[str, Any]) -> dict[str, Any]:
    response = client.post(path, json=body)
    assert response.status_code == 200, response.text
    result: dict[str, Any] = response.json()
    return result


def relative_differences(warm: dict[str, Any], cold: dict[str, Any]) -> dict[str, float]:
    def rel(a: Any, b: Any) -> float:
        a, b = np.atleast_1d(np.asarray(a, float)), np.atleast_1d(np.asarray(b, float))
        scale = np.max(np.abs(b))
        return float(np.max(np.abs(a - b)) / scale) if scale > 0 else float(np.max(np.abs(a)))

    diffs = {f"stations.{k}": rel(warm["stations"][k], cold["stations"][k]) for k in STATION_FIELDS}
    diffs |= {f"panels.{k}": rel(warm["panels"][k], cold["panels"][k]) for k in PANEL_FIELDS}
    diffs |= {f"totals.{k}": rel(warm["totals"][k], cold["totals"][k]) for k in TOTALS}
    return diffs


def assert_same_equilibrium(warm: dict[str, Any], cold: dict[str, Any]) -> None:
    diffs = relative_differences(warm, cold)
    worst = max(diffs, key=diffs.__getitem__)
    assert diffs[worst] <= TWO_PATHS, (worst, diffs[worst])
    assert warm["stability"]["stable"] == cold["stability"]["stable"]


def without_timing(body: Any) -> Any:
    """The body without the fields that legitimately differ on a cache hit."""
    if isinstance(body, dict):
        return {k: without_timing(v) for k, v in body.items() if k not in ("seconds", "cached")}
    if isinstance(body, list):
        return [without_timing(v) for v in body]
    return body


def floats(body: Any) -> Iterator[float]:
    if isinstance(body, dict):
        for value in body.values():
            yield from floats(value)
    elif isinstance(body, list):
        for value in body:
            yield from floats(value)
    elif isinstance(body, float):
        yield body


# ---------------------------------------------------------------------------- result cache


@pytest.mark.parametrize(
    ("path", "make_body"),
    [
        ("/solve", lambda: solve_body(fresh_wing(), 14.0)),
        ("/solve", lambda: solve_body(fresh_wing(), 14.0, options={"find_fold": True})),
        ("/sweep", lambda: {"wing": fresh_wing(), "flight": {"alpha": 5.0}, "velocities": SPEEDS}),
    ],
    ids=["solve", "solve_with_fold", "sweep"],
)
def test_a_cached_answer_is_bit_identical(
    client: httpx.Client, path: str, make_body: Callable[[], dict[str, Any]]
) -> None:
    body = make_body()
    first = post(client, path, body)
    again = post(client, path, body)
    assert first["solver"]["cached"] is False
    assert again["solver"]["cached"] is True
    assert without_timing(again) == without_timing(first)
    pairs = list(zip(floats(without_timing(again)), floats(without_timing(first)), strict=True))
    assert pairs and all(math.copysign(1, a) == math.copysign(1, b) for a, b in pairs)


def test_a_cached_no_equilibrium_problem_is_identical(client: httpx.Client) -> None:
    body = solve_body(fresh_wing(), 23.0)
    first, again = client.post("/solve", json=body), client.post("/solve", json=body)
    assert first.status_code == again.status_code == 422
    assert first.json()["type"] == "/problems/no-equilibrium"
    assert again.json() == first.json()


# ------------------------------------------------------------------------------- history


@pytest.fixture(scope="module")
def uncached_server(make_server: Callable[..., Server]) -> Server:
    """No result cache: every request is solved."""
    return make_server("uncached_server", FLEXWING_RESULT_CACHE_BYTES="0")


HISTORIES: dict[str, list[tuple[str, Callable[[dict[str, Any]], dict[str, Any]]]]] = {
    "slower_first": [("/solve", lambda w: solve_body(w, 6.0))],
    "faster_first": [("/solve", lambda w: solve_body(w, 21.0))],
    "beyond_the_fold_first": [("/solve", lambda w: solve_body(w, 23.0))],
    "sweep_first": [
        ("/sweep", lambda w: {"wing": w, "flight": {"alpha": 5.0}, "velocities": SPEEDS})
    ],
    "many": [("/solve", lambda w, v=v: solve_body(w, v)) for v in (20.0, 7.0, 19.5, 12.5, 30.0)]
    + [("/solve", lambda w: solve_body(w, 12.0, options={"find_fold": True}))],
}


def _answer(client: httpx.Client, path: str, body: dict[str, Any]) -> Any:
    response = client.post(path, json=body)
    return response.status_code, without_timing(response.json())


@pytest.mark.parametrize("history", list(HISTORIES))
@pytest.mark.parametrize("kind", ["study", "tapered"])
def test_a_request_gets_the_same_bits_after_any_other_requests(
    uncached_server: Server, history: str, kind: str
) -> None:
    """The first request for a wing, and the same request after others for that wing (in either
    worker process: the pool has two)."""
    wing = fresh_wing(kind)
    request = solve_body(wing, 14.0)
    with uncached_server.client() as client:
        alone = _answer(client, "/solve", request)
        for path, make in HISTORIES[history]:
            client.post(path, json=make(wing))
        later = _answer(client, "/solve", request)
    assert alone[0] == later[0] == 200
    assert later[1] == alone[1]


BISTABLE_FLIGHT = {"alpha": 0.5, "density": 1.038}


@pytest.mark.parametrize("order", ["target_first", "neighbour_first"])
def test_the_bistable_wing_gets_the_jig_branchs_answer_in_either_order(
    uncached_server: Server, order: str
) -> None:
    """Found by fuzzing: this wing has two stable equilibria at 1 m/s (+69.93 deg tip twist on
    the branch from the jig, -70.48 deg on another). After a request at 0.8 m/s the service's old
    warm start answered -70.48 deg."""
    wing = study.bistable_wing_json()
    target = {"wing": wing, "flight": BISTABLE_FLIGHT | {"velocity": 1.0}}
    neighbour = {"wing": wing, "flight": BISTABLE_FLIGHT | {"velocity": 0.8}}
    with uncached_server.client() as client:
        sequence = [target, neighbour] if order == "target_first" else [neighbour, target]
        answers = [_answer(client, "/solve", body) for body in sequence]
    answer = answers[0] if order == "target_first" else answers[1]
    assert answer[0] == 200
    assert answer[1]["totals"]["tip_twist"] == pytest.approx(69.933, abs=1e-3)
    assert answer[1]["stability"]["branch"] == "jig"


@pytest.mark.parametrize("order", ["absurd_first", "neighbour_first"])
def test_an_absurd_airspeed_is_invalid_input_in_either_order(
    uncached_server: Server, order: str
) -> None:
    """Found by fuzzing (solver-level tests in tests/solver/test_solve.py): 1.08e9 m/s is far
    past what an incompressible lattice can mean; the API's limit on flight.velocity says so."""
    wing = {"y": np.linspace(0, 1, 8).tolist(), "chord": 1.0, "elastic_axis": 0.25,
            "bending_stiffness": 10.0, "torsional_stiffness": 1.0}  # fmt: skip
    absurd = {"wing": wing, "flight": {"velocity": 1081208826.6422322, "alpha": 1.0}}
    neighbour = {"wing": wing, "flight": {"velocity": 300.0, "alpha": 1.0}}
    with uncached_server.client() as client:
        sequence = [absurd, neighbour] if order == "absurd_first" else [neighbour, absurd]
        answers = [client.post("/solve", json=body) for body in sequence]
    response = answers[0] if order == "absurd_first" else answers[1]
    assert response.status_code == 422
    problem = response.json()
    assert problem["type"] == "/problems/invalid-input"
    assert [e["field"] for e in problem["errors"]] == ["flight.velocity"]


# ------------------------------------------------------------------------ other paths


@pytest.mark.parametrize("start", [6.0, 18.0], ids=["from_6mps", "from_18mps"])
def test_a_clients_initial_guess_on_the_jig_branch_gets_the_cold_answer(
    uncached_server: Server, start: float
) -> None:
    wing = fresh_wing()
    with uncached_server.client() as client:
        cold = post(client, "/solve", solve_body(wing, 12.0))
        earlier = post(client, "/solve", solve_body(wing, start))
        guess = {k: earlier["stations"][k] for k in ("heave", "slope", "twist")}
        guessed = post(client, "/solve", solve_body(wing, 12.0, initial_guess=guess))
    assert guessed["stability"]["branch"] == "jig"
    assert without_timing(guessed) == without_timing(cold)


def test_a_sweep_point_agrees_with_the_solve_of_its_speed(client: httpx.Client) -> None:
    wing = fresh_wing()
    swept = post(client, "/sweep", {"wing": wing, "flight": {"alpha": 5.0}, "velocities": SPEEDS})
    for point in swept["points"]:
        alone = post(client, "/solve", solve_body(wing, point["velocity"]))
        assert_same_equilibrium(point["equilibrium"], alone)
