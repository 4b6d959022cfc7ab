"""The service's memory of finished answers, kept in the web process (no locks: the event loop
owns it).

`ResultCache` maps a request's canonical key (the wing's `solver.Wing.key`, the flight condition,
the options) to its finished response; a repeated request is answered without solving. It is
bounded in bytes (`FLEXWING_RESULT_CACHE_BYTES`): each entry's size is estimated from its JSON
content. Answers do not depend on what is cached: the solver's answer to a request is the same
whatever was asked before, so a cached response is exactly what a new solve would give.
"""

from __future__ import annotations

import sys
from collections import OrderedDict
from collections.abc import Hashable
from typing import Any, Generic, TypeVar

__all__ = ["ResultCache", "estimated_bytes"]

V = TypeVar("V")

_FLOAT_BYTES = sys.getsizeof(1.0)  # a float object (its list slot is in the list's size)
_ENTRY_BYTES = 100  # a dict entry with its key


def estimated_bytes(value: Any) -> int:
    """[bytes] roughly what a JSON-like value (dicts, lists, numbers, strings) holds in memory."""
    if isinstance(value, dict):
        return sys.getsizeof(value) + sum(_ENTRY_BYTES + estimated_bytes(v) for v in value.values())
    if isinstance(value, list | tuple):
        if value and all(isinstance(v, float) for v in value):
            return sys.getsizeof(value) + len(value) * _FLOAT_BYTES
        return sys.getsizeof(value) + sum(estimated_bytes(v) for v in value)
    return sys.getsizeof(value)


class ResultCache(Generic[V]):
    """A least-recently-used mapping bounded in bytes; a budget of 0 disables it.

    An entry larger than the whole budget is not kept.
    """

    def __init__(self, max_bytes: int) -> None:
        self.max_bytes = max_bytes
        self.bytes = 0
        self._entries: OrderedDict[Hashable, tuple[V, int]] = OrderedDict()

    def __len__(self) -> int:
        return len(self._entries)

    def get(self, key: Hashable) -> V | None:
        entry = self._entries.get(key)
        if entry is None:
            return None
        self._entries.move_to_end(key)
        return entry[0]

    def put(self, key: Hashable, value: V, nbytes: int | None = None) -> None:
        size = estimated_bytes(value) if nbytes is None else nbytes
        if size > self.max_bytes:
            return
        old = self._entries.pop(key, None)
        if old is not None:
            self.bytes -= old[1]
        self._entries[key] = (value, size)
        self.bytes += size
        while self.bytes > self.max_bytes:
            _, (_, evicted) = self._entries.popitem(last=False)
            self.bytes -= evicted
