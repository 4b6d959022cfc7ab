"""Safe to share (issue 16), against real servers over real HTTP.

- API keys: with a key file every route but the probes, the page and the documentation is 401
  without a key (missing and wrong told apart, a wrong key's answer the same whatever the key),
  and works with one; jobs belong to the key that created them (another key gets 404, its list
  shows none of them); job ids are 128 random bits, unique and in no order.
- Rate limits: a client (a key, or an address without keys) over its bucket gets 429 with
  Retry-After while another is served; counted per key fingerprint, never the key.
- Security headers on the page, the API and the refusals; CORS closed unless origins are listed.
- Nothing secret in the logs: no key, no request body.
- The OpenAPI document declares the bearer scheme, and a client generated from it carries a key.

Servers (on CasADi's virtual machine, one worker each): `keyed_server` (keys, the default rate
limits, one CORS origin, uvicorn logging at debug level), `limited_server` (keys, a bucket of 5
refilled every 100 s) and `open_server` (no keys, the same small bucket, CORS by default).
"""

from __future__ import annotations

import asyncio
import base64
import itertools
import json
import secrets
import sqlite3
import statistics
from collections import Counter
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import httpx
import pytest
from fastapi.routing import APIRoute
from starlette.routing import BaseRoute, Mount, Route

from app.jobs.store import Store, new_job_id
from app.main import create_app
from app.security.keys import add_key, digest
from app.settings import Settings
from openapi.generate import PATH as OPENAPI_PATH
from tests import study
from tests.app.conftest import Server
from tests.app.routes.test_health import generated_client  # noqa: F401 (a fixture)

ORIGIN = "https://wings.example.org"  # the one origin keyed_server lets call it
HANG_GUARD = 120.0  # [s] only a hang fails on it


@dataclass(frozen=True)
class Keys:
    file: Path
    alice: str
    bob: str

    @staticmethod
    def fingerprint(key: str) -> str:
        return digest(key).hex()[:8]


def bearer(key: str) -> dict[str, str]:
    return {"Authorization": f"Bearer {key}"}


def from_address(server: Server, address: str, **options: Any) -> httpx.Client:
    """A client of `server` whose requests come from `address` (127.0.0.0/8 is all this
    machine's): a client address of its own, for the rate limits without keys."""
    transport = httpx.HTTPTransport(local_address=address)
    return httpx.Client(base_url=server.base_url, transport=transport, timeout=60, **options)


@pytest.fixture(scope="module")
def keys(tmp_path_factory: pytest.TempPathFactory) -> Keys:
    file = tmp_path_factory.mktemp("keys") / "keys.txt"
    return Keys(file, add_key(file, "alice"), add_key(file, "bob"))


def _env(tmp: Path, **settings: str) -> dict[str, str]:
    """A server on the virtual machine (no compilation), one worker, its own jobs database."""
    return {
        "FLEXWING_COMPILE": "0",
        "FLEXWING_CACHE_DIR": str(tmp / "cache"),
        "FLEXWING_WORKERS": "1",
        "FLEXWING_JOBS_DB": str(tmp / "jobs.sqlite3"),
        **settings,
    }


@pytest.fixture(scope="module")
def keyed_server(
    make_server: Callable[..., Server], keys: Keys, tmp_path_factory: pytest.TempPathFactory
) -> Server:
    env = _env(
        tmp_path_factory.mktemp("keyed"),
        FLEXWING_API_KEYS_FILE=str(keys.file),
        FLEXWING_CORS_ORIGINS=json.dumps([ORIGIN]),
    )
    return make_server("keyed_server", log_level="debug", **env)


SMALL_BUCKET = {"FLEXWING_RATE_BURST": "5", "FLEXWING_RATE_LIMIT": "0.01"}  # a token per 100 s


