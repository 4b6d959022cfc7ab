"""Token buckets (`app.security.ratelimit`), on a clock the test advances: a client may send its
burst at once and its rate for ever, never more; clients do not share buckets (an IPv6 /64 is one
client); with PostgreSQL, buckets live in the store and one client's limit holds across
replicas (on both backends, `database`), each replica's own buckets standing in while the store
is away. tests/app/security/test_access.py tests the limit over HTTP."""

from __future__ import annotations

import asyncio
from pathlib import Path

import pytest

from app.jobs.store import Store
from app.security.ratelimit import SharedBuckets, TokenBuckets, address_bucket, rate_limited
from tests.app.jobs.conftest import Backend
from tests.postgres import free_port


class Clock:
    """Seconds that pass only when the test says so."""

    def __init__(self) -> None:
        self.now = 1000.0

    def __call__(self) -> float:
        return self.now


def test_a_client_may_send_its_burst_at_once_then_one_request_per_token() -> None:
    clock = Clock()
    buckets = TokenBuckets(rate=2.0, burst=5, clock=clock)
    assert [buckets.take("alice") for _ in range(5)] == [0.0] * 5
    assert buckets.take("alice") == pytest.approx(0.5)  # a token every 1/2 s
    clock.now += 0.25
    assert buckets.take("alice") == pytest.approx(0.25)
    clock.now += 0.25
    assert buckets.take("alice") == 0.0
    assert buckets.take("alice") == pytest.approx(0.5)


def test_over_a_long_run_a_client_gets_its_rate_and_no_more() -> None:
    clock = Clock()
    buckets = TokenBuckets(rate=10.0, burst=20, clock=clock)
    answered = 0
    for _ in range(10_000):  # 100 requests a second for 100 s
        answered += buckets.take("script") == 0.0
        clock.now += 0.01
    assert answered == pytest.approx(20 + 10 * 100, abs=2)


def test_an_idle_bucket_refills_to_its_burst_and_no_further() -> None:
    clock = Clock()
    buckets = TokenBuckets(rate=1.0, burst=3, clock=clock)
    for _ in range(3):
        buckets.take("alice")
    clock.now += 3600.0
    assert [buckets.take("alice") == 0.0 for _ in range(4)] == [True, True, True, False]


def test_one_clients_requests_leave_anothers_bucket_full() -> None:
    clock = Clock()
    buckets = TokenBuckets(rate=0.01, burst=2, clock=clock)
    for _ in range(10):
        buckets.take("alice")
    assert buckets.take("alice") > 0.0
    assert [buckets.take("bob"), buckets.take("bob")] == [0.0, 0.0]


def test_at_most_max_clients_buckets_are_kept_the_least_recent_dropped() -> None:
    clock = Clock()
    buckets = TokenBuckets(rate=0.01, burst=1, max_clients=100, clock=clock)
    for n in range(1000):
        buckets.take(f"client-{n}")
    assert len(buckets) == 100
    assert buckets.take("client-999") > 0.0  # kept: still empty
    assert buckets.take("client-0") == 0.0  # dropped: a new client


ADDRESSES = {
    "IPv4": ("192.0.2.7", "address:192.0.2.7"),
    "IPv6, its /64": ("2001:db8:1:2:aaaa::1", "address:2001:db8:1:2::/64"),
    "IPv6, the same /64": ("2001:db8:1:2:ffff::9", "address:2001:db8:1:2::/64"),
    "IPv4-mapped IPv6": ("::ffff:192.0.2.7", "address:192.0.2.7"),
    "no address (a Unix socket)": (None, "address:unknown"),
}


@pytest.mark.parametrize(("host", "bucket"), list(ADDRESSES.values()), ids=list(ADDRESSES))
def test_the_bucket_of_a_client_address(host: str | None, bucket: str) -> None:
    assert address_bucket(host) == bucket


@pytest.mark.parametrize(
    ("wait", "retry_after"), [(0.001, "1"), (1.0, "1"), (1.2, "2"), (99.5, "100")]
)
def test_retry_after_is_the_wait_rounded_up_to_whole_seconds(wait: float, retry_after: str) -> None:
    problem = rate_limited(wait, TokenBuckets(rate=1.0, burst=1))
    assert problem.status == 429
    assert problem.headers["Retry-After"] == retry_after
    assert problem.extensions == {"rate_limit": 1.0, "burst": 1}


# ------------------------------------------------------------- buckets shared by replicas


def _shared(
    stores: list[Store], clock: Clock, rate: float = 2.0, burst: int = 3
) -> list[SharedBuckets]:
    return [SharedBuckets(store, rate, burst, clock=clock) for store in stores]


def test_buckets_in_the_store_hold_one_limit_across_replicas(database: Backend) -> None:
    """Two replicas' buckets, one client: its burst between them, not each (the limit is not
    multiplied by the replica count), then its rate; another client is not affected."""
    clock = Clock()

    async def scenario() -> None:
        stores = [database.store(), database.store()]
        for store in stores:
            await store.open()
        try:
            a, b = _shared(stores, clock)
            waits = [await replica.take("key:alice") for replica in (a, b, a, b)]
            assert waits[:3] == [0.0, 0.0, 0.0] and waits[3] == pytest.approx(0.5)
            assert await a.take("key:bob") == 0.0
            clock.now += 0.5
            assert await b.take("key:alice") == 0.0
            assert await a.take("key:alice") == pytest.approx(0.5)
            assert len(a.local) == len(b.local) == 0  # the store counted every one
        finally:
            for store in stores:
                await store.close()

    asyncio.run(scenario())


def test_while_the_store_is_away_each_replica_limits_with_its_own_buckets() -> None:
    """A database that cannot be reached (nothing listens on its port): requests are still
    limited, per replica, and never refused for the database's sake."""
    clock = Clock()
    url = f"postgresql://flexwing@127.0.0.1:{free_port()}/flexwing"

    async def scenario() -> None:
        store = Store.of(url, Path())
        await store.open()
        try:
            assert not store.available
            (alone,) = _shared([store], clock)
            waits = [await alone.take("key:alice") for _ in range(4)]
            assert waits[:3] == [0.0, 0.0, 0.0] and waits[3] == pytest.approx(0.5)
            assert len(alone.local) == 1
        finally:
            await store.close()

    asyncio.run(scenario())
