"""Request models derived from the solver's input types, as the response models are from its
result types (`app.schemas.responses`): every field's name, unit, limits, default and
description is the solver's declaration (`solver.fields`), so the API cannot drift from what
the solver accepts, and a new input field appears in the API without an edit here.

`request_model(cls)` builds the pydantic model of a solver input dataclass (nested ones
included); a validated instance's `to_solver()` builds the solver input itself, naming any
input the solver refuses from the request's root (`wing.chord[3]`). JSON Schema cannot state
every rule (one wing's lists have one length, stations increase from 0): those the solver
checks, and the descriptions say.

Limits set by the service's settings (most stations, most sweep points) are marked
`x-flexwing-limit` here and written into the OpenAPI document from the running configuration
(`app.main`); `app.schemas.limits` checks them.
"""

from __future__ import annotations

import dataclasses
import functools
import inspect
import threading
import typing
from collections import OrderedDict
from collections.abc import Callable
from typing import Annotated, Any, ClassVar, Literal, TypeVar, Union

from pydantic import BaseModel, BeforeValidator, ConfigDict, Discriminator, Field, Tag, create_model

import solver
from app.settings import MAX_ARRAY_LENGTH

__all__ = ["RequestModel", "request_model", "to_solver"]

Number = TypeVar("Number")

# The service's own limits, written into the document from the settings (`app.main`).
STATIONS_LIMIT: dict[str, Any] = {"x-flexwing-limit": "max_stations"}
SWEEP_POINTS_LIMIT: dict[str, Any] = {"x-flexwing-limit": "max_sweep_points"}
# The settings limit a list of items is held to (by the item's class): at most one per station
# unless named here.
_LOAD_CASES_LIMIT: dict[str, Any] = {"x-flexwing-limit": "max_load_cases"}
ITEM_LIMITS: dict[str, dict[str, Any]] = {
    "FlightCase": _LOAD_CASES_LIMIT,
    "DesignLoadCase": _LOAD_CASES_LIMIT,
}
# A list of values (an envelope's weights, its altitudes): at most this many.
MAX_VALUES = 64

# A flight over airspeeds (a sweep's, a flutter or controls analysis's) leaves its airspeed out.
_OVER_AIRSPEEDS = solver.FlightCondition.AIRSPEEDS
# Component names the published document has always used, where they differ from the
# solver's class names: (class, way or None, without) -> name.
_NAMES: dict[tuple[type, str | None, tuple[str, ...]], str] = {
    (solver.SparDesign, None, ()): "TubeSpar",
    (solver.Material, None, ()): "SparMaterial",
    (solver.FlightCondition, "alpha", ()): "FlightAtAlpha",
    (solver.FlightCondition, "lift", ()): "FlightAtLift",
    (solver.FlightCondition, "weight", ()): "FlightAtWeight",
    (solver.FlightCondition, "alpha", _OVER_AIRSPEEDS): "SweepFlightAtAlpha",
    (solver.FlightCondition, "lift", _OVER_AIRSPEEDS): "SweepFlightAtLift",
    (solver.FlightCondition, "weight", _OVER_AIRSPEEDS): "SweepFlightAtWeight",
    (solver.DesignCondition, "lift", ()): "OptimizeFlightAtLift",
    (solver.DesignCondition, "weight", ()): "OptimizeFlightAtWeight",
}
# An operation's request model is named after it: POST /{name} takes {Name}Request.
_NAMES.update({(op.input, None, ()): f"{op.name.title()}Request" for op in solver.OPERATION_TABLE})

# The docstring a way's model says of itself.
_WAY_DOCS: dict[tuple[type, str], str] = {
    (solver.FlightCondition, "alpha"): "Steady, symmetric flight at a given angle of attack.",
    (solver.FlightCondition, "lift"): "Trimmed flight: the angle of attack at which the "
    "flexible wing carries `lift`.",
    (solver.FlightCondition, "weight"): "Trimmed flight: the angle of attack at which the "
    "flexible wing carries `load_factor * weight`.",
    (solver.DesignCondition, "lift"): "The flight the design is for: `lift` at `velocity`, at "
    "a fixed jig angle `alpha`.",
    (solver.DesignCondition, "weight"): "The flight the design is for: `load_factor * weight` "
    "at `velocity`, at a fixed `alpha`.",
}


