"""API keys: creating them, and the key file that holds their hashes (``python -m app.keys``).

A key is ``fw_`` and 43 URL-safe base64 characters: 32 bytes (256 bits) from `secrets`. It is
printed once, when it is created, and stored nowhere: the key file (FLEXWING_API_KEYS_FILE) holds
one line per key, ``<name> sha256:<64 hex digits>``, the SHA-256 digest of the key's text, and
may hold ``#`` comments and blank lines.

    python -m app.keys create --file keys.txt --name alice   # prints alice's key, once
    python -m app.keys list --file keys.txt                  # names and fingerprints
    python -m app.keys revoke --file keys.txt --name alice

Why one SHA-256 and not a salted, slow password hash (scrypt, PBKDF2): those make *guessing* a
low-entropy password expensive. A key has 256 random bits, so there is nothing to guess: finding
a key from its digest is a 2^256 preimage search with or without salt and stretching, and no
precomputed table covers 2^256 inputs. A slow hash would only cost every request tens of
milliseconds of CPU (a lever for denial of service) where SHA-256 costs about a microsecond.

With many replicas the keys may live in the jobs database instead (FLEXWING_API_KEYS_IN_DATABASE,
the `api_keys` table of FLEXWING_DATABASE_URL's PostgreSQL): the same digests, created and
revoked with ``--database URL`` in place of ``--file FILE`` (``import`` copies a key file's
digests there), seen by every replica within a second (`StoredKeys`).

    python -m app.keys create --database postgresql://flexwing@db/flexwing --name alice
    python -m app.keys import --file keys.txt --database postgresql://flexwing@db/flexwing

Checking a key hashes what was presented and compares the digest with every stored one by
`hmac.compare_digest`, without stopping at a match: the time taken does not depend on which key,
if any, matched. The key ring re-reads its file when it changes (checked at most once a second),
so keys are added and revoked without a restart.
"""

from __future__ import annotations

import argparse
import asyncio
import hashlib
import hmac
import logging
import os
import re
import secrets
import sys
import tempfile
import time
from collections.abc import Awaitable, Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TypeVar

from app.jobs.store import Store
from app.problems import Problem

__all__ = [
    "ApiKey",
    "KeyFileError",
    "KeyRing",
    "StoredKeys",
    "add_key",
    "digest",
    "main",
    "new_key",
    "read_key_file",
    "revoke_key",
    "verify",
]

T = TypeVar("T")

log = logging.getLogger(__name__)

KEY_PREFIX = "fw_"
KEY_BYTES = 32  # 256 random bits
FINGERPRINT_LENGTH = 8  # hex digits of the digest shown in metrics and `list`
_NAME = r"[A-Za-z0-9][A-Za-z0-9_.@-]{0,63}"
_LINE = re.compile(rf"^(?P<name>{_NAME})\s+sha256:(?P<digest>[0-9a-f]{{64}})$")
_HEADER = (
    "# flexwing API keys (FLEXWING_API_KEYS_FILE): one per line, '<name> sha256:<hex digest>'.\n"
    "# Only digests are stored here; create keys with: python -m app.keys create --name NAME\n"
)


class KeyFileError(ValueError):
    """A key file that cannot be used (a malformed line, a name or key listed twice)."""


@dataclass(frozen=True)
class ApiKey:
    """One key of the key file: its name and the SHA-256 digest of its text (32 bytes)."""

    name: str
    digest: bytes

    @property
    def principal(self) -> str:
        """Who owns what this key creates (jobs): the digest in hex. Not the key, and not
        reversible to it."""
        return self.digest.hex()

    @property
    def fingerprint(self) -> str:
        """A short public label for metrics and listings: the first hex digits of the digest."""
        return self.digest.hex()[:FINGERPRINT_LENGTH]


def new_key() -> str:
    """A new key: ``fw_`` and 256 random bits as URL-safe base64 (46 characters)."""
    return KEY_PREFIX + secrets.token_urlsafe(KEY_BYTES)


def digest(key: str | bytes) -> bytes:
    """SHA-256 of a key's text (the bytes of its header value)."""
    return hashlib.sha256(key.encode() if isinstance(key, str) else key).digest()


def _parse(text: str, source: str) -> list[ApiKey]:
    keys: list[ApiKey] = []
    names: set[str] = set()
    digests: set[bytes] = set()
    for number, raw in enumerate(text.splitlines(), start=1):
        line = raw.strip()
        if not line or line.startswith("#"):
            continue
        match = _LINE.match(line)
        if match is None:
            raise KeyFileError(
                f"{source}:{number}: expected '<name> sha256:<64 lowercase hex digits>'"
            )
        key = ApiKey(match["name"], bytes.fromhex(match["digest"]))
        if key.name in names:
            raise KeyFileError(f"{source}:{number}: the name {key.name!r} is listed twice")
        if key.digest in digests:
            raise KeyFileError(f"{source}:{number}: this key is listed twice")
        names.add(key.name)
        digests.add(key.digest)
        keys.append(key)
    return keys


