"""app.routes.deps: a route gets the app's own service and settings (those `create_app` was
given) by `ServiceDep` and `SettingsDep`, never a fresh or a global one."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import httpx
import pytest
from fastapi import FastAPI

from app.main import create_app
from app.routes.deps import ServiceDep, SettingsDep
from app.settings import Settings, get_settings
from tests.app.conftest import _InProcess


def _probe(app: FastAPI) -> dict[str, Any]:
    """What a route of `app` gets by the two dependencies."""
    seen: dict[str, Any] = {}

    @app.get("/probe-dependencies")
    async def probe(service: ServiceDep, settings: SettingsDep) -> dict[str, str]:
        seen.update(service=service, settings=settings)
        return {}

    with httpx.Client(transport=_InProcess(app), base_url="http://in-process") as client:
        assert client.get("/probe-dependencies").status_code == 200
    return seen


@pytest.mark.parametrize("max_stations", [40, 150], ids=["configured", "default"])
def test_a_route_gets_the_service_and_settings_its_app_was_created_with(
    tmp_path: Path, max_stations: int
) -> None:
    settings = Settings(workers=1, jobs_db=tmp_path / "jobs.sqlite3", max_stations=max_stations)
    app = create_app(settings)
    seen = _probe(app)
    assert seen["settings"] is settings and seen["settings"].max_stations == max_stations
    assert seen["service"] is app.state.service
    assert seen["service"].settings is settings  # the service runs by the same settings
    assert seen["settings"] is not get_settings()


def test_two_apps_in_one_process_keep_their_own(tmp_path: Path) -> None:
    first = create_app(Settings(workers=1, jobs_db=tmp_path / "a.sqlite3", max_stations=40))
    second = create_app(Settings(workers=1, jobs_db=tmp_path / "b.sqlite3", max_stations=60))
    one, two = _probe(first), _probe(second)
    assert (one["settings"].max_stations, two["settings"].max_stations) == (40, 60)
    assert one["service"] is not two["service"]
