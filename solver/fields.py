"""Input fields, defined once: the unit, limits, default and description of every input.

The solver's input dataclasses declare each field with `parameter(...)`. The same declaration
validates a value (`number`, `stations`) and is what the web service's request schema is derived
from (`app.schemas`), so a limit, a default or a description is stated in one place, and a test
fails when the API and the solver disagree on one.

A field is a number, or (`per_station`) a number for every station or N numbers. Limits are
inclusive (`ge`, `le`) or exclusive (`gt`, `lt`), each stated with the reason it is there
(`why`): the lattice's attached flow, a physical range, what the numerics can mean.
"""

from __future__ import annotations

import contextlib
import dataclasses
import hashlib
import math
import pickle
import struct
import types
from collections.abc import Iterator, Mapping
from dataclasses import dataclass
from typing import Any, TypeVar

import numpy as np

from solver.errors import InvalidInput

T = TypeVar("T")

__all__ = [
    "FORMS",
    "Limits",
    "Spec",
    "digest",
    "digested_once",
    "integer",
    "is_number",
    "number",
    "parameter",
    "pickled_once",
    "prefixed",
    "spec_of",
    "specs",
    "stations",
]


@dataclass(frozen=True)
class Limits:
    """A range of real numbers, each end inclusive (ge, le), exclusive (gt, lt) or open (None),
    and why it is there."""

    ge: float | None = None
    gt: float | None = None
    le: float | None = None
    lt: float | None = None
    why: str = ""

    def contains(self, values: np.ndarray) -> np.ndarray:
        """Elementwise: each value lies in the range."""
        inside = np.ones(np.shape(values), dtype=bool)
        if self.ge is not None:
            inside &= values >= self.ge
        if self.gt is not None:
            inside &= values > self.gt
        if self.le is not None:
            inside &= values <= self.le
        if self.lt is not None:
            inside &= values < self.lt
        return inside

    def admits(self, value: float) -> bool:
        """One number lies in the range (`contains` for a scalar, without numpy's costs)."""
        return not (
            (self.ge is not None and not value >= self.ge)
            or (self.gt is not None and not value > self.gt)
            or (self.le is not None and not value <= self.le)
            or (self.lt is not None and not value < self.lt)
        )

    def phrase(self) -> str:
        """'from 0.01 to 1000', 'strictly between -60 and 60', 'positive', '' (no limit)."""
        low = self.ge if self.ge is not None else self.gt
        high = self.le if self.le is not None else self.lt
        strict = self.gt is not None or self.lt is not None
        if low is not None and high is not None:
            if strict:
                ends = (
                    "above" if self.gt is not None else "from",
                    "below" if self.lt is not None else "to",
                )
                return f"{ends[0]} {low:g} {ends[1]} {high:g}"
            return f"from {low:g} to {high:g}"
        if low is not None:
            return "positive" if low == 0 and self.gt is not None else f"at least {low:g}"
        if high is not None:
            return f"at most {high:g}"
        return ""


# How a field is given (what the API's schema for it is derived from):
#   number       a real number within the limits
#   integer      a whole number within the limits (a count)
#   flag         true or false
#   choice       one of `choices`
#   text         a name: a string of 1 to `le` characters
#   per_station  one number for every station, or N numbers, each within the limits
#   positions    the stations: N increasing numbers from 0, or evenly spaced ones
#                (`solver.inputs.wing.StationSpacing`)
#   airfoil      a camber line for every station or one per station (`solver.inputs.airfoil`)
#   diameter     per_station, or a `solver.inputs.spar.ThicknessFraction`
#   nested       an input dataclass of its own (`given`)
#   items        a list of `given` input dataclasses (at most one per station)
#   velocities   airspeeds: a list, or `solver.inputs.flight.VelocityRange`
#   deformation  N numbers (a starting deformation), each within the limits
FORMS = (
    "number",
    "integer",
    "flag",
    "choice",
    "text",
    "per_station",
    "positions",
    "airfoil",
    "diameter",
    "nested",
    "items",
    "velocities",
    "deformation",
)


