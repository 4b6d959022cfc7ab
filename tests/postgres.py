"""A real PostgreSQL server for the tests: Debian's `postgresql` binaries
(/usr/lib/postgresql/<version>/bin; .ci/run installs the package where it is absent), a cluster
made by initdb in a temporary directory and started by pg_ctl on a free loopback port, TCP only.

PostgreSQL refuses to run as root (CI's user): then the cluster belongs to `nobody` and its
commands run through `runuser`. Each test gets a schema of its own (`Cluster.schema()`), made in
milliseconds, so one cluster serves a whole test process; `stop()`/`start()` take the server
away and bring it back (the outage tests).

`postgres` is the fixture (one cluster per test process); without the binaries it skips, saying
why.
"""

from __future__ import annotations

import contextlib
import glob
import os
import pwd
import secrets
import shutil
import socket
import subprocess
import tempfile
from collections.abc import Iterator
from pathlib import Path

import psycopg
import pytest

__all__ = ["BINARIES", "Cluster", "free_port", "postgres"]

_FOUND = sorted(glob.glob("/usr/lib/postgresql/*/bin/pg_ctl"))
BINARIES = Path(_FOUND[-1]).parent if _FOUND else None
_TIMEOUT = 60.0  # [s] a hang guard for initdb and pg_ctl


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


class Cluster:
    """One PostgreSQL cluster in a temporary directory of its own (`remove()` deletes it),
    listening on 127.0.0.1:`port` (a free one unless given)."""

    def __init__(self, port: int | None = None, *, fsync: bool = False) -> None:
        assert BINARIES is not None
        # Not under pytest's tmp_path: its root is private to root, and the server runs as
        # nobody when the tests run as root.
        self.directory = Path(tempfile.mkdtemp(prefix="flexwing-postgres-"))
        self.data = self.directory / "data"
        self.port = port or free_port()
        # Off for the tests: a server killed (pg_ctl -m immediate) loses nothing the machine's
        # page cache holds, and its crash recovery takes 0.1 s instead of ~3 s. On for the
        # benchmarks, which measure what a deployment pays.
        self.fsync = fsync
        self._as: list[str] = []
        if os.geteuid() == 0:  # initdb and postgres refuse root
            nobody = pwd.getpwnam("nobody")
            os.chown(self.directory, nobody.pw_uid, nobody.pw_gid)
            self._as = ["runuser", "-u", "nobody", "--"]
        self._run("initdb", "-D", str(self.data), "-U", "flexwing", "--auth=trust", "-E", "UTF8",
                  "--no-sync")  # fmt: skip

    def _run(self, program: str, *args: str) -> None:
        assert BINARIES is not None
        subprocess.run(
            [*self._as, str(BINARIES / program), *args],
            check=True,
            capture_output=True,
            timeout=_TIMEOUT,
        )

    def start(self) -> None:
        options = (
            f"-c listen_addresses=127.0.0.1 -c port={self.port} -c unix_socket_directories='' "
            f"-c max_connections=200 -c fsync={'on' if self.fsync else 'off'}"
        )
        self._run("pg_ctl", "-D", str(self.data), "-o", options, "-l",
                  str(self.directory / "server.log"), "-w", "-t", "60", "start")  # fmt: skip

    def stop(self, mode: str = "immediate") -> None:
        """Stop the server: `immediate` is a crash as far as clients can tell."""
        self._run("pg_ctl", "-D", str(self.data), "-m", mode, "-w", "stop")

    @property
    def base_url(self) -> str:
        return f"postgresql://flexwing@127.0.0.1:{self.port}/postgres"

    def schema(self) -> str:
        """A new empty schema; the URL of a connection whose tables go there."""
        name = "test_" + secrets.token_hex(6)
        with psycopg.connect(self.base_url, autocommit=True) as connection:
            connection.execute(f"CREATE SCHEMA {name}")
        return f"{self.base_url}?options=-csearch_path%3D{name}"

    def log(self) -> str:
        path = self.directory / "server.log"
        return path.read_text() if path.exists() else ""

    def remove(self) -> None:
        """Stop the server if it runs, and delete the cluster."""
        with contextlib.suppress(subprocess.CalledProcessError):
            self.stop()
        shutil.rmtree(self.directory, ignore_errors=True)


@pytest.fixture(scope="session")
def postgres() -> Iterator[Cluster]:
    """A running cluster for this test process (skipped without PostgreSQL's binaries)."""
    if BINARIES is None or (os.geteuid() == 0 and shutil.which("runuser") is None):
        pytest.skip(
            "PostgreSQL's binaries are not installed (Debian's postgresql package: "
            "apt-get install postgresql; .ci/run installs it)"
        )
    cluster = Cluster()
    try:
        cluster.start()
        yield cluster
    finally:
        cluster.remove()