@pytest.fixture(scope="module")
def limited_server(
    make_server: Callable[..., Server], keys: Keys, tmp_path_factory: pytest.TempPathFactory
) -> Server:
    env = _env(tmp_path_factory.mktemp("limited"), FLEXWING_API_KEYS_FILE=str(keys.file))
    return make_server("limited_server", **env, **SMALL_BUCKET)


@pytest.fixture(scope="module")
def open_server(
    make_server: Callable[..., Server], tmp_path_factory: pytest.TempPathFactory
) -> Server:
    return make_server("open_server", **_env(tmp_path_factory.mktemp("open"), **SMALL_BUCKET))


@pytest.fixture
def alice(keyed_server: Server, keys: Keys) -> Iterator[httpx.Client]:
    with httpx.Client(base_url=keyed_server.base_url, headers=bearer(keys.alice), timeout=60) as c:
        yield c


@pytest.fixture
def bob(keyed_server: Server, keys: Keys) -> Iterator[httpx.Client]:
    with httpx.Client(base_url=keyed_server.base_url, headers=bearer(keys.bob), timeout=60) as c:
        yield c


@pytest.fixture
def nobody(keyed_server: Server) -> Iterator[httpx.Client]:
    with keyed_server.client() as c:
        yield c


def finished(client: httpx.Client, location: str) -> dict[str, Any]:
    """The job's final state, from its event stream (one request, however long it runs)."""
    with client.stream("GET", location + "/events", timeout=HANG_GUARD) as stream:
        assert stream.status_code == 200
        events = [line for line in stream.iter_lines() if line.startswith("data: ")]
    return dict(json.loads(events[-1].removeprefix("data: ")))


BATCH = {"operation": "batch", "request": {"items": [study.solve_request(v) for v in (8, 9)]}}


@pytest.fixture(scope="module")
def alices_job(keyed_server: Server, keys: Keys) -> str:
    """A finished batch job of alice's: its id."""
    with httpx.Client(base_url=keyed_server.base_url, headers=bearer(keys.alice)) as client:
        response = client.post("/jobs", json=BATCH)
        assert response.status_code == 202, response.text
        assert finished(client, response.headers["location"])["status"] == "succeeded"
        return str(response.json()["id"])


# ----------------------------------------------------------------------- routes and keys

# Served without a key with keys on: the probes, and what a browser loads before a key can be
# typed (the page, its files, the documentation, the problem types). Nothing of a user's.
PUBLIC = {"/healthz", "/readyz", "/", "/docs", "/openapi.json", "/problems/{slug}", "/static"}


def _routes() -> list[tuple[str, str]]:
    """(method, path template) of every route of the app, HEAD aside; /static as one file."""
    found: set[tuple[str, str]] = set()

    def walk(routes: list[BaseRoute], prefix: str) -> None:
        for route in routes:
            included = getattr(route, "original_router", None)  # FastAPI's included routers
            if included is not None:
                walk(included.routes, prefix + route.include_context.prefix)  # type: ignore[attr-defined]
            elif isinstance(route, Mount):
                found.add(("GET", prefix + route.path))
            elif isinstance(route, Route | APIRoute):
                found.update((m, prefix + route.path) for m in route.methods or () if m != "HEAD")

    walk(create_app(Settings(workers=1)).routes, "")
    return sorted(found)


ROUTES = _routes()
ROUTE_IDS = [f"{method} {path}" for method, path in ROUTES]

