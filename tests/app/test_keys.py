"""The keys command line, `app.security.keys.main` (`_cli` runs it as the documented
`python -m app.keys`): `create` prints a key of 256 random bits once and stores only
its SHA-256 digest, `list` shows names and fingerprints, `revoke` removes a key, which a running
key ring then refuses without a restart. The key ring and the key file themselves:
tests/app/security/test_keys.py."""

from __future__ import annotations

import base64
import hashlib
import stat
import subprocess
import sys
from pathlib import Path

import pytest

from app.security.keys import KeyRing, add_key, main
from tests.app.conftest import ROOT


def _cli(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "app.keys", *args], cwd=ROOT, capture_output=True, text=True
    )


def test_create_prints_a_256_bit_key_once_and_stores_only_its_digest(tmp_path: Path) -> None:
    keys = tmp_path / "keys.txt"
    created = _cli("create", "--file", str(keys), "--name", "alice")
    assert created.returncode == 0, created.stderr
    key = created.stdout.strip()
    assert key.startswith("fw_")
    assert len(base64.urlsafe_b64decode(key[3:] + "=")) == 32  # 256 random bits
    text = keys.read_text()
    assert key not in text and key[3:] not in text
    assert f"alice sha256:{hashlib.sha256(key.encode()).hexdigest()}" in text.splitlines()
    assert stat.S_IMODE(keys.stat().st_mode) == 0o600
    listed = _cli("list", "--file", str(keys))
    assert listed.stdout == f"alice\t{hashlib.sha256(key.encode()).hexdigest()[:8]}\n"


def test_a_name_already_in_the_file_is_refused(tmp_path: Path) -> None:
    keys = tmp_path / "keys.txt"
    add_key(keys, "alice")
    again = _cli("create", "--file", str(keys), "--name", "alice")
    assert again.returncode == 1
    assert "already" in again.stderr
    assert again.stdout == ""


def test_a_revoked_key_is_refused_without_a_restart(tmp_path: Path) -> None:
    keys = tmp_path / "keys.txt"
    alice, bob = add_key(keys, "alice"), add_key(keys, "bob")
    ring = KeyRing(keys, recheck=0.0)  # looks at the file on every check
    assert ring.verify(alice.encode()) is not None
    revoked = _cli("revoke", "--file", str(keys), "--name", "alice")
    assert revoked.returncode == 0, revoked.stderr
    assert ring.verify(alice.encode()) is None
    assert ring.verify(bob.encode()) is not None
    carol = add_key(keys, "carol")
    assert ring.verify(carol.encode()) is not None


def test_keys_are_created_listed_revoked_and_imported_in_a_database(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """`--database` in place of `--file` (here an SQLite jobs database; a PostgreSQL URL the
    same way): the key printed once, its digest kept in the api_keys table; `import` copies a
    key file's digests there, once. In process (`main`), but for one run of the command."""
    database = str(tmp_path / "jobs.sqlite3")

    def cli(*args: str) -> tuple[int, str, str]:
        code = main(list(args))
        out, err = capsys.readouterr()
        return code, out, err

    created = _cli("create", "--database", database, "--name", "alice")
    assert created.returncode == 0, created.stderr
    alice = created.stdout.strip()
    assert alice.startswith("fw_") and database in created.stderr
    fingerprint = hashlib.sha256(alice.encode()).hexdigest()[:8]
    assert cli("list", "--database", database) == (0, f"alice\t{fingerprint}\n", "")
    code, out, err = cli("create", "--database", database, "--name", "alice")
    assert (code, out) == (1, "") and "already" in err
    keys = tmp_path / "keys.txt"
    bob = add_key(keys, "bob")
    assert cli("import", "--file", str(keys), "--database", database)[::2] == (
        0,
        f"1 keys added to {database}\n",
    )
    assert "0 keys added" in cli("import", "--file", str(keys), "--database", database)[2]
    assert cli("revoke", "--database", database, "--name", "alice")[0] == 0
    assert cli("revoke", "--database", database, "--name", "alice")[0] == 1
    bob_fingerprint = hashlib.sha256(bob.encode()).hexdigest()[:8]
    assert cli("list", "--database", database)[1] == f"bob\t{bob_fingerprint}\n"