def read_key_file(path: Path) -> list[ApiKey]:
    """The keys of a key file; OSError when it cannot be read, KeyFileError when malformed."""
    return _parse(path.read_text(encoding="utf-8"), str(path))


def _write(path: Path, text: str) -> None:
    """Replace `path` by `text` at once (a reader sees the old file or the new one), mode 0600."""
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, temporary = tempfile.mkstemp(prefix=f".{path.name}.", dir=path.parent)
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as out:
            out.write(text)
        os.chmod(temporary, 0o600)
        os.replace(temporary, path)
    except BaseException:
        Path(temporary).unlink(missing_ok=True)
        raise


def add_key(path: Path, name: str) -> str:
    """Create a key named `name`, store its digest in the key file (created if absent) and
    return the key: the only time it exists in clear."""
    if not re.fullmatch(_NAME, name):
        raise KeyFileError(
            f"a key name is 1-64 letters, digits, '_', '.', '@' or '-' (not first): {name!r}"
        )
    text = path.read_text(encoding="utf-8") if path.exists() else _HEADER
    if any(key.name == name for key in _parse(text, str(path))):
        raise KeyFileError(f"{path} has a key named {name!r} already (revoke it first)")
    key = new_key()
    line = f"{name} sha256:{digest(key).hex()}\n"
    _write(path, text + ("" if text.endswith("\n") else "\n") + line)
    return key


def revoke_key(path: Path, name: str) -> bool:
    """Remove the key named `name` from the key file; whether it was there."""
    text = path.read_text(encoding="utf-8")
    kept = [
        line
        for line in text.splitlines(keepends=True)
        if not ((match := _LINE.match(line.strip())) and match["name"] == name)
    ]
    if len(kept) == len(text.splitlines(keepends=True)):
        return False
    _write(path, "".join(kept))
    return True


class KeyRing:
    """The keys of a key file, re-read when the file changes (its size, time or inode; looked at
    every `recheck` seconds at most). A file that becomes unreadable or malformed keeps the keys
    it had (logged as an error); at construction it raises instead."""

    def __init__(
        self, path: Path, *, recheck: float = 1.0, clock: Callable[[], float] = time.monotonic
    ) -> None:
        self.path = path
        self.recheck = recheck
        self._clock = clock
        self._stat = self._signature()
        self._keys: tuple[ApiKey, ...] = tuple(read_key_file(path))
        self._checked = clock()

    def __len__(self) -> int:
        return len(self._keys)

    def _signature(self) -> tuple[int, int, int]:
        stat = os.stat(self.path)
        return (stat.st_ino, stat.st_size, stat.st_mtime_ns)

    def _refresh(self) -> None:
        now = self._clock()
        if now - self._checked < self.recheck:
            return
        self._checked = now
        try:
            signature = self._signature()
            if signature == self._stat:
                return
            keys = tuple(read_key_file(self.path))
        except (OSError, KeyFileError) as error:
            log.error("API keys: keeping the %d keys read before: %s", len(self._keys), error)
            return
        self._stat, self._keys = signature, keys
        log.warning("API keys: %d keys read from %s", len(keys), self.path)

    def verify(self, presented: bytes) -> ApiKey | None:
        """The key whose digest is that of `presented`, or None: in the same time whichever."""
        self._refresh()
        return _match(self._keys, presented)


def _match(keys: Sequence[ApiKey], presented: bytes) -> ApiKey | None:
    """The key whose digest is that of `presented`, compared with every key (no early exit)."""
    wanted = digest(presented)
    found = None
    for key in keys:
        if hmac.compare_digest(wanted, key.digest):
            found = key
    return found


class StoredKeys:
    """The keys of the store's `api_keys` table, re-read at most every `recheck` seconds (by
    the request that finds them older). While the store cannot be reached the keys read before
    stay in force; before any were read, a request is 503 database-unavailable, not 401."""

    def __init__(
        self, store: Store, *, recheck: float = 1.0, clock: Callable[[], float] = time.monotonic
    ) -> None:
        self.store = store
        self.recheck = recheck
        self._clock = clock
        self._keys: tuple[ApiKey, ...] | None = None
        self._checked = -float("inf")

    def __len__(self) -> int:
        return len(self._keys or ())

    async def _refresh(self) -> tuple[ApiKey, ...]:
        now = self._clock()
        if self._keys is not None and now - self._checked < self.recheck:
            return self._keys
        self._checked = now
        try:
            rows = await self.store.api_keys()
        except Problem:
            if self._keys is None:
                raise
            return self._keys  # the store is away: the keys read before
        keys = tuple(ApiKey(name, bytes.fromhex(hexdigest)) for name, hexdigest in rows)
        if keys != self._keys and self._keys is not None:
            log.warning("API keys: %d keys read from %s", len(keys), self.store.name)
        self._keys = keys
        return keys

    async def verify(self, presented: bytes) -> ApiKey | None:
        """As `KeyRing.verify`."""
        return _match(await self._refresh(), presented)


