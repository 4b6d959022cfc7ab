"""HTTP routes: every operation of `solver.OPERATION_TABLE` (`operations`, one router each,
derived from its row), /jobs (`jobs`), /wing/stations (`wing`: a wing as the solver takes it),
the health checks (`health`) and the page (`page`); `answers` is how an operation answers (at
once or as a job), `responses` its error responses."""

from app.routes import health, jobs, operations, page, responses, wing

__all__ = ["health", "jobs", "operations", "page", "responses", "wing"]
