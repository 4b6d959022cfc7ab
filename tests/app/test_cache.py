"""app.cache: the result cache, a least-recently-used map bounded in bytes."""

from __future__ import annotations

from app.cache import ResultCache, estimated_bytes


def _payload(n: int) -> dict[str, object]:
    return {"stations": {"y": [float(i) for i in range(n)]}, "totals": {"lift": 1.0}}


def test_the_result_cache_is_an_lru_bounded_in_bytes() -> None:
    size = estimated_bytes(_payload(100))
    cache: ResultCache[dict[str, object]] = ResultCache(max_bytes=2 * size + size // 2)
    cache.put("a", _payload(100))
    cache.put("b", _payload(100))
    assert cache.get("a") is not None  # a is now the most recent
    cache.put("c", _payload(100))
    assert (cache.get("a") is not None, cache.get("b"), cache.get("c") is not None) == (
        True,
        None,
        True,
    )
    assert cache.bytes <= cache.max_bytes


def test_an_entry_larger_than_the_budget_is_not_kept() -> None:
    cache: ResultCache[dict[str, object]] = ResultCache(max_bytes=estimated_bytes(_payload(10)))
    cache.put("big", _payload(1000))
    assert cache.get("big") is None and cache.bytes == 0
    disabled: ResultCache[dict[str, object]] = ResultCache(0)
    disabled.put("a", _payload(1))
    assert disabled.get("a") is None


def test_the_byte_estimate_grows_with_the_content() -> None:
    """About 32 bytes per float in a list (the float object and its slot)."""
    small, large = estimated_bytes(_payload(100)), estimated_bytes(_payload(1100))
    assert 31_000 < large - small < 33_000