@dataclass(frozen=True)
class Spec:
    """What an input field is: its unit ("-" dimensionless, "" none), a one-line description,
    its limits, how it is given (`form`, above; `given` the input dataclass of nested forms,
    `choices` those of a choice), an example value for documentation, for a nested field whose
    fields appear in its place in the API (`flatten`), the fields of `given` a nested one
    is given `without` (a sweep's flight has no airspeed of its own), and whether the field
    enters the compiled model as a parameter (`compiled`: a slot of its own in the model's
    parameter vector, named after the field, `solver.model.layout`)."""

    unit: str
    description: str
    limits: Limits = Limits()
    form: str = "number"
    example: Any = None
    given: type | None = None
    choices: tuple[str, ...] = ()
    flatten: bool = False
    without: tuple[str, ...] = ()
    compiled: bool = False

    def __post_init__(self) -> None:
        if self.form not in FORMS:
            raise ValueError(f"unknown input form {self.form!r}")

    @property
    def per_station(self) -> bool:
        return self.form in ("per_station", "diameter")


def parameter(
    unit: str,
    description: str,
    *,
    ge: float | None = None,
    gt: float | None = None,
    le: float | None = None,
    lt: float | None = None,
    why: str = "",
    per_station: bool = False,
    form: str | None = None,
    given: type | None = None,
    choices: tuple[str, ...] = (),
    flatten: bool = False,
    without: tuple[str, ...] = (),
    example: Any = None,
    compiled: bool = False,
    **field_kwargs: Any,
) -> Any:
    """A dataclass field of an input, documented and limited (`field_kwargs`: default,
    default_factory, kw_only, ...). `per_station=True` is form "per_station"; `compiled=True`
    makes the field a parameter of the compiled model (`Spec.compiled`)."""
    kind = form or ("per_station" if per_station else "number")
    limits = Limits(ge, gt, le, lt, why)
    spec = Spec(
        unit, description, limits, kind, example, given, choices, flatten, without, compiled
    )
    return dataclasses.field(metadata={"input": spec}, **field_kwargs)


_SPECS: dict[type, Mapping[str, Spec]] = {}


def specs(cls: type) -> Mapping[str, Spec]:
    """Every input field of dataclass `cls` and its `Spec`, in declaration order (read once
    per class: a class's fields never change)."""
    found = _SPECS.get(cls)
    if found is None:
        found = _SPECS[cls] = types.MappingProxyType(
            {
                field.name: field.metadata["input"]
                for field in dataclasses.fields(cls)  # type: ignore[arg-type]
                if isinstance(field.metadata.get("input"), Spec)
            }
        )
    return found


def spec_of(cls: type, name: str) -> Spec:
    """The `Spec` of input dataclass `cls`'s field `name`."""
    spec = specs(cls).get(name)
    if spec is None:
        raise KeyError(f"{cls.__name__}.{name} is not an input field")
    return spec


_PLAIN_NUMBERS = {float, int}  # what JSON numbers become: checked by type at once


def is_number(value: object) -> bool:
    """A real number: bool (a Python int) and strings are not."""
    return isinstance(value, int | float | np.integer | np.floating) and not isinstance(
        value, bool | np.bool_
    )


def _out_of_range(path: str, spec: Spec, every: str = "") -> InvalidInput:
    why = f" ({spec.limits.why})" if spec.limits.why else ""
    unit = f" {spec.unit}" if spec.unit not in ("", "-") else ""
    return InvalidInput(path, f"must be {spec.limits.phrase()}{unit}{every}{why}")


def number(path: str, value: object, spec: Spec) -> float:
    """`value` as a finite float within `spec`'s limits, else `InvalidInput` naming `path`."""
    if not is_number(value):
        raise InvalidInput(path, "must be a number")
    result = float(value)  # type: ignore[arg-type]
    if not math.isfinite(result):
        raise InvalidInput(path, "must be a finite number")
    if not spec.limits.admits(result):
        raise _out_of_range(path, spec)
    return result + 0.0  # -0.0 is 0.0


