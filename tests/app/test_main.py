"""app.main: the ASGI application's own parts.

- BodyLimitMiddleware: a body over its limit is a 413 problem (/problems/body-too-large, with
  `max_body_bytes` and the setting to change) whether its size is declared (Content-Length,
  refused before a byte is read) or only streamed; a path may have a limit of its own (POST
  /jobs); a body within the limit reaches the app whole; other methods pass untouched.
- The OpenAPI document carries the limits of the running configuration where the schema marks
  them (`x-flexwing-limit`), and no marker is left.

In process: the middleware driven through raw ASGI messages, the app through `in_process_client`.
"""

from __future__ import annotations

import asyncio
import json
import re
from collections.abc import Iterator, MutableMapping
from pathlib import Path
from typing import Any

import httpx
import pytest

from app.main import BodyLimitMiddleware
from app.settings import Settings
from tests import study
from tests.app.conftest import in_process_client

LIMIT = 100  # [bytes] the default limit of the middleware under test
JOBS_LIMIT = 1000  # [bytes] /jobs' own


class Inner:
    """The app behind the middleware: records the body it was handed, answers 200."""

    def __init__(self) -> None:
        self.bodies: list[bytes] = []

    async def __call__(self, scope: Any, receive: Any, send: Any) -> None:
        body = b""
        if scope["method"] in ("POST", "PUT", "PATCH"):
            while True:
                message = await receive()
                body += message.get("body", b"")
                if not message.get("more_body", False):
                    break
        self.bodies.append(body)
        await send({"type": "http.response.start", "status": 200, "headers": []})
        await send({"type": "http.response.body", "body": b"ok"})


def _exchange(
    chunks: list[bytes], *, path: str = "/solve", method: str = "POST", declare: bool = True
) -> tuple[int, dict[str, Any] | None, Inner, int]:
    """Send a request of `chunks` through the middleware: (status, problem body or None, the
    inner app, how many chunks the middleware read)."""
    inner = Inner()
    middleware = BodyLimitMiddleware(
        inner, limit=LIMIT, path_limits={"/jobs": (JOBS_LIMIT, "FLEXWING_MAX_JOB_BODY_BYTES")}
    )
    headers = [(b"content-type", b"application/json")]
    if declare:
        headers.append((b"content-length", str(sum(map(len, chunks))).encode()))
    scope = {"type": "http", "method": method, "path": path, "headers": headers}
    pending: Iterator[bytes] = iter(chunks)
    read = 0

    async def receive() -> dict[str, Any]:
        nonlocal read
        chunk = next(pending, None)
        if chunk is None:
            return {"type": "http.disconnect"}
        read += 1
        return {"type": "http.request", "body": chunk, "more_body": read < len(chunks)}

    sent: list[MutableMapping[str, Any]] = []

    async def send(message: MutableMapping[str, Any]) -> None:
        sent.append(message)

    asyncio.run(middleware(scope, receive, send))
    status = sent[0]["status"]
    body = b"".join(m.get("body", b"") for m in sent[1:])
    problem = json.loads(body) if status != 200 else None
    return status, problem, inner, read


def _assert_too_large(problem: dict[str, Any] | None, limit: int, setting: str) -> None:
    assert problem is not None
    assert (problem["type"], problem["status"]) == ("/problems/body-too-large", 413)
    assert problem["max_body_bytes"] == limit
    assert f"at most {limit} are accepted ({setting})" in problem["detail"]


def test_a_declared_body_over_the_limit_is_413_before_a_byte_is_read() -> None:
    status, problem, inner, read = _exchange([b"x" * (LIMIT + 1)])
    assert status == 413 and read == 0 and inner.bodies == []
    _assert_too_large(problem, LIMIT, "FLEXWING_MAX_BODY_BYTES")
    assert problem is not None and f"has {LIMIT + 1} bytes" in problem["detail"]


def test_a_streamed_body_over_the_limit_is_413_once_it_passes_it() -> None:
    """No Content-Length: read until the limit is passed (here in the third of five chunks of
    40 bytes), not to the end."""
    status, problem, inner, read = _exchange([b"x" * 40] * 5, declare=False)
    assert status == 413 and read == 3 and inner.bodies == []
    _assert_too_large(problem, LIMIT, "FLEXWING_MAX_BODY_BYTES")
    assert problem is not None and f"has more than {LIMIT} bytes" in problem["detail"]


@pytest.mark.parametrize("declare", [True, False], ids=["declared", "streamed"])
def test_a_body_at_the_limit_reaches_the_app_whole(declare: bool) -> None:
    chunks = [b"a" * 60, b"b" * (LIMIT - 60)]
    status, problem, inner, _ = _exchange(chunks, declare=declare)
    assert status == 200 and problem is None
    assert inner.bodies == [b"".join(chunks)]


