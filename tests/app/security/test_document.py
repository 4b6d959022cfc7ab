"""app.security.document: what the OpenAPI document says of API keys and rate limits.

- The bearer scheme is declared always; without keys it is optional (`security` lists it and
  the empty requirement), with a key file it is required.
- Every operation but the public paths documents 401 (key missing or invalid); public ones
  need no key (`security: []`).
- Every operation but the probes documents 429 with Retry-After; the description says which
  limits are in force.

Directly on a small document, and on the app's own document through `in_process_client`."""

from __future__ import annotations

import copy
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import httpx
import pytest

from app.security import PUBLIC_PATHS, SECURITY_SCHEME, UNLIMITED_PATHS, document, is_public
from app.security.keys import add_key
from app.settings import Settings
from tests.app.conftest import in_process_client

SMALL: dict[str, Any] = {
    "info": {"description": "The service."},
    "paths": {
        "/healthz": {"get": {"responses": {"200": {"description": "alive"}}}},
        "/docs": {"get": {"responses": {}}},
        "/solve": {"post": {"responses": {"200": {"description": "the equilibrium"}}}},
        "/jobs/{job_id}": {"get": {"responses": {}}, "delete": {"responses": {}}},
    },
}


def _documented(settings: Settings) -> dict[str, Any]:
    schema = copy.deepcopy(SMALL)
    document(schema, settings)
    return schema


@pytest.fixture(scope="module")
def keys_file(tmp_path_factory: pytest.TempPathFactory) -> Path:
    path = tmp_path_factory.mktemp("keys") / "keys.txt"
    add_key(path, "alice")
    return path


def test_without_keys_the_bearer_scheme_is_declared_and_optional() -> None:
    schema = _documented(Settings(workers=1))
    scheme = schema["components"]["securitySchemes"][SECURITY_SCHEME]
    assert (scheme["type"], scheme["scheme"]) == ("http", "bearer")
    assert schema["security"] == [{SECURITY_SCHEME: []}, {}]


def test_with_a_keys_file_the_bearer_scheme_is_required(keys_file: Path) -> None:
    schema = _documented(Settings(workers=1, api_keys_file=keys_file))
    assert schema["security"] == [{SECURITY_SCHEME: []}]


@pytest.mark.parametrize("keyed", [False, True], ids=["no-keys", "keys"])
def test_every_operation_but_the_public_ones_documents_401(keyed: bool, keys_file: Path) -> None:
    settings = Settings(workers=1, api_keys_file=keys_file if keyed else None)
    for path, item in _documented(settings)["paths"].items():
        for operation in item.values():
            if is_public(path):
                assert operation["security"] == [] and "401" not in operation["responses"]
            else:
                unauthorized = operation["responses"]["401"]
                assert "/problems/key-missing" in unauthorized["description"]
                assert "/problems/key-invalid" in unauthorized["description"]
                assert "WWW-Authenticate" in unauthorized["headers"]
                assert "security" not in operation  # the document's own applies


def test_every_operation_but_the_probes_documents_429_with_retry_after() -> None:
    for path, item in _documented(Settings(workers=1))["paths"].items():
        for operation in item.values():
            if path in UNLIMITED_PATHS:
                assert "429" not in operation["responses"]
            else:
                limited = operation["responses"]["429"]
                assert "/problems/rate-limited" in limited["description"]
                assert limited["headers"]["Retry-After"]["schema"] == {"type": "integer"}
                assert limited["content"]["application/problem+json"]["schema"] == {
                    "$ref": "#/components/schemas/ProblemDetails"
                }


def test_a_response_the_route_documents_itself_is_kept() -> None:
    schema = copy.deepcopy(SMALL)
    own = {"description": "the route's own 401"}
    schema["paths"]["/solve"]["post"]["responses"]["401"] = own
    document(schema, Settings(workers=1))
    assert schema["paths"]["/solve"]["post"]["responses"]["401"] is own


DESCRIPTIONS = {
    "no limits": ({}, "Rate limits: none here"),
    "a configured rate": (
        {"rate_limit": 5.0, "rate_burst": 7},
        "may send 7 requests at once and 5 per second",
    ),
}


@pytest.mark.parametrize(("changes", "says"), list(DESCRIPTIONS.values()), ids=list(DESCRIPTIONS))
def test_the_description_says_which_limits_are_in_force(changes: dict[str, Any], says: str) -> None:
    description = _documented(Settings(workers=1, **changes))["info"]["description"]
    assert description.startswith("The service.\n\n")
    assert says in description
    assert "Authorization: Bearer <key>" in description


# ------------------------------------------------------------------------ the app's own


@pytest.fixture(scope="module")
def keyed(keys_file: Path, tmp_path_factory: pytest.TempPathFactory) -> Iterator[httpx.Client]:
    db = tmp_path_factory.mktemp("keyed") / "jobs.sqlite3"
    with in_process_client(Settings(workers=1, jobs_db=db, api_keys_file=keys_file)) as client:
        yield client


@pytest.fixture(scope="module")
def keyed_document(keyed: httpx.Client) -> dict[str, Any]:
    answer = keyed.get("/openapi.json")  # public: served without a key
    assert answer.status_code == 200
    built: dict[str, Any] = answer.json()
    return built


def test_the_apps_document_requires_a_key_with_keys_and_the_public_paths_need_none(
    keyed_document: dict[str, Any], in_process: httpx.Client
) -> None:
    for client_document, security in (
        (keyed_document, [{SECURITY_SCHEME: []}]),
        (in_process.get("/openapi.json").json(), [{SECURITY_SCHEME: []}, {}]),
    ):
        assert client_document["security"] == security
        for path, item in client_document["paths"].items():
            for operation in item.values():
                assert ("401" in operation["responses"]) is not is_public(path), path
                assert ("429" in operation["responses"]) is (path not in UNLIMITED_PATHS), path
    documented = set(keyed_document["paths"])
    assert {"/healthz", "/readyz"} <= documented & PUBLIC_PATHS


def test_the_apps_document_says_the_default_rate_per_key(keyed_document: dict[str, Any]) -> None:
    """With keys on and FLEXWING_RATE_LIMIT unset, each key has 50 per second, burst 100."""
    description = keyed_document["info"]["description"]
    assert "may send 100 requests at once and 50 per second" in description


def test_what_the_document_calls_public_is_served_without_a_key(
    keyed: httpx.Client, keyed_document: dict[str, Any]
) -> None:
    """And what it documents 401 for is refused without one (the document says what is)."""
    paths = keyed_document["paths"]
    assert keyed.get("/healthz").status_code == 200
    assert "401" not in paths["/healthz"]["get"]["responses"]
    refused = keyed.post("/solve", json={})
    assert refused.status_code == 401 and "401" in paths["/solve"]["post"]["responses"]
    assert refused.json()["type"] == "/problems/key-missing"