# A request each route answers with success, and that success; a route missing here (a new one)
# is still checked: 401 without a key, anything but 401 with one.
SUCCESS: dict[tuple[str, str], tuple[dict[str, Any], int]] = {
    ("POST", "/solve"): ({"json": study.solve_request(10.0)}, 200),
    ("POST", "/sweep"): (
        {"json": {"wing": study.wing_json(), "flight": {"alpha": 5.0}, "velocities": [6, 10]}},
        200,
    ),
    ("POST", "/jobs"): ({"json": BATCH}, 202),
    ("GET", "/jobs"): ({}, 200),
    ("GET", "/jobs/{job_id}"): ({}, 200),
    ("DELETE", "/jobs/{job_id}"): ({}, 200),  # finished: it stays as it is
    ("GET", "/jobs/{job_id}/events"): ({}, 200),
    ("GET", "/jobs/{job_id}/items.ndjson"): ({}, 200),
    ("GET", "/metrics"): ({}, 200),
    ("GET", "/openapi.json"): ({}, 200),
    ("GET", "/healthz"): ({}, 200),
    ("GET", "/readyz"): ({}, 200),
    ("GET", "/"): ({}, 200),
    ("GET", "/docs"): ({}, 200),
    ("GET", "/problems/{slug}"): ({}, 200),
    ("GET", "/static"): ({}, 200),
}


def _url(path: str, job_id: str) -> str:
    return (
        path.replace("{job_id}", job_id)
        .replace("{slug}", "key-missing")
        .replace("/static", "/static/js/main.js")
    )


def test_the_public_routes_are_the_probes_the_page_and_the_documentation() -> None:
    served = {path for _, path in ROUTES}
    assert served >= PUBLIC


@pytest.mark.parametrize(("method", "path"), ROUTES, ids=ROUTE_IDS)
def test_with_keys_on_a_route_without_a_key_is_401_unless_public(
    nobody: httpx.Client, alices_job: str, method: str, path: str
) -> None:
    request, _ = SUCCESS.get((method, path), ({}, 0))
    response = nobody.request(method, _url(path, alices_job), **request)
    if path in PUBLIC:
        assert response.status_code == 200
        return
    assert response.status_code == 401, response.text
    assert response.headers["content-type"] == "application/problem+json"
    assert response.headers["www-authenticate"] == 'Bearer realm="flexwing"'
    problem = response.json()
    assert problem["type"] == "/problems/key-missing"
    assert problem["status"] == 401


@pytest.mark.parametrize(("method", "path"), ROUTES, ids=ROUTE_IDS)
def test_with_keys_on_a_route_with_a_key_works(
    alice: httpx.Client, alices_job: str, method: str, path: str
) -> None:
    request, status = SUCCESS.get((method, path), ({}, 0))
    response = alice.request(method, _url(path, alices_job), **request)
    if status:
        assert response.status_code == status, response.text
    else:
        assert response.status_code != 401, response.text


WRONG_KEYS = {
    "a random key": "fw_" + secrets.token_urlsafe(32),
    "junk": "not-a-key",
    "very long": "x" * 4000,
}


@pytest.fixture
def wrong_keys(keys: Keys) -> dict[str, str]:
    """Keys that are not the service's, some close to one that is."""
    return WRONG_KEYS | {
        "a real key, last character changed": keys.alice[:-1]
        + ("A" if keys.alice[-1] != "A" else "B"),
        "a real key without its prefix": keys.alice.removeprefix("fw_"),
        "a real key's stored digest": digest(keys.alice).hex(),
    }


def test_a_wrong_key_is_401_and_the_answer_is_the_same_whatever_the_key(
    nobody: httpx.Client, wrong_keys: dict[str, str]
) -> None:
    answers = {}
    for name, key in wrong_keys.items():
        response = nobody.get("/jobs", headers=bearer(key))
        assert response.status_code == 401, name
        assert response.headers["www-authenticate"] == (
            'Bearer realm="flexwing", error="invalid_token"'
        )
        answers[name] = response.json()
    assert answers["a random key"]["type"] == "/problems/key-invalid"
    assert all(answer == answers["a random key"] for answer in answers.values()), answers
    for key in wrong_keys.values():
        assert key not in json.dumps(answers["a random key"])


AUTHORIZATIONS = {
    "no header": None,
    "the scheme alone": "Bearer",
    "another scheme": "Basic YWxpY2U6c2VjcmV0",
    "a bare key": "fw_" + secrets.token_urlsafe(32),
}