async def verify(keys: KeyRing | StoredKeys, presented: bytes) -> ApiKey | None:
    """The key of `presented` from either source of keys, or None."""
    if isinstance(keys, StoredKeys):
        return await keys.verify(presented)
    return keys.verify(presented)


# ------------------------------------------------------------------------ keys in a database


def _store_of(database: str) -> Store:
    """A PostgreSQL URL, or the path of an SQLite jobs database."""
    if database.startswith(("postgresql://", "postgres://")):
        return Store.of(database, Path())
    return Store.of(None, Path(database))


def _in_store(database: str, work: Callable[[Store], Awaitable[T]]) -> T:
    async def run() -> T:
        store = _store_of(database)
        await store.open()
        try:
            if not store.available:
                raise KeyFileError(f"cannot reach {store.name}: {store.reason}")
            return await work(store)
        finally:
            await store.close()

    return asyncio.run(run())


def add_stored_key(database: str, name: str) -> str:
    """As `add_key`, the digest kept in the database's api_keys table."""
    if not re.fullmatch(_NAME, name):
        raise KeyFileError(
            f"a key name is 1-64 letters, digits, '_', '.', '@' or '-' (not first): {name!r}"
        )
    key = new_key()
    hexdigest = digest(key).hex()
    if not _in_store(database, lambda store: store.add_api_key(name, hexdigest, time.time())):
        raise KeyFileError(f"the database has a key named {name!r} already (revoke it first)")
    return key


def import_key_file(path: Path, database: str) -> int:
    """Copy the digests of a key file into the database; how many were new there."""
    keys = read_key_file(path)

    async def copy(store: Store) -> int:
        added = [await store.add_api_key(k.name, k.digest.hex(), time.time()) for k in keys]
        return sum(added)

    return _in_store(database, copy)


# ------------------------------------------------------------------------------- the CLI


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        prog="python -m app.keys",
        description="Create, list and revoke flexwing's API keys.",
    )
    commands = parser.add_subparsers(dest="command", required=True)
    create = commands.add_parser("create", help="create a key: printed once, its digest stored")
    listing = commands.add_parser("list", help="names and fingerprints (the metrics' labels)")
    revoke = commands.add_parser("revoke", help="remove a key by name")
    copy = commands.add_parser("import", help="copy a key file's digests into a database")
    for command in (create, listing, revoke):
        source = command.add_mutually_exclusive_group(required=True)
        source.add_argument("--file", type=Path, help="the key file")
        source.add_argument(
            "--database", help="a PostgreSQL URL (or an SQLite jobs database) holding the keys"
        )
    copy.add_argument("--file", type=Path, required=True, help="the key file to copy")
    copy.add_argument("--database", required=True, help="the PostgreSQL URL to copy it to")
    for command in (create, revoke):
        command.add_argument("--name", required=True, help="whose key (unique in the file)")
    args = parser.parse_args(argv)
    where = args.file if args.database is None else redacted_source(args.database)
    try:
        if args.command == "import":
            added = import_key_file(args.file, args.database)
            print(f"{added} keys added to {where}", file=sys.stderr)
        elif args.command == "create":
            if args.database is None:
                print(add_key(args.file, args.name))
            else:
                print(add_stored_key(args.database, args.name))
            print(
                f"(the key of {args.name!r}: shown once, only its digest is in {where})",
                file=sys.stderr,
            )
        elif args.command == "list":
            if args.database is None:
                listed = [(key.name, key.fingerprint) for key in read_key_file(args.file)]
            else:
                rows = _in_store(args.database, lambda store: store.api_keys())
                listed = [(name, hexdigest[:FINGERPRINT_LENGTH]) for name, hexdigest in rows]
            for name, fingerprint in listed:
                print(f"{name}\t{fingerprint}")
        else:
            if args.database is None:
                revoked = revoke_key(args.file, args.name)
            else:
                revoked = _in_store(args.database, lambda store: store.revoke_api_key(args.name))
            if not revoked:
                print(f"{where} has no key named {args.name!r}", file=sys.stderr)
                return 1
    except (OSError, KeyFileError) as error:
        print(f"error: {error}", file=sys.stderr)
        return 1
    return 0


def redacted_source(database: str) -> str:
    """A database as the CLI names it: without the password of a URL."""
    return _store_of(database).name


if __name__ == "__main__":
    raise SystemExit(main())
