"""HTTP routes, one module per tag."""

from app.routes import health, page, solve, sweep

__all__ = ["health", "page", "solve", "sweep"]
