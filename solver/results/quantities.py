"""How a result type declares its fields: each with its unit and a one-line description
(`quantity`), or kept in Python (`internal`: solver state for warm starts and continuation).

The web service's response models are derived from the result dataclasses (`app.schemas`), so a
field added to one appears in the API with its unit and description, and none can be dropped
silently. Arrays over stations are (N,), over right-half panels (N - 1,), root to tip. Totals
are for both halves of the wing.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import field
from typing import Any

__all__ = ["Progress", "quantity"]


# What long work reports as it goes: progress(done, total), e.g. airspeeds answered of a sweep's.
Progress = Callable[[int, int], None]


def quantity(unit: str, description: str, **kwargs: Any) -> Any:
    """A dataclass field documented with its unit ("-" for dimensionless, "" for none)."""
    return field(metadata={"unit": unit, "description": description}, **kwargs)


def internal(**kwargs: Any) -> Any:
    """A field kept in Python only: never sent by the web service."""
    return field(metadata={"internal": True}, **kwargs)
