"""Service settings, read from environment variables prefixed with ``FLEXWING_``.

Every field below is documented with its unit; docs/deployment.md's settings table is generated
from them (``table()``). The solver's own variables (``FLEXWING_CACHE_DIR``,
``FLEXWING_COMPILE``, ``FLEXWING_CC``, ``FLEXWING_SOLVER_CACHE_BYTES``) are read by the solver
directly and are not repeated here.
"""

from __future__ import annotations

import json
import os
import re
from functools import lru_cache
from pathlib import Path
from typing import Literal

from pydantic import AliasChoices, Field, field_validator, model_validator
from pydantic_settings import BaseSettings, SettingsConfigDict

__all__ = [
    "KEYED_RATE_LIMIT",
    "MAX_ARRAY_LENGTH",
    "MAX_BATCH_ITEMS",
    "Settings",
    "default_jobs_db",
    "get_settings",
    "table",
]

# Hard ceiling on every array in a request, whatever the settings: validation stops at one
# `too_long` error instead of judging (and listing) every item of a huge array. The configured
# limits (max_stations, max_sweep_points) apply below it.
MAX_ARRAY_LENGTH = 1000


# [requests/s] the rate limit of one API key when FLEXWING_RATE_LIMIT is unset and keys are on.
KEYED_RATE_LIMIT = 50.0

# Hard ceiling on the items of one batch job, whatever the settings (FLEXWING_MAX_BATCH_ITEMS
# applies below it).
MAX_BATCH_ITEMS = 10_000


def default_jobs_db() -> Path:
    """The jobs database under the user's cache directory (XDG_CACHE_HOME, else ~/.cache)."""
    cache = os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
    return Path(cache) / "flexwing" / "jobs.sqlite3"


def _cpu_count() -> int:
    """CPUs this process may run on (its affinity, e.g. a container's cpuset)."""
    if hasattr(os, "sched_getaffinity"):
        return len(os.sched_getaffinity(0))
    return os.cpu_count() or 1


