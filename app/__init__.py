"""flexwing's web service: a thin FastAPI layer over `solver`, solving in worker processes.

Run it with ``uvicorn app.main:app``; settings come from ``FLEXWING_*`` environment variables
(`app.settings`).
"""

from importlib.metadata import PackageNotFoundError, version

try:
    __version__ = version("flexwing")
except PackageNotFoundError:  # pragma: no cover - running from a source tree
    __version__ = "0.0.0"

__all__ = ["__version__"]
