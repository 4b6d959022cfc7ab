"""app.security.keys: keys of 256 random bits, stored only as SHA-256 digests in a key file of
one `<name> sha256:<hex>` line per key; a key ring that knows each key, refuses every other
string, follows its file without a restart (looking at it once per `recheck` at most) and keeps
the keys it had when the file breaks; keys kept in the store instead (`StoredKeys`, on both
backends) seen by every replica within a `recheck`. The command line: tests/app/test_keys.py."""

from __future__ import annotations

import asyncio
import base64
import hashlib
from pathlib import Path

import pytest

from app.jobs.store import Store
from app.problems import Problem
from app.security.keys import (
    ApiKey,
    KeyFileError,
    KeyRing,
    StoredKeys,
    add_key,
    digest,
    new_key,
    read_key_file,
    revoke_key,
)
from tests.app.jobs.conftest import Backend
from tests.postgres import free_port


def test_a_new_key_is_256_random_bits_behind_its_prefix() -> None:
    keys = {new_key() for _ in range(100)}
    assert len(keys) == 100
    for key in keys:
        assert key.startswith("fw_") and len(key) == 46
        assert len(base64.urlsafe_b64decode(key[3:] + "=")) == 32


def test_a_keys_principal_and_fingerprint_come_from_its_digest_not_the_key(
    tmp_path: Path,
) -> None:
    keys = tmp_path / "keys.txt"
    key = add_key(keys, "alice")
    (stored,) = read_key_file(keys)
    assert stored.digest == digest(key) == hashlib.sha256(key.encode()).digest()
    assert digest(key.encode()) == digest(key)  # a header's bytes and its text alike
    assert stored.principal == hashlib.sha256(key.encode()).hexdigest()
    assert stored.fingerprint == stored.principal[:8]
    assert key not in keys.read_text() and key[3:] not in keys.read_text()


def test_two_keys_created_for_two_names_differ(tmp_path: Path) -> None:
    keys = tmp_path / "keys.txt"
    assert add_key(keys, "alice") != add_key(keys, "bob")
    assert [k.name for k in read_key_file(keys)] == ["alice", "bob"]


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


@pytest.mark.parametrize(
    "name",
    ["", "-alice", "a b", "x" * 65, "al:ice"],
    ids=["empty", "leading-dash", "space", "65-characters", "colon"],
)
def test_a_key_name_is_a_short_plain_word(tmp_path: Path, name: str) -> None:
    with pytest.raises(KeyFileError):
        add_key(tmp_path / "keys.txt", name)


class Clock:
    """A monotonic clock the test moves."""

    def __init__(self) -> None:
        self.now = 100.0

    def __call__(self) -> float:
        return self.now


def test_the_key_ring_looks_at_its_file_once_per_recheck_at_most(tmp_path: Path) -> None:
    keys = tmp_path / "keys.txt"
    alice = add_key(keys, "alice")
    clock = Clock()
    ring = KeyRing(keys, recheck=1.0, clock=clock)
    assert revoke_key(keys, "alice") is True
    clock.now += 0.75  # (binary fractions: the sums are exact)
    assert ring.verify(alice.encode()) is not None  # not looked at yet
    clock.now += 0.25
    assert ring.verify(alice.encode()) is None  # a second on: the revocation is seen
    assert len(ring) == 0


# ------------------------------------------------------------------ keys in the database


def test_keys_in_the_database_are_seen_and_revoked_within_the_recheck(database: Backend) -> None:
    """Keys another replica (or the command line) adds or revokes in the store are seen a
    `recheck` later, not before; a key never added is refused."""
    clock = Clock()

    async def scenario() -> None:
        store = database.store()
        await store.open()
        try:
            alice = new_key()
            assert await store.add_api_key("alice", digest(alice).hex(), 0.0)
            keys = StoredKeys(store, recheck=1.0, clock=clock)
            found = await keys.verify(alice.encode())
            assert found is not None and found == ApiKey("alice", digest(alice))
            assert await keys.verify(new_key().encode()) is None
            assert await store.revoke_api_key("alice")
            clock.now += 0.75
            assert await keys.verify(alice.encode()) is not None  # not looked at yet
            clock.now += 0.25
            assert await keys.verify(alice.encode()) is None
            assert len(keys) == 0
        finally:
            await store.close()

    asyncio.run(scenario())


def test_keys_in_an_unreachable_database_are_503_until_read_then_kept(tmp_path: Path) -> None:
    """Before the keys were ever read, a request is 503 database-unavailable (not 401: its key
    may well be valid); once read, they stay in force while the store is away."""
    clock = Clock()

    async def scenario() -> None:
        url = f"postgresql://flexwing@127.0.0.1:{free_port()}/flexwing"
        away = Store.of(url, tmp_path)
        await away.open()
        try:
            with pytest.raises(Problem) as refused:
                await StoredKeys(away, clock=clock).verify(b"fw_anything")
            assert refused.value.type.slug == "database-unavailable"
        finally:
            await away.close()
        store = Store.of(None, tmp_path / "jobs.sqlite3")
        await store.open()
        alice = new_key()
        await store.add_api_key("alice", digest(alice).hex(), 0.0)
        keys = StoredKeys(store, clock=clock)
        assert await keys.verify(alice.encode()) is not None
        await store.close()  # the store goes away
        clock.now += 10.0
        assert await keys.verify(alice.encode()) is not None

    asyncio.run(scenario())