class Settings(BaseSettings):
    model_config = SettingsConfigDict(env_prefix="FLEXWING_", extra="ignore", populate_by_name=True)

    workers: int = Field(
        default_factory=_cpu_count,
        ge=1,
        description="Worker processes that run solves (default: the CPUs available).",
    )
    executor: str = Field(
        default="process",
        description=(
            "'process' for the local worker processes, 'dask' for a Dask cluster "
            "(FLEXWING_DASK_SCHEDULER), or 'module:callable' naming a factory that takes the "
            "Settings and returns a concurrent.futures.Executor."
        ),
    )
    start_method: Literal["forkserver", "spawn"] = Field(
        default="forkserver",
        description="multiprocessing start method of the local pool: forkserver or spawn.",
    )
    warm_stations: list[int] = Field(
        default=[30],
        description=(
            "Mesh sizes N each worker compiles or loads before the service is ready "
            '(a JSON list, e.g. "[30, 60]").'
        ),
    )
    warmup_timeout: float = Field(
        default=0.0,
        ge=0,
        description=(
            "[s] longest a worker waits, before the service is ready, for the compiled library "
            "of a warm mesh size that is not on the disk cache yet. 0: ready at once, serving "
            "on CasADi's virtual machine (the same answers, slower) while the library compiles "
            "in the background; each worker swaps it in when it is there."
        ),
    )
    solve_timeout: float = Field(
        default=20.0, gt=0, description="[s] time budget of one /solve (and one /roll) in a worker."
    )
    sweep_timeout: float = Field(
        default=120.0,
        gt=0,
        description="[s] time budget of one /sweep (and one /controls) in a worker.",
    )
    optimize_timeout: float = Field(
        default=120.0, gt=0, description="[s] time budget of one /optimize in a worker."
    )
    flutter_timeout: float = Field(
        default=120.0, gt=0, description="[s] time budget of one /flutter in a worker."
    )
    loads_timeout: float = Field(
        default=120.0,
        gt=0,
        description="[s] time budget of one /loads chunk of cases in a worker (and its envelope).",
    )
    sync_wait: float = Field(
        default=10.0,
        gt=0,
        description=(
            "[s] how long a synchronous request to an operation (POST /solve, /sweep, /loads, "
            "...) waits for its answer; "
            "past it the request becomes a job at once (202 Accepted, Location: /jobs/{id}) "
            "that runs on within its time budget. A client may ask for a longer wait, up to that "
            "budget, with Prefer: wait=<seconds> (RFC 7240)."
        ),
    )
    tasks_per_worker: int = Field(
        default=2,
        ge=1,
        le=8,
        validation_alias=AliasChoices("flexwing_tasks_per_worker", "flexwing_jobs_per_worker"),
        description=(
            "Tasks (solves, sweeps, designs, batch items) handed to each worker at once: one "
            "running, the rest queued behind it so the worker never idles between them (a time "
            "budget counts only the run). FLEXWING_JOBS_PER_WORKER, its former name, is read too."
        ),
    )
    max_pending: int = Field(
        default=64,
        ge=1,
        description="Solves running or waiting for a worker; beyond it requests get 503.",
    )
    retry_on_worker_loss: bool = Field(
        default=True,
        description="Run a request once more when its worker died under it (else 503 at once).",
    )
    max_stations: int = Field(
        default=150, ge=3, le=MAX_ARRAY_LENGTH, description="Largest mesh size N accepted."
    )
    max_panels: int = Field(
        default=240,
        ge=1,
        description=(
            "Most vortex panels on each half wing, (N - 1) k: the study's 30 stations with 8 "
            "chordwise panels. A mesh's first solve runs on CasADi's virtual machine while its "
            "library compiles: 3.6-5.2 s at 240 panels, 14 s at 298 (N = 150, k = 2) and past "
            "the 20 s budget at 1,192 (k = 8)."
        ),
    )
    max_sweep_points: int = Field(
        default=50, ge=1, le=MAX_ARRAY_LENGTH, description="Most velocities in one /sweep."
    )
    max_load_cases: int = Field(
        default=500,
        ge=1,
        le=100_000,
        description=(
            "Most load cases in one /loads: those given and those its envelope derives "
            "together (a 200-case envelope of the study's wing takes about a second); and in "
            "one /optimize (its load_cases: each case adds an equilibrium to every step of "
            "the design)."
        ),
    )
    max_body_bytes: int = Field(
        default=1_000_000, ge=1024, description="[bytes] largest request body accepted."
    )
    result_cache_bytes: int = Field(
        default=64 * 2**20,
        ge=0,
        description=(
            "[bytes] memory for finished responses kept for repeated requests (0: none); "
            "estimated from their content, least recently used evicted first."
        ),
    )
    retry_after: int = Field(
        default=1, ge=0, description="[s] Retry-After sent with 503 responses."
    )

    # ------------------------------------------------------------------------ jobs (issue 13)
    jobs_db: Path = Field(
        default_factory=default_jobs_db,
        description=(
            "SQLite file of the jobs (POST /jobs): finished jobs survive a restart. Default: "
            "~/.cache/flexwing/jobs.sqlite3 (under XDG_CACHE_HOME when set). Unused with "
            "FLEXWING_DATABASE_URL."
        ),
    )
    database_url: str | None = Field(
        default=None,
        description=(
            "PostgreSQL database shared by every replica (postgresql://user:password@host:5432/"
            "dbname; libpq parameters such as sslmode may follow): jobs, their items, API keys "
            "(FLEXWING_API_KEYS_IN_DATABASE) and rate-limit buckets live there, and any replica "
            "answers for any job. The service creates and migrates its tables. Unset: the "
            "SQLite file FLEXWING_JOBS_DB (one machine)."
        ),
    )
    job_lease: float = Field(
        default=10.0,
        ge=1.0,
        le=3600.0,
        description=(
            "[s] how long a replica's claim on a job it runs lasts unless renewed (every "
            "lease/4, at most every second): a replica that dies leaves its jobs to another "
            "after at most this."
        ),
    )
    job_poll_interval: float = Field(
        default=0.5,
        gt=0,
        le=60.0,
        description=(
            "[s] how often an idle replica looks for queued jobs in the store (one submitted "
            "here starts at once)."
        ),
    )
    job_attempts: int = Field(
        default=3,
        ge=1,
        le=100,
        description=(
            "Times a job is taken up after the replica running it died; then it fails with "
            "/problems/job-interrupted (a job that kills its replica does not kill them all)."
        ),
    )
    job_retention: float = Field(
        default=86_400.0,
        gt=0,
        description="[s] how long a finished (succeeded, failed, cancelled) job is kept.",
    )
    max_queued_jobs: int = Field(
        default=100,
        ge=1,
        description="Jobs waiting to start; beyond it POST /jobs gets 503 with Retry-After.",
    )
    job_runners: int = Field(
        default=2,
        ge=1,
        le=64,
        description=(
            "Jobs running at once; each fans its work out over every worker (a batch keeps "
            "workers x tasks_per_worker items in flight)."
        ),
    )
    max_batch_items: int = Field(
        default=MAX_BATCH_ITEMS,
        ge=1,
        le=MAX_BATCH_ITEMS,
        description=f"Most /solve requests in one batch job (at most {MAX_BATCH_ITEMS}).",
    )
    max_job_body_bytes: int = Field(
        default=50_000_000,
        ge=1024,
        description=(
            "[bytes] largest POST /jobs body (a batch of 10,000 solves of 30 stations is about "
            "25 MB); other requests keep FLEXWING_MAX_BODY_BYTES."
        ),
    )
    # ----------------------------------------------------------------- Dask (issue 13)
    dask_scheduler: str | None = Field(
        default=None,
        description=(
            "Address of the dask.distributed scheduler (e.g. tcp://10.0.0.5:8786) used when "
            "FLEXWING_EXECUTOR=dask."
        ),
    )
    dask_tasks_per_thread: int = Field(
        default=8,
        ge=1,
        le=64,
        description=(
            "Dask tasks in flight per worker thread of the cluster: hides Dask's ~20 ms round "
            "trip per task (its batched messages). A solve's time budget counts from submission "
            "on Dask, so it includes waiting behind at most this many tasks."
        ),
    )

    # ------------------------------------------------------- sharing the service (issue 16)
    api_keys_file: Path | None = Field(
        default=None,
        description=(
            "Key file of the API keys (python -m app.keys create --file FILE --name NAME): with "
            "it, every request but /healthz, /readyz, the page and the documentation needs "
            "Authorization: Bearer <key>, and jobs belong to the key that created them. Unset: "
            "no keys (keep the service on loopback)."
        ),
    )
    api_keys_in_database: bool = Field(
        default=False,
        description=(
            "Keys in the jobs database (FLEXWING_DATABASE_URL's, or the SQLite file) instead of "
            "a key file: python -m app.keys create --database URL --name NAME; every replica "
            "sees a key created or revoked within a second. Turns keys on as "
            "FLEXWING_API_KEYS_FILE does (use one or the other)."
        ),
    )
    rate_limit: float | None = Field(
        default=None,
        ge=0,
        description=(
            "[requests/s] sustained rate of one client (an API key; a client address without "
            "keys); beyond it 429 with Retry-After. 0: no rate limit. Unset: 50 per API key "
            "with keys (a shared service), none without (the embedded deployment has one owner, "
            "whose design loops and batches must not be throttled)."
        ),
    )
    rate_burst: int = Field(
        default=100,
        ge=1,
        description="[requests] what one client may send at once after idling (its bucket).",
    )
    cors_origins: list[str] = Field(
        default=[],
        description=(
            "Origins whose pages may call the API from a browser (CORS), a JSON list such as "
            "'[\"https://wings.example.org\"]'. Empty (the default): no CORS headers at all."
        ),
    )

    @property
    def keys_on(self) -> bool:
        """Whether requests need an API key (a key file, or keys in the database)."""
        return self.api_keys_file is not None or self.api_keys_in_database

    @property
    def client_rate_limit(self) -> float:
        """[requests/s] the rate limit in force: FLEXWING_RATE_LIMIT, or when unset 50 per key
        with API keys and none (0) without."""
        if self.rate_limit is not None:
            return self.rate_limit
        return KEYED_RATE_LIMIT if self.keys_on else 0.0

    @field_validator("database_url")
    @classmethod
    def _postgres(cls, url: str | None) -> str | None:
        if url is None or url == "":
            return None
        if not re.match(r"postgres(ql)?://", url):
            raise ValueError("a PostgreSQL URL: postgresql://user:password@host:port/dbname")
        return url

    @model_validator(mode="after")
    def _one_key_source(self) -> Settings:
        if self.api_keys_file is not None and self.api_keys_in_database:
            raise ValueError(
                "FLEXWING_API_KEYS_FILE and FLEXWING_API_KEYS_IN_DATABASE: keys come from one"
            )
        return self

    @field_validator("cors_origins")
    @classmethod
    def _origins(cls, origins: list[str]) -> list[str]:
        for origin in origins:
            if not re.fullmatch(r"https?://[^/\s*]+", origin):
                raise ValueError(f"not an origin (scheme://host[:port], no path): {origin!r}")
        return origins


