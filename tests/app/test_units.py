"""The service's pieces without a server: caches, fingerprints, error paths."""

from __future__ import annotations

import numpy as np
import pytest

from app.cache import ResultCache, StateCache, fingerprint
from app.problems import validation_errors
from solver import Wing
from tests.app import study


def _wing(**changes: object) -> Wing:
    raw = study.wing() | changes
    return Wing.create(
        raw["y"],
        raw["chord"],
        raw["elastic_axis"],
        raw["bending_stiffness"],
        raw["torsional_stiffness"],
    )


def test_fingerprint_is_canonical() -> None:
    assert fingerprint(_wing()) == fingerprint(_wing(elastic_axis=[0.4] * 30))
    assert fingerprint(_wing()) == fingerprint(_wing(y=[-0.0, *study.wing()["y"][1:]]))
    assert fingerprint(_wing()) != fingerprint(_wing(elastic_axis=0.41))
    stiffer = study.wing(stiffness_scale=1 + 1e-15)
    assert fingerprint(_wing()) != fingerprint(_wing(**stiffer))


def test_result_cache_is_a_bounded_lru() -> None:
    cache: ResultCache[int] = ResultCache(2)
    cache.put("a", 1)
    cache.put("b", 2)
    assert cache.get("a") == 1  # a is now the most recent
    cache.put("c", 3)
    assert (cache.get("a"), cache.get("b"), cache.get("c")) == (1, None, 3)
    disabled: ResultCache[int] = ResultCache(0)
    disabled.put("a", 1)
    assert disabled.get("a") is None


def test_state_cache_returns_the_nearest_state_of_the_same_wing() -> None:
    cache = StateCache(wings=2, per_wing=3)
    for q in (50.0, 100.0, 200.0):
        cache.add("w", q, 5.0, np.full(3, q))
    found = cache.nearest("w", 120.0, 5.0)
    assert found is not None and found.dynamic_pressure == 100.0
    cache.add("w", 120.0, 7.0, np.zeros(3))  # evicts the least recent, 50 Pa
    found = cache.nearest("w", 125.0, 7.0)
    assert found is not None and (found.dynamic_pressure, found.alpha) == (120.0, 7.0)
    # One degree of alpha weighs like doubling q: at 5 deg, 100 Pa beats 120 Pa at 7 deg.
    found = cache.nearest("w", 125.0, 5.0)
    assert found is not None and (found.dynamic_pressure, found.alpha) == (100.0, 5.0)
    assert cache.nearest("other", 100.0, 5.0) is None
    cache.add("x", 1.0, 0.0, np.zeros(3))
    cache.add("y", 1.0, 0.0, np.zeros(3))  # evicts the least recently used wing: "w"
    assert cache.nearest("w", 100.0, 5.0) is None
    assert len(cache) == 2


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
