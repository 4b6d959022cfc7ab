"""Any concurrent.futures.Executor can replace the process pool by configuration."""

from __future__ import annotations

import asyncio

import httpx
import pytest

from app.main import create_app
from app.settings import Settings
from tests import study


async def _solve_in_process(settings: Settings) -> tuple[dict, httpx.Response]:
    app = create_app(settings)
    async with app.router.lifespan_context(app):
        assert await app.state.pool.wait_ready(timeout=120)
        transport = httpx.ASGITransport(app=app)
        async with httpx.AsyncClient(transport=transport, base_url="http://app") as client:
            ready = (await client.get("/readyz")).json()
            return ready, await client.post("/solve", json=study.solve_request(10.0))


@pytest.mark.server  # warms a pool: compiles N = 30 on a machine without the library
def test_a_configured_executor_serves_solves() -> None:
    settings = Settings(workers=1, executor="tests.app.executors:threads")
    ready, response = asyncio.run(_solve_in_process(settings))
    assert ready["ready"] is True
    assert ready["pids"] == []  # no local processes
    assert response.status_code == 200
    assert response.json()["totals"]["lift"] == pytest.approx(304.1, abs=0.05)


def test_a_malformed_executor_setting_is_refused() -> None:
    with pytest.raises(ValueError, match="module:callable"):
        asyncio.run(_solve_in_process(Settings(workers=1, executor="nonsense")))
