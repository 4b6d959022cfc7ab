"""Hypothesis profiles for every property-based test (solver fuzzing, schema fuzzing).

HYPOTHESIS_PROFILE selects one:
    ci (default)  bounded example counts, derandomized: the same cases on every run, so a red CI
                  means the code changed, not the dice.
    nightly       random and about 20x more examples (see benchmarks/ for the figures).
Tests scale their own `max_examples` with `fuzz_examples`.
"""

from __future__ import annotations

import os

# The suite runs on CasADi's virtual machine unless a test is about compilation (those set
# FLEXWING_COMPILE=1 with a cache of their own: tests/solver/test_compiled.py, test_warm.py,
# tests/app/routes/test_health.py). The virtual machine and the compiled code give the same
# bits (tests/solver/test_compiled.py), and a machine without the disk cache would otherwise
# compile every mesh the tests touch in the background, about a minute of a core each at
# N = 30: more than the tests themselves. Servers the tests start inherit it.
os.environ.setdefault("FLEXWING_COMPILE", "0")

import pytest
from hypothesis import HealthCheck, settings

PROFILE = os.environ.get("HYPOTHESIS_PROFILE", "ci")

settings.register_profile(
    "ci",
    deadline=None,  # solve times vary with N and VM-vs-compiled; tests guard hangs themselves
    derandomize=True,
    print_blob=True,
    suppress_health_check=[HealthCheck.too_slow],
)
settings.register_profile(
    "nightly",
    deadline=None,
    print_blob=True,
    suppress_health_check=[HealthCheck.too_slow],
)
settings.load_profile(PROFILE)

_SCALE = {"ci": 1, "nightly": 20}


def fuzz_examples(ci: int) -> int:
    """`ci` examples under the ci profile, proportionally more under the longer ones."""
    return ci * _SCALE.get(PROFILE, 1)


# Fixtures that start a real server: a test module using any of them is a live-server module.
_SERVER_FIXTURES = {"server", "fault_server", "make_server"}


def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    """Mark every test that needs a live server (one of its fixtures starts one) `server` and
    run them after everything else: the in-process tests (seconds) fail first, the live
    servers (minutes) come last. The sort is stable, so each module's server tests stay
    together and its module-scoped servers start once."""
    for item in items:
        if isinstance(item, pytest.Function) and _SERVER_FIXTURES & set(item.fixturenames):
            item.add_marker(pytest.mark.server)
    items.sort(key=lambda item: item.get_closest_marker("server") is not None)