def _whole_number(value: object) -> object:
    """30.0 is the integer 30 to JSON Schema (and to JSON: one number type), so it is to us."""
    if type(value) is float and value.is_integer():
        return int(value)
    return value


# A count or an index: JSON Schema's "integer", which 30.0 is; 30.5, "30" and true are not.
Integer = Annotated[int, BeforeValidator(_whole_number)]


class RequestModel(BaseModel):
    """A request model derived from a solver input type (`__solver__`).

    Strict: a JSON value of another type than documented ("10" or true for a number) is
    invalid input, not converted. Integers are still accepted for numbers."""

    model_config = ConfigDict(extra="forbid", strict=True)

    __solver__: ClassVar[Callable[..., Any]]
    __fixed__: ClassVar[dict[str, Any]] = {}  # fields given without the API: their values
    __flattened__: ClassVar[dict[str, tuple[str, ...]]] = {}  # solver field -> its members
    __per_station__: ClassVar[frozenset[str]] = frozenset()  # fields of up to N values
    # How many solver inputs of this model to keep, by the request's JSON (0: none): a design
    # loop sends one wing thousands of times, built and checked once (solver inputs are immutable).
    __kept__: ClassVar[int] = 0

    def to_solver(self) -> Any:
        """The solver input this request describes (`InvalidInput` named from here)."""
        if self.__kept__:
            return _kept(self)
        return self._built()

    def _built(self) -> Any:
        values: dict[str, Any] = dict(self.__fixed__)
        for name, members in self.__flattened__.items():
            values[name] = _build(self, members)
        for name in _own_fields(type(self)):
            values[name] = _named(name, getattr(self, name))
        return self.__solver__(**values)


_KEPT: dict[type[RequestModel], OrderedDict[str, Any]] = {}
_KEEPING = threading.Lock()  # requests are built on the event loop; any other thread waits


def _kept(model: RequestModel) -> Any:
    """`model._built()`, the last `__kept__` of them remembered by their request's JSON (equal
    JSON, equal values: another spelling of the same numbers is only a miss)."""
    # Exact: floats as their shortest round-trip repr, every field, a union's member by its shape
    # (warnings off: a union tries its members in turn, and says so for each it passes over).
    text = model.model_dump_json(warnings=False)
    with _KEEPING:
        kept = _KEPT.setdefault(type(model), OrderedDict())
        value = kept.get(text)
        if value is not None:
            kept.move_to_end(text)
            return value
    value = model._built()  # an invalid one raises, and is not kept
    with _KEEPING:
        kept[text] = value
        if len(kept) > model.__kept__:
            kept.popitem(last=False)
    return value


@functools.cache
def _own_fields(model: type[RequestModel]) -> tuple[str, ...]:
    """The fields of `model` taken as they are (not members of a flattened one)."""
    flattened = {m for members in model.__flattened__.values() for m in members}
    return tuple(name for name in model.model_fields if name not in flattened)


def _named(name: str, value: Any) -> Any:
    """`to_solver(value)`, an `InvalidInput` inside named from `name` on. Only a model or a
    list can raise one: a scalar passes as it is, without the naming's cost (every field of
    every request comes through here)."""
    if not isinstance(value, RequestModel | list):
        return value
    with solver.fields.prefixed(name):
        return to_solver(value)


def _build(model: RequestModel, members: tuple[str, ...]) -> Any:
    """A flattened field's solver value from its members, named from the request's root."""
    nested: dict[str, Any] = {}
    for name in members:
        nested[name] = _named(name, getattr(model, name))
    flat = type(model).__flat_types__[members]  # type: ignore[attr-defined]
    return flat(**nested)