def _default(name: str) -> str:
    """A setting's default as the table shows it."""
    field = Settings.model_fields[name]
    if field.default_factory is not None:
        return {"workers": "CPUs available", "jobs_db": "~/.cache/flexwing/jobs.sqlite3"}.get(
            name, "computed"
        )
    value = field.default
    if value is None:
        return "unset"
    if isinstance(value, list):
        return json.dumps(value)
    if isinstance(value, bool):
        return "true" if value else "false"
    return str(value)


def table() -> str:
    """The settings as a Markdown table (docs/deployment.md holds it; a test keeps it current):
    each variable, its default and what it means, from the fields' own descriptions."""
    rows = ["| variable | default | meaning |", "| --- | --- | --- |"]
    for name, field in Settings.model_fields.items():
        meaning = " ".join((field.description or "").split()).replace("|", "\\|")
        rows.append(f"| `FLEXWING_{name.upper()}` | `{_default(name)}` | {meaning} |")
    return "\n".join(rows) + "\n"


@lru_cache(maxsize=1)
def get_settings() -> Settings:
    return Settings()


_TABLE_START, _TABLE_END = (
    "<!-- settings: generated by app.settings.table() -->\n",
    "<!-- /settings -->",
)


def write_table(guide: Path) -> None:
    """Replace the settings table in `guide` (docs/deployment.md) with `table()`."""
    text = guide.read_text()
    start = text.index(_TABLE_START) + len(_TABLE_START)
    guide.write_text(text[:start] + table() + text[text.index(_TABLE_END) :])


if __name__ == "__main__":  # python -m app.settings: regenerate docs/deployment.md's table
    write_table(Path(__file__).resolve().parents[1] / "docs" / "deployment.md")
