"""``python -m app.keys``: create, list and revoke API keys (`app.security.keys`)."""

from __future__ import annotations

from app.security.keys import main

__all__ = ["main"]

if __name__ == "__main__":
    raise SystemExit(main())
