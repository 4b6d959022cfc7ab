"""The operation x option matrix, generated from the declarations (tests/app/test_matrix.py).

Nothing here names an operation, an option or a wing part: the factors of a case are read from
`solver.OPERATION_TABLE` and the input fields' declarations (`solver.fields`):

- the operation's own options, everywhere in its input but its wing, flight and airspeeds: each
  choice, each flag both ways, each small count (a range of at most 16) at its lowest and
  middle values, each optional nested input absent or at its defaults (or its example), each
  optional number, and each optional list of inputs (a design's load cases), absent or at its
  example;
- the wing's optional parts: every field of the wing with a default, absent or at its declared
  example (an optional field without an example is a declaration to complete, and fails here),
  always present where the operation's row says it `requires` it;
- the flight, wherever the input declares it (its own, a design problem's, each load case's):
  each way of giving it the flight condition declares (`WAYS`: at an alpha, trimmed to a lift,
  or to a weight and load factor), and each of its alternatives (`ALTERNATIVES`: a true or an
  equivalent airspeed, a density or an altitude), with the declared examples.

The cases are a covering array of all pairs of factor values (each value of each factor meets
each value of every other factor in some case), greedy and deterministic, plus the case with
every factor at its last value and the one with every factor at its first. A value the
service's checks refuse whatever the rest (one chordwise panel for a wing whose surfaces need a
hinge node, for an operation that requires surfaces) gets a case of its own and leaves the
covering array, whose cases then reach a worker (validation only decides it: nothing is solved
to build the cases).
"""

from __future__ import annotations

import dataclasses
import itertools
import json
import math
from collections.abc import Iterator
from dataclasses import dataclass
from typing import Any

from pydantic import ValidationError

import solver
from app.problems import Problem
from app.schemas import REQUESTS
from app.service import task_of
from app.settings import Settings
from solver import fields

__all__ = ["Case", "cases", "factors", "small_wing"]

# What every case has and no factor varies: a small wing (the study's planform on 6 stations)
# and its airspeeds (below the study wing's divergence).
_STATIONS = 6
_AIRSPEEDS = [8.0, 12.0]
_CASE_OWN = ("wing", "flight", "velocities", "initial_guess")
_SMALL_COUNT = 16
# Wing.create's one rule between parts: a spar is given instead of the stiffnesses.
_REPLACES = {"spar": ("bending_stiffness", "torsional_stiffness")}
# Every combination of this many factors' values meets in some case.
STRENGTH = 2
_SETTINGS = Settings()


def small_wing() -> dict[str, Any]:
    """The design study's planform and stiffness on 6 stations, as the API takes it [SI]."""
    y = [5.0 * i / (_STATIONS - 1) for i in range(_STATIONS)]
    chord = [math.sqrt(2.0 - 1.98 * i / (_STATIONS - 1)) for i in range(_STATIONS)]
    return {
        "y": y,
        "chord": chord,
        "elastic_axis": 0.4,
        "bending_stiffness": [2e4 * c**3 for c in chord],
        "torsional_stiffness": [1e3 * c**3 for c in chord],
    }


Factor = tuple[str, list[Any]]  # (dotted path in the request body, its values; None: absent)
# Optional inputs with required fields, absent or at their example: their own options are moot
# (and left out of the body) where they are absent.
_WHOLE_OR_ABSENT: set[str] = set()


def _default(field: dataclasses.Field[Any]) -> Any:
    if field.default is not dataclasses.MISSING:
        return field.default
    if field.default_factory is not dataclasses.MISSING:
        return "factory"
    return dataclasses.MISSING


def _required_fields(cls: type) -> list[str]:
    return [f.name for f in dataclasses.fields(cls) if _default(f) is dataclasses.MISSING]  # type: ignore[arg-type]


