"""The store's backends for the jobs tests: every test that takes `database` runs once on an
SQLite file and once on a real PostgreSQL server (marked `server`: it starts one)."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pytest

from app.jobs.store import Store
from app.settings import Settings
from tests.postgres import postgres

__all__ = ["Backend", "database", "postgres"]


@dataclass(frozen=True)
class Backend:
    """One empty database: an SQLite file, or a PostgreSQL schema of its own."""

    kind: str
    url: str | None  # FLEXWING_DATABASE_URL; None for SQLite
    path: Path  # FLEXWING_JOBS_DB

    def store(self, retry_after: int = 1) -> Store:
        """A new store on this database (another replica's, if called again)."""
        return Store.of(self.url, self.path, retry_after)

    def settings(self, **changes: Any) -> Settings:
        defaults: dict[str, Any] = {"workers": 1, "jobs_db": self.path, "database_url": self.url}
        return Settings(**(defaults | changes))

    def env(self) -> dict[str, str]:
        """The environment of a server on this database."""
        if self.url is None:
            return {"FLEXWING_JOBS_DB": str(self.path)}
        return {"FLEXWING_DATABASE_URL": self.url}


@pytest.fixture(
    params=[
        pytest.param("sqlite", id="sqlite"),
        pytest.param("postgresql", id="postgresql", marks=pytest.mark.server),
    ]
)
def database(request: pytest.FixtureRequest, tmp_path: Path) -> Backend:
    path = tmp_path / "jobs.sqlite3"
    if request.param == "sqlite":
        return Backend("sqlite", None, path)
    cluster = request.getfixturevalue("postgres")
    return Backend("postgresql", cluster.schema(), path)
