"""app.schemas.derive: every solver input field is an API field with the solver's own limits and
default, and every API field is a solver input's; a validated request becomes the solver input
it describes, a refused one named from the request's root."""

from __future__ import annotations

import copy
import dataclasses
from collections.abc import Iterator
from typing import Any

import pytest

import solver
from app.schemas import (
    SOLVE_EXAMPLES,
    FlutterRequest,
    OptimizeRequest,
    SolveRequest,
    SweepRequest,
    derive,
)
from solver import InvalidInput
from tests import study

OPERATIONS = {
    "solve": (solver.SolveInput, SolveRequest),
    "sweep": (solver.SweepInput, SweepRequest),
    "optimize": (solver.OptimizeInput, OptimizeRequest),
    "flutter": (solver.FlutterInput, FlutterRequest),
}
# Forms whose JSON Schema numbers carry the declared limits (on the value or on its items).
NUMERIC = ("number", "integer", "per_station", "positions", "diameter", "deformation")


def _components(model: Any) -> dict[str, Any]:
    schema = model.model_json_schema(ref_template="#/$defs/{model}")
    return {**schema.get("$defs", {}), model.__name__: schema}


def _numbers(node: Any) -> Iterator[dict[str, Any]]:
    """Every schema node of a number (type number or integer), anywhere under `node`."""
    if isinstance(node, dict):
        if node.get("type") in ("number", "integer"):
            yield node
        for child in node.values():
            yield from _numbers(child)
    elif isinstance(node, list):
        for child in node:
            yield from _numbers(child)


def _declared(
    cls: type, without: tuple[str, ...] = (), owner: type | None = None
) -> Iterator[tuple[type, str, Any, Any]]:
    """(class the API shows it in, field, spec, its dataclass field) of every input field
    reachable from `cls`: a flattened field's members are its owner's."""
    owner = owner or cls
    for field in dataclasses.fields(cls):  # type: ignore[arg-type]
        spec = field.metadata.get("input")
        if spec is None or field.name in without:
            continue
        if spec.flatten:
            yield from _declared(spec.given, spec.without, owner)
            continue
        yield owner, field.name, spec, field
        if spec.form == "nested":
            yield from _declared(spec.given, spec.without)


def _api_properties(cls: type, components: dict[str, Any]) -> list[dict[str, Any]]:
    """The JSON Schema properties objects the API has for solver class `cls` (one per way,
    and per set of fields left out)."""
    models = [model for key, model in derive._models.items() if key[0] is cls]
    schemas = [components[m.__name__] for m in models if m.__name__ in components]
    return [schema["properties"] for schema in schemas]


def _limits(spec: solver.Spec) -> dict[str, float]:
    limits = spec.limits
    names = {"ge": "minimum", "le": "maximum", "gt": "exclusiveMinimum", "lt": "exclusiveMaximum"}
    return {
        names[k]: float(v)
        for k, v in dataclasses.asdict(limits).items()
        if k in names and v is not None
    }


@pytest.mark.parametrize("operation", list(OPERATIONS))
def test_every_solver_input_field_is_an_api_field_with_its_limits(operation: str) -> None:
    """What the solver declares is what the API publishes: each field is there, in every way a
    condition is given that uses it, with the solver's limits on every number it holds."""
    cls, model = OPERATIONS[operation]
    components = _components(model)
    for owner, name, spec, field in _declared(cls):
        ways: dict[str, tuple[str, ...]] = getattr(owner, "WAYS", {})
        expected = _limits(spec) if spec.form in NUMERIC else {}
        seen = 0
        for properties in _api_properties(owner, components):
            if name not in properties:
                # Only a way's own fields are absent from the other ways.
                assert any(name in names for names in ways.values()) or name == "velocity", (
                    owner.__name__,
                    name,
                )
                continue
            seen += 1
            numbers = list(_numbers(properties[name]))
            if spec.form == "positions":
                numbers = numbers[:1]  # the list's items; the spacing object is its own class
            for number in numbers:
                for key, value in expected.items():
                    assert number.get(key) == value, (owner.__name__, name, key, number)
            if "default" in properties[name] and spec.form in ("number", "integer", "flag"):
                assert properties[name]["default"] == field.default, (owner.__name__, name)
        assert seen, f"{owner.__name__}.{name} has no API field"


@pytest.mark.parametrize("operation", list(OPERATIONS))
def test_every_api_field_is_a_solver_input_field(operation: str) -> None:
    cls, model = OPERATIONS[operation]
    components = _components(model)
    declared: dict[type, set[str]] = {}
    for owner, name, _, _ in _declared(cls):
        declared.setdefault(owner, set()).add(name)
    for owner, names in declared.items():
        for properties in _api_properties(owner, components):
            assert set(properties) <= names, (owner.__name__, set(properties) - names)


def test_the_published_components_keep_their_names() -> None:
    """Clients generated from the document name their classes after its components."""
    components = set(_components(SolveRequest)) | set(_components(SweepRequest))
    components |= set(_components(OptimizeRequest))
    assert {
        "SolveRequest",
        "SweepRequest",
        "OptimizeRequest",
        "Wing",
        "TubeSpar",
        "SparMaterial",
        "ThicknessFraction",
        "StationSpacing",
        "CamberTable",
        "FlightAtAlpha",
        "FlightAtLift",
        "FlightAtWeight",
        "SweepFlightAtAlpha",
        "SweepFlightAtLift",
        "SweepFlightAtWeight",
        "OptimizeFlightAtLift",
        "OptimizeFlightAtWeight",
        "SolverOptions",
        "ValidityLimits",
        "InitialGuess",
        "VelocityRange",
        "Design",
        "TwistDesign",
        "WallDesign",
        "DesignConstraints",
    } <= components


