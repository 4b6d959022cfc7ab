"""The tube spar through the API: stiffness from the tube, stresses, margin and mass."""

from __future__ import annotations

from typing import Any

import httpx
import pytest

from app.schemas import SOLVE_EXAMPLES
from tests import study

CARBON = {"youngs_modulus": 70e9, "shear_modulus": 27e9, "density": 1600.0, "yield_stress": 600e6}


def _wing(**spar: Any) -> dict[str, Any]:
    wing = {k: v for k, v in study.wing_json().items() if not k.endswith("stiffness")}
    tube = {"outer_diameter": 0.05, "wall_thickness": 0.001, "material": CARBON} | spar
    return wing | {"spar": tube}


def test_the_documented_example_reports_stresses_margin_and_mass(client: httpx.Client):
    response = client.post("/solve", json=SOLVE_EXAMPLES["tube_spar"]["value"])
    assert response.status_code == 200, response.text
    body = response.json()
    stations, totals = body["stations"], body["totals"]
    assert len(stations["von_mises_stress"]) == len(stations["y"])
    assert totals["lift"] == pytest.approx(2.5 * 300.0, rel=1e-9)
    assert totals["max_von_mises_stress"] == max(stations["von_mises_stress"])
    margin = 600e6 / (1.5 * totals["max_von_mises_stress"]) - 1
    assert totals["failure_margin"] == pytest.approx(margin, rel=1e-12)
    assert totals["spar_mass"] > 0
    assert stations["bending_stiffness"][0] > stations["bending_stiffness"][-1]  # tapered tube


def test_a_uniform_tube_echoes_its_stiffness(client: httpx.Client):
    body = {"wing": _wing(), "flight": {"velocity": 10.0, "alpha": 3.0}}
    response = client.post("/solve", json=body)
    assert response.status_code == 200, response.text
    stations = response.json()["stations"]
    inner = 0.048
    ei = 70e9 * 3.141592653589793 / 64 * (0.05**4 - inner**4)
    assert stations["bending_stiffness"] == pytest.approx([ei] * 30, rel=1e-12)
    assert stations["torsional_stiffness"] == pytest.approx([2 * 27e9 / 70e9 * ei] * 30, rel=1e-12)


def test_without_a_spar_the_stresses_are_null(client: httpx.Client):
    response = client.post("/solve", json=study.solve_request(10.0))
    body = response.json()
    assert body["stations"]["von_mises_stress"] is None
    assert body["totals"]["failure_margin"] is None and body["totals"]["spar_mass"] is None


@pytest.mark.parametrize(
    ("wing", "field"),
    [
        pytest.param(_wing() | {"bending_stiffness": 1e4}, "wing.spar", id="spar-and-stiffness"),
        pytest.param(
            _wing(outer_diameter={"fraction_of_thickness": 0.8}),
            "wing.spar.outer_diameter",
            id="fraction-without-airfoil-thickness",
        ),
        pytest.param(_wing(wall_thickness=0.03), "wing.spar.wall_thickness", id="wall-past-centre"),
        pytest.param(
            _wing(material=CARBON | {"yield_stress": 0.0}),
            "wing.spar.material.yield_stress",
            id="no-yield-stress",
        ),
        pytest.param(
            {k: v for k, v in _wing().items() if k != "spar"},
            "wing.bending_stiffness",
            id="neither",
        ),
    ],
)
def test_a_spar_that_cannot_be_built_is_a_422_naming_the_field(
    in_process: httpx.Client, wing, field
):
    response = in_process.post(
        "/solve", json={"wing": wing, "flight": {"velocity": 10.0, "alpha": 3.0}}
    )
    assert response.status_code == 422, response.text
    assert field in [e["field"] for e in response.json()["errors"]], response.text