@pytest.mark.parametrize(
    ("size", "status"), [(JOBS_LIMIT, 200), (JOBS_LIMIT + 1, 413)], ids=["at", "over"]
)
@pytest.mark.parametrize("declare", [True, False], ids=["declared", "streamed"])
def test_a_path_with_a_limit_of_its_own_is_held_to_it(
    size: int, status: int, declare: bool
) -> None:
    answered, problem, inner, _ = _exchange([b"x" * size], path="/jobs", declare=declare)
    assert answered == status
    if status == 413:
        _assert_too_large(problem, JOBS_LIMIT, "FLEXWING_MAX_JOB_BODY_BYTES")
    else:
        assert inner.bodies == [b"x" * size]  # over the default limit, within its own


def test_a_request_without_a_body_method_passes_untouched() -> None:
    """GET (and DELETE) are not read: the app sees the request as it came."""
    status, _, inner, read = _exchange([b"x" * (LIMIT + 1)], method="GET")
    assert status == 200 and read == 0 and inner.bodies == [b""]


# --------------------------------------------------------------------------- the app


@pytest.fixture(scope="module")
def limited(tmp_path_factory: pytest.TempPathFactory) -> Iterator[httpx.Client]:
    """The app with small limits: 40 stations, 7 sweep points, 2 kB bodies (20 kB for jobs)."""
    settings = Settings(
        workers=1,
        jobs_db=tmp_path_factory.mktemp("limited") / "jobs.sqlite3",
        max_stations=40,
        max_sweep_points=7,
        max_body_bytes=2048,
        max_job_body_bytes=20_480,
        max_batch_items=20,
    )
    with in_process_client(settings) as client:
        yield client


def test_the_app_refuses_a_body_over_its_configured_limit(limited: httpx.Client) -> None:
    body = study.solve_request(10.0)  # ~2.6 kB of JSON
    assert 2048 < len(json.dumps(body)) < 20_480
    refused = limited.post("/solve", json=body)
    assert refused.status_code == 413
    assert refused.headers["content-type"] == "application/problem+json"
    assert refused.json()["max_body_bytes"] == 2048
    # The same body as a job is within FLEXWING_MAX_JOB_BODY_BYTES: it gets past the limit.
    job = limited.post("/jobs", json={"operation": "solve", "request": body, "x": 1})
    assert job.status_code == 422, job.text


def _markers(node: Any) -> int:
    return len(re.findall(r'"x-flexwing-limit"', json.dumps(node)))


def test_the_document_carries_the_configured_limits_where_marked(limited: httpx.Client) -> None:
    document = limited.get("/openapi.json").json()
    assert _markers(document) == 0
    schemas = document["components"]["schemas"]
    y_list, spacing = schemas["Wing"]["properties"]["y"]["oneOf"]
    assert y_list["maxItems"] == 40
    assert spacing == {"$ref": "#/components/schemas/StationSpacing"}
    assert schemas["StationSpacing"]["properties"]["stations"]["maximum"] == 40
    chord_list = schemas["Wing"]["properties"]["chord"]["oneOf"][1]
    assert (chord_list["type"], chord_list["maxItems"]) == ("array", 40)
    velocities = schemas["SweepRequest"]["properties"]["velocities"]["oneOf"][0]
    assert velocities["maxItems"] == 7
    assert schemas["VelocityRange"]["properties"]["count"]["maximum"] == 7


def test_every_station_list_of_the_document_has_the_configured_limit(
    limited: httpx.Client, tmp_path: Path
) -> None:
    """Every array the default document bounds at the default 150 stations is bounded at 40 in
    the document of a service with 40, and no other bound changes."""
    with in_process_client(Settings(workers=1, jobs_db=tmp_path / "jobs.sqlite3")) as default:
        default_text = json.dumps(default.get("/openapi.json").json())
    text = json.dumps(limited.get("/openapi.json").json())
    for bound in ("maxItems", "maximum"):
        gained = text.count(f'"{bound}": 40') - default_text.count(f'"{bound}": 40')
        lost = default_text.count(f'"{bound}": 150') - text.count(f'"{bound}": 150')
        assert gained == lost > 0, bound
    assert default_text.count('"maxItems": 150') > 10  # every per-station list, every model


def test_the_document_carries_the_configured_batch_limit(limited: httpx.Client) -> None:
    schemas = limited.get("/openapi.json").json()["components"]["schemas"]
    assert schemas["BatchRequest"]["properties"]["items"]["maxItems"] == 20
