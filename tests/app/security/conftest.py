"""The store's backends (SQLite, a real PostgreSQL) for the tests of keys and rate limits kept
in the store: tests/app/jobs/conftest.py."""

from tests.app.jobs.conftest import database, postgres

__all__ = ["database", "postgres"]
