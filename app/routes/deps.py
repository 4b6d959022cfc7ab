"""The routes' shared state, as FastAPI dependencies (`Annotated[..., Depends(...)]`)."""

from __future__ import annotations

from typing import Annotated

from fastapi import Depends, Request

from app.service import Service
from app.settings import Settings

__all__ = ["ServiceDep", "SettingsDep"]


def _service(request: Request) -> Service:
    service: Service = request.app.state.service
    return service


def _settings(request: Request) -> Settings:
    settings: Settings = request.app.state.settings
    return settings


ServiceDep = Annotated[Service, Depends(_service)]
SettingsDep = Annotated[Settings, Depends(_settings)]
