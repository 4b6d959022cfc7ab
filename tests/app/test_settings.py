"""app.settings: what the service runs with when nothing is set."""

from __future__ import annotations

from pathlib import Path

import pytest

from app.settings import KEYED_RATE_LIMIT, Settings


@pytest.mark.parametrize(
    ("keys", "rate_limit", "in_force"),
    [
        pytest.param(None, None, 0.0, id="no-keys-unset: one owner, no limit"),
        pytest.param(Path("keys.txt"), None, KEYED_RATE_LIMIT, id="keys-unset: 50 per key"),
        pytest.param(None, 20.0, 20.0, id="no-keys-set: per address"),
        pytest.param(Path("keys.txt"), 0.0, 0.0, id="keys-off: none"),
    ],
)
def test_the_rate_limit_in_force(keys: Path | None, rate_limit: float | None, in_force: float):
    settings = Settings(api_keys_file=keys, rate_limit=rate_limit)
    assert settings.client_rate_limit == in_force


def test_an_unset_rate_limit_is_read_as_unset(monkeypatch: pytest.MonkeyPatch):
    monkeypatch.delenv("FLEXWING_RATE_LIMIT", raising=False)
    assert Settings().rate_limit is None
    monkeypatch.setenv("FLEXWING_RATE_LIMIT", "7.5")
    assert Settings().rate_limit == 7.5
