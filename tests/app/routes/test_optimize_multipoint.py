"""POST /optimize with load cases (a multipoint design) through the service: the documented
example answered as Python answers it, each case's equilibrium and each constraint's case; the
refusals naming the field (a case at a given alpha, more cases than FLEXWING_MAX_LOAD_CASES);
an infeasible case named in the problem; the published schema saying what is accepted."""

from __future__ import annotations

import copy
from typing import Any

import httpx
import pytest

import solver
from app.problems import problem_of
from app.schemas import OPTIMIZE_EXAMPLES, REQUESTS
from app.settings import Settings
from tests.app.conftest import in_process_client


def _request(**changes: Any) -> dict[str, Any]:
    return copy.deepcopy(OPTIMIZE_EXAMPLES["multipoint"]["value"]) | changes


def test_the_multipoint_example_is_designed_like_python(client: httpx.Client):
    response = client.post("/optimize", json=_request())
    assert response.status_code == 200, response.text
    body = response.json()
    task = REQUESTS["optimize"].model_validate(_request()).to_solver()
    ours = solver.optimize(task.wing, task.problem)
    # The same problem, the same computation: the mass to what IPOPT's stop holds (1e-8).
    assert body["spar_mass"] == pytest.approx(ours.spar_mass, rel=1e-8)
    cases = {case["name"]: case for case in body["cases"]}
    assert list(cases) == ["flight", "pull-up"]
    allowable = 30e6
    for name, lift in (("flight", 300.0), ("pull-up", 750.0)):
        totals = cases[name]["equilibrium"]["totals"]
        assert totals["lift"] == pytest.approx(lift, rel=1e-8)
        assert cases[name]["max_von_mises_stress"] <= allowable * (1 + 1e-8)
    assert cases["pull-up"]["alpha"] > cases["flight"]["alpha"] == 0.0
    stresses = [c for c in body["constraints"] if c["name"] == "von_mises"]
    assert {c["case"] for c in stresses} == {"flight", "pull-up"}
    assert any(c["active"] for c in stresses if c["case"] == "pull-up")


def test_a_case_the_wing_cannot_fly_is_an_infeasible_design_naming_the_case(
    client: httpx.Client,
):
    too_much = {"name": "too-much", "flight": {"velocity": 6.0, "weight": 300.0, "load_factor": 10}}
    response = client.post("/optimize", json=_request(load_cases=[too_much]))
    assert response.status_code == 422, response.text
    problem = response.json()
    assert problem["type"].endswith("/infeasible-design")
    assert problem["case"] == "too-much" and problem["constraint"] == "lift"


@pytest.mark.parametrize(
    ("case", "field"),
    [
        ({"name": "pull-up", "flight": {"velocity": 14.0, "alpha": 5.0}}, "load_cases[0].flight"),
        (
            {"name": "flight", "flight": {"velocity": 14.0, "weight": 300.0}},
            "load_cases[0].name",
        ),
        ({"name": "pull-up", "flight": {"weight": 300.0}}, "load_cases[0].flight"),
    ],
    ids=["at-an-alpha", "named-as-the-design-flight", "no-airspeed"],
)
def test_a_load_case_that_cannot_be_posed_is_a_422_naming_the_field(
    in_process: httpx.Client, case: dict[str, Any], field: str
):
    response = in_process.post("/optimize", json=_request(load_cases=[case]))
    assert response.status_code == 422, response.text
    fields = [e["field"] for e in response.json()["errors"]]
    assert any(f.startswith(field) for f in fields), fields


def test_two_cases_of_one_name_are_a_422_naming_the_second(in_process: httpx.Client):
    case = _request()["load_cases"][0]
    response = in_process.post("/optimize", json=_request(load_cases=[case, case]))
    assert response.status_code == 422, response.text
    assert [e["field"] for e in response.json()["errors"]] == ["load_cases[1].name"]


def test_more_cases_than_the_limit_is_refused_naming_it():
    """FLEXWING_MAX_LOAD_CASES bounds the list (checked before any work, in process)."""
    case = _request()["load_cases"][0]
    many = [case | {"name": f"case {i}"} for i in range(13)]
    with in_process_client(Settings(workers=1, max_load_cases=12)) as client:
        refused = client.post("/optimize", json=_request(load_cases=many))
        document = client.get("/openapi.json").json()
    assert refused.status_code == 422
    (error,) = refused.json()["errors"]
    assert error["field"] == "load_cases"
    assert "at most 12" in error["reason"] and "FLEXWING_MAX_LOAD_CASES" in error["reason"]
    schemas = document["components"]["schemas"]
    (request,) = [s for name, s in schemas.items() if name.startswith("OptimizeRequest")]
    assert request["properties"]["load_cases"]["maxItems"] == 12


def test_a_list_of_cases_over_the_stations_limit_is_checked_against_the_cases_limit():
    """11 cases with a stations' limit of 10: past validation, to the pool (not started here:
    503), not refused as 'at most 10 stations'."""
    case = _request()["load_cases"][0]
    eleven = [case | {"name": f"case {i}"} for i in range(11)]
    body = _request(load_cases=eleven)
    body["wing"] |= {"y": {"semispan": 5.0, "stations": 10}, "chord": 1.0}
    with in_process_client(Settings(workers=1, max_stations=10)) as client:
        response = client.post("/optimize", json=body)
    assert response.status_code == 503, response.text


def test_the_published_schema_takes_trimmed_flights_only_for_load_cases(in_process: httpx.Client):
    schemas = in_process.get("/openapi.json").json()["components"]["schemas"]
    flight = schemas["DesignLoadCase"]["properties"]["flight"]
    members = {ref["$ref"].rsplit("/", 1)[-1] for ref in flight["oneOf"]}
    assert members == {"FlightAtLift", "FlightAtWeight"}
    assert "case" in schemas["ProblemDetails"]["properties"]


def test_an_optimizer_stopped_by_its_limit_is_not_converged_not_infeasible():
    error = solver.OptimizerNotConverged(14.0, 500, 1e-3, "IPOPT stopped with its limit")
    problem = problem_of(error)
    assert problem.type.slug == "not-converged" and problem.type.status == 422
    assert problem.extensions["iterations"] == 500
