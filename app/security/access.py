"""Who asks, and whether they may: API keys and rate limits, in one middleware.

A request passes, outermost first:

    SecurityHeadersMiddleware  every response: X-Content-Type-Options, a Content-Security-Policy
                               (the route's own, e.g. the page's; else one that allows nothing:
                               API answers are data), frame-ancestors and X-Frame-Options,
                               Referrer-Policy, Cross-Origin-Resource-Policy
    CORSMiddleware             only with FLEXWING_CORS_ORIGINS: those origins may call the API
    MetricsMiddleware          (app.metrics) 401 and 429 answers are counted there too
    AccessMiddleware           who asks (an API key, else the client address); 401 without a
                               valid key where one is needed; 429 over the client's rate
    ... the body limit and the routes.

With keys on (FLEXWING_API_KEYS_FILE, `app.security.keys`), every path needs ``Authorization: Bearer
<key>`` except the probes (/healthz, /readyz) and what a browser loads before anyone can type a
key: the page (/), its files (/static/), the documentation (/docs, /openapi.json) and the problem
types (/problems/...). None of those holds anything of a user's. A missing key and a wrong one
are told apart (/problems/key-missing, /problems/key-invalid); a wrong key's answer is the same
whether it was mistyped, revoked or never issued. Routes get the request's owner of jobs by
``Depends(principal)``.

Rate limits (`app.security.ratelimit`) apply per key, or per client address without keys (behind a
proxy, the address uvicorn takes from X-Forwarded-For when the proxy is in --forwarded-allow-ips),
to every path but the probes. Keys never reach a log: nothing here logs a header, and uvicorn's
access log has the request line only (keys are never accepted in a URL).
"""

from __future__ import annotations

from collections.abc import Awaitable, Callable
from dataclasses import dataclass

from fastapi import FastAPI, Request
from prometheus_client import CollectorRegistry, Counter

from app.jobs.store import Store
from app.metrics import ASGIApp, Message, Metrics, Scope
from app.problems import PROBLEM_TYPES, Problem, ProblemType, problem_response
from app.security.keys import ApiKey, KeyRing, StoredKeys, verify
from app.security.ratelimit import SharedBuckets, TokenBuckets, address_bucket, rate_limited, take
from app.settings import Settings

__all__ = [
    "ANONYMOUS",
    "PUBLIC_PATHS",
    "UNLIMITED_PATHS",
    "AccessMiddleware",
    "Client",
    "install_access",
    "is_public",
    "owner",
    "principal",
]

PROBLEM_TYPES["key-missing"] = ProblemType(
    "key-missing",
    "API key missing",
    401,
    "This service has API keys (FLEXWING_API_KEYS_FILE): send `Authorization: Bearer <key>`. "
    "Its operator creates keys with `python -m app.keys create`. /healthz, /readyz, the page "
    "and the documentation need none.",
)
PROBLEM_TYPES["key-invalid"] = ProblemType(
    "key-invalid",
    "API key not accepted",
    401,
    "The key sent as `Authorization: Bearer <key>` is not one of this service's keys. The "
    "answer is the same whether it was mistyped, revoked or never issued.",
)

# Needs no key: the probes, and what a browser loads before anyone can type a key.
PUBLIC_PATHS = frozenset({"/healthz", "/readyz", "/", "/docs", "/openapi.json"})
PUBLIC_PREFIXES = ("/static/", "/problems/")
# Not rate limited: probes poll.
UNLIMITED_PATHS = frozenset({"/healthz", "/readyz"})

ANONYMOUS = "anonymous"  # the metrics label of requests without a key
_STATE = "flexwing_client"


def is_public(path: str) -> bool:
    """Whether `path` is served without a key when keys are on."""
    return path in PUBLIC_PATHS or path.startswith(PUBLIC_PREFIXES)


@dataclass(frozen=True)
class Client:
    """Who sent a request: the owner of the jobs it creates or sees (`principal`: an API key's,
    "" without one), its metrics label and its rate-limit bucket."""

    principal: str
    label: str
    bucket: str

    @classmethod
    def of_key(cls, key: ApiKey) -> Client:
        return cls(key.principal, key.fingerprint, f"key:{key.principal}")

    @classmethod
    def of_address(cls, scope: Scope) -> Client:
        client = scope.get("client")
        return cls("", ANONYMOUS, address_bucket(client[0] if client else None))


def owner(request: Request) -> str:
    """The owner of the jobs this request creates or sees (its API key's digest in hex; ""
    without keys, where every client is the same owner)."""
    client = request.scope.get("state", {}).get(_STATE)
    return client.principal if isinstance(client, Client) else ""


async def principal(request: Request) -> str:
    """A dependency: `owner` (a coroutine: FastAPI runs a plain function dependency in a
    worker thread)."""
    return owner(request)


