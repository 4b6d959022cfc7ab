"""Jobs (issue 13): long work accepted at once and run in the background (POST /jobs).

`operations`: the registry of what a job can run (solve, sweep, optimize, batch); `models`: the
API's models; `store`: the SQLite database; `manager`: queueing, running, cancelling, streaming.
"""

from app.jobs.manager import JobManager
from app.jobs.operations import JOB_KINDS, JobKind, register

__all__ = ["JOB_KINDS", "JobKind", "JobManager", "register"]
