"""POST /roll and POST /controls: the solver's roll response and control effectiveness through
HTTP, unchanged; what the lattice cannot mean refused naming the field; a control sweep as a job
counting its airspeeds.

The live tests use the study's planform on 12 stations and 3 chordwise panels (hinges at the
75 % node): a small mesh whose libraries the server compiles in seconds."""

from __future__ import annotations

import time
from typing import Any

import httpx
import pytest

import solver
from app.schemas.examples import ROLL_EXAMPLES, STUDY_CONTROLS, STUDY_ROLL
from tests import study

SURFACES = [
    {"name": "flap", "start": 0.0, "end": 0.45, "hinge": 0.75, "deflection": 5.0},
    {"name": "aileron", "start": 0.55, "end": 0.95, "hinge": 0.75, "deflection": 5.0,
     "kind": "aileron"},
]  # fmt: skip
OPTIONS = {"chordwise_panels": 3}
WING = study.wing_json(12) | {"control_surfaces": SURFACES}
# Newton stops at a residual of ~1e-10 of its scale: answers computed the same way by the
# compiled library and by CasADi's virtual machine agree far inside this.
SAME = 1e-6


def _solver_wing() -> solver.Wing:
    return solver.Wing.create(**study.study_arrays(12), control_surfaces=SURFACES)


def _roll_request(**extra: Any) -> dict[str, Any]:
    flight = {"velocity": 12.0, "alpha": study.ALPHA, "density": study.DENSITY}
    return {"wing": WING, "flight": flight, "options": OPTIONS} | extra


def test_the_rolling_moment_is_the_solvers(client: httpx.Client) -> None:
    response = client.post("/roll", json=_roll_request())
    assert response.status_code == 200, response.text
    body = response.json()
    expected = solver.roll(
        _solver_wing(),
        study.flight(12.0),
        solver.SolverOptions(chordwise_panels=3),
    )
    assert body["method"] == "linearised"  # alpha 5 deg: about the symmetric equilibrium
    assert body["rolling_moment"] == pytest.approx(expected.rolling_moment, rel=SAME)
    assert body["rigid_rolling_moment"] == pytest.approx(expected.rigid_rolling_moment, rel=SAME)
    # Flexibility takes back part of a trailing-edge surface's rolling moment below reversal.
    assert 0.0 < body["rolling_moment"] < body["rigid_rolling_moment"]
    assert [h["name"] for h in body["hinge_moments"]] == ["flap", "aileron"]
    assert len(body["right"]["heave"]) == len(body["left"]["heave"]) == 12


def test_a_free_roll_has_no_rolling_moment_and_its_helix_angle(client: httpx.Client) -> None:
    response = client.post("/roll", json=_roll_request(free_roll=True))
    assert response.status_code == 200, response.text
    body = response.json()
    rigid_scale = abs(body["rigid_rolling_moment"]) or 1.0
    assert body["free_roll"] is True and body["roll_rate"] > 0.0  # a positive aileron: right up
    assert abs(body["rolling_moment"]) < 1e-8 * max(rigid_scale, 1.0)
    assert body["helix_angle"] == pytest.approx(body["roll_rate"] * study.SPAN / (2 * 12.0))


def test_control_effectiveness_and_reversal_are_the_solvers(client: httpx.Client) -> None:
    velocities = [6.0, 12.0, 18.0]
    request = {
        "wing": WING,
        "flight": {"alpha": 0.0, "density": study.DENSITY},
        "velocities": velocities,
        "options": OPTIONS,
    }
    response = client.post("/controls", json=request)
    assert response.status_code == 200, response.text
    body = response.json()
    expected = solver.control_sweep(
        _solver_wing(), velocities, 0.0, study.DENSITY, solver.SolverOptions(chordwise_panels=3)
    )
    for ours, theirs in zip(body["reversals"], expected.reversals, strict=True):
        assert ours["name"] == theirs.name and ours["first"] == theirs.first
        assert ours["reversal"]["velocity"] == pytest.approx(theirs.reversal.velocity, rel=SAME)
    aileron = body["reversals"][1]
    assert aileron["kind"] == "aileron" and aileron["first"] == "reversal"
    effectiveness = [p["controls"][1]["effectiveness"] for p in body["points"]]
    assert effectiveness == sorted(effectiveness, reverse=True)  # falls as q rises
    assert all(0.0 < e < 1.0 for e in effectiveness)


