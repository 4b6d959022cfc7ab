"""The security headers of every answer, refusals included, and CORS (closed by default).

Outermost on every response: X-Content-Type-Options, a Content-Security-Policy (the route's own,
e.g. the page's; else one that allows nothing: API answers are data), frame-ancestors and
X-Frame-Options, Referrer-Policy, Cross-Origin-Resource-Policy; and, only with
FLEXWING_CORS_ORIGINS, those origins may call the API.
"""

from __future__ import annotations

from collections.abc import Awaitable, Callable

from fastapi import FastAPI
from starlette.middleware.cors import CORSMiddleware

from app.metrics import ASGIApp, Message, Scope
from app.settings import Settings

__all__ = ["API_CONTENT_SECURITY_POLICY", "SecurityHeadersMiddleware", "install_headers"]

# What an API answer (data, never a document to render) allows: nothing.
API_CONTENT_SECURITY_POLICY = (
    "default-src 'none'; frame-ancestors 'none'; base-uri 'none'; form-action 'none'"
)
_SECURITY_HEADERS: tuple[tuple[bytes, bytes], ...] = (
    (b"x-content-type-options", b"nosniff"),
    (b"content-security-policy", API_CONTENT_SECURITY_POLICY.encode()),
    (b"x-frame-options", b"DENY"),
    (b"referrer-policy", b"no-referrer"),
    (b"cross-origin-resource-policy", b"same-origin"),
)


class SecurityHeadersMiddleware:
    """Adds the security headers a response does not set itself (pure ASGI); responses other
    than the app's files get ``Cache-Control: no-store`` unless they say otherwise."""

    def __init__(self, app: ASGIApp) -> None:
        self.app = app

    async def __call__(
        self,
        scope: Scope,
        receive: Callable[[], Awaitable[Message]],
        send: Callable[[Message], Awaitable[None]],
    ) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return
        static = scope["path"].startswith("/static/")

        async def send_with_headers(message: Message) -> None:
            if message["type"] == "http.response.start":
                headers = list(message.get("headers") or [])
                present = {name.lower() for name, _ in headers}
                headers += [(n, v) for n, v in _SECURITY_HEADERS if n not in present]
                if not static and b"cache-control" not in present:
                    headers.append((b"cache-control", b"no-store"))
                message["headers"] = headers
            await send(message)

        await self.app(scope, receive, send_with_headers)


def install_headers(app: FastAPI, settings: Settings) -> None:
    """CORS (FLEXWING_CORS_ORIGINS; none by default) and the security headers, outermost."""
    if settings.cors_origins:
        app.add_middleware(
            CORSMiddleware,
            allow_origins=settings.cors_origins,
            allow_methods=["GET", "HEAD", "POST", "DELETE"],
            allow_headers=["Authorization", "Content-Type", "Accept", "Prefer"],
            expose_headers=["Location", "Retry-After", "Preference-Applied", "WWW-Authenticate"],
            max_age=600,
        )
    app.add_middleware(SecurityHeadersMiddleware)
