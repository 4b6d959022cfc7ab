"""Jobs for the pool tests: plain module-level functions, so worker processes can import them."""

from __future__ import annotations

import os
import time


def sleep_then_pid(seconds: float) -> int:
    """Sleep `seconds` [s] in the worker, then return its process id."""
    time.sleep(seconds)
    return os.getpid()


def fail(message: str) -> None:
    raise ValueError(message)
