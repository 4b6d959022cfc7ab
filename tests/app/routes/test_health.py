"""Health, readiness, metrics, the OpenAPI document and a generated client."""

from __future__ import annotations

import importlib
import json
import shutil
import subprocess
import sys
import time
from collections.abc import Callable
from pathlib import Path

import httpx
import pytest

from openapi.generate import PATH as OPENAPI_PATH
from openapi.generate import render
from tests import study
from tests.app.conftest import ROOT, Server


def test_healthz_and_readyz(client: httpx.Client) -> None:
    assert client.get("/healthz").json() == {"status": "ok"}
    ready = client.get("/readyz")
    assert ready.status_code == 200
    body = ready.json()
    assert body["ready"] is True
    assert body["workers"] == 2
    assert len(body["pids"]) == 2
    assert body["warm_stations"] == [30]


def test_metrics_count_requests_solves_and_cache_hits(server: Server) -> None:
    before_hits = server.metric("flexwing_cache_lookups_total", cache="result", result="hit")
    before_ok = server.metric(
        "flexwing_http_requests_total", route="/solve", method="POST", status="200"
    )
    before_solves = server.metric("flexwing_solves_total", kind="solve", outcome="equilibrium")
    before_in_worker = server.metric("flexwing_worker_task_duration_seconds_count")
    with server.client() as client:
        body = study.solve_request(7.75)
        assert client.post("/solve", json=body).status_code == 200
        assert client.post("/solve", json=body).status_code == 200
    assert server.metric(
        "flexwing_http_requests_total", route="/solve", method="POST", status="200"
    ) == (before_ok + 2)
    assert server.metric("flexwing_cache_lookups_total", cache="result", result="hit") == (
        before_hits + 1
    )
    assert server.metric("flexwing_solves_total", kind="solve", outcome="equilibrium") == (
        before_solves + 1
    )
    # The miss ran in a worker, which said for how long (jobs of other tests may add theirs).
    assert server.metric("flexwing_worker_task_duration_seconds_count") >= before_in_worker + 1
    assert server.metric("flexwing_ready") == 1.0


def test_committed_openapi_is_current() -> None:
    assert OPENAPI_PATH.read_text() == render(), "stale: run python -m openapi.generate"


def test_operation_ids_are_clean() -> None:
    schema = json.loads(OPENAPI_PATH.read_text())
    ids = {op["operationId"] for path in schema["paths"].values() for op in path.values()}
    assert ids == {"solve", "sweep", "optimize", "flutter", "roll", "controls"} | {
        "healthz",
        "readyz",
        "submit_job",
        "list_jobs",
        "get_job",
        "cancel_job",
        "job_events",
        "job_items",
        "wing_stations",
    }
    solve = schema["paths"]["/solve"]["post"]
    assert "application/problem+json" in solve["responses"]["422"]["content"]


@pytest.fixture(scope="module")
def generated_client(tmp_path_factory: pytest.TempPathFactory) -> object:
    out = tmp_path_factory.mktemp("client")
    config = out / "config.json"
    # The generator reads no NDJSON (a batch job's items): it gets them as bytes.
    overrides = {"application/x-ndjson": "application/octet-stream"}
    config.write_text(json.dumps({"post_hooks": [], "content_type_overrides": overrides}))
    generator = Path(sys.executable).with_name("openapi-python-client")
    subprocess.run(
        [
            *(str(generator), "generate", "--path", str(OPENAPI_PATH), "--meta", "none"),
            *("--output-path", str(out / "flexwing_client"), "--config", str(config)),
            "--fail-on-warning",
        ],
        cwd=out,
        check=True,
        capture_output=True,
    )
    sys.path.insert(0, str(out))
    try:
        return importlib.import_module("flexwing_client")
    finally:
        sys.path.remove(str(out))


