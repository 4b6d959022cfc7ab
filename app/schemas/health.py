"""The operations routes' response models (liveness, readiness)."""

from __future__ import annotations

from typing import Literal

from pydantic import BaseModel, Field

__all__ = ["ClusterWorker", "HealthResponse", "ReadyResponse"]


class HealthResponse(BaseModel):
    status: Literal["ok"] = Field(description="The process is alive.")


class ClusterWorker(BaseModel):
    """One worker of a Dask cluster (FLEXWING_EXECUTOR=dask)."""

    address: str = Field(description="Its address, e.g. tcp://10.0.0.7:40123.")
    name: str = Field(description="Its name (dask worker --name).")
    threads: int = Field(description="[-] threads it runs tasks on.")
    warm: bool = Field(description="It has compiled or loaded the warm mesh sizes.")
    pid: int | None = Field(description="Its process id on its machine, once warm.")


class ReadyResponse(BaseModel):
    ready: bool = Field(description="Workers are warm and accepting solves.")
    workers: int = Field(description="[-] configured worker count.")
    pids: list[int] = Field(description="Process ids of the local workers (empty if remote).")
    warm_stations: list[int] = Field(description="Mesh sizes N warmed in every worker.")
    compiled: list[int] = Field(
        default_factory=list,
        description=(
            "The warm mesh sizes N whose compiled library is on the service's disk cache: "
            "served by compiled code (the others run on CasADi's virtual machine, with the same "
            "answers, until their library is compiled and swapped in)."
        ),
    )
    detail: str = Field(description="What the pool is doing.")
    cluster: list[ClusterWorker] | None = Field(
        default=None,
        description="FLEXWING_EXECUTOR=dask: the cluster's workers and whether each is warm.",
    )
