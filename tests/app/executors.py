"""Executor factories for FLEXWING_EXECUTOR=module:callable (a Dask factory would look alike:
``return distributed.Client(address).get_executor()``)."""

from __future__ import annotations

from concurrent.futures import Executor, ThreadPoolExecutor

from app.settings import Settings


def threads(settings: Settings) -> Executor:
    return ThreadPoolExecutor(max_workers=settings.workers, thread_name_prefix="flexwing-test")