def test_generated_client_solves_and_sweeps(generated_client: object, server: Server) -> None:
    from flexwing_client import Client  # type: ignore[import-not-found]
    from flexwing_client.api.equilibrium import solve, sweep  # type: ignore[import-not-found]
    from flexwing_client.models import (  # type: ignore[import-not-found]
        ProblemDetails,
        SolveRequest,
        SolveResponse,
        SweepRequest,
        SweepResponse,
    )

    client = Client(base_url=server.base_url, timeout=httpx.Timeout(60))
    result = solve.sync(client=client, body=SolveRequest.from_dict(study.solve_request(10.0)))
    assert isinstance(result, SolveResponse)
    assert result.totals.lift == pytest.approx(304.1, abs=0.05)
    assert result.totals.tip_twist == pytest.approx(1.71, abs=0.005)

    request = SweepRequest.from_dict(
        {"wing": study.wing_json(), "flight": {"alpha": 5.0}, "velocities": [6, 22]}
    )
    swept = sweep.sync(client=client, body=request)
    assert isinstance(swept, SweepResponse)
    assert [p.status for p in swept.points] == ["equilibrium", "no_equilibrium"]
    assert 21.43 < swept.divergence.fold.velocity < 21.45

    problem = solve.sync(client=client, body=SolveRequest.from_dict(study.solve_request(23.0)))
    assert isinstance(problem, ProblemDetails)
    assert problem.type_ == "/problems/no-equilibrium"


def test_openapi_generator_runs_as_a_script(tmp_path: Path) -> None:
    result = subprocess.run(
        [sys.executable, "openapi/generate.py", "--check"], cwd=ROOT, capture_output=True
    )
    assert result.returncode == 0, result.stderr


_GATED_COMPILER = """#!/bin/sh
# A C compiler whose library builds wait for the test's go-ahead (flag probes pass at once).
case "$*" in *-shared*) while [ ! -e "$GATE" ]; do sleep 0.05; done;; esac
exec cc "$@"
"""


@pytest.mark.skipif(shutil.which("cc") is None, reason="no C compiler: nothing compiles")
def test_a_fresh_machine_is_ready_on_the_virtual_machine_and_swaps_the_library_in(
    make_server: Callable[..., Server], tmp_path: Path
) -> None:
    """Without a compiled cache the service is ready at once and answers on CasADi's virtual
    machine while the warm mesh size compiles; once the library is there it serves compiled
    code, with the same numbers to the bit."""
    compiler, gate = tmp_path / "cc", tmp_path / "go"
    compiler.write_text(_GATED_COMPILER)
    compiler.chmod(0o755)
    n = 5
    server = make_server(
        "fresh_machine",
        FLEXWING_COMPILE="1",
        FLEXWING_CC=str(compiler),
        FLEXWING_CACHE_DIR=str(tmp_path / "cache"),
        FLEXWING_WARM_STATIONS=f"[{n}]",
        FLEXWING_RESULT_CACHE_BYTES="0",  # the same request is solved again, not remembered
        GATE=str(gate),
    )
    y = [i / (n - 1) * 5 for i in range(n)]
    body = {
        "wing": {
            "y": y,
            "chord": 1.0,
            "elastic_axis": 0.4,
            "bending_stiffness": 2e4,
            "torsional_stiffness": 1e3,
        },
        "flight": {"velocity": 10.0, "alpha": 5.0},
    }
    with server.client() as client:
        ready = client.get("/readyz").json()
        assert ready["ready"] is True and ready["compiled"] == []  # its compile is held back
        on_the_vm = client.post("/solve", json=body)
        assert on_the_vm.status_code == 200
        gate.touch()
        while client.get("/readyz").json()["compiled"] != [n]:
            time.sleep(0.1)  # the hang guard bounds a compile that never ends
        compiled = client.post("/solve", json=body)
    assert compiled.status_code == 200
    timing = {"seconds"}
    vm, cc = on_the_vm.json(), compiled.json()
    assert {k: v for k, v in vm.items() if k != "solver"} == {
        k: v for k, v in cc.items() if k != "solver"
    }
    assert {k: v for k, v in vm["solver"].items() if k not in timing} == {
        k: v for k, v in cc["solver"].items() if k not in timing
    }
