"""POST /solve against a live server: the study's numbers, caches, warm starts, the fold."""

from __future__ import annotations

import json

import httpx
import numpy as np
import pytest

from tests import study
from tests.app.conftest import ROOT


def _solve(client: httpx.Client, body: dict) -> dict:
    response = client.post("/solve", json=body)
    assert response.status_code == 200, response.text
    return response.json()


def test_study_wing_at_cruise_matches_the_study(client: httpx.Client) -> None:
    result = _solve(client, study.solve_request(10.0))
    totals = result["totals"]
    # The study prints: lift 304.1 N flexible vs 259.4 N rigid (+17.3 %), tip twist +1.71 deg,
    # tip heave 0.050 m; each to its printed precision (half a unit of the last digit).
    assert totals["lift"] == pytest.approx(304.1, abs=0.05)
    assert totals["rigid_lift"] == pytest.approx(259.4, abs=0.05)
    assert totals["lift_amplification"] == pytest.approx(1.173, abs=0.0005)
    assert totals["tip_twist"] == pytest.approx(1.71, abs=0.005)
    assert totals["tip_heave"] == pytest.approx(0.050, abs=0.0005)
    assert result["stability"]["stable"] is True
    # Linear divergence of the study's wing: 359.3 Pa, 24.22 m/s (shared/notes).
    assert result["stability"]["divergence_dynamic_pressure"] == pytest.approx(359.3, abs=0.05)
    assert result["stability"]["divergence_velocity"] == pytest.approx(24.22, abs=0.005)
    assert len(result["stations"]["twist"]) == 30
    assert len(result["panels"]["lift"]) == 29
    # Internal loads are outboard sums of the panel loads: the root shear is the half-wing lift.
    assert result["stations"]["shear"][0] == pytest.approx(sum(result["panels"]["lift"]))


@pytest.mark.skipif(not study.REFERENCE.exists(), reason="shared/reference is not beside the repo")
def test_study_wing_matches_aerosandbox_through_http(client: httpx.Client) -> None:
    """Every field AeroSandbox reports, to 1e-6 relative: the solver agrees with it to ~4e-9
    (IPOPT's stopping tolerance), and JSON carries floats exactly."""
    for velocity, ref in study.reference().items():
        result = _solve(client, study.solve_request(velocity))
        stations = result["stations"]
        for ours, theirs in (
            (stations["heave"], ref["u"]),
            (stations["twist"], ref["theta_deg"]),
            (stations["bending_moment"], ref["M"]),
            (stations["torque"], ref["T"]),
            (result["panels"]["lift"], ref["Fz"]),
        ):
            scale = np.max(np.abs(theirs))
            np.testing.assert_allclose(ours, theirs, rtol=0, atol=1e-6 * scale)
        assert result["totals"]["lift"] == pytest.approx(ref["L"], rel=1e-6)
        assert result["totals"]["CL_deformed_area"] == pytest.approx(ref["CL"], rel=1e-6)


def _examples(path: str) -> dict:
    schema = json.loads((ROOT / "openapi" / "openapi.json").read_text())
    body = schema["paths"][path]["post"]["requestBody"]["content"]["application/json"]
    return {name: example["value"] for name, example in body["examples"].items()}


def test_the_documented_examples_run_as_they_are(client: httpx.Client) -> None:
    """/docs pre-fills these: the study's wing at 10 m/s and 23 m/s, and two sweeps."""
    solve = _examples("/solve")
    # Inputs rounded to 10 digits, density 1.225 instead of 1.2249992: 304.1 N still holds.
    assert _solve(client, solve["study"])["totals"]["lift"] == pytest.approx(304.1, abs=0.05)
    beyond = client.post("/solve", json=solve["beyond_divergence"])
    assert beyond.status_code == 422
    assert beyond.json()["type"] == "/problems/no-equilibrium"
    sweep = _examples("/sweep")
    for name, statuses in (
        ("study", ["equilibrium"] * 6),
        ("to_the_fold", ["equilibrium"] * 4 + ["no_equilibrium"] * 2),
    ):
        response = client.post("/sweep", json=sweep[name])
        assert response.status_code == 200
        assert [p["status"] for p in response.json()["points"]] == statuses


def test_repeated_request_is_answered_from_the_cache(client: httpx.Client) -> None:
    body = study.solve_request(13.25)
    first = _solve(client, body)
    second = _solve(client, body)
    assert first["solver"]["cached"] is False
    assert second["solver"]["cached"] is True
    assert second["totals"] == first["totals"]
    assert second["stations"] == first["stations"]


def test_no_warm_start_can_change_the_answer_past_the_fold(client: httpx.Client) -> None:
    """After a 21 m/s request of the same wing, 22 m/s is still what it always is: no
    equilibrium (the service keeps no solver state between requests)."""
    wing = study.wing_json(stiffness_scale=1 - 3e-11)
    flight = {"alpha": 5.0, "density": study.DENSITY}
    _solve(client, {"wing": wing, "flight": flight | {"velocity": 21.0}})
    response = client.post("/solve", json={"wing": wing, "flight": flight | {"velocity": 22.0}})
    assert response.status_code == 422
    assert response.json()["type"] == "/problems/no-equilibrium"