@pytest.mark.parametrize("header", list(AUTHORIZATIONS.values()), ids=list(AUTHORIZATIONS))
def test_a_request_without_a_bearer_key_is_told_its_key_is_missing(
    nobody: httpx.Client, header: str | None
) -> None:
    headers = {} if header is None else {"Authorization": header}
    response = nobody.get("/jobs", headers=headers)
    assert response.status_code == 401
    assert response.json()["type"] == "/problems/key-missing"


def test_the_bearer_scheme_is_case_insensitive(nobody: httpx.Client, keys: Keys) -> None:
    assert nobody.get("/jobs", headers={"Authorization": f"bearer {keys.alice}"}).status_code == 200


# --------------------------------------------------------------------------- jobs and keys

ACTIONS = {
    "read": ("GET", ""),
    "follow its events": ("GET", "/events"),
    "stream its items": ("GET", "/items.ndjson"),
    "cancel": ("DELETE", ""),
}


@pytest.mark.parametrize(("method", "suffix"), list(ACTIONS.values()), ids=list(ACTIONS))
def test_a_second_key_cannot_touch_the_first_keys_job(
    alice: httpx.Client, bob: httpx.Client, alices_job: str, method: str, suffix: str
) -> None:
    """Bob gets exactly what a job that does not exist gets: 404, not 403."""
    unknown = new_job_id()
    theirs = bob.request(method, f"/jobs/{alices_job}{suffix}")
    nothing = bob.request(method, f"/jobs/{unknown}{suffix}")
    assert theirs.status_code == nothing.status_code == 404
    assert theirs.headers["content-type"] == "application/problem+json"
    assert theirs.json()["detail"].replace(alices_job, "ID") == (
        nothing.json()["detail"].replace(unknown, "ID")
    )
    assert alice.request(method, f"/jobs/{alices_job}{suffix}").status_code == 200


def test_a_second_key_cannot_cancel_the_first_keys_running_job(
    alice: httpx.Client, bob: httpx.Client
) -> None:
    items = [
        {
            "wing": study.wing_json(n=60, stiffness_scale=1 + 0.01 * i),
            "flight": {"velocity": 10, "alpha": 5},
        }
        for i in range(10)
    ]  # ~0.2 s each on the virtual machine: bob asks while it runs
    response = alice.post("/jobs", json={"operation": "batch", "request": {"items": items}})
    assert response.status_code == 202
    location = response.headers["location"]
    assert bob.delete(location).status_code == 404
    job = finished(alice, location)
    assert job["status"] == "succeeded"
    assert job["progress"]["done"] == 10


def test_a_listing_shows_only_ones_own_jobs(
    alice: httpx.Client, bob: httpx.Client, alices_job: str
) -> None:
    sweep = {"wing": study.wing_json(), "flight": {"alpha": 5.0}, "velocities": [6, 10]}
    bobs = bob.post("/sweep", json=sweep, headers={"Prefer": "respond-async"})
    assert bobs.status_code == 202
    alices_ids = {job["id"] for job in alice.get("/jobs", params={"limit": 200}).json()["jobs"]}
    bobs_ids = {job["id"] for job in bob.get("/jobs", params={"limit": 200}).json()["jobs"]}
    assert alices_job in alices_ids
    assert bobs.json()["id"] in bobs_ids
    assert not alices_ids & bobs_ids
    assert bob.get(bobs.headers["location"]).status_code == 200
    assert alice.get(bobs.headers["location"]).status_code == 404


