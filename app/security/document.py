"""What the OpenAPI document says of keys and rate limits: the bearer scheme, 401 and 429."""

from __future__ import annotations

from typing import Any

from app.problems import PROBLEM_MEDIA_TYPE
from app.security.access import UNLIMITED_PATHS, is_public
from app.settings import Settings

__all__ = ["SECURITY_SCHEME", "document"]

SECURITY_SCHEME = "apiKey"


def _problem(description: str, header: str, meaning: str, kind: str) -> dict[str, Any]:
    problem = {"schema": {"$ref": "#/components/schemas/ProblemDetails"}}
    return {
        "description": description,
        "headers": {header: {"description": meaning, "schema": {"type": kind}}},
        "content": {PROBLEM_MEDIA_TYPE: problem},
    }


def document(schema: dict[str, Any], settings: Settings) -> None:
    """Declare the bearer key scheme (required with keys on; optional, `{}`, without), the 401
    and 429 answers, and say so in the description."""
    schema.setdefault("components", {}).setdefault("securitySchemes", {})[SECURITY_SCHEME] = {
        "type": "http",
        "scheme": "bearer",
        "description": (
            "An API key from the service's operator (`python -m app.keys create`), sent as "
            "`Authorization: Bearer <key>`; needed when the service has keys "
            "(FLEXWING_API_KEYS_FILE)."
        ),
    }
    keyed = settings.keys_on
    schema["security"] = [{SECURITY_SCHEME: []}] if keyed else [{SECURITY_SCHEME: []}, {}]
    unauthorized = _problem(
        "No API key or a wrong one (/problems/key-missing, /problems/key-invalid).",
        "WWW-Authenticate",
        'Bearer realm="flexwing" (and error="invalid_token" for a wrong key)',
        "string",
    )
    limited = _problem(
        "Over this client's rate limit (/problems/rate-limited): retry after Retry-After. Only "
        "where the service has rate limits: with API keys, or FLEXWING_RATE_LIMIT set.",
        "Retry-After",
        "[s] until this client's next request is accepted",
        "integer",
    )
    for path, item in schema.get("paths", {}).items():
        for operation in item.values():
            responses = operation.setdefault("responses", {})
            if is_public(path):
                operation["security"] = []
            else:
                responses.setdefault("401", unauthorized)
            if path not in UNLIMITED_PATHS:
                responses.setdefault("429", limited)
    sharing = (
        "Sharing: with API keys on (FLEXWING_API_KEYS_FILE) every operation but healthz and readyz "
        "needs `Authorization: Bearer <key>` (401 /problems/key-missing or /problems/key-invalid "
        "otherwise), and a job is seen only by the key that created it."
    )
    if settings.client_rate_limit > 0:
        sharing += (
            f" Each client (its key; its address without keys) may send {settings.rate_burst} "
            f"requests at once and {settings.client_rate_limit:g} per second "
            "(FLEXWING_RATE_BURST, FLEXWING_RATE_LIMIT); beyond that 429 /problems/rate-limited "
            "with Retry-After."
        )
    else:
        sharing += (
            " Rate limits: none here (FLEXWING_RATE_LIMIT unset without API keys: one owner). "
            "With API keys each key may send FLEXWING_RATE_BURST (default 100) requests at once "
            "and FLEXWING_RATE_LIMIT (default 50) per second; beyond that 429 "
            "/problems/rate-limited with Retry-After."
        )
    info = schema.setdefault("info", {})
    info["description"] = info.get("description", "").rstrip() + "\n\n" + sharing + "\n"