_PLAIN = {float, int, str, bool, type(None)}  # JSON scalars: a list of them is taken as it is


def to_solver(value: Any) -> Any:
    """A validated request value as the solver takes it: models built, lists as tuples."""
    if isinstance(value, RequestModel):
        return value.to_solver()
    if isinstance(value, list):
        if set(map(type, value)) <= _PLAIN or not any(
            isinstance(item, RequestModel | list) for item in value
        ):
            return tuple(value)  # numbers and names: nothing inside to name an error from
        return tuple(_named(f"[{index}]", item) for index, item in enumerate(value))
    return value


# ------------------------------------------------------------------------- one field's type


def _phrase(spec: solver.Spec) -> str:
    phrase = spec.limits.phrase()
    why = f" ({spec.limits.why})" if spec.limits.why else ""
    return f"{phrase}{why}" if phrase else ""


def _describe(spec: solver.Spec, tail: str = "") -> str:
    """'[unit] Description: from a to b (why); tail.'"""
    text = spec.description[:1].upper() + spec.description[1:]
    unit = f"[{spec.unit}] " if spec.unit else ""
    limits = _phrase(spec)
    each = "each " if spec.form in ("per_station", "diameter", "velocities", "deformation") else ""
    body = f"{unit}{text}" + (f": {each}{limits}" if limits else "")
    return body + (f"; {tail}" if tail else "") + "."


def _number(spec: solver.Spec, kind: type = float) -> Any:
    """A number within the spec's limits (as a JSON Schema minimum/maximum)."""
    limits = spec.limits
    constraints: dict[str, Any] = {
        "ge": limits.ge,
        "gt": limits.gt,
        "le": limits.le,
        "lt": limits.lt,
    }
    if kind is float:
        constraints["allow_inf_nan"] = False
    field = Field(**{k: v for k, v in constraints.items() if v is not None})
    if kind is int:
        return Annotated[int, field, BeforeValidator(_whole_number)]
    return Annotated[float, field]


def _list_or_object(value: Any) -> str:
    return "@list" if isinstance(value, list) else "@object"


def _station_values(item: Any) -> Any:
    """One number for every station, or a list of N (a wing's station arrays)."""
    return Annotated[
        Annotated[item, Tag("@number")]
        | Annotated[
            list[item],  # type: ignore[valid-type]
            Field(min_length=solver.MIN_STATIONS, max_length=MAX_ARRAY_LENGTH),
            Field(json_schema_extra=STATIONS_LIMIT),
            Tag("@list"),
        ],
        Discriminator(lambda value: "@list" if isinstance(value, list) else "@number"),
    ]


class CamberTable(RequestModel):
    """A camber line as points, linear between them: x / chord from 0 to 1 (increasing), and
    camber / chord at each."""

    __solver__ = dict

    x: Annotated[
        list[Annotated[float, Field(ge=0.0, le=1.0, allow_inf_nan=False)]],
        Field(min_length=2, max_length=MAX_ARRAY_LENGTH),
    ] = Field(description="[-] x / chord of the points, 0 first and 1 last, strictly increasing.")
    camber: Annotated[
        list[
            Annotated[
                float,
                Field(ge=-solver.MAX_CAMBER, le=solver.MAX_CAMBER, allow_inf_nan=False),
            ]
        ],
        Field(min_length=2, max_length=MAX_ARRAY_LENGTH),
    ] = Field(
        description=f"[-] camber / chord at each point, -{solver.MAX_CAMBER:g} to "
        f"{solver.MAX_CAMBER:g}; as many as x."
    )

    def to_solver(self) -> Any:
        return {"x": self.x, "camber": self.camber}


