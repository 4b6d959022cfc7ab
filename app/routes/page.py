"""The browser page (GET /) and offline API documentation (GET /docs); no part of the API.

Every asset is a file under `app/static/` (mounted at /static by `app.main`), vendored libraries
included, so neither page loads anything from another origin. Neither has an inline script, inline
style or event-handler attribute, so both are served with a strict Content-Security-Policy.
"""

from __future__ import annotations

from pathlib import Path

from fastapi import APIRouter
from fastapi.responses import FileResponse

__all__ = ["CONTENT_SECURITY_POLICY", "DOCS_CONTENT_SECURITY_POLICY", "STATIC_DIR", "router"]

STATIC_DIR = Path(__file__).resolve().parents[1] / "static"

# The page needs nothing but its own origin: no inline code, no eval, no data: images.
CONTENT_SECURITY_POLICY = (
    "default-src 'self'; base-uri 'self'; form-action 'self'; frame-ancestors 'none'; "
    "object-src 'none'"
)
# Swagger UI's stylesheet draws its icons as data: SVG images; nothing else is relaxed.
DOCS_CONTENT_SECURITY_POLICY = CONTENT_SECURITY_POLICY + "; img-src 'self' data:"

router = APIRouter(include_in_schema=False)


def _html(name: str, policy: str) -> FileResponse:
    return FileResponse(
        STATIC_DIR / name,
        media_type="text/html; charset=utf-8",
        headers={
            "Content-Security-Policy": policy,
            "X-Content-Type-Options": "nosniff",
            "Cache-Control": "no-cache",
        },
    )


@router.api_route("/", methods=["GET", "HEAD"])
async def page() -> FileResponse:
    """The wing editor, flight panel and the design study's figures, live from this service."""
    return _html("index.html", CONTENT_SECURITY_POLICY)


@router.api_route("/docs", methods=["GET", "HEAD"])
async def docs() -> FileResponse:
    """Swagger UI on /openapi.json, served from vendored files (works offline)."""
    return _html("docs.html", DOCS_CONTENT_SECURITY_POLICY)
