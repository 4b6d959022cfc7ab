"""The store's schema, created and migrated by the service itself, one numbered step at a time.

`schema_version` holds the last step applied. Every connection runs `migrate` before anything
else, under a lock (SQLite: BEGIN IMMEDIATE; PostgreSQL: an advisory lock), so replicas that
start together migrate once, and an older database (an SQLite file of issue 13, without the
version table) is brought up to date in place. Steps are only ever added.

Tables (times in s since the epoch, as the replicas' clocks read them):

    jobs      one row per job: id, operation, status, owner (the replica that holds its lease,
              or accepted it), principal (the API key that submitted it,
              `app.security.keys.ApiKey.principal`; "" without keys), times, progress (done,
              total, problems), result and problem as JSON text; since step 2 its request (JSON,
              so any replica can run it), its lease (lease_expires), its attempts and whether a
              cancel was asked for (cancel_requested) where another replica runs it;
    items     one row per answered batch item: (job, idx) -> its NDJSON line; seq is the order
              in which items were answered (what items.ndjson streams by);
    buckets   (step 2) one rate-limit token bucket per client: tokens left when last counted,
              when, and whether that request was granted;
    api_keys  (step 2) name -> SHA-256 digest (hex) of each API key, when keys are kept here.
"""

from __future__ import annotations

from collections.abc import Callable

from app.jobs.stores.database import Session

__all__ = ["MIGRATIONS", "SCHEMA_VERSION", "migrate"]


def _jobs_and_items(session: Session) -> None:
    """Step 1 (issue 13): jobs and their batch items."""
    session.execute(
        """CREATE TABLE IF NOT EXISTS jobs (
            id TEXT PRIMARY KEY,
            operation TEXT NOT NULL,
            status TEXT NOT NULL,
            owner TEXT NOT NULL,
            principal TEXT NOT NULL DEFAULT '',
            created DOUBLE PRECISION NOT NULL,
            started DOUBLE PRECISION,
            finished DOUBLE PRECISION,
            expires DOUBLE PRECISION,
            done INTEGER NOT NULL DEFAULT 0,
            total INTEGER NOT NULL,
            problems INTEGER NOT NULL DEFAULT 0,
            result TEXT,
            problem TEXT
        )"""
    )
    if "principal" not in session.dialect.columns(session, "jobs"):
        # an SQLite file from before API keys: its jobs are keyless
        session.execute("ALTER TABLE jobs ADD COLUMN principal TEXT NOT NULL DEFAULT ''")
    for index in (
        "jobs_by_creation ON jobs (created DESC, id DESC)",
        "jobs_by_expiry ON jobs (expires)",
        "jobs_by_owner ON jobs (owner, status)",
        "jobs_by_principal ON jobs (principal, created DESC, id DESC)",
    ):
        session.execute(f"CREATE INDEX IF NOT EXISTS {index}")
    session.execute(
        """CREATE TABLE IF NOT EXISTS items (
            job TEXT NOT NULL,
            idx INTEGER NOT NULL,
            seq INTEGER NOT NULL,
            ok INTEGER NOT NULL,
            line TEXT NOT NULL,
            PRIMARY KEY (job, idx)
        )"""
    )
    session.execute("CREATE INDEX IF NOT EXISTS items_by_answer ON items (job, seq)")


def _shared(session: Session) -> None:
    """Step 2 (issue 39): what replicas share: requests and leases, buckets, keys."""
    for column in (
        "request TEXT",
        "lease_expires DOUBLE PRECISION",
        "attempts INTEGER NOT NULL DEFAULT 0",
        "cancel_requested INTEGER NOT NULL DEFAULT 0",
    ):
        session.execute(f"ALTER TABLE jobs ADD COLUMN {column}")
    session.execute("CREATE INDEX IF NOT EXISTS jobs_by_status ON jobs (status, created, id)")
    session.execute(
        """CREATE TABLE IF NOT EXISTS buckets (
            client TEXT PRIMARY KEY,
            tokens DOUBLE PRECISION NOT NULL,
            updated DOUBLE PRECISION NOT NULL,
            granted INTEGER NOT NULL
        )"""
    )
    session.execute(
        """CREATE TABLE IF NOT EXISTS api_keys (
            name TEXT PRIMARY KEY,
            digest TEXT NOT NULL UNIQUE,
            created DOUBLE PRECISION NOT NULL
        )"""
    )


MIGRATIONS: tuple[Callable[[Session], None], ...] = (_jobs_and_items, _shared)
SCHEMA_VERSION = len(MIGRATIONS)


def migrate(session: Session) -> None:
    """Bring the schema to `SCHEMA_VERSION` (the caller commits)."""
    session.dialect.lock_schema(session)
    session.execute("CREATE TABLE IF NOT EXISTS schema_version (version INTEGER NOT NULL)")
    (found,) = session.execute("SELECT MAX(version) FROM schema_version").fetchone()
    version = found or 0
    if version > SCHEMA_VERSION:
        raise RuntimeError(
            f"the jobs database has schema version {version}; this service knows up to "
            f"{SCHEMA_VERSION} (a newer flexwing migrated it)"
        )
    for number, step in enumerate(MIGRATIONS[version:], start=version + 1):
        step(session)
        session.execute("INSERT INTO schema_version (version) VALUES (?)", (number,))