_NACA = Annotated[
    str,
    Field(
        pattern=r"^[nN][aA][cC][aA][0-9]{4}$",
        description="A NACA 4-digit section, e.g. 'naca4412' (its analytic mean line).",
    ),
]
_CAMBER_LINE = Annotated[
    Annotated[_NACA, Tag("@string")] | Annotated[CamberTable, Tag("@object")],
    Discriminator(lambda value: "@string" if isinstance(value, str) else "@object"),
]
_AIRFOIL = Annotated[
    Annotated[_CAMBER_LINE, Tag("@one")]
    | Annotated[
        list[_CAMBER_LINE],  # type: ignore[valid-type]
        Field(max_length=MAX_ARRAY_LENGTH, json_schema_extra=STATIONS_LIMIT),
        Tag("@list"),
    ],
    Discriminator(lambda value: "@list" if isinstance(value, list) else "@one"),
]


def _diameter_kind(value: Any) -> str:
    if isinstance(value, list):
        return "@list"
    return "@fraction" if isinstance(value, dict) else "@number"


def _annotation(spec: solver.Spec, hint: Any) -> Any:
    """The pydantic type of a field given as `spec` says (`hint`: its Python annotation)."""
    form = spec.form
    if form == "number":
        return _number(spec)
    if form == "integer":
        return _number(spec, int)
    if form == "flag":
        return bool
    if form == "choice":
        return Literal[spec.choices]  # type: ignore[valid-type]
    if form == "text":
        assert spec.limits.le is not None
        return Annotated[str, Field(min_length=1, max_length=int(spec.limits.le))]
    if form == "per_station":
        return _station_values(_number(spec))
    if form == "positions":
        spacing = request_model(solver.StationSpacing)
        return Annotated[
            Annotated[
                list[_number(spec)],  # type: ignore[misc]
                Field(min_length=solver.MIN_STATIONS, max_length=MAX_ARRAY_LENGTH),
                # The root station is at 0 and the list increases: the description says so
                # (JSON Schema's prefixItems could say the first, but generated clients then
                # refuse every station after it: openapi-python-client 0.2x reads it as items).
                Field(json_schema_extra=STATIONS_LIMIT),
                Tag("@list"),
            ]
            | Annotated[spacing, Tag("@object")],
            Discriminator(_list_or_object),
        ]
    if form == "airfoil":
        return _AIRFOIL
    if form == "diameter":
        assert spec.given is not None
        number = _number(spec)
        return Annotated[
            Annotated[number, Tag("@number")]
            | Annotated[
                list[number],  # type: ignore[valid-type]
                Field(min_length=solver.MIN_STATIONS, max_length=MAX_ARRAY_LENGTH),
                Field(json_schema_extra=STATIONS_LIMIT),
                Tag("@list"),
            ]
            | Annotated[request_model(spec.given), Tag("@fraction")],
            Discriminator(_diameter_kind),
        ]
    if form == "velocities":
        assert spec.given is not None
        item = _number(solver.spec_of(solver.FlightCondition, "velocity"))
        return Annotated[
            Annotated[
                list[item],  # type: ignore[valid-type]
                Field(min_length=1, max_length=MAX_ARRAY_LENGTH),
                Field(json_schema_extra=SWEEP_POINTS_LIMIT),
                Tag("@list"),
            ]
            | Annotated[request_model(spec.given), Tag("@object")],
            Discriminator(_list_or_object),
        ]
    if form == "deformation":
        return Annotated[
            list[_number(spec)],  # type: ignore[misc]
            Field(max_length=MAX_ARRAY_LENGTH, json_schema_extra=STATIONS_LIMIT),
        ]
    if form == "values":
        return Annotated[
            list[_number(spec)],  # type: ignore[misc]
            Field(min_length=1, max_length=MAX_VALUES),
        ]
    if form == "indices":
        return Annotated[
            list[Annotated[int, Field(ge=0)]],
            Field(min_length=1, max_length=MAX_ARRAY_LENGTH, json_schema_extra=STATIONS_LIMIT),
        ]
    if form == "nested":
        assert spec.given is not None
        return request_model(spec.given, spec.without)
    if form == "items":
        assert spec.given is not None
        limit = ITEM_LIMITS.get(spec.given.__name__, STATIONS_LIMIT)
        return Annotated[
            list[request_model(spec.given)],  # type: ignore[misc]
            Field(max_length=MAX_ARRAY_LENGTH, json_schema_extra=limit),
        ]
    raise TypeError(f"no API type for input form {form!r}")


