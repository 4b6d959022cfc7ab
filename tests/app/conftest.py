"""Real servers for the integration tests: uvicorn subprocesses on free loopback ports.

`server`: the default configuration with a pool of 2 workers (compiling N = 30 into the default
disk cache, FLEXWING_CACHE_DIR, if it is not there yet).
`fault_server`: 2 workers on CasADi's virtual machine (no compilation, a private cache dir), with
short limits, for the tests that kill workers, overrun budgets and overload the pool.
Servers run with the defaults, so without API keys they have no rate limit (the load, fuzz and
fault tests measure the service from one address, not the limiter);
tests/app/security/test_access.py tests the limiter, with its defaults under keys too.
"""

from __future__ import annotations

import asyncio
import contextlib
import os
import signal
import socket
import subprocess
import sys
import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import httpx
import pytest

from app.main import create_app
from app.settings import Settings

ROOT = Path(__file__).resolve().parents[2]
# The first start on a machine compiles N = 30 (about 15 s per process on this 2-core machine).
_READY_TIMEOUT = 300.0


@dataclass
class Server:
    base_url: str
    process: subprocess.Popen[bytes]
    log: Path

    def client(self, timeout: float = 60.0) -> httpx.Client:
        return httpx.Client(base_url=self.base_url, timeout=timeout)

    def pids(self) -> list[int]:
        return list(httpx.get(self.base_url + "/readyz", timeout=10).json()["pids"])

    def wait_ready(self, exclude_pids: frozenset[int] = frozenset()) -> list[int]:
        """Wait until ready with a full pool, none of whose pids is in `exclude_pids`."""
        deadline = time.monotonic() + _READY_TIMEOUT
        while time.monotonic() < deadline:
            if self.process.poll() is not None:
                raise RuntimeError(f"server exited:\n{self.log.read_text()}")
            try:
                response = httpx.get(self.base_url + "/readyz", timeout=5)
                body = response.json()
                if (
                    response.status_code == 200
                    and len(body["pids"]) == body["workers"]
                    and not exclude_pids & set(body["pids"])
                ):
                    return list(body["pids"])
            except httpx.TransportError:
                pass
            time.sleep(0.05)
        raise TimeoutError(f"server not ready:\n{self.log.read_text()}")

    def metric(self, name: str, *, key: str | None = None, **labels: str) -> float:
        """The value of one sample of /metrics (0 if absent); `key`: the API key to ask with."""
        headers = {} if key is None else {"Authorization": f"Bearer {key}"}
        text = httpx.get(self.base_url + "/metrics", headers=headers, timeout=10).text
        wanted = ",".join(f'{k}="{v}"' for k, v in sorted(labels.items()))
        for line in text.splitlines():
            if line.startswith("#"):
                continue
            series, _, value = line.rpartition(" ")
            metric, _, rest = series.partition("{")
            found = ",".join(sorted(rest.rstrip("}").split(","))) if rest else ""
            if metric == name and found == wanted:
                return float(value)
        return 0.0


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def _start(
    tmp: Path, name: str, env: dict[str, str], log_level: str = "warning"
) -> Iterator[Server]:
    port = _free_port()
    log = tmp / f"{name}.log"
    defaults = {"FLEXWING_WORKERS": "2", "PYTHONUNBUFFERED": "1"}
    full_env = os.environ | defaults | env
    with open(log, "wb") as out:
        process = subprocess.Popen(
            [
                *(sys.executable, "-m", "uvicorn", "app.main:app"),
                *("--host", "127.0.0.1", "--port", str(port), "--log-level", log_level),
                *("--timeout-keep-alive", "75"),  # as the README and Dockerfile run it
            ],
            cwd=ROOT,
            env=full_env,
            stdout=out,
            stderr=subprocess.STDOUT,
            start_new_session=True,  # its own process group: workers included, see below
        )
    server = Server(f"http://127.0.0.1:{port}", process, log)
    try:
        server.wait_ready()
        yield server
    finally:
        process.send_signal(signal.SIGINT)
        try:
            process.wait(timeout=30)
        except subprocess.TimeoutExpired:
            process.kill()
            process.wait()
        # Whatever outlived the server (a forkserver and its workers, if it was killed) goes too.
        with contextlib.suppress(ProcessLookupError):
            os.killpg(process.pid, signal.SIGKILL)


@pytest.fixture(scope="session")
def server(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Server]:
    yield from _start(tmp_path_factory.mktemp("server"), "server", {})


@pytest.fixture(scope="session")
def fault_server(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Server]:
    tmp = tmp_path_factory.mktemp("fault")
    env = {
        "FLEXWING_COMPILE": "0",
        "FLEXWING_CACHE_DIR": str(tmp / "cache"),
        "FLEXWING_SOLVE_TIMEOUT": "60",
        "FLEXWING_SWEEP_TIMEOUT": "0.5",
        "FLEXWING_MAX_PENDING": "3",
    }
    yield from _start(tmp, "fault_server", env)


@pytest.fixture(scope="module")
def make_server(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Callable[..., Server]]:
    """A factory of extra servers with their own FLEXWING_* environment, e.g.
    ``make_server("tiny_budget", FLEXWING_SOLVE_TIMEOUT="0.2")`` (and uvicorn's `log_level`);
    each is stopped (SIGINT) at the end of the module unless the test has stopped it already."""
    with contextlib.ExitStack() as stack:

        def make(name: str, *, log_level: str = "warning", **env: str) -> Server:
            started = _start(tmp_path_factory.mktemp(name), name, env, log_level)
            server = next(started)
            stack.callback(started.close)
            return server

        yield make


@pytest.fixture
def client(server: Server) -> Iterator[httpx.Client]:
    with server.client() as c:
        yield c


def in_process_client(settings: Settings) -> httpx.Client:
    """An HTTP client of the app with `settings`, in this process, without its lifespan: no
    worker starts, so it answers what needs no solve (validation, 4xx problems, documents, the
    page's files), and a request that reaches the pool is 503 not-ready. For the tests that
    only check validation: no server."""
    return httpx.Client(transport=_InProcess(create_app(settings)), base_url="http://in-process")


@pytest.fixture(scope="session")
def in_process(tmp_path_factory: pytest.TempPathFactory) -> Iterator[httpx.Client]:
    """`in_process_client` of the default settings (one for the session: it keeps nothing a
    validation test could see)."""
    jobs_db = tmp_path_factory.mktemp("in_process") / "jobs.sqlite3"
    with in_process_client(Settings(workers=1, jobs_db=jobs_db)) as client:
        yield client


class _InProcess(httpx.BaseTransport):
    """A synchronous transport into an ASGI app, on an event loop of its own: httpx's own
    ASGITransport, each exchange run to its end (the body read whole)."""

    def __init__(self, app: Any) -> None:
        self.loop = asyncio.new_event_loop()
        self.asgi = httpx.ASGITransport(app=app)

    def handle_request(self, request: httpx.Request) -> httpx.Response:
        async def exchange() -> httpx.Response:
            body = b"".join([chunk async for chunk in _chunks(request.stream)])
            sent = httpx.Request(request.method, request.url, headers=request.headers, content=body)
            response = await self.asgi.handle_async_request(sent)
            content = await response.aread()
            return httpx.Response(response.status_code, headers=response.headers, content=content)

        return self.loop.run_until_complete(exchange())

    def close(self) -> None:
        self.loop.close()


async def _chunks(stream: Any) -> Any:
    for chunk in stream:
        yield chunk
