"""The service's pieces without a server: the result cache, error paths, packaging."""

from __future__ import annotations

import pytest

from app.cache import ResultCache, estimated_bytes
from app.problems import validation_errors
from tests import study


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


@pytest.mark.parametrize(
    ("loc", "field"),
    [
        (("body", "wing", "chord", 3), "wing.chord[3]"),
        (("body", "wing", "elastic_axis", "@list", 1), "wing.elastic_axis[1]"),
        (("body", "velocities", "@range", "count"), "velocities.count"),
        (("body",), "body"),
    ],
)
def test_validation_error_paths(loc: tuple[object, ...], field: str) -> None:
    errors = validation_errors([{"loc": loc, "msg": "bad", "type": "x"}])
    assert [(e.field, e.reason) for e in errors] == [(field, "bad")]


def test_every_app_package_is_installed() -> None:
    """pyproject lists packages explicitly: a new subpackage of app/ must be added there, or
    `pip install .` (the Dockerfile) ships an app that cannot import it."""
    import tomllib

    pyproject = tomllib.loads((study.ROOT / "pyproject.toml").read_text())
    listed = set(pyproject["tool"]["setuptools"]["packages"])
    app_dir = study.ROOT / "app"
    found = {
        ".".join(init.parent.relative_to(study.ROOT).parts) for init in app_dir.rglob("__init__.py")
    }
    assert found <= listed