def stations(path: str, value: object, n: int | None, spec: Spec | None = None) -> np.ndarray:
    """(n,) read-only float array from one number (for every station) or n numbers, finite and
    within `spec`'s limits; n None: any length of at least one."""
    # Lists first: what a request gives (its JSON numbers, taken by type at once).
    if isinstance(value, list | tuple) and (
        set(map(type, value)) <= _PLAIN_NUMBERS or all(is_number(v) for v in value)
    ):
        array = np.asarray(value, dtype=float)
    elif isinstance(value, np.ndarray):
        if not (np.issubdtype(value.dtype, np.integer) or np.issubdtype(value.dtype, np.floating)):
            raise InvalidInput(path, "must contain only numbers")
        array = value.astype(float)
    elif is_number(value):
        array = np.asarray(float(value))  # type: ignore[arg-type]
    else:
        raise InvalidInput(path, "must be a number or a list of numbers")
    if array.ndim == 0 and n is not None:
        array = np.full(n, float(array))
    if array.ndim != 1 or array.size == 0:
        raise InvalidInput(path, "must be a one-dimensional list of numbers")
    if n is not None and array.shape[0] != n:
        raise InvalidInput(path, f"has {array.shape[0]} values but y has {n} stations")
    # The extremes decide both checks (a NaN is both; a range is an interval), in two numpy
    # calls instead of one per check and per bound: this runs for every per-station input of
    # every request.
    low, high = float(np.minimum.reduce(array)), float(np.maximum.reduce(array))
    if not (math.isfinite(low) and math.isfinite(high)):
        raise InvalidInput(path, "must contain only finite numbers")
    if spec is not None and not (spec.limits.admits(low) and spec.limits.admits(high)):
        raise _out_of_range(path, spec, " at every station")
    array = array + 0.0
    array.setflags(write=False)
    return array


def integer(path: str, value: object, spec: Spec) -> int:
    """`value` as an int within `spec`'s limits (a whole float such as 4.0 is 4: JSON has one
    number type), else `InvalidInput` naming `path`."""
    if isinstance(value, float) and value.is_integer():
        value = int(value)
    if isinstance(value, bool) or not isinstance(value, int | np.integer):
        raise InvalidInput(path, "must be a whole number")
    if not spec.limits.admits(float(value)):
        raise _out_of_range(path, spec)
    return int(value)


@contextlib.contextmanager
def prefixed(path: str) -> Iterator[None]:
    """Name an `InvalidInput` raised inside from `path` on: "chord" in "wing" is "wing.chord"
    (an empty field names `path` itself)."""
    try:
        yield
    except InvalidInput as error:
        inner = error.field
        joined = (
            path if not inner else f"{path}{inner}" if inner.startswith("[") else f"{path}.{inner}"
        )
        raise InvalidInput(joined, error.reason) from None


def digest(value: object) -> bytes:
    """A canonical identity of an input value: equal for equal numbers (-0.0 and 0.0 alike,
    one number and the array it stands for are not the same value), recursing into
    dataclasses (every field, by name), sequences and mappings. What every cache keys by."""
    hasher = hashlib.blake2b(digest_size=16)
    _feed(hasher, value, {})
    return hasher.digest()


_SCALAR = b"A(1,)"  # a number, fed as np.ascontiguousarray makes it: a (1,) float64 array
_DOUBLE = struct.Struct("=d")  # native order, as ndarray.tobytes
_LABELS: dict[type, tuple[tuple[str, bytes], ...]] = {}


def _field_labels(kind: type) -> tuple[tuple[str, bytes], ...]:
    """A dataclass's fields as (name, b"." + name), in declaration order (computed once)."""
    labels = _LABELS.get(kind)
    if labels is None:
        fields = dataclasses.fields(kind)  # type: ignore[arg-type]
        labels = _LABELS[kind] = tuple((f.name, b"." + f.name.encode()) for f in fields)
    return labels