# A jobs database from before API keys (its jobs table without `principal`).
OLD_JOBS_TABLE = """
CREATE TABLE jobs (
    id TEXT PRIMARY KEY, operation TEXT NOT NULL, status TEXT NOT NULL, owner TEXT NOT NULL,
    created REAL NOT NULL, started REAL, finished REAL, expires REAL,
    done INTEGER NOT NULL DEFAULT 0, total INTEGER NOT NULL, problems INTEGER NOT NULL DEFAULT 0,
    result TEXT, problem TEXT
);
INSERT INTO jobs (id, operation, status, owner, created, total)
    VALUES ('old-job', 'solve', 'succeeded', 'gone', 1.0, 1);
"""


def test_jobs_from_before_keys_are_kept_and_belong_to_no_key(tmp_path: Path) -> None:
    database = tmp_path / "jobs.sqlite3"
    with sqlite3.connect(database) as connection:
        connection.executescript(OLD_JOBS_TABLE)

    async def listed() -> tuple[list[str], list[str]]:
        jobs = Store.of(None, database)
        await jobs.open()  # adds the column
        try:
            anyone = await jobs.list_jobs(10, None, None, 0.0, "")
            a_key = await jobs.list_jobs(10, None, None, 0.0, digest("fw_x").hex())
        finally:
            await jobs.close()
        return [row["id"] for row in anyone], [row["id"] for row in a_key]

    assert asyncio.run(listed()) == (["old-job"], [])


# --------------------------------------------------------------------------------- job ids


def test_job_ids_are_128_random_bits_unique_and_in_no_order() -> None:
    ids = [new_job_id() for _ in range(10_000)]  # what the jobs store gives every job
    assert len(set(ids)) == len(ids)
    raw = [base64.urlsafe_b64decode(i + "==") for i in ids]
    assert {len(i) for i in ids} == {22} and {len(r) for r in raw} == {16}  # 128 bits >= 122
    # Each of the 128 bits is 1 in about half the ids (binomial: sd 50 of 10,000; 6 sd allowed).
    numbers = [int.from_bytes(r, "big") for r in raw]
    ones = [sum(n >> bit & 1 for n in numbers) for bit in range(128)]
    assert all(abs(count - 5000) < 300 for count in ones), ones
    # No order: a later id is larger about half the time, and rank follows creation not at all.
    rises = sum(b > a for a, b in itertools.pairwise(ids))
    assert abs(rises - 5000) < 300
    ranks = {job_id: rank for rank, job_id in enumerate(sorted(ids))}
    assert abs(statistics.correlation(list(range(len(ids))), [ranks[i] for i in ids])) < 0.06
    # No shared stems: no two ids agree on their first 8 characters (48 bits).
    assert len({i[:8] for i in ids}) == len(ids)


@pytest.mark.parametrize("which", ["keys on", "keys off"])
def test_a_jobs_id_over_http_is_22_characters_of_128_bits(
    which: str, keyed_server: Server, open_server: Server, keys: Keys
) -> None:
    server, headers = (keyed_server, bearer(keys.bob)) if which == "keys on" else (open_server, {})
    with from_address(server, "127.0.0.3", headers=headers) as client:
        response = client.post(
            "/jobs", json={"operation": "solve", "request": study.solve_request(7)}
        )
        assert response.status_code == 202, response.text
        job_id = response.json()["id"]
    assert len(job_id) == 22
    assert len(base64.urlsafe_b64decode(job_id + "==")) == 16


# ------------------------------------------------------------------------------ rate limits


@dataclass
class Pair:
    """Two clients of one server: `greedy` drains its bucket, `other` must still be served."""

    greedy: httpx.Client
    other: httpx.Client
    label: str  # greedy's metrics label
    metrics: httpx.Client  # who reads /metrics


@pytest.fixture(params=["two keys", "two addresses without keys"])
def pair(
    request: pytest.FixtureRequest, keys: Keys, limited_server: Server, open_server: Server
) -> Iterator[Pair]:
    if request.param == "two keys":
        url = limited_server.base_url
        greedy = httpx.Client(base_url=url, headers=bearer(keys.alice), timeout=60)
        other = httpx.Client(base_url=url, headers=bearer(keys.bob), timeout=60)
        label = Keys.fingerprint(keys.alice)
    else:
        greedy = from_address(open_server, "127.0.0.5")
        other = from_address(open_server, "127.0.0.6")
        label = "anonymous"
    with greedy, other:
        yield Pair(greedy, other, label, other)