def _optional(hint: Any) -> bool:
    return type(None) in typing.get_args(hint)


def _field(
    cls: type, field: dataclasses.Field[Any], spec: solver.Spec, hint: Any, required: bool
) -> Any:
    """(annotation, FieldInfo) of one solver input field (`required`: the field that names a
    way of giving `cls`, required in that way's model)."""
    annotation = _annotation(spec, hint)
    tail = {
        "per_station": "one number for every station, or N values",
        "deformation": "N values",
    }.get(spec.form, "")
    kwargs: dict[str, Any] = {"description": _describe(spec, tail)}
    if spec.example is not None:
        kwargs["examples"] = [spec.example]
    if required:
        pass
    elif field.default is not dataclasses.MISSING:
        default = field.default
        # The normalised defaults of the solver's own types mean "none given" at the API: an
        # empty list of items, a null for the rest.
        if isinstance(default, tuple):
            default = [] if spec.form == "items" else None
        kwargs["default"] = default
    elif field.default_factory is not dataclasses.MISSING:
        kwargs["default_factory"] = annotation  # a nested model of its defaults
    has_default = "default" in kwargs or "default_factory" in kwargs
    if has_default and (_optional(hint) or kwargs.get("default", 0) is None):
        annotation = annotation | None
    if spec.form == "integer" and spec.limits.le is None and _unbounded_count(cls, field.name):
        kwargs["le"] = MAX_ARRAY_LENGTH
        kwargs["json_schema_extra"] = _COUNT_LIMITS[(cls, field.name)]
    return annotation, Field(**kwargs)


# Counts bounded by the service's settings: (class, field) -> its x-flexwing-limit.
_COUNT_LIMITS: dict[tuple[type, str], dict[str, Any]] = {
    (solver.StationSpacing, "stations"): STATIONS_LIMIT,
    (solver.VelocityRange, "count"): SWEEP_POINTS_LIMIT,
}


def _unbounded_count(cls: type, name: str) -> bool:
    return (cls, name) in _COUNT_LIMITS


# ---------------------------------------------------------------------------- whole models

# Forms given as up to one value per station (FLEXWING_MAX_STATIONS bounds their lists).
_PER_STATION_FORMS = ("per_station", "positions", "airfoil", "diameter", "deformation", "items")

_models: dict[tuple[type, str | None, tuple[str, ...]], Any] = {}


def request_model(cls: type, without: tuple[str, ...] = ()) -> Any:
    """The request model of solver input dataclass `cls` (its fields `without` left out): a
    pydantic model, or for a type given in several ways (`cls.WAYS`) their tagged union."""
    declared: dict[str, tuple[str, ...]] | None = getattr(cls, "WAYS", None)
    if declared is None:
        return _model(cls, None, without)
    # A way whose naming field is left out is no way here (a design's load case is trimmed: its
    # flight has no alpha); the others leave out what their way has not anyway.
    ways = {way: names for way, names in declared.items() if names[0] not in without}
    absent = {name for names in declared.values() for name in names}
    members = [
        Annotated[
            _model(cls, way, tuple(n for n in without if n not in absent - set(names))),
            Tag(f"@{way}"),
        ]
        for way, names in ways.items()
    ]
    rule: str = cls.RULE  # type: ignore[attr-defined]
    if len(ways) < len(declared):
        optional = sorted({name for names in ways.values() for name in names[1:]})
        rule = (
            f"give exactly one of {' or '.join(names[0] for names in ways.values())}"
            + (f", with an optional {', '.join(optional)}" if optional else "")
            + f" (no {', '.join(way for way in declared if way not in ways)} here)"
        )

    def which(value: Any) -> str | None:
        """The tag of the one way the value is given; None if none or several are."""
        if not isinstance(value, dict):
            return f"@{next(iter(ways))}"  # not an object at all: let the model say so
        given = [way for way, names in ways.items() if names[0] in value]
        others = {name for names in ways.values() for name in names[1:]}
        orphans = [name for name in others if name in value]
        if len(given) != 1 or any(name not in ways[given[0]] for name in orphans):
            return None
        return f"@{given[0]}"

    discriminator = Discriminator(which, custom_error_type="flight_way", custom_error_message=rule)
    return Annotated[Union[tuple(members)], discriminator]  # noqa: UP007