def _feed(hasher: Any, value: object, seen: dict[int, bytes]) -> None:
    """Feed `value`'s canonical bytes; a dataclass met again within the same value (a wing's
    one airfoil, repeated at every station) is fed as the digest it had the first time."""
    kind = type(value)
    # The common cases first, by exact type (a request digests ~60 values on the hot path):
    # bytes equal to the general branches' below.
    if kind is float or kind is int:
        hasher.update(_SCALAR + _DOUBLE.pack(float(value) + 0.0))  # type: ignore[arg-type]
    elif isinstance(value, np.ndarray) and kind is np.ndarray and value.dtype == np.float64:
        array = np.ascontiguousarray(value + 0.0)
        hasher.update(b"A" + repr(array.shape).encode() + array.tobytes())
    elif kind in _LABELS:  # a dataclass of a kind met before (a wing's 30 camber lines)
        _feed_dataclass(hasher, value, seen)
    elif value is None:
        hasher.update(b"N")
    elif isinstance(value, bool | np.bool_):
        hasher.update(b"T" if value else b"F")
    elif isinstance(value, np.ndarray) or is_number(value):
        array = np.ascontiguousarray(np.asarray(value, dtype=np.float64) + 0.0)
        hasher.update(b"A" + repr(array.shape).encode() + array.tobytes())
    elif isinstance(value, str):
        hasher.update(b"S" + str(len(value)).encode() + b":" + value.encode())
    elif dataclasses.is_dataclass(value) and not isinstance(value, type):
        _feed_dataclass(hasher, value, seen)
    elif isinstance(value, list | tuple):
        hasher.update(b"L" + str(len(value)).encode())
        for item in value:
            _feed(hasher, item, seen)
    elif isinstance(value, dict):
        hasher.update(b"M" + str(len(value)).encode())
        for key in sorted(value):
            _feed(hasher, key, seen)
            _feed(hasher, value[key], seen)
    else:
        raise TypeError(f"no canonical identity for {type(value).__name__}")


_ONCE: set[type] = set()  # immutable input types whose instances keep their digest
_DIGEST_ATTRIBUTE = "_fields_digest"  # where an instance of one keeps it (in its __dict__)


def digested_once(cls: type[T]) -> type[T]:
    """Class decorator for an immutable input dataclass (frozen, its arrays read-only): each
    instance keeps its digest once computed, so one that many requests share (the service keeps
    the wings it has built, `app.schemas.derive`) is digested once."""
    _ONCE.add(cls)
    return cls


_PICKLE_ATTRIBUTE = "_fields_pickle"  # where an instance of a `pickled_once` type keeps its state


def pickled_once(cls: type[T]) -> type[T]:
    """Class decorator for an immutable input dataclass (frozen, its arrays read-only): each
    instance pickles its fields once and sends those bytes every time after (the service hands
    one kept wing to its workers with thousands of requests); unpickled, it is an equal
    instance."""

    def __reduce__(self: Any) -> tuple[Any, ...]:
        state = self.__dict__.get(_PICKLE_ATTRIBUTE)
        if state is None:
            fields = {k: v for k, v in self.__dict__.items() if k != _PICKLE_ATTRIBUTE}
            state = pickle.dumps(fields, protocol=pickle.HIGHEST_PROTOCOL)
            object.__setattr__(self, _PICKLE_ATTRIBUTE, state)  # frozen: set past its guard, once
        return _unpickled, (type(self), state)

    cls.__reduce__ = __reduce__  # type: ignore[assignment,method-assign]
    return cls


def _unpickled(cls: type[T], state: bytes) -> T:
    """An instance of `cls` with the fields pickled in `state` (`pickled_once`)."""
    value = object.__new__(cls)
    value.__dict__.update(pickle.loads(state))
    return value


def _feed_dataclass(hasher: Any, value: object, seen: dict[int, bytes]) -> None:
    """A dataclass instance: its own digest (its type's name, then each field by name), fed
    as b"D" + that digest, computed once per instance within one value (and once for good for
    a type `digested_once`)."""
    kind = type(value)
    known = seen.get(id(value))
    if known is None and kind in _ONCE:
        known = value.__dict__.get(_DIGEST_ATTRIBUTE)
    if known is None:
        inner = hashlib.blake2b(digest_size=16)
        inner.update(kind.__name__.encode())
        for name, label in _field_labels(kind):
            inner.update(label)
            _feed(inner, getattr(value, name), seen)
        known = seen[id(value)] = inner.digest()
        if kind in _ONCE:
            object.__setattr__(value, _DIGEST_ATTRIBUTE, known)  # frozen: set past its guard, once
    hasher.update(b"D" + known)
