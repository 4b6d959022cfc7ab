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

import dataclasses
import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from solver.errors import InvalidInput

__all__ = ["Limits", "Spec", "is_number", "number", "parameter", "spec_of", "stations"]


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


@dataclass(frozen=True)
class Spec:
    """What an input field is: its unit ("-" dimensionless, "" none), a one-line description,
    its limits, whether it is given per station, and an example value for documentation."""

    unit: str
    description: str
    limits: Limits = Limits()
    per_station: bool = False
    example: Any = None


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
    example: Any = None,
    **field_kwargs: Any,
) -> Any:
    """A dataclass field of an input, documented and limited (`field_kwargs`: default,
    default_factory, ...)."""
    spec = Spec(unit, description, Limits(ge, gt, le, lt, why), per_station, example)
    return dataclasses.field(metadata={"input": spec}, **field_kwargs)


def spec_of(cls: type, name: str) -> Spec:
    """The `Spec` of input dataclass `cls`'s field `name`."""
    for field in dataclasses.fields(cls):  # type: ignore[arg-type]
        if field.name == name:
            spec = field.metadata.get("input")
            if isinstance(spec, Spec):
                return spec
    raise KeyError(f"{cls.__name__}.{name} is not an input field")


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
    if not spec.limits.contains(np.asarray(result)):
        raise _out_of_range(path, spec)
    return result + 0.0  # -0.0 is 0.0


def stations(path: str, value: object, n: int | None, spec: Spec | None = None) -> np.ndarray:
    """(n,) read-only float array from one number (for every station) or n numbers, finite and
    within `spec`'s limits; n None: any length of at least one."""
    if isinstance(value, np.ndarray):
        if not (np.issubdtype(value.dtype, np.integer) or np.issubdtype(value.dtype, np.floating)):
            raise InvalidInput(path, "must contain only numbers")
        array = value.astype(float)
    elif is_number(value):
        array = np.asarray(float(value))  # type: ignore[arg-type]
    elif isinstance(value, list | tuple) and all(is_number(v) for v in value):
        array = np.asarray(value, dtype=float)
    else:
        raise InvalidInput(path, "must be a number or a list of numbers")
    if array.ndim == 0 and n is not None:
        array = np.full(n, float(array))
    if array.ndim != 1 or array.size == 0:
        raise InvalidInput(path, "must be a one-dimensional list of numbers")
    if n is not None and array.shape[0] != n:
        raise InvalidInput(path, f"has {array.shape[0]} values but y has {n} stations")
    if not np.all(np.isfinite(array)):
        raise InvalidInput(path, "must contain only finite numbers")
    if spec is not None and not np.all(spec.limits.contains(array)):
        raise _out_of_range(path, spec, " at every station")
    array = array + 0.0
    array.setflags(write=False)
    return array
