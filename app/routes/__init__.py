"""HTTP routes, one module per resource: /solve and /sweep (tag equilibrium), /optimize
(design), /jobs (jobs), /wing/stations (wing), the health checks (operations) and the page;
`responses` describes their error responses."""

from app.routes import health, jobs, optimize, page, responses, solve, sweep, wing

__all__ = ["health", "jobs", "optimize", "page", "responses", "solve", "sweep", "wing"]
