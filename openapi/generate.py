"""Write openapi/openapi.json from the app: ``python -m openapi.generate`` (or ``--check``).

The document is deterministic (sorted keys, two-space indent, trailing newline) and independent of
the environment, so a test can tell when the committed file is stale.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
from pathlib import Path

if __package__ in (None, ""):  # run as a script: python openapi/generate.py
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from app.main import create_app
from app.settings import Settings

__all__ = ["PATH", "render"]

PATH = Path(__file__).resolve().with_name("openapi.json")


def render() -> str:
    """The document of the default settings, whatever FLEXWING_* variables this shell has."""
    configured = {k: v for k, v in os.environ.items() if k.startswith("FLEXWING_")}
    for name in configured:
        del os.environ[name]
    try:
        app = create_app(Settings(workers=1))  # no pool starts: the lifespan never runs
    finally:
        os.environ.update(configured)
    return json.dumps(app.openapi(), indent=2, sort_keys=True, ensure_ascii=False) + "\n"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--check", action="store_true", help="fail if the file is stale")
    args = parser.parse_args(argv)
    text = render()
    if args.check:
        if PATH.read_text() != text:
            print(f"{PATH} is stale: run python -m openapi.generate", file=sys.stderr)
            return 1
        return 0
    PATH.write_text(text)
    print(f"wrote {PATH}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
