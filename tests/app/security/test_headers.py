"""app.security.headers: the security headers on every answer (an API answer, a problem, the
page, its files), each set once, the route's own policy kept; CORS closed by default (no CORS
header at all) and open only to the configured origins.

In process, through `in_process_client`s of different Settings (tests/app/conftest.py)."""

from __future__ import annotations

import asyncio
from collections.abc import Iterator, MutableMapping
from typing import Any

import httpx
import pytest

from app.routes.page import CONTENT_SECURITY_POLICY
from app.security import API_CONTENT_SECURITY_POLICY, SecurityHeadersMiddleware
from app.settings import Settings
from tests.app.conftest import in_process_client

ORIGIN = "https://wings.example.org"
ELSEWHERE = "https://elsewhere.example"
ALWAYS = {
    "x-content-type-options": "nosniff",
    "x-frame-options": "DENY",
    "referrer-policy": "no-referrer",
    "cross-origin-resource-policy": "same-origin",
}


@pytest.fixture(scope="module")
def open_to_one(tmp_path_factory: pytest.TempPathFactory) -> Iterator[httpx.Client]:
    """The app with FLEXWING_CORS_ORIGINS = [ORIGIN]."""
    db = tmp_path_factory.mktemp("cors") / "jobs.sqlite3"
    with in_process_client(Settings(workers=1, jobs_db=db, cors_origins=[ORIGIN])) as client:
        yield client


ANSWERS = {
    "an API answer": ("GET", "/healthz", 200, "application/json"),
    "the document": ("GET", "/openapi.json", 200, "application/json"),
    "a 404 problem": ("GET", "/no-such-thing", 404, "application/problem+json"),
    "a 422 problem": ("POST", "/solve", 422, "application/problem+json"),
    "a 503 not ready": ("GET", "/readyz", 503, "application/json"),
}


@pytest.mark.parametrize(
    ("method", "path", "status", "media_type"), list(ANSWERS.values()), ids=list(ANSWERS)
)
def test_api_answers_and_problems_carry_the_security_headers_and_allow_nothing(
    in_process: httpx.Client, method: str, path: str, status: int, media_type: str
) -> None:
    answer = in_process.request(method, path, json={} if method == "POST" else None)
    assert answer.status_code == status
    assert answer.headers["content-type"] == media_type
    for name, value in ALWAYS.items():
        assert answer.headers.get_list(name) == [value], name
    assert answer.headers.get_list("content-security-policy") == [API_CONTENT_SECURITY_POLICY]
    assert answer.headers["cache-control"] == "no-store"


def test_the_page_keeps_its_own_policy_and_its_files_may_be_cached(
    in_process: httpx.Client,
) -> None:
    page = in_process.get("/")
    assert page.status_code == 200
    assert page.headers.get_list("content-security-policy") == [CONTENT_SECURITY_POLICY]
    assert page.headers.get_list("x-content-type-options") == ["nosniff"]  # set once
    assert page.headers["cache-control"] == "no-cache"  # the page's own
    asset = in_process.get("/static/favicon.svg")
    assert asset.status_code == 200
    assert asset.headers["x-frame-options"] == "DENY"
    assert "no-store" not in asset.headers.get("cache-control", "")


def test_a_header_the_response_sets_itself_is_kept_and_not_doubled() -> None:
    async def inner(scope: Any, receive: Any, send: Any) -> None:
        headers = [(b"X-Frame-Options", b"SAMEORIGIN"), (b"cache-control", b"max-age=60")]
        await send({"type": "http.response.start", "status": 200, "headers": headers})
        await send({"type": "http.response.body", "body": b""})

    sent: list[MutableMapping[str, Any]] = []

    async def send(message: MutableMapping[str, Any]) -> None:
        sent.append(message)

    async def receive() -> dict[str, Any]:
        return {"type": "http.request", "body": b""}

    scope = {"type": "http", "method": "GET", "path": "/x", "headers": []}
    asyncio.run(SecurityHeadersMiddleware(inner)(scope, receive, send))
    headers = [(name.lower(), value) for name, value in sent[0]["headers"]]
    assert [v for n, v in headers if n == b"x-frame-options"] == [b"SAMEORIGIN"]
    assert [v for n, v in headers if n == b"cache-control"] == [b"max-age=60"]
    assert (b"x-content-type-options", b"nosniff") in headers


def _preflight(client: httpx.Client, origin: str) -> httpx.Response:
    return client.options(
        "/solve",
        headers={
            "Origin": origin,
            "Access-Control-Request-Method": "POST",
            "Access-Control-Request-Headers": "authorization, content-type",
        },
    )


def _has_cors(response: httpx.Response) -> bool:
    return any(name.lower().startswith("access-control-") for name in response.headers)


def test_cors_is_closed_by_default(in_process: httpx.Client) -> None:
    """No FLEXWING_CORS_ORIGINS: no CORS header on any answer, a preflight is not one."""
    answer = in_process.get("/healthz", headers={"Origin": ORIGIN})
    assert answer.status_code == 200 and not _has_cors(answer)
    preflight = _preflight(in_process, ORIGIN)
    assert preflight.status_code == 405 and not _has_cors(preflight)


def test_cors_opens_to_a_configured_origin(open_to_one: httpx.Client) -> None:
    preflight = _preflight(open_to_one, ORIGIN)
    assert preflight.status_code == 200
    assert preflight.headers["access-control-allow-origin"] == ORIGIN
    allowed = {
        h.strip().lower() for h in preflight.headers["access-control-allow-headers"].split(",")
    }
    assert {"authorization", "content-type"} <= allowed
    assert "POST" in preflight.headers["access-control-allow-methods"]
    assert preflight.headers["access-control-max-age"] == "600"
    # A problem answered to that origin can be read by its page, and says why.
    refused = open_to_one.post("/solve", json={}, headers={"Origin": ORIGIN})
    assert refused.status_code == 422
    assert refused.headers["access-control-allow-origin"] == ORIGIN
    exposed = refused.headers["access-control-expose-headers"].lower()
    assert {"location", "retry-after"} <= {h.strip() for h in exposed.split(",")}
    assert refused.headers["x-content-type-options"] == "nosniff"  # still outermost


def test_cors_stays_closed_to_any_other_origin(open_to_one: httpx.Client) -> None:
    preflight = _preflight(open_to_one, ELSEWHERE)
    assert preflight.status_code == 400
    assert "access-control-allow-origin" not in preflight.headers
    answer = open_to_one.get("/healthz", headers={"Origin": ELSEWHERE})
    assert "access-control-allow-origin" not in answer.headers


@pytest.mark.parametrize(
    "origins",
    [["*"], ["https://wings.example.org/app"], ["wings.example.org"]],
    ids=["wildcard", "with-a-path", "no-scheme"],
)
def test_only_an_origin_may_be_configured(origins: list[str]) -> None:
    with pytest.raises(ValueError, match="not an origin"):
        Settings(workers=1, cors_origins=origins)
