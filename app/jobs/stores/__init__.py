"""Where the store's rows live: the connection and its thread (`database`), the two databases
it can be (`dialects`: SQLite, PostgreSQL) and the schema's numbered steps (`schema`). What is
stored and how it is asked for is `app.jobs.store`, the one interface in front of both."""

from app.jobs.stores.database import Database, Session, Unavailable, unavailable
from app.jobs.stores.dialects import Dialect, PostgreSQL, SQLite, redacted
from app.jobs.stores.schema import SCHEMA_VERSION, migrate

__all__ = [
    "SCHEMA_VERSION",
    "Database",
    "Dialect",
    "PostgreSQL",
    "SQLite",
    "Session",
    "Unavailable",
    "migrate",
    "redacted",
    "unavailable",
]
