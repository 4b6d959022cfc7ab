"""HTTP routes, one module per tag."""

from app.routes import health, solve, sweep

__all__ = ["health", "solve", "sweep"]
