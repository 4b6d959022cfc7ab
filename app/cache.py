"""The service's memory of past solves, kept in the web process (no locks: the event loop owns it).

- `ResultCache`: finished responses by request key; a repeated request is answered without solving.
- `StateCache`: per wing, a bounded LRU of recent stable equilibria (solver state vectors) with
  their dynamic pressure and alpha; a new solve of that wing starts from the nearest one.

A wing is identified by `fingerprint`, a hash of its canonical geometry and stiffness (the
validated arrays of `solver.Wing`, so `elastic_axis: 0.4` and thirty 0.4s are the same wing).
"""

from __future__ import annotations

import hashlib
from collections import OrderedDict
from collections.abc import Hashable
from dataclasses import dataclass
from typing import Generic, TypeVar

import numpy as np

from solver import Wing

__all__ = ["ResultCache", "StateCache", "StoredState", "fingerprint"]

V = TypeVar("V")


def fingerprint(wing: Wing) -> str:
    digest = hashlib.blake2b(digest_size=16)
    for array in (
        wing.y,
        wing.chord,
        wing.elastic_axis,
        wing.bending_stiffness,
        wing.torsional_stiffness,
    ):
        # + 0.0 turns -0.0 into 0.0, so equal numbers hash equally
        digest.update(np.ascontiguousarray(array + 0.0, dtype=np.float64).tobytes())
    return digest.hexdigest()


class ResultCache(Generic[V]):
    """A bounded LRU mapping; size 0 disables it."""

    def __init__(self, size: int) -> None:
        self.size = size
        self._entries: OrderedDict[Hashable, V] = OrderedDict()

    def __len__(self) -> int:
        return len(self._entries)

    def get(self, key: Hashable) -> V | None:
        value = self._entries.get(key)
        if value is not None:
            self._entries.move_to_end(key)
        return value

    def put(self, key: Hashable, value: V) -> None:
        if self.size <= 0:
            return
        self._entries[key] = value
        self._entries.move_to_end(key)
        while len(self._entries) > self.size:
            self._entries.popitem(last=False)


@dataclass(frozen=True)
class StoredState:
    dynamic_pressure: float  # [Pa]
    alpha: float  # [deg]
    state: np.ndarray  # (4N - 1,) solver state of a stable equilibrium

    def distance(self, dynamic_pressure: float, alpha: float) -> float:
        """Relative distance in q plus distance in alpha per degree (1 deg ~ doubling q)."""
        dq = abs(self.dynamic_pressure - dynamic_pressure) / max(dynamic_pressure, 1e-12)
        return dq + abs(self.alpha - alpha)


class StateCache:
    """Per wing, the last `per_wing` stable equilibria; at most `wings` wings (LRU both)."""

    def __init__(self, wings: int, per_wing: int) -> None:
        self.wings = wings
        self.per_wing = per_wing
        self._by_wing: OrderedDict[str, OrderedDict[tuple[float, float], StoredState]] = (
            OrderedDict()
        )

    def __len__(self) -> int:
        return len(self._by_wing)

    def nearest(self, wing: str, dynamic_pressure: float, alpha: float) -> StoredState | None:
        states = self._by_wing.get(wing)
        if not states:
            return None
        self._by_wing.move_to_end(wing)
        best = min(states.values(), key=lambda s: s.distance(dynamic_pressure, alpha))
        states.move_to_end((best.dynamic_pressure, best.alpha))
        return best

    def add(self, wing: str, dynamic_pressure: float, alpha: float, state: np.ndarray) -> None:
        if self.wings <= 0:
            return
        states = self._by_wing.get(wing)
        if states is None:
            states = self._by_wing[wing] = OrderedDict()
        self._by_wing.move_to_end(wing)
        key = (dynamic_pressure, alpha)
        states[key] = StoredState(dynamic_pressure, alpha, state)
        states.move_to_end(key)
        while len(states) > self.per_wing:
            states.popitem(last=False)
        while len(self._by_wing) > self.wings:
            self._by_wing.popitem(last=False)
