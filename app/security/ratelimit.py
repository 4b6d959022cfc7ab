"""Rate limits: a token bucket per client (an API key, or a client address without keys).

A client's bucket holds at most `burst` tokens and refills at `rate` tokens per second; each
request takes one. A client idle for a while may send `burst` requests at once, and `rate` per
second for as long as it likes; beyond that it gets 429 /problems/rate-limited with Retry-After
(the seconds until its next token), while other clients are served as before. This is about
fairness between clients; the pool's admission (503 /problems/overloaded, FLEXWING_MAX_PENDING)
still protects the service as a whole, and the two are told apart by status and type.

With the SQLite store (one machine) buckets live in memory, per service process
(`TokenBuckets`): at most `max_clients` are kept, the least recently used dropped first (a
dropped client starts again with a full bucket, as a new one would). With PostgreSQL
(FLEXWING_DATABASE_URL) they are rows of the shared store (`SharedBuckets`, one atomic upsert a
request), so a client's limit holds across replicas instead of being multiplied by their
count; while the database cannot be reached, each replica's own buckets stand in, so requests
are still limited (per replica) and never refused for the database's sake.
"""

from __future__ import annotations

import ipaddress
import logging
import math
import time
from collections import OrderedDict
from collections.abc import Callable

from app.jobs.store import Store
from app.problems import PROBLEM_TYPES, Problem, ProblemType

__all__ = ["SharedBuckets", "TokenBuckets", "address_bucket", "rate_limited", "take"]

log = logging.getLogger(__name__)

PROBLEM_TYPES["rate-limited"] = ProblemType(
    "rate-limited",
    "Rate limit exceeded",
    429,
    "This client (its API key, or its address when the service has no keys) sent more requests "
    "than its token bucket allows: FLEXWING_RATE_BURST at once, FLEXWING_RATE_LIMIT per second "
    "sustained (`rate_limit` [1/s], `burst`). Retry after the Retry-After header's seconds; other "
    "clients are not affected. Not the same as /problems/overloaded (503), the whole service "
    "being busy. Many solves are one batch job (POST /jobs), one request.",
)


class TokenBuckets:
    """Token buckets by client: `burst` tokens at most, refilled at `rate` [1/s]."""

    def __init__(
        self,
        rate: float,
        burst: int,
        *,
        max_clients: int = 10_000,
        clock: Callable[[], float] = time.monotonic,
    ) -> None:
        if rate <= 0 or burst < 1:
            raise ValueError("a token bucket needs rate > 0 and burst >= 1")
        self.rate = rate
        self.burst = burst
        self.max_clients = max_clients
        self._clock = clock
        # client -> (tokens, when they were counted [s, clock]), least recently used first
        self._buckets: OrderedDict[str, tuple[float, float]] = OrderedDict()

    def __len__(self) -> int:
        return len(self._buckets)

    def take(self, client: str) -> float:
        """Take a token for one request of `client`: 0.0 if it may go ahead, else the seconds
        [s] until its bucket holds a token again (nothing is taken then)."""
        now = self._clock()
        tokens, then = self._buckets.pop(client, (float(self.burst), now))
        tokens = min(float(self.burst), tokens + (now - then) * self.rate)
        wait = 0.0
        if tokens >= 1.0:
            tokens -= 1.0
        else:
            wait = (1.0 - tokens) / self.rate
        self._buckets[client] = (tokens, now)
        while len(self._buckets) > self.max_clients:
            self._buckets.popitem(last=False)
        return wait


class SharedBuckets:
    """Token buckets in the shared store (`Store.take_token`, its clock the replicas'), with
    this process's own `TokenBuckets` standing in while the store cannot be reached."""

    def __init__(
        self, store: Store, rate: float, burst: int, *, clock: Callable[[], float] = time.time
    ) -> None:
        self.store = store
        self.local = TokenBuckets(rate, burst, clock=clock)
        self.rate, self.burst = self.local.rate, self.local.burst
        self._clock = clock
        self._alone = False  # the local buckets stand in (logged once per outage)

    async def take(self, client: str) -> float:
        """As `TokenBuckets.take`, across every replica."""
        if self.store.coordination.available:
            try:
                wait = await self.store.take_token(client, self.rate, self.burst, self._clock())
            except Problem:
                pass  # the database went away in the meantime
            else:
                self._alone = False
                return wait
        if not self._alone:
            self._alone = True
            log.warning("rate limits: the store is unavailable, this replica's own buckets count")
        return self.local.take(client)


async def take(buckets: TokenBuckets | SharedBuckets, client: str) -> float:
    """One request of `client` from either kind of buckets: 0.0, or [s] to wait."""
    if isinstance(buckets, SharedBuckets):
        return await buckets.take(client)
    return buckets.take(client)


def address_bucket(host: str | None) -> str:
    """The bucket of a client address: an IPv4 address, or an IPv6 address's /64 (one host
    usually has a whole /64 to pick addresses from)."""
    if not host:
        return "address:unknown"
    try:
        address = ipaddress.ip_address(host)
    except ValueError:
        return f"address:{host}"
    if isinstance(address, ipaddress.IPv6Address):
        if address.ipv4_mapped is not None:
            return f"address:{address.ipv4_mapped}"
        return f"address:{ipaddress.IPv6Network((address, 64), strict=False)}"
    return f"address:{address}"


def rate_limited(wait: float, buckets: TokenBuckets | SharedBuckets) -> Problem:
    """The 429 problem for a client that must wait `wait` [s]; Retry-After in whole seconds."""
    retry_after = max(1, math.ceil(wait))
    return Problem(
        "rate-limited",
        f"more than {buckets.burst} requests at once or {buckets.rate:g} per second from this "
        f"client; retry in {retry_after} s",
        extensions={"rate_limit": buckets.rate, "burst": buckets.burst},
        headers={"Retry-After": str(retry_after)},
    )