def test_a_control_sweep_job_counts_its_airspeeds(client: httpx.Client) -> None:
    request = {
        "wing": WING,
        "flight": {"alpha": 0.0, "density": study.DENSITY},
        "velocities": [8.0, 12.0, 16.0, 20.0],
        "options": OPTIONS,
    }
    accepted = client.post("/jobs", json={"operation": "controls", "request": request})
    assert accepted.status_code == 202, accepted.text
    deadline = time.monotonic() + 120
    while (job := client.get(accepted.headers["location"]).json())["status"] in (
        "queued",
        "running",
    ):
        assert time.monotonic() < deadline
        time.sleep(0.05)
    assert job["status"] == "succeeded" and job["progress"]["total"] == 4
    assert len(job["result"]["points"]) == 4


def _without_surfaces(body: dict[str, Any]) -> dict[str, Any]:
    return body | {"wing": {k: v for k, v in body["wing"].items() if k != "control_surfaces"}}


def _with_surfaces(body: dict[str, Any], *surfaces: dict[str, Any]) -> dict[str, Any]:
    return body | {"wing": body["wing"] | {"control_surfaces": list(surfaces)}}


AILERON = STUDY_ROLL["wing"]["control_surfaces"][1]


@pytest.mark.parametrize(
    ("path", "body", "field"),
    [
        ("/roll", _without_surfaces(STUDY_ROLL), "wing.control_surfaces"),
        ("/controls", _without_surfaces(STUDY_CONTROLS), "wing.control_surfaces"),
        ("/roll", STUDY_ROLL | {"free_roll": True, "roll_rate": 0.1}, "roll_rate"),
        ("/roll", STUDY_ROLL | {"roll_rate": 25.0}, "roll_rate"),
        ("/roll", STUDY_ROLL | {"method": "exact"}, "method"),
        (
            "/roll",
            STUDY_ROLL | {"options": {"chordwise_panels": 1}},
            "wing.control_surfaces[0].hinge",
        ),
        (
            "/roll",
            {k: v for k, v in STUDY_ROLL.items() if k != "options"},
            "wing.control_surfaces[0].hinge",
        ),
        (
            "/roll",
            _with_surfaces(STUDY_ROLL, AILERON | {"hinge": 0.0}),
            "wing.control_surfaces[0].hinge",
        ),
        (
            "/roll",
            _with_surfaces(STUDY_ROLL, AILERON | {"deflection": 30.0}),
            "wing.control_surfaces[0].deflection",
        ),
        (
            "/roll",
            _with_surfaces(STUDY_ROLL, AILERON | {"end": 1.2}),
            "wing.control_surfaces[0].end",
        ),
        (
            "/roll",
            _with_surfaces(STUDY_ROLL, AILERON, AILERON | {"name": "other"}),
            "wing.control_surfaces[1]",
        ),
        (
            "/roll",
            STUDY_ROLL | {"flight": {"alpha": 5.0, "density": study.DENSITY}},
            "flight.velocity",
        ),
        ("/controls", STUDY_CONTROLS | {"velocities": []}, "velocities"),
    ],
    ids=[
        "roll-without-surfaces",
        "controls-without-surfaces",
        "free-roll-with-a-rate",
        "roll-rate-past-any-aircraft",
        "unknown-method",
        "hinge-one-panel-cannot-carry",
        "hinge-the-default-panel-cannot-carry",
        "hinge-at-the-leading-edge",
        "deflection-past-linear",
        "surface-past-the-tip",
        "overlapping-surfaces",
        "roll-without-airspeed",
        "no-airspeeds",
    ],
)
def test_what_the_lattice_cannot_mean_is_refused_naming_the_field(
    in_process: httpx.Client, path: str, body: dict[str, Any], field: str
) -> None:
    response = in_process.post(path, json=body)
    assert response.status_code == 422, response.text
    fields = [error["field"] for error in response.json()["errors"]]
    assert any(f == field or f.startswith(field + ".") for f in fields), fields


def test_every_roll_example_is_a_valid_request(in_process: httpx.Client) -> None:
    """Validated to the pool (503 not-ready: no workers in process), never a 422."""
    for example in ROLL_EXAMPLES.values():
        assert in_process.post("/roll", json=example["value"]).status_code == 503