def test_a_client_over_its_rate_gets_429_while_another_is_served(pair: Pair) -> None:
    answers = [pair.greedy.get("/jobs").status_code for _ in range(5)]  # its burst
    assert answers == [200] * 5
    refused = pair.greedy.get("/jobs")
    assert refused.status_code == 429
    assert refused.headers["content-type"] == "application/problem+json"
    assert 1 <= int(refused.headers["retry-after"]) <= 100  # a token per 100 s
    problem = refused.json()
    assert problem["type"] == "/problems/rate-limited"
    assert (problem["rate_limit"], problem["burst"]) == (0.01, 5)
    assert pair.other.get("/jobs").status_code == 200
    assert pair.greedy.get("/healthz").status_code == 200  # probes are never limited
    assert pair.greedy.get("/readyz").status_code == 200
    refusals = pair.metrics.get("/metrics").text
    line = f'flexwing_client_refusals_total{{key_fingerprint="{pair.label}",reason="rate-limited"}}'
    assert any(
        row.startswith(line) and float(row.split()[-1]) >= 1 for row in refusals.splitlines()
    )


def test_rate_limited_and_overloaded_are_different_problems(nobody: httpx.Client) -> None:
    limited = nobody.get("/problems/rate-limited").json()
    overloaded = nobody.get("/problems/overloaded").json()
    assert (limited["status"], overloaded["status"]) == (429, 503)
    assert "overloaded" in limited["description"]


def test_metrics_count_requests_and_refusals_by_fingerprint_never_the_key(
    keyed_server: Server, keys: Keys, nobody: httpx.Client
) -> None:
    fingerprint = Keys.fingerprint(keys.bob)
    before = keyed_server.metric(
        "flexwing_client_requests_total", key=keys.alice, key_fingerprint=fingerprint
    )
    missing = keyed_server.metric(
        "flexwing_client_refusals_total",
        key=keys.alice,
        key_fingerprint="anonymous",
        reason="key-missing",
    )
    with httpx.Client(base_url=keyed_server.base_url, headers=bearer(keys.bob)) as bob:
        for _ in range(3):
            assert bob.get("/jobs").status_code == 200
    assert nobody.get("/jobs").status_code == 401
    assert (
        keyed_server.metric(
            "flexwing_client_requests_total", key=keys.alice, key_fingerprint=fingerprint
        )
        == before + 3
    )
    assert (
        keyed_server.metric(
            "flexwing_client_refusals_total",
            key=keys.alice,
            key_fingerprint="anonymous",
            reason="key-missing",
        )
        == missing + 1
    )
    text = httpx.get(keyed_server.base_url + "/metrics", headers=bearer(keys.alice)).text
    for secret in (keys.alice, keys.bob, digest(keys.alice).hex(), digest(keys.bob).hex()[:16]):
        assert secret not in text


# -------------------------------------------------------------------------- headers, CORS

PAGE_PATHS = {"/", "/docs"}
RESPONSES = {
    "the page": ("GET", "/", None),
    "the documentation": ("GET", "/docs", None),
    "a static file": ("GET", "/static/js/main.js", None),
    "healthz": ("GET", "/healthz", None),
    "a solve": ("POST", "/solve", study.solve_request(10.0)),
    "the job list": ("GET", "/jobs", None),
    "the OpenAPI document": ("GET", "/openapi.json", None),
    "a 404": ("GET", "/no-such-thing", None),
    "a 422": ("POST", "/solve", {"wing": {}}),
}