class AccessMetrics:
    """Requests and refusals per client, labelled by a key's fingerprint (never the key)."""

    def __init__(self, registry: CollectorRegistry) -> None:
        self.requests = Counter(
            "flexwing_client_requests",
            "Requests by client: an API key's fingerprint (python -m app.keys list), or "
            "anonymous (no keys, or no key on a public path).",
            ["key_fingerprint"],
            registry=registry,
        )
        self.refusals = Counter(
            "flexwing_client_refusals",
            "Requests refused, by client and reason: rate-limited (429), key-missing and "
            "key-invalid (401, anonymous).",
            ["key_fingerprint", "reason"],
            registry=registry,
        )


def _bearer(scope: Scope) -> bytes | None:
    """The key of an ``Authorization: Bearer <key>`` header, None without one."""
    for name, value in scope.get("headers") or ():
        if name == b"authorization":
            scheme, _, key = value.strip().partition(b" ")
            key = key.strip()
            return key if scheme.lower() == b"bearer" and key else None
    return None


class AccessMiddleware:
    """Identifies the client, refuses a request without a valid key where one is needed (401)
    and one over the client's rate (429); pure ASGI, the body is never read."""

    def __init__(
        self,
        app: ASGIApp,
        keys: KeyRing | StoredKeys | None,
        buckets: TokenBuckets | SharedBuckets | None,
        metrics: AccessMetrics,
    ) -> None:
        self.app = app
        self.keys = keys
        self.buckets = buckets
        self.metrics = metrics

    async def __call__(
        self,
        scope: Scope,
        receive: Callable[[], Awaitable[Message]],
        send: Callable[[Message], Awaitable[None]],
    ) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return
        path = scope["path"]
        key = None
        if self.keys is not None:
            presented = _bearer(scope)
            try:
                key = None if presented is None else await verify(self.keys, presented)
            except Problem as problem:  # keys in a database not reached yet
                if not is_public(path):
                    await problem_response(problem, path)(scope, receive, send)
                    return
            if key is None and not is_public(path):
                await self._unauthorized(presented is None, scope, receive, send)
                return
        client = Client.of_address(scope) if key is None else Client.of_key(key)
        scope.setdefault("state", {})[_STATE] = client
        self.metrics.requests.labels(client.label).inc()
        if self.buckets is not None and path not in UNLIMITED_PATHS:
            wait = await take(self.buckets, client.bucket)
            if wait > 0.0:
                self.metrics.refusals.labels(client.label, "rate-limited").inc()
                await problem_response(rate_limited(wait, self.buckets), path)(scope, receive, send)
                return
        await self.app(scope, receive, send)

    async def _unauthorized(
        self,
        missing: bool,
        scope: Scope,
        receive: Callable[[], Awaitable[Message]],
        send: Callable[[Message], Awaitable[None]],
    ) -> None:
        if missing:
            reason = "key-missing"
            problem = Problem(
                reason,
                "this request needs an API key: send Authorization: Bearer <key>",
                headers={"WWW-Authenticate": 'Bearer realm="flexwing"'},
            )
        else:
            reason = "key-invalid"
            problem = Problem(
                reason,
                "the API key sent is not one of this service's keys",
                headers={"WWW-Authenticate": 'Bearer realm="flexwing", error="invalid_token"'},
            )
        self.metrics.requests.labels(ANONYMOUS).inc()
        self.metrics.refusals.labels(ANONYMOUS, reason).inc()
        await problem_response(problem, scope["path"])(scope, receive, send)


# ------------------------------------------------------------------------ installation


def install_access(
    app: FastAPI, settings: Settings, metrics: Metrics, store: Store | None = None
) -> None:
    """API keys (FLEXWING_API_KEYS_FILE, an unreadable or malformed file stops the start; or
    FLEXWING_API_KEYS_IN_DATABASE, the keys of `store`) and rate limits (FLEXWING_RATE_LIMIT,
    FLEXWING_RATE_BURST; in `store` when replicas share it). Add it inside the metrics."""
    keys: KeyRing | StoredKeys | None = None
    if settings.api_keys_file is not None:
        keys = KeyRing(settings.api_keys_file)
    elif settings.api_keys_in_database:
        if store is None:
            raise ValueError("FLEXWING_API_KEYS_IN_DATABASE needs the service's store")
        keys = StoredKeys(store)
    buckets: TokenBuckets | SharedBuckets | None = None
    if settings.client_rate_limit > 0:
        if store is not None and store.shared:
            buckets = SharedBuckets(store, settings.client_rate_limit, settings.rate_burst)
        else:
            buckets = TokenBuckets(settings.client_rate_limit, settings.rate_burst)
    app.state.keys = keys
    app.add_middleware(
        AccessMiddleware, keys=keys, buckets=buckets, metrics=AccessMetrics(metrics.registry)
    )
