"""The two databases a store can live in, and the little that differs between them.

`SQLite` (the default): a file on this machine (FLEXWING_JOBS_DB), for one service or several
processes on one machine. `PostgreSQL` (FLEXWING_DATABASE_URL): a server that several replicas
share. The store's SQL is written once, with ``?`` placeholders and types both read alike
(TEXT, INTEGER, DOUBLE PRECISION); a dialect says how to connect, how to lock what a statement
claims, and whether an error means the connection is gone.
"""

from __future__ import annotations

import contextlib
import sqlite3
from functools import lru_cache
from pathlib import Path
from typing import Any, Protocol

import psycopg
from psycopg.conninfo import conninfo_to_dict

__all__ = ["Dialect", "PostgreSQL", "SQLite", "redacted"]


class Dialect(Protocol):
    name: str  # what /readyz and the logs call the database (never with a password)
    shared: bool  # replicas on other machines can share it
    least: str  # the SQL function of the smaller of two values
    greatest: str
    skip_locked: str  # appended to the SELECT of a claim: rows another claim holds are passed
    share_lock: str  # appended to a fence's SELECT: its row is held until the commit

    def connect(self) -> Any: ...
    def close(self, connection: Any) -> None: ...
    def begin(self, connection: Any, operations: int) -> None: ...
    def commit(self, connection: Any) -> None: ...
    def rollback(self, connection: Any) -> None: ...
    def sql(self, text: str) -> str: ...
    def broken(self, connection: Any, error: BaseException) -> bool: ...
    def describe(self, error: BaseException) -> str: ...
    def relax_commit(self, session: Any) -> None: ...
    def lock_schema(self, session: Any) -> None: ...
    def columns(self, session: Any, table: str) -> set[str]: ...


class SQLite:
    """An SQLite file in WAL mode; `synchronous=NORMAL`: a commit survives the service's death
    (a SIGKILL), not the machine's power loss."""

    shared = False
    least, greatest = "MIN", "MAX"
    skip_locked = share_lock = ""  # one writer at a time holds the whole database

    def __init__(self, path: Path) -> None:
        self.path = path
        self.name = str(path)

    def connect(self) -> sqlite3.Connection:
        self.path.parent.mkdir(parents=True, exist_ok=True)
        # timeout: several processes sharing the file wait for each other's commits
        connection = sqlite3.connect(self.path, isolation_level="DEFERRED", timeout=30)
        connection.execute("PRAGMA journal_mode=WAL")
        connection.execute("PRAGMA synchronous=NORMAL")
        return connection

    def close(self, connection: Any) -> None:
        connection.close()

    def begin(self, connection: Any, operations: int) -> None:
        pass  # the sqlite3 module begins a transaction before the first write

    def commit(self, connection: Any) -> None:
        connection.commit()

    def rollback(self, connection: Any) -> None:
        connection.rollback()

    def sql(self, text: str) -> str:
        return text

    def broken(self, connection: Any, error: BaseException) -> bool:
        return False  # a file does not go away as a server does: its errors are the operation's

    def describe(self, error: BaseException) -> str:
        return f"{type(error).__name__}: {error}"

    def relax_commit(self, session: Any) -> None:
        pass  # synchronous=NORMAL already: commits do not wait for the disk

    def lock_schema(self, session: Any) -> None:
        if not session.connection.in_transaction:
            session.connection.execute("BEGIN IMMEDIATE")  # one process migrates at a time

    def columns(self, session: Any, table: str) -> set[str]:
        return {row[1] for row in session.execute(f"PRAGMA table_info({table})").fetchall()}


# Connection defaults a URL may override: fail fast at the start, and notice a server that
# vanished from the network (not only one that closed its connections) within ~15 s.
_POSTGRES_DEFAULTS = {
    "connect_timeout": "5",
    "keepalives": "1",
    "keepalives_idle": "5",
    "keepalives_interval": "2",
    "keepalives_count": "3",
    "tcp_user_timeout": "15000",  # [ms]
    "application_name": "flexwing",
}
_SCHEMA_LOCK = 39_0039  # the advisory lock replicas take to migrate the schema one at a time


def redacted(url: str) -> str:
    """A PostgreSQL URL without its password: postgresql://user@host:port/dbname."""
    parts = conninfo_to_dict(url)
    user = str(parts.get("user") or "")
    host = parts.get("host") or "localhost"
    port = parts.get("port") or "5432"
    return f"postgresql://{user + '@' if user else ''}{host}:{port}/{parts.get('dbname') or ''}"


@lru_cache(maxsize=512)
def _pyformat(text: str) -> str:
    return text.replace("?", "%s")


class PostgreSQL:
    """A PostgreSQL server (psycopg 3), shared by every replica."""

    shared = True
    least, greatest = "LEAST", "GREATEST"
    skip_locked = " FOR UPDATE SKIP LOCKED"
    share_lock = " FOR SHARE"

    def __init__(self, url: str) -> None:
        self.url = url
        self.name = redacted(url)

    def connect(self) -> psycopg.Connection[Any]:
        parameters: dict[str, Any] = _POSTGRES_DEFAULTS | conninfo_to_dict(self.url)
        # Autocommit: a lone operation is one round trip (no BEGIN, no COMMIT); a batch of
        # several opens its transaction itself (`begin`).
        return psycopg.connect(autocommit=True, **parameters)

    def close(self, connection: Any) -> None:
        with contextlib.suppress(psycopg.Error):
            connection.close()

    def begin(self, connection: Any, operations: int) -> None:
        if operations > 1:
            connection.execute("BEGIN")

    def commit(self, connection: Any) -> None:
        if connection.info.transaction_status != psycopg.pq.TransactionStatus.IDLE:
            connection.execute("COMMIT")

    def rollback(self, connection: Any) -> None:
        if connection.info.transaction_status != psycopg.pq.TransactionStatus.IDLE:
            connection.execute("ROLLBACK")

    def sql(self, text: str) -> str:
        return _pyformat(text)

    def broken(self, connection: Any, error: BaseException) -> bool:
        if isinstance(error, psycopg.InterfaceError):
            return True
        return isinstance(error, psycopg.Error) and bool(connection.broken or connection.closed)

    def describe(self, error: BaseException) -> str:
        text = str(error).strip().splitlines()
        return text[0] if text else type(error).__name__

    def relax_commit(self, session: Any) -> None:
        # Only on the store's coordination connection (claims, leases, rate-limit buckets):
        # see `app.jobs.store.Store`.
        session.execute("SET synchronous_commit TO OFF")

    def lock_schema(self, session: Any) -> None:
        if session.connection.info.transaction_status == psycopg.pq.TransactionStatus.IDLE:
            session.execute("BEGIN")
        session.execute("SELECT pg_advisory_xact_lock(?)", (_SCHEMA_LOCK,))

    def columns(self, session: Any, table: str) -> set[str]:
        rows = session.execute(
            "SELECT column_name FROM information_schema.columns "
            "WHERE table_schema = current_schema() AND table_name = ?",
            (table,),
        ).fetchall()
        return {row[0] for row in rows}