@pytest.mark.parametrize(("method", "path", "body"), list(RESPONSES.values()), ids=list(RESPONSES))
def test_every_answer_carries_the_security_headers(
    alice: httpx.Client, method: str, path: str, body: Any
) -> None:
    response = alice.request(method, path, json=body)
    _assert_security_headers(response, page=path in PAGE_PATHS)


def test_refusals_carry_the_security_headers_too(nobody: httpx.Client, pair: Pair) -> None:
    _assert_security_headers(nobody.get("/jobs"), page=False)  # 401
    for _ in range(6):
        limited = pair.greedy.get("/openapi.json")
    assert limited.status_code == 429
    _assert_security_headers(limited, page=False)


def _assert_security_headers(response: httpx.Response, *, page: bool) -> None:
    headers = response.headers
    assert headers["x-content-type-options"] == "nosniff"
    assert headers["x-frame-options"] == "DENY"
    assert headers["referrer-policy"] == "no-referrer"
    policy = {
        directive.split()[0]: directive.split()[1:]
        for directive in headers["content-security-policy"].split(";")
    }
    assert policy["frame-ancestors"] == ["'none'"]
    # Only the app's own origin (a page) or nothing at all (data): no inline code, no eval, no
    # other origin.
    assert policy["default-src"] == (["'self'"] if page else ["'none'"])
    for sources in policy.values():
        assert not {"'unsafe-inline'", "'unsafe-eval'", "*", "http:", "https:"} & set(sources)
    if not page and not response.url.path.startswith("/static/"):
        assert headers["cache-control"] == "no-store"


def test_cors_is_closed_by_default(open_server: Server) -> None:
    origin = {"Origin": "https://elsewhere.example"}
    with from_address(open_server, "127.0.0.4") as client:
        assert "access-control-allow-origin" not in client.get("/healthz", headers=origin).headers
        preflight = client.options(
            "/solve", headers=origin | {"Access-Control-Request-Method": "POST"}
        )
        assert "access-control-allow-origin" not in preflight.headers


def test_cors_opens_to_the_listed_origins_only(nobody: httpx.Client, alice: httpx.Client) -> None:
    ask = {
        "Access-Control-Request-Method": "POST",
        "Access-Control-Request-Headers": "authorization, content-type",
    }
    preflight = nobody.options("/solve", headers={"Origin": ORIGIN} | ask)  # no key needed
    assert preflight.status_code == 200
    assert preflight.headers["access-control-allow-origin"] == ORIGIN
    assert "authorization" in preflight.headers["access-control-allow-headers"].lower()
    answer = alice.post("/solve", json=study.solve_request(10.0), headers={"Origin": ORIGIN})
    assert answer.status_code == 200
    assert answer.headers["access-control-allow-origin"] == ORIGIN
    refused = nobody.get("/jobs", headers={"Origin": ORIGIN})  # a page can read why
    assert refused.status_code == 401
    assert refused.headers["access-control-allow-origin"] == ORIGIN
    assert "retry-after" in refused.headers["access-control-expose-headers"].lower()

    elsewhere = {"Origin": "https://elsewhere.example"}
    assert (
        "access-control-allow-origin"
        not in nobody.options("/solve", headers=elsewhere | ask).headers
    )
    answer = alice.post("/solve", json=study.solve_request(10.0), headers=elsewhere)
    assert "access-control-allow-origin" not in answer.headers


# ------------------------------------------------------------------------------------ logs


def test_nothing_secret_reaches_the_log(
    keyed_server: Server, keys: Keys, alice: httpx.Client, nobody: httpx.Client
) -> None:
    marker = f"body-marker-{secrets.token_hex(8)}"
    wrong = "fw_" + secrets.token_urlsafe(32)
    request = study.solve_request(10.0)
    assert alice.post("/solve", json=request | {"note": marker}).status_code == 422
    assert alice.post("/solve", json=request).status_code == 200
    assert nobody.get("/jobs", headers=bearer(wrong)).status_code == 401
    job = alice.post("/jobs", json={"operation": "solve", "request": request | {"note": marker}})
    assert job.status_code == 422
    log = keyed_server.log.read_text()
    assert '"POST /solve HTTP/1.1" 200' in log  # uvicorn logs every request (debug level)
    for secret in (keys.alice, keys.bob, wrong, marker, digest(keys.alice).hex()):
        assert secret not in log
    assert "Bearer" not in log