def test_beyond_the_fold_is_a_no_equilibrium_problem(client: httpx.Client) -> None:
    response = client.post("/solve", json=study.solve_request(23.0))
    assert response.status_code == 422
    assert response.headers["content-type"] == "application/problem+json"
    problem = response.json()
    assert problem["type"] == "/problems/no-equilibrium"
    assert problem["velocity"] == 23.0
    # AeroSandbox converges at 21.43 m/s and finds no solution at 21.45 (shared/notes).
    assert 21.43 < problem["fold_velocity"] < 21.45


def test_fold_on_request(client: httpx.Client) -> None:
    result = _solve(client, study.solve_request(10.0, options={"find_fold": True}))
    assert 21.43 < result["fold"]["velocity"] < 21.45
    # Past the fold's twist the branch turns back: the fold carries more twist than 21 m/s (18.2).
    assert result["fold"]["tip_twist"] > 18.2
    plain = _solve(client, study.solve_request(10.0))
    assert plain["fold"] is None


def test_initial_guess_from_an_earlier_response(client: httpx.Client) -> None:
    """A guess that reaches the jig branch's equilibrium gets the plain answer, bit for bit."""
    earlier = _solve(client, study.solve_request(15.0))
    guess = {k: earlier["stations"][k] for k in ("heave", "slope", "twist")}
    result = _solve(client, study.solve_request(15.0, initial_guess=guess))
    assert result["solver"]["cached"] is False
    assert result["stability"]["branch"] == "jig"
    assert result["totals"] == earlier["totals"]


def test_an_initial_guess_on_another_branch_is_answered_flagged(client: httpx.Client) -> None:
    """rect_public at 20 m/s: beyond its fold the jig's branch has no equilibrium, and a guess
    on the nose-down side reaches AeroSandbox's unstable -520.44 N "equilibrium": returned, as
    the caller asked, and said to be another branch's and unstable."""
    n = 24
    wing = {"y": np.linspace(0, 4, n).tolist(), "chord": 0.8, "elastic_axis": 0.35,
            "bending_stiffness": 5000.0, "torsional_stiffness": 400.0}  # fmt: skip
    flight = {"alpha": 4.0, "density": study.DENSITY}
    ten = _solve(client, {"wing": wing, "flight": flight | {"velocity": 10.0}})
    guess = {
        "heave": [-h for h in ten["stations"]["heave"]],
        "slope": [-s for s in ten["stations"]["slope"]],
        "twist": [-8 * t for t in ten["stations"]["twist"]],
    }
    body = {"wing": wing, "flight": flight | {"velocity": 20.0}, "initial_guess": guess}
    result = _solve(client, body)
    assert result["totals"]["lift"] == pytest.approx(-520.442301323639, rel=1e-6)
    assert result["stability"]["branch"] == "other"
    assert result["stability"]["stable"] is False
    plain = client.post("/solve", json={"wing": wing, "flight": flight | {"velocity": 20.0}})
    assert plain.status_code == 422 and plain.json()["type"] == "/problems/no-equilibrium"


def test_zero_alpha_carries_no_lift(client: httpx.Client) -> None:
    """An uncambered jig at alpha = 0 carries nothing: the amplification L/L_rigid is undefined
    and reported as null, not as NaN (which JSON cannot carry)."""
    result = _solve(client, study.solve_request(10.0, alpha=0.0))
    assert result["totals"]["lift"] == 0.0
    assert result["totals"]["rigid_lift"] == 0.0
    assert result["totals"]["lift_amplification"] is None


def test_evenly_spaced_stations_from_the_semispan(client: httpx.Client) -> None:
    body = study.solve_request(10.0)
    body["wing"]["y"] = {"semispan": 5.0, "stations": 30}
    response = client.post("/solve", json=body)
    assert response.status_code == 200
    assert response.json()["totals"]["lift"] == pytest.approx(304.13, abs=0.01)


def test_a_wing_folded_back_on_itself_is_a_problem_naming_the_station(client: httpx.Client) -> None:
    """Under the geometrically exact beam, the study's wing with 1/500 of its bending stiffness
    curls past vertical at 10 m/s: 422 no-equilibrium naming the station, not a failure; with
    1/200 it answers, its tip above 70 % of the semispan."""
    body = study.solve_request(10.0, options={"structure": "geometrically_exact"})
    wing = body["wing"]
    body["wing"] = wing | {"bending_stiffness": [0.002 * v for v in wing["bending_stiffness"]]}
    response = client.post("/solve", json=body)
    assert response.status_code == 422, response.text
    problem = response.json()
    assert problem["type"] == "/problems/no-equilibrium"
    assert 0 < problem["station"] < 30 and problem["field"] == f"stations[{problem['station']}]"
    assert f"station {problem['station']}" in problem["detail"]
    body["wing"] = wing | {"bending_stiffness": [0.005 * v for v in wing["bending_stiffness"]]}
    answer = _solve(client, body)
    assert answer["stations"]["heave"][-1] > 0.7 * 5.0
    assert answer["stations"]["axis_y"][-1] < 0.8 * 5.0
