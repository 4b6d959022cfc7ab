"""app.schemas.health: the operations routes' models are what /healthz and /readyz answer.

In process no worker has started (no lifespan): the process is alive (/healthz 200) and not
ready (/readyz 503), and both answers are their published models."""

from __future__ import annotations

import httpx
import pytest
from pydantic import ValidationError

from app.schemas import ClusterWorker, HealthResponse, ReadyResponse


def test_healthz_answers_its_model(in_process: httpx.Client) -> None:
    answer = in_process.get("/healthz")
    assert answer.status_code == 200
    assert HealthResponse.model_validate(answer.json()) == HealthResponse(status="ok")
    assert answer.json() == {"status": "ok"}


def test_readyz_answers_its_model_and_is_503_before_the_pool_is_warm(
    in_process: httpx.Client,
) -> None:
    answer = in_process.get("/readyz")
    assert answer.status_code == 503
    ready = ReadyResponse.model_validate(answer.json())
    assert ready.ready is False
    assert ready.workers == 1  # the in_process settings
    assert ready.pids == []  # no worker process exists
    assert ready.warm_stations == [30]  # the mesh sizes it would warm (FLEXWING_WARM_STATIONS)
    assert ready.detail == "not started"
    assert ready.cluster is None  # the local pool, not Dask
    assert set(answer.json()) == set(ReadyResponse.model_fields)


def test_the_document_publishes_both_models_for_both_answers(in_process: httpx.Client) -> None:
    paths = in_process.get("/openapi.json").json()["paths"]

    def schema(path: str, status: str) -> object:
        return paths[path]["get"]["responses"][status]["content"]["application/json"]["schema"]

    assert schema("/healthz", "200") == {"$ref": "#/components/schemas/HealthResponse"}
    assert schema("/readyz", "200") == {"$ref": "#/components/schemas/ReadyResponse"}
    assert schema("/readyz", "503") == {"$ref": "#/components/schemas/ReadyResponse"}


@pytest.mark.parametrize(
    "body",
    [{"status": "degraded"}, {}],
    ids=["another-status", "no-status"],
)
def test_health_is_only_ever_ok(body: dict[str, str]) -> None:
    with pytest.raises(ValidationError):
        HealthResponse.model_validate(body)


def test_a_dask_worker_is_described_before_and_after_it_is_warm() -> None:
    cold = ClusterWorker(address="tcp://10.0.0.7:40123", name="w1", threads=2, warm=False, pid=None)
    warm = cold.model_copy(update={"warm": True, "pid": 4242})
    ready = ReadyResponse(
        ready=True, workers=1, pids=[], warm_stations=[30], detail="ready", cluster=[cold, warm]
    )
    again = ReadyResponse.model_validate_json(ready.model_dump_json())
    assert again.cluster is not None and [w.pid for w in again.cluster] == [None, 4242]