def _option_factors(cls: type, prefix: str) -> Iterator[Factor]:
    """The options of an input class (its wing, flight and airspeeds left to the case)."""
    for field in dataclasses.fields(cls):  # type: ignore[arg-type]
        spec = fields.specs(cls).get(field.name)
        if spec is None or field.name in _CASE_OWN:
            continue
        path = prefix if spec.flatten else f"{prefix}{field.name}"
        default = _default(field)
        if spec.form == "nested" and spec.given is not None:
            if default is None and not _required_fields(spec.given):
                yield path, [None, {}]  # an optional input, absent or at its defaults
            elif default is None and spec.example is not None:
                _WHOLE_OR_ABSENT.add(path)
                yield path, [None, spec.example]
            yield from _option_factors(spec.given, path if spec.flatten else path + ".")
        elif spec.form == "choice":
            yield path, list(spec.choices)
        elif spec.form == "flag":
            yield path, [False, True]
        elif spec.form == "integer":
            low, high = spec.limits.ge, spec.limits.le
            if low is not None and high is not None and high - low <= _SMALL_COUNT:
                yield path, [int(low), int((low + high) // 2)]
        elif spec.form == "number" and default is None and spec.example is not None:
            yield path, [None, spec.example]
        elif spec.form == "items" and spec.example is not None:
            yield path, [None, spec.example]  # an optional list of inputs, absent or its example


def _wing_factors(requires: tuple[str, ...]) -> Iterator[Factor]:
    """Every optional part of the wing, absent or at its declared example (present only, where
    the operation `requires` it)."""
    for field in dataclasses.fields(solver.Wing):
        spec = fields.specs(solver.Wing)[field.name]
        default = _default(field)
        if default is dataclasses.MISSING or field.name in small_wing():
            continue
        if spec.example is None:
            raise AssertionError(f"Wing.{field.name} is optional and declares no example")
        path = f"wing.{field.name}"
        yield path, [spec.example] if path in requires else [None, spec.example]


def _flight_values(cls: type, without: tuple[str, ...]) -> list[dict[str, Any]]:
    """Each way of giving a flight condition (`WAYS`) with its declared examples, and each
    member of each group of alternatives (`ALTERNATIVES`: its airspeed true or equivalent, its
    air by density or altitude) in turn: the k-th value takes the k-th way and the k-th member
    of each group (cyclically), so every way and every member is met."""
    declared = fields.specs(cls)
    ways: list[tuple[str, ...]] = list(cls.WAYS.values())  # type: ignore[attr-defined]
    groups = [
        tuple(name for name in group if name not in without)
        for group in getattr(cls, "ALTERNATIVES", ())
    ]
    groups = [group for group in groups if group]
    special = {n for way in ways for n in way} | {n for group in groups for n in group}
    base = {
        name: spec.example
        for name, spec in declared.items()
        if name not in without and name not in special and spec.example is not None
    }
    values = []
    for k in range(max([len(ways), *(len(group) for group in groups)])):
        value = dict(base)
        for name in ways[k % len(ways)]:
            value[name] = declared[name].example
        for group in groups:
            name = group[k % len(group)]
            value[name] = declared[name].example
        values.append(value)
    return values


def _flight_factor(cls: type) -> Factor:
    """Where `cls` (an operation's input) is told its flight, and how: a field given in ways
    (`WAYS`), within a flattened input (a design problem's), or within each item of a list (a
    load case's, the list then one item with its other required fields at their examples)."""
    for name, spec in fields.specs(cls).items():
        given = spec.given
        if given is None:
            continue
        if hasattr(given, "WAYS"):
            return name, _flight_values(given, spec.without)
        if spec.flatten or spec.form == "items":
            found = _flight_factor(given)
            if found is None:
                continue
            inner, values = found
            if spec.flatten:
                return inner, values
            required = {
                n: s.example
                for n, s in fields.specs(given).items()
                if n in _required_fields(given) and n != inner
            }
            return name, [[required | {inner: value}] for value in values]
    return None  # type: ignore[return-value]


def factors(operation: solver.Operation) -> list[Factor]:
    """The factors of `operation`'s cases."""
    found = list(_option_factors(operation.input, ""))
    flight = _flight_factor(operation.input)
    if flight is None:
        raise AssertionError(f"{operation.name}'s input declares no flight given in ways")
    return [*found, flight, *_wing_factors(operation.requires)]


def _allowed(row: dict[int, int], k: int, value: int, forbidden: set[Pair]) -> bool:
    """Setting factor k to `value` forms no forbidden pair with the row's values."""
    return not any(
        ((k, value), (i, v)) in forbidden or ((i, v), (k, value)) in forbidden
        for i, v in row.items()
    )


def _allowed_row(values: list[int], forbidden: set[Pair], domains: list[int]) -> tuple[int, ...]:
    """`values` with each value that forms a forbidden pair with the ones before it replaced by
    its factor's first allowed one (the all-first and all-last cases)."""
    row: dict[int, int] = {}
    for k, value in enumerate(values):
        choices = [value, *range(domains[k])]
        row[k] = next(v for v in choices if _allowed(row, k, v, forbidden))
    return tuple(row[k] for k in range(len(values)))


def _covering(
    domains: list[int],
    strength: int,
    forbidden: set[Pair] = frozenset(),  # type: ignore[assignment]
) -> list[tuple[int, ...]]:
    """Rows of value indices in which every combination of values of every `strength`
    factors meets (a covering array), but the `forbidden` pairs' combinations, built
    greedily: each row starts from the first combination not yet met and takes, factor by
    factor, the allowed value that meets the most new ones (the lowest on a tie)."""
    strength = min(strength, len(domains))
    groups = list(itertools.combinations(range(len(domains)), strength))
    uncovered = {
        (group, values)
        for group in groups
        for values in itertools.product(*(range(domains[i]) for i in group))
        if all(
            _allowed(dict(zip(group[:a], values[:a], strict=True)), group[a], values[a], forbidden)
            for a in range(len(group))
        )
    }
    rows: list[tuple[int, ...]] = []

    def _gain(row: dict[int, int], k: int, value: int) -> int:
        """Combinations not yet met that setting factor k to `value` meets."""
        trial = row | {k: value}
        return sum(
            (g, tuple(trial[i] for i in g)) in uncovered
            for g in groups
            if k in g and all(i in trial for i in g)
        )

    while uncovered:
        group, values = min(uncovered)
        row: dict[int, int] = dict(zip(group, values, strict=True))
        for k in range(len(domains)):
            if k not in row:
                allowed = [v for v in range(domains[k]) if _allowed(row, k, v, forbidden)]
                row[k] = max(allowed, key=lambda v, k=k: (_gain(row, k, v), -v))
        done = tuple(row[k] for k in range(len(domains)))
        uncovered -= {(g, tuple(done[i] for i in g)) for g in groups}
        rows.append(done)
    return rows


@dataclass(frozen=True)
class Case:
    operation: str
    body: dict[str, Any]
    id: str


def _body(operation: solver.Operation, settings: dict[str, Any]) -> dict[str, Any]:
    wing = small_wing()
    body: dict[str, Any] = {"wing": wing}
    if "velocities" in fields.specs(operation.input):
        body["velocities"] = list(_AIRSPEEDS)
    absent = {path for path, value in settings.items() if value is None}
    for path, value in settings.items():
        if value is None or any(path.startswith(p + ".") for p in absent & _WHOLE_OR_ABSENT):
            continue
        for replaced in _REPLACES.get(path.removeprefix("wing."), ()):
            wing.pop(replaced, None)
        *parents, leaf = path.split(".") if path else [""]
        node = body
        for parent in parents:
            node = node.setdefault(parent, {})
        if leaf:
            node[leaf] = value
        else:
            node.update(value)
    if "velocities" not in body:
        for flight in _flights(body):
            if not set(solver.FlightCondition.AIRSPEEDS) & set(flight):
                flight["velocity"] = _AIRSPEEDS[-1]
    return body


def _flights(body: dict[str, Any]) -> list[dict[str, Any]]:
    """The flights of a case's body: its own, or its items' (load cases)."""
    found = [body["flight"]] if isinstance(body.get("flight"), dict) else []
    for value in body.values():
        if isinstance(value, list):
            found += [
                item["flight"] for item in value if isinstance(item, dict) and "flight" in item
            ]
    return found


def _id(settings: dict[str, Any]) -> str:
    shown = []
    absent = {path for path, value in settings.items() if value is None} & _WHOLE_OR_ABSENT
    for path, value in settings.items():
        if value is None or value is False or any(path.startswith(p + ".") for p in absent):
            continue
        name = path.rsplit(".", 1)[-1]
        if isinstance(value, list) and value and isinstance(value[0], dict):
            value = value[0].get("flight", value[0])
        if isinstance(value, dict) and {"alpha", "lift", "weight"} & set(value):
            name = "+".join(
                k
                for k in ("alpha", "lift", "weight", "equivalent_airspeed", "altitude")
                if k in value
            )
        elif not isinstance(value, bool):
            name = f"{name}={value}" if isinstance(value, str | int) else name
        shown.append(name)
    return ",".join(shown) or "plain"


def _accepted(operation: solver.Operation, settings: dict[str, Any]) -> bool:
    """The service's checks let the case through to a worker (validation only: no solve)."""
    try:
        task_of(REQUESTS[operation.name].model_validate(_body(operation, settings)), _SETTINGS)
    except (ValidationError, Problem):
        return False
    return True


Pair = tuple[tuple[int, int], tuple[int, int]]  # two (factor, value) indices never together


def _split(
    operation: solver.Operation, table: list[Factor]
) -> tuple[list[Factor], list[dict[str, Any]], set[Pair]]:
    """The factors with the values the service refuses whatever the rest (a surface's hinge
    with one chordwise panel, for an operation that needs surfaces) taken out, and one case for
    each such value, beside a base the service accepts: so the combinations of the rest are
    met in cases that reach a worker. A value refused beside the base but accepted once one
    other factor takes another value (a wing's in-plane stiffness, which needs the exact beam)
    stays, with the pairs it is refused in (that factor's other values) never formed."""
    base = {path: values[0] for path, values in table}
    if not _accepted(operation, base):
        for path, values in table:
            found = next((v for v in values[1:] if _accepted(operation, base | {path: v})), None)
            if found is not None:
                base[path] = found
                break
    accepted = [
        [v for v in values if _accepted(operation, base | {path: v})] or values
        for path, values in table
    ]
    kept = [[*values] for values in accepted]
    alone: list[dict[str, Any]] = []
    forbidden: set[Pair] = set()
    for i, (path, values) in enumerate(table):
        for v in values:
            if v in accepted[i]:
                continue
            enabling = next(
                (
                    (
                        j,
                        [
                            w
                            for w in accepted[j]
                            if _accepted(operation, base | {path: v, other: w})
                        ],
                    )
                    for j, (other, _) in enumerate(table)
                    if j != i
                    and any(
                        _accepted(operation, base | {path: v, other: w})
                        for w in accepted[j]
                        if w != base[other]
                    )
                ),
                None,
            )
            if enabling is None:
                alone.append(base | {path: v})
                continue
            kept[i].append(v)
            j, enablers = enabling
            forbidden |= {
                ((i, len(kept[i]) - 1), (j, k)) for k, w in enumerate(kept[j]) if w not in enablers
            }
    return [(path, kept[i]) for i, (path, _) in enumerate(table)], alone, forbidden


def cases() -> list[Case]:
    """Every operation's cases: every `STRENGTH` factors' values met, all first and all last;
    and each value the service refuses whatever the rest, once."""
    found = []
    for operation in solver.OPERATION_TABLE:
        table, alone, forbidden = _split(operation, factors(operation))
        domains = [len(values) for _, values in table]
        rows = [
            _allowed_row([0 for _ in domains], forbidden, domains),
            _allowed_row([d - 1 for d in domains], forbidden, domains),
            *_covering(domains, STRENGTH, forbidden),
        ]
        every = [
            {path: values[v] for (path, values), v in zip(table, row, strict=True)} for row in rows
        ]
        seen: set[str] = set()
        for settings in [*every, *alone]:
            body = _body(operation, settings)
            key = json.dumps(body, sort_keys=True)
            if key not in seen:
                seen.add(key)
                found.append(Case(operation.name, body, f"{operation.name}:{_id(settings)}"))
    return found