# -------------------------------------------------------------------------- the document


def test_the_committed_document_declares_an_optional_bearer_key(alice: httpx.Client) -> None:
    committed = json.loads(OPENAPI_PATH.read_text())
    live = alice.get("/openapi.json").json()  # keys on
    for document in (committed, live):
        scheme = document["components"]["securitySchemes"]["apiKey"]
        assert (scheme["type"], scheme["scheme"]) == ("http", "bearer")
        for path, item in document["paths"].items():
            for operation in item.values():
                if path in ("/healthz", "/readyz"):
                    assert operation["security"] == []
                    assert "429" not in operation["responses"]
                else:
                    assert "security" not in operation  # the document's own
                    assert {"401", "429"} <= set(operation["responses"])
    assert committed["security"] == [{"apiKey": []}, {}]  # keys are off by default
    assert live["security"] == [{"apiKey": []}]


def test_a_generated_client_carries_the_key(
    generated_client: object,  # noqa: F811 (the fixture imported above)
    keyed_server: Server,
    keys: Keys,
) -> None:
    # The client is generated when the fixture runs (as in tests/app/routes/test_health.py).
    from flexwing_client import AuthenticatedClient, Client  # type: ignore[import-not-found]
    from flexwing_client.api.equilibrium import solve  # type: ignore[import-not-found]
    from flexwing_client.models import (  # type: ignore[import-not-found]
        ProblemDetails,
        SolveRequest,
        SolveResponse,
    )

    body = SolveRequest.from_dict(study.solve_request(10.0))
    url, timeout = keyed_server.base_url, httpx.Timeout(60)
    client = AuthenticatedClient(base_url=url, token=keys.alice, timeout=timeout)
    result = solve.sync(client=client, body=body)
    assert isinstance(result, SolveResponse)
    assert result.totals.lift == pytest.approx(304.1, abs=0.05)
    keyless = Client(base_url=url, timeout=timeout)
    problem = solve.sync(client=keyless, body=body)
    assert isinstance(problem, ProblemDetails)
    assert problem.type_ == "/problems/key-missing"


def test_the_embedded_deployment_never_throttles_its_owner(server: Server) -> None:
    """The README's command (no keys, no FLEXWING_RATE_LIMIT): a design loop of 500 requests
    from one client, faster than any default bucket, is answered without a 429."""
    with server.client() as client:
        statuses = Counter(client.get("/jobs").status_code for _ in range(500))
        assert statuses == Counter({200: 500})
        description = client.get("/openapi.json").json()["info"]["description"]
        assert "Rate limits: none here" in description


def test_with_keys_the_default_limit_applies_per_key(keyed_server: Server, keys: Keys) -> None:
    """Keys on and FLEXWING_RATE_LIMIT unset: each key's bucket holds the default burst (100) and
    refills at 50/s, so 600 requests as fast as one client sends them meet 429s; the document
    says so."""
    with httpx.Client(base_url=keyed_server.base_url, headers=bearer(keys.bob), timeout=60) as c:
        statuses = Counter(c.get("/jobs").status_code for _ in range(600))
        assert statuses[429] > 0 and statuses[200] > 0 and set(statuses) == {200, 429}
    # The document is public (read here without a key: bob's bucket is empty).
    document = httpx.get(f"{keyed_server.base_url}/openapi.json", timeout=60).json()
    assert "429" in document["paths"]["/solve"]["post"]["responses"]
    assert "50 per second" in document["info"]["description"]
