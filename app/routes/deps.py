"""The routes' shared state, as FastAPI dependencies (`Annotated[..., Depends(...)]`)."""

from __future__ import annotations

from typing import Annotated

from fastapi import Depends, Request

from app.service import Service
from app.settings import Settings

__all__ = ["ServiceDep", "SettingsDep"]


# Coroutines, not functions: FastAPI runs a plain function dependency in a worker thread, a
# thread hop on every request for reading an attribute (benchmarks/load_benchmark.py, profiled).
async def _service(request: Request) -> Service:
    service: Service = request.app.state.service
    return service


async def _settings(request: Request) -> Settings:
    settings: Settings = request.app.state.settings
    return settings


ServiceDep = Annotated[Service, Depends(_service)]
SettingsDep = Annotated[Settings, Depends(_settings)]