def test_a_request_becomes_the_solver_input_it_describes() -> None:
    body = study.solve_request(12.0, options={"chordwise_panels": 2})
    body["flight"] = {"velocity": 12.0, "weight": 300.0, "load_factor": 2.0}
    task = SolveRequest.model_validate(body).to_solver()
    assert isinstance(task, solver.SolveInput)
    assert task.flight.required_lift == 600.0 and task.flight.trimmed
    assert task.modelled.chordwise_panels == 2
    assert task.wing.key == study.study_wing().key  # the example's wing is the study's


def _stiffened(factor: float) -> dict[str, Any]:
    body = study.solve_request(12.0)
    body["wing"]["torsional_stiffness"] = [
        factor * gj for gj in body["wing"]["torsional_stiffness"]
    ]
    return body


def test_a_wing_asked_about_again_is_built_once() -> None:
    """A design loop sends one wing with many flight conditions: its solver wing (validated,
    digested) is built once and shared, an equal one by value; another wing is another."""
    first = SolveRequest.model_validate(_stiffened(1.5)).to_solver()
    again = SolveRequest.model_validate(
        _stiffened(1.5) | {"flight": study.solve_request(9.0)["flight"]}
    )
    assert again.to_solver().wing is first.wing
    assert again.to_solver().flight.velocity == 9.0  # only the wing is kept
    other = SolveRequest.model_validate(_stiffened(1.5 * (1 + 1e-12))).to_solver()
    assert other.wing is not first.wing and other.wing.key != first.wing.key


def test_a_wing_given_another_way_is_kept_apart() -> None:
    """Kept by the request's exact JSON: a spar's diameter as a thickness fraction and one in
    metres, a NACA section and a camber table, are other wings."""
    tube = copy.deepcopy(SOLVE_EXAMPLES["tube_spar"]["value"])
    metres = copy.deepcopy(tube)
    metres["wing"]["spar"]["outer_diameter"] = 0.02
    tabled = copy.deepcopy(metres)  # a table has no thickness: the diameter in metres
    tabled["wing"]["airfoil"] = {"x": [0.0, 0.5, 1.0], "camber": [0.0, 0.02, 0.0]}
    wings = [SolveRequest.model_validate(b).to_solver().wing for b in (tube, metres, tabled)]
    assert len({w.key for w in wings}) == 3
    assert SolveRequest.model_validate(copy.deepcopy(tube)).to_solver().wing is wings[0]


def test_only_the_last_wings_are_kept_and_no_invalid_one() -> None:
    kept = SolveRequest.model_fields["wing"].annotation.__kept__
    oldest = SolveRequest.model_validate(_stiffened(2.0)).to_solver().wing
    for i in range(kept):
        SolveRequest.model_validate(_stiffened(2.0 + (i + 1) * 1e-6)).to_solver()
    rebuilt = SolveRequest.model_validate(_stiffened(2.0)).to_solver().wing
    assert rebuilt is not oldest and rebuilt.key == oldest.key  # built again, the same wing
    bad = study.solve_request(12.0)
    bad["wing"]["y"] = [0.0, 2.0, 1.0, *bad["wing"]["y"][3:]]  # the solver's check, not pydantic's
    for _ in range(2):  # refused each time, never remembered as an answer
        with pytest.raises(InvalidInput, match="increasing"):
            SolveRequest.model_validate(bad).to_solver()


@pytest.mark.parametrize(
    ("change", "field"),
    [
        (lambda b: b["wing"].update(y=[0.0, 2.0, 1.0, *b["wing"]["y"][3:]]), "wing.y"),
        (lambda b: b["wing"].update(chord=[1.0] * 29), "wing.chord"),
        (lambda b: b["wing"].update(airfoil=["naca0012"] * 29), "wing.airfoil"),
        (lambda b: b.update(initial_guess={"heave": [0.0] * 29, "twist": [0.0] * 30}), None),
        (lambda b: b["flight"].update(velocity=12.0, alpha=None) or b["flight"].pop("alpha"), None),
    ],
    ids=["stations-not-increasing", "short-chord", "short-airfoil", "short-guess", "no-way"],
)
def test_what_only_the_solver_can_tell_is_named_from_the_request_root(
    change: Any, field: str | None
) -> None:
    body = study.solve_request(12.0)
    change(body)
    try:
        request = SolveRequest.model_validate(body)
    except Exception:
        assert field is None  # the schema itself refused it (a way with no field of its own)
        return
    with pytest.raises(InvalidInput) as raised:
        request.to_solver()
    expected = field or "initial_guess.heave"
    assert raised.value.field == expected


def test_a_type_given_in_ways_is_one_model_per_way() -> None:
    flight = _components(SolveRequest)["SolveRequest"]["properties"]["flight"]
    refs = {member["$ref"].rsplit("/", 1)[-1] for member in flight["oneOf"]}
    assert refs == {"FlightAtAlpha", "FlightAtLift", "FlightAtWeight"}