def _model(cls: type, way: str | None, without: tuple[str, ...]) -> type[RequestModel]:
    key = (cls, way, without)
    model = _models.get(key)
    if model is not None:
        return model  # type: ignore[no-any-return]
    hints = typing.get_type_hints(cls)
    ways: dict[str, tuple[str, ...]] = getattr(cls, "WAYS", {})
    excluded = set(without)
    if way is not None:
        excluded |= {name for other in ways.values() for name in other} - set(ways[way])
    definitions: dict[str, Any] = {}
    flattened: dict[str, tuple[str, ...]] = {}
    flat_types: dict[tuple[str, ...], Any] = {}
    for field in dataclasses.fields(cls):  # type: ignore[arg-type]
        spec = field.metadata.get("input")
        if not isinstance(spec, solver.Spec) or field.name in excluded:
            continue
        if spec.flatten:
            assert spec.given is not None
            inner = _model(spec.given, None, ())
            members = tuple(inner.model_fields)
            flattened[field.name] = members
            flat_types[members] = spec.given
            for name, info in inner.model_fields.items():
                definitions[name] = (info.annotation, info)
            continue
        required = way is not None and field.name == ways[way][0]
        definitions[field.name] = _field(cls, field, spec, hints[field.name], required)
    name = _NAMES.get(key, cls.__name__)
    doc = _WAY_DOCS.get((cls, way)) if way else None
    model = create_model(  # type: ignore[call-overload]
        name,
        __base__=RequestModel,
        __doc__=doc or (cls.__doc__ or "").strip(),
        **definitions,
    )
    model.__solver__ = _builder(cls)
    model.__fixed__ = dict.fromkeys(without)
    if way is not None:
        # The other ways' fields are absent: the solver's defaults (None) stand for them.
        model.__fixed__ |= {
            name: None
            for other in ways.values()
            for name in other
            if name not in ways[way] and _has_none_default(cls, name)
        }
    model.__flattened__ = flattened
    model.__per_station__ = frozenset(
        field.name
        for field in dataclasses.fields(cls)  # type: ignore[arg-type]
        if isinstance(spec := field.metadata.get("input"), solver.Spec)
        and spec.form in _PER_STATION_FORMS
        and not (spec.form == "items" and getattr(spec.given, "__name__", "") in ITEM_LIMITS)
    )
    model.__flat_types__ = flat_types
    _models[key] = model
    return model  # type: ignore[no-any-return]


def _builder(cls: type) -> Callable[..., Any]:
    """What builds `cls` from its fields: its `create` (which validates and normalises) when
    that takes nothing but fields; else its fields as given, a mapping its owner resolves once
    (as `Wing.create` resolves the wing's `MassModel` for its stations)."""
    create = getattr(cls, "create", None)
    if create is None:
        return cls
    names = {field.name for field in dataclasses.fields(cls)}  # type: ignore[arg-type]
    required = [
        parameter.name
        for parameter in inspect.signature(create).parameters.values()
        if parameter.default is inspect.Parameter.empty
        and parameter.kind is not inspect.Parameter.VAR_KEYWORD
    ]
    return create if set(required) <= names else dict


def _has_none_default(cls: type, name: str) -> bool:
    field = next(f for f in dataclasses.fields(cls) if f.name == name)  # type: ignore[arg-type]
    return field.default is None
