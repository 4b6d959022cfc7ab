"""HTTP routes: every operation of `solver.OPERATION_TABLE` (`operations`, one router each,
derived from its row), /jobs (`jobs`), the health checks (`health`) and the page (`page`);
`answers` is how an operation answers (at once or as a job), `responses` its error responses."""

from app.routes import health, jobs, operations, page, responses

__all__ = ["health", "jobs", "operations", "page", "responses"]
