"""Swept elastic axes, built-in twist, chordwise panels and camber through the API."""

from __future__ import annotations

from typing import Any

import httpx
import pytest

from tests import study
from tests.reference import extended_references


def _swept_cambered(**changes: Any) -> dict[str, Any]:
    return {
        "wing": study.wing_json() | {"sweep": 25.0, "jig_twist": -1.0, "airfoil": "naca2412"},
        "flight": {"velocity": 10.0, "alpha": 5.0},
        "options": {"chordwise_panels": 3},
    } | changes


def test_a_swept_cambered_twisted_wing_is_solved(client: httpx.Client) -> None:
    response = client.post("/solve", json=_swept_cambered())
    assert response.status_code == 200, response.text
    body = response.json()
    assert len(body["panels"]["lift"]) == 29  # per strip, whatever the chordwise panels
    twist, axis_twist = body["stations"]["twist"], body["stations"]["axis_twist"]
    # Aft sweep: bending up washes the streamwise sections out relative to the axis twist.
    assert twist[-1] < axis_twist[-1]
    assert body["totals"]["pitching_moment"] != 0


def test_the_api_answers_like_aerosandbox_on_an_extended_reference(client: httpx.Client) -> None:
    (reference,) = [r for r in extended_references() if r.name == "k4_cambered"]
    equilibrium = reference.equilibrium_at(10)
    wing = reference.wing
    body = {
        "wing": {
            "y": wing.y.tolist(),
            "chord": wing.chord.tolist(),
            "elastic_axis": wing.elastic_axis.tolist(),
            "bending_stiffness": wing.bending_stiffness.tolist(),
            "torsional_stiffness": wing.torsional_stiffness.tolist(),
            "airfoil": {k: list(v) for k, v in reference.data["camber_line"].items()},
        },
        "flight": {"velocity": 10, "alpha": reference.alpha, "density": reference.rho},
        "options": {"chordwise_panels": 4},
    }
    response = client.post("/solve", json=body)
    assert response.status_code == 200, response.text
    totals = response.json()["totals"]
    assert totals["lift"] == pytest.approx(equilibrium["L"], rel=1e-6)
    # The number: AeroSandbox's tip twist +0.19 deg (one panel: +1.76 deg).
    assert totals["tip_twist"] == pytest.approx(0.1918, abs=1e-4)


@pytest.mark.parametrize(
    ("change", "field"),
    [
        pytest.param({"sweep": 60.0}, "wing.sweep", id="sweep-60"),
        pytest.param({"airfoil": "naca44"}, "wing.airfoil", id="not-naca-4-digit"),
        pytest.param({"airfoil": "naca4012"}, "wing.airfoil", id="camber-without-position"),
        pytest.param(
            {"airfoil": {"x": [0.1, 1.0], "camber": [0.0, 0.0]}}, "wing.airfoil", id="x-not-from-0"
        ),
        pytest.param(
            {"airfoil": {"x": [0.0, 1.0], "camber": [0.0, 0.3]}},
            "wing.airfoil.camber[1]",
            id="camber-0.3",
        ),
        pytest.param({"airfoil": ["naca2412"] * 3}, "wing.airfoil", id="wrong-count"),
        pytest.param({"jig_twist": 31.0}, "wing.jig_twist", id="jig-twist-31"),
    ],
)
def test_a_bad_wing_model_input_names_its_field(
    in_process: httpx.Client, change: dict[str, Any], field: str
) -> None:
    body = study.solve_request(10.0)
    body["wing"] |= change
    response = in_process.post("/solve", json=body)
    assert response.status_code == 422, response.text
    fields = [e["field"] for e in response.json()["errors"]]
    assert fields == [field], fields


def test_too_many_chordwise_panels_is_invalid_input(in_process: httpx.Client) -> None:
    body = study.solve_request(10.0, options={"chordwise_panels": 9})
    response = in_process.post("/solve", json=body)
    assert response.status_code == 422
    assert [e["field"] for e in response.json()["errors"]] == ["options.chordwise_panels"]


@pytest.mark.parametrize(
    ("route", "n", "k"),
    [("/solve", 150, 8), ("/solve", 122, 2), ("/sweep", 62, 4)],
    ids=["solve-n150-k8", "solve-n122-k2", "sweep-n62-k4"],
)
def test_a_lattice_past_the_panel_limit_is_invalid_input(
    in_process: httpx.Client, route: str, n: int, k: int
) -> None:
    """(N - 1) k <= 240 by default: a larger lattice's first solve, on the virtual machine
    while its library compiles, would outlast the time budget (N = 150, k = 8 took 20 s)."""
    body = study.solve_request(10.0, options={"chordwise_panels": k})
    body["wing"] = study.wing_json(n=n)
    if route == "/sweep":
        body["velocities"] = [8.0, 10.0]
        body["flight"].pop("velocity")
    response = in_process.post(route, json=body)
    assert response.status_code == 422, response.text
    (error,) = response.json()["errors"]
    assert error["field"] == "options.chordwise_panels"
    assert f"{(n - 1) * k} panels" in error["reason"] and "at most 240" in error["reason"]
