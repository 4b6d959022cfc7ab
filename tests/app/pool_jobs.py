"""Jobs for the pool tests: plain module-level functions, so worker processes can import them."""

from __future__ import annotations

import os
import time
from collections.abc import Callable


def sleep_then_pid(seconds: float) -> int:
    """Sleep `seconds` [s] in the worker, then return its process id."""
    time.sleep(seconds)
    return os.getpid()


def fail(message: str) -> None:
    raise ValueError(message)


def counts_to(total: int, progress: Callable[[int, int], None]) -> int:
    """Reports each of `total` steps done, then answers how many there were."""
    for done in range(1, total + 1):
        progress(done, total)
    return total
