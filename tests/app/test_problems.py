"""app.problems: every error is a problem+json answer, an unexpected one (a bug) included."""

from __future__ import annotations

import asyncio

import httpx
import pytest
from fastapi import FastAPI

from app import security
from app.problems import PROBLEM_MEDIA_TYPE, install_handlers, validation_errors
from app.settings import Settings


def _app_with_a_bug() -> FastAPI:
    app = FastAPI()
    install_handlers(app)

    @app.get("/bug")
    async def bug() -> None:
        raise RuntimeError("a defect")

    @app.get("/fine")
    async def fine() -> dict[str, bool]:
        return {"fine": True}

    security.install_headers(app, Settings())
    return app


def test_an_unexpected_error_is_a_500_problem_with_the_security_headers() -> None:
    async def ask() -> tuple[httpx.Response, httpx.Response]:
        # raise_app_exceptions (the default): an exception that left the app would raise here.
        transport = httpx.ASGITransport(app=_app_with_a_bug())
        async with httpx.AsyncClient(transport=transport, base_url="http://test") as client:
            return await client.get("/bug"), await client.get("/fine")

    bug, fine = asyncio.run(ask())
    assert bug.status_code == 500
    assert bug.headers["content-type"] == PROBLEM_MEDIA_TYPE
    assert bug.json() == {
        "type": "/problems/internal-error",
        "title": "Internal error",
        "status": 500,
        "detail": "unexpected RuntimeError",
        "instance": "/bug",
    }
    for response in (bug, fine):
        assert response.headers["x-content-type-options"] == "nosniff"
        assert response.headers["cache-control"] == "no-store"
    assert fine.json() == {"fine": True}


@pytest.mark.parametrize(
    ("loc", "field"),
    [
        (("body", "wing", "chord", 3), "wing.chord[3]"),
        (("body", "wing", "elastic_axis", "@list", 1), "wing.elastic_axis[1]"),
        (("body", "velocities", "@range", "count"), "velocities.count"),
        (("body",), "body"),
    ],
)
def test_validation_error_paths(loc: tuple[object, ...], field: str) -> None:
    errors = validation_errors([{"loc": loc, "msg": "bad", "type": "x"}])
    assert [(e.field, e.reason) for e in errors] == [(field, "bad")]
