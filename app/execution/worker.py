"""What runs inside a worker process: one function for every operation.

A task is a solver operation input (`solver.SolveInput`, `SweepInput`, `OptimizeInput`,
`FlutterInput`: frozen dataclasses of numpy arrays and floats, validated before they left the
service); `run` answers it with its result's response body, serialised here once
(`app.schemas.Answer`), or with the solver's own typed error when there is no answer
(`solver.SolverError`, or `InvalidInput` for an input the service's validation let through: a
defect of that validation, still answered as that input's 422). Solver errors pickle, so they
cross the process boundary as they are; no CasADi object ever does: each process builds (or
loads from the disk cache) the compiled functions of a mesh size once and keeps them in the
solver's cache.
"""

from __future__ import annotations

import logging
import os
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from app.schemas.responses import Answer
from solver import InvalidInput, Progress, SolverError, warm_up

__all__ = ["Outcome", "WarmReport", "assemble", "plan", "run", "run_each", "run_parts", "warm"]

log = logging.getLogger(__name__)


@dataclass(frozen=True)
class Outcome:
    """A task's answer: its result's response body, or the error that says why there is
    none."""

    answer: Answer | None
    error: SolverError | InvalidInput | None = None


@dataclass(frozen=True)
class WarmReport:
    pid: int
    compiled: dict[int, bool]


def warm(warm_stations: tuple[int, ...], timeout: float) -> WarmReport:
    """Compile or load the solver functions of the common mesh sizes in this worker (each one
    waits up to `timeout` seconds) and report which are served compiled.

    Never raises: a worker whose compilation failed still serves from CasADi's virtual machine.
    """
    compiled = {}
    for n in warm_stations:
        try:
            compiled[n] = warm_up(n, timeout)
        except Exception:
            log.exception("warming N=%d failed; this worker uses CasADi's VM for it", n)
            compiled[n] = False
    return WarmReport(os.getpid(), compiled)


def run(task: Any, progress: Progress | None = None) -> Outcome:
    """The answer to one operation input (`task.run(progress)`), as data."""
    try:
        result = task.run(progress)
    except (SolverError, InvalidInput) as error:
        return Outcome(None, error)
    return Outcome(Answer.of(result))


def run_each(tasks: tuple[Any, ...], progress: Progress | None = None) -> list[Outcome]:
    """The answers to many operation inputs (a batch's chunk), in order: one round trip for
    all of them; `progress(done, total)` after each."""
    outcomes = []
    for done, task in enumerate(tasks, start=1):
        outcomes.append(run(task))
        if progress is not None:
            progress(done, len(tasks))
    return outcomes


def plan(task: Any) -> tuple[Any, ...] | Outcome:
    """A spread input's parts (`solver.SpreadInput.plan`: inputs of their own), or the error
    that says why it has none."""
    try:
        return tuple(task.plan)
    except (SolverError, InvalidInput) as error:
        return Outcome(None, error)


def run_parts(parts: tuple[Any, ...]) -> list[Any]:
    """The answers of some of a spread input's parts, in order, as the solver gives them (the
    whole's answer is assembled from them: `assemble`)."""
    return [part.run() for part in parts]


def assemble(task_and_answers: tuple[Any, Sequence[Any]]) -> Outcome:
    """The answer of a spread input from its parts' answers (`task.assemble(answers)`)."""
    task, answers = task_and_answers
    try:
        result = task.assemble(answers)
    except (SolverError, InvalidInput) as error:
        return Outcome(None, error)
    return Outcome(Answer.of(result))
