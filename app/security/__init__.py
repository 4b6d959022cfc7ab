"""Sharing the service (issue 16): API keys (`keys`), rate limits (`ratelimit`), who asks and
whether they may (`access`), the security headers and CORS (`headers`), and what the OpenAPI
document says of them (`document`).

A request passes, outermost first: the security headers (and CORS), the metrics
(`app.metrics`: 401 and 429 answers are counted there too), access (a valid key where one is
needed; 429 over the client's rate), then the body limit and the routes.
"""

from __future__ import annotations

from app.security.access import (
    PUBLIC_PATHS,
    UNLIMITED_PATHS,
    AccessMiddleware,
    Client,
    install_access,
    is_public,
    owner,
    principal,
)
from app.security.document import SECURITY_SCHEME, document
from app.security.headers import (
    API_CONTENT_SECURITY_POLICY,
    SecurityHeadersMiddleware,
    install_headers,
)

__all__ = [
    "API_CONTENT_SECURITY_POLICY",
    "PUBLIC_PATHS",
    "SECURITY_SCHEME",
    "UNLIMITED_PATHS",
    "AccessMiddleware",
    "Client",
    "SecurityHeadersMiddleware",
    "document",
    "install_access",
    "install_headers",
    "is_public",
    "owner",
    "principal",
]
