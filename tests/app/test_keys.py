"""API keys and their key file (`app.security.keys`, `python -m app.keys`): keys of 256 random bits,
shown once, stored only as SHA-256 digests; a key ring that knows each key, refuses every other
string, and follows its file without a restart."""

from __future__ import annotations

import base64
import hashlib
import stat
import subprocess
import sys
from pathlib import Path

import pytest

from app.security.keys import KeyFileError, KeyRing, add_key, read_key_file, revoke_key
from tests.app.conftest import ROOT


def _cli(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "app.security.keys", *args], cwd=ROOT, capture_output=True, text=True
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


def test_two_keys_created_for_two_names_differ(tmp_path: Path) -> None:
    keys = tmp_path / "keys.txt"
    assert add_key(keys, "alice") != add_key(keys, "bob")
    assert [k.name for k in read_key_file(keys)] == ["alice", "bob"]


def test_a_name_already_in_the_file_is_refused(tmp_path: Path) -> None:
    keys = tmp_path / "keys.txt"
    add_key(keys, "alice")
    again = _cli("create", "--file", str(keys), "--name", "alice")
    assert again.returncode == 1
    assert "already" in again.stderr
    assert again.stdout == ""


def test_the_key_ring_knows_each_key_and_nothing_else(tmp_path: Path) -> None:
    keys = tmp_path / "keys.txt"
    alice, bob = add_key(keys, "alice"), add_key(keys, "bob")
    ring = KeyRing(keys)
    assert len(ring) == 2
    found_alice, found_bob = ring.verify(alice.encode()), ring.verify(bob.encode())
    assert found_alice is not None and found_alice.name == "alice"
    assert found_bob is not None and found_bob.name == "bob"
    assert found_alice.principal != found_bob.principal
    assert alice not in found_alice.principal  # the owner of jobs is the digest, not the key
    for other in (alice[:-1], alice + "x", alice.upper(), "", "fw_", bob[3:]):
        assert ring.verify(other.encode()) is None, other


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


def test_revoking_an_unknown_name_changes_nothing(tmp_path: Path) -> None:
    keys = tmp_path / "keys.txt"
    add_key(keys, "alice")
    before = keys.read_text()
    assert revoke_key(keys, "mallory") is False
    assert keys.read_text() == before


def test_a_key_file_broken_after_the_start_keeps_the_keys_it_had(tmp_path: Path) -> None:
    keys = tmp_path / "keys.txt"
    alice = add_key(keys, "alice")
    ring = KeyRing(keys, recheck=0.0)
    keys.write_text("alice sha256:not-hex\n")
    assert ring.verify(alice.encode()) is not None


BROKEN_FILES = {
    "not a digest": "alice sha256:1234\n",
    "no name": f"sha256:{'0' * 64}\n",
    "another hash": f"alice md5:{'0' * 32}\n",
    "a name twice": f"alice sha256:{'0' * 64}\nalice sha256:{'1' * 64}\n",
    "a key twice": f"alice sha256:{'0' * 64}\nbob sha256:{'0' * 64}\n",
}


@pytest.mark.parametrize("text", list(BROKEN_FILES.values()), ids=list(BROKEN_FILES))
def test_a_malformed_key_file_stops_the_start(tmp_path: Path, text: str) -> None:
    keys = tmp_path / "keys.txt"
    keys.write_text("# comment\n\n" + text)
    with pytest.raises(KeyFileError, match=r"keys.txt:\d+"):
        KeyRing(keys)


@pytest.mark.parametrize("name", ["", "-alice", "a b", "x" * 65, "al:ice"])
def test_a_key_name_is_a_short_plain_word(tmp_path: Path, name: str) -> None:
    with pytest.raises(KeyFileError):
        add_key(tmp_path / "keys.txt", name)
