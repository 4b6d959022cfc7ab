"""The solver's one process-wide cache, bounded in bytes.

It keeps what is expensive to rebuild and identical when rebuilt: compiled models per mesh,
jig solutions and linear divergence pressures per wing, the model's parameter vectors and
branches from the jig per wing and alpha. Entries are keyed by a kind and the wing's canonical
key (`Wing.key`), and evicted least recently used first once their estimated sizes exceed the
budget. Nothing in it can change an answer: every entry is a deterministic function of its
key, so a cached value is bit-identical to a recomputed one (see `solver.numerics.compiled` on the
virtual machine and compiled code). Clearing it, or a cache too small to keep anything, makes
solves slower, never different.

Environment:
    FLEXWING_SOLVER_CACHE_BYTES  the budget [bytes] (default 268435456, 256 MiB). The entry
                                 in use is always kept, even when it alone exceeds it.
"""

from __future__ import annotations

import os
import threading
from collections import OrderedDict
from collections.abc import Callable, Hashable
from dataclasses import dataclass
from typing import Any, TypeVar

from solver.model.layout import Layout
from solver.numerics.compiled import CompiledModel, build_model

__all__ = ["CacheInfo", "cache_info", "cached", "clear_caches", "model_for", "resize"]

T = TypeVar("T")

_DEFAULT_BUDGET = 256 * 2**20


def _budget() -> int:
    return max(0, int(os.environ.get("FLEXWING_SOLVER_CACHE_BYTES", _DEFAULT_BUDGET)))


@dataclass(frozen=True)
class CacheInfo:
    """entries: count by kind; bytes: estimated total [bytes]; budget [bytes]; hits, misses."""

    entries: dict[str, int]
    bytes: int
    budget: int
    hits: int
    misses: int


class _Store:
    def __init__(self) -> None:
        self._entries: OrderedDict[Hashable, tuple[Any, int]] = OrderedDict()
        self._lock = threading.RLock()
        self._bytes = 0
        self.hits = 0
        self.misses = 0

    def get(self, key: Hashable) -> Any | None:
        with self._lock:
            entry = self._entries.get(key)
            if entry is None:
                self.misses += 1
                return None
            self.hits += 1
            self._entries.move_to_end(key)
            return entry[0]

    def put(self, key: Hashable, value: Any, nbytes: int) -> None:
        with self._lock:
            old = self._entries.pop(key, None)
            if old is not None:
                self._bytes -= old[1]
            self._entries[key] = (value, nbytes)
            self._bytes += nbytes
            budget = _budget()
            while self._bytes > budget and len(self._entries) > 1:
                _, (_, evicted) = self._entries.popitem(last=False)
                self._bytes -= evicted

    def clear(self) -> None:
        with self._lock:
            self._entries.clear()
            self._bytes = 0
            self.hits = self.misses = 0

    def info(self) -> CacheInfo:
        with self._lock:
            kinds: dict[str, int] = {}
            for key in self._entries:
                kind = str(key[0]) if isinstance(key, tuple) else str(key)
                kinds[kind] = kinds.get(kind, 0) + 1
            return CacheInfo(kinds, self._bytes, _budget(), self.hits, self.misses)


_store = _Store()
# One lock per key being built, so two threads never build the same entry twice.
_building: dict[Hashable, threading.Lock] = {}
_building_lock = threading.Lock()


def cached(key: tuple[Hashable, ...], build: Callable[[], T], size: Callable[[T], int]) -> T:
    """The entry under `key` (its first item names the kind), built and sized on a miss."""
    value = _store.get(key)
    if value is not None:
        return value  # type: ignore[no-any-return]
    with _building_lock:
        lock = _building.setdefault(key, threading.Lock())
    with lock:
        value = _store.get(key)
        if value is None:
            value = build()
            _store.put(key, value, size(value))
    with _building_lock:
        _building.pop(key, None)
    return value  # type: ignore[no-any-return]


def resize(key: tuple[Hashable, ...], value: Any, nbytes: int) -> None:
    """Record a new size for an entry that grew in place (a branch traced further)."""
    _store.put(key, value, nbytes)


def _model_bytes(model: CompiledModel) -> int:
    """Measured: CasADi's graphs of one mesh take about 5 MB + 5.2 kB (M + 1)^2 (M panels)."""
    m = model.layout.n_panels + 1
    return 5_000_000 + 5_200 * m * m


def model_for(layout: Layout, flow: bool = False) -> CompiledModel:
    """The model of `layout` (its flow model with `flow`, `solver.numerics.compiled`): from the
    cache, else built (compiling in the background)."""
    key = ("flow_model", layout) if flow else ("model", layout)
    model = cached(key, lambda: build_model(layout, flow), _model_bytes)
    model.refresh()
    return model


def clear_caches() -> None:
    """Forget everything cached (models, jig solutions, parameters, branches, divergence
    pressures)."""
    _store.clear()


def cache_info() -> CacheInfo:
    return _store.info()
