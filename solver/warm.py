"""Preparing a process to serve: compile (or load) the models of the common mesh sizes."""

from __future__ import annotations

from solver.cache import model_for
from solver.layout import Layout

__all__ = ["warm_up"]


def warm_up(stations: int, timeout: float | None = None, chordwise_panels: int = 1) -> bool:
    """Build the model of an N-station mesh (k chordwise panels) and wait (up to `timeout`
    seconds) for its compiled library: loaded from the disk cache, or compiled here. Returns
    whether compiled code serves it (False: CasADi's virtual machine, e.g. compilation disabled,
    failed or still running)."""
    model = model_for(Layout(stations, chordwise_panels))
    model.wait_compiled(timeout)
    return model.compiled
