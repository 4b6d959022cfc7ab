"""Preparing a process to serve: compile (or load) the models of the common mesh sizes."""

from __future__ import annotations

from solver.model.layout import Layout
from solver.numerics.cache import model_for
from solver.numerics.compiled import library_on_disk

__all__ = ["is_compiled", "warm_up"]


def warm_up(stations: int, timeout: float | None = None, chordwise_panels: int = 1) -> bool:
    """Build the model of an N-station mesh (k chordwise panels) and wait (up to `timeout`
    seconds; None: as long as it takes; 0: not at all) for its compiled library: loaded from
    the disk cache, or compiled here in the background. Returns whether compiled code serves it
    (False: CasADi's virtual machine, which gives the same answers, until the library is
    swapped in; or for good if compilation is disabled or fails)."""
    model = model_for(Layout(stations, chordwise_panels))
    model.wait_compiled(timeout)
    return model.compiled


def is_compiled(stations: int, chordwise_panels: int = 1) -> bool:
    """An N-station mesh's compiled library is on the disk cache: its next solve runs it."""
    return library_on_disk(Layout(stations, chordwise_panels))
