"""POST /flutter: the Goland wing's flutter through HTTP as the solver computes it, a wing
without mass refused naming `wing.mass`, and the analysis as a job counting its airspeeds."""

from __future__ import annotations

import time
from typing import Any

import httpx
import pytest

from app.schemas.examples import GOLAND_FLUTTER, GOLAND_WING

# Goland 1945 (J. Appl. Mech. 12, A197), strip theory at sea level: ~137 m/s and ~70 rad/s; the
# solver's tests hold this mesh to the exact continuous answer (136.98 m/s) within 1e-4.
GOLAND_SPEED, GOLAND_FREQUENCY = 137.0, 70.7


def test_the_goland_wing_flutters_where_goland_found(client: httpx.Client) -> None:
    response = client.post("/flutter", json=GOLAND_FLUTTER)
    assert response.status_code == 200, response.text
    body = response.json()
    assert body["status"] == "flutter" and body["about"] == "alpha"
    assert body["flutter"]["velocity"] == pytest.approx(GOLAND_SPEED, rel=0.03)
    assert body["flutter"]["frequency"] == pytest.approx(GOLAND_FREQUENCY, rel=0.05)
    assert len(body["points"]) == 50 and len(body["modes"]) == 6
    # The fundamental's vacuum frequency: bending, 48.15 rad/s exact (the solver's tests).
    assert body["modes"][0]["frequency"] == pytest.approx(48.15, rel=0.01)
    again = client.post("/flutter", json=GOLAND_FLUTTER).json()
    assert again["solver"]["cached"] is True and again["flutter"] == body["flutter"]


def test_a_wing_without_mass_is_refused_naming_it(in_process: httpx.Client) -> None:
    body = GOLAND_FLUTTER | {"wing": {k: v for k, v in GOLAND_WING.items() if k != "mass"}}
    response = in_process.post("/flutter", json=body)
    assert response.status_code == 422
    assert [e["field"] for e in response.json()["errors"]] == ["wing.mass"]


@pytest.mark.parametrize(
    ("change", "field"),
    [
        ({"mass_per_length": -1.0}, "wing.mass.mass_per_length"),
        ({"center_of_gravity": 1.5}, "wing.mass.center_of_gravity"),
        ({"concentrated": [{"station": 40, "mass": 5.0, "inertia": 0.0, "offset": 0.0}]}, None),
    ],
    ids=["negative-mass", "cg-off-the-section", "store-past-the-tip"],
)
def test_a_mass_model_that_means_nothing_is_refused(
    in_process: httpx.Client, change: dict[str, Any], field: str | None
) -> None:
    wing = GOLAND_WING | {"mass": GOLAND_WING["mass"] | change}
    response = in_process.post("/flutter", json=GOLAND_FLUTTER | {"wing": wing})
    assert response.status_code == 422
    fields = [e["field"] for e in response.json()["errors"]]
    assert fields == [field or "wing.mass.concentrated[0].station"]


def test_a_flutter_job_counts_its_airspeeds(client: httpx.Client) -> None:
    request = GOLAND_FLUTTER | {"velocities": [60.0, 100.0, 140.0, 180.0]}
    accepted = client.post("/jobs", json={"operation": "flutter", "request": request})
    assert accepted.status_code == 202
    location = accepted.headers["location"]
    deadline = time.monotonic() + 120
    while (job := client.get(location).json())["status"] in ("queued", "running"):
        assert time.monotonic() < deadline
        time.sleep(0.05)
    assert job["status"] == "succeeded" and job["progress"]["total"] == 4
    assert job["result"]["flutter"]["velocity"] == pytest.approx(GOLAND_SPEED, rel=0.03)
