"""Token buckets (`app.security.ratelimit`), on a clock the test advances: a client may send its
burst at once and its rate for ever, never more; clients do not share buckets (an IPv6 /64 is one
client). tests/app/security/test_access.py tests the limit over HTTP."""

from __future__ import annotations

import pytest

from app.security.ratelimit import TokenBuckets, address_bucket, rate_limited


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
