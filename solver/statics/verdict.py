"""From a converged state to an `Equilibrium`: its loads, its static-stability verdict and where
it leaves the model's validity."""

from __future__ import annotations

import math
import time
from typing import Literal

import numpy as np

from solver.errors import FoldedWing
from solver.inputs.flight import OperatingPoint, velocity_for
from solver.inputs.options import SolverOptions
from solver.numerics.evaluation import Evaluation
from solver.numerics.stability import divergence_pressure
from solver.results.equilibrium import Equilibrium, SolveInfo, Stability
from solver.statics.jig import at_rest, jig, linear_pressure
from solver.statics.loads import RigidLoads, equilibrium_loads
from solver.statics.system import CoupledSystem
from solver.statics.validity import assess

__all__ = ["judge", "stability_of"]


def stability_of(
    system: CoupledSystem,
    flight: OperatingPoint,
    evaluation: Evaluation,
    branch: Literal["jig", "other"] = "jig",
) -> Stability:
    """The verdict at the state whose Jacobians `evaluation` holds, at `flight`'s q."""
    q = flight.dynamic_pressure
    local = divergence_pressure(evaluation, system.layout, at_rest(system).beam)
    linear = linear_pressure(system)
    return Stability(
        stable=local is None or local > q,
        margin=0.0 if local is None else q / local,
        local_divergence_pressure=local,
        divergence_dynamic_pressure=linear,
        divergence_velocity=(None if linear is None else velocity_for(linear, flight.density)),
        branch=branch,
    )


def judge(
    system: CoupledSystem,
    flight: OperatingPoint,
    options: SolverOptions,
    x: np.ndarray,
    evaluation: Evaluation,
    *,
    iterations: int,
    residual_norm: float,
    warm_start: bool,
    started: float,
    branch: Literal["jig", "other"] = "jig",
    rigid: RigidLoads | None = None,
    stability: Stability | None = None,
) -> Equilibrium:
    """The converged state x at `flight` with every reported quantity and its verdict.

    `evaluation`: r0, r1 at x, Jacobians at x or one Newton step away; `started`: the
    `time.perf_counter()` at which the solve began; `rigid`: the rigid loads per unit q to
    compare with (default: the jig's at the same alpha); `stability`: the verdict, when the
    caller has it already (`stability_of` at the same state). The findings of `validity`
    (`solver.statics.validity`) read the answer only.
    """
    q = flight.dynamic_pressure
    _representable(system, flight, x)
    if rigid is None:
        at_alpha = jig(system)
        rigid, unloaded = at_alpha.rigid, at_alpha.unloaded
    else:
        unloaded = False
    stations, panels, totals = equilibrium_loads(
        system, x, q, rigid, unloaded, options.safety_factor
    )
    stability = stability or stability_of(system, flight, evaluation, branch)
    return Equilibrium(
        wing=system.wing,
        flight=flight,
        options=options,
        state=x,
        evaluation=evaluation,
        stations=stations,
        panels=panels,
        totals=totals,
        stability=stability,
        solver=SolveInfo(
            iterations=iterations,
            residual_norm=residual_norm,
            warm_start=warm_start,
            seconds=time.perf_counter() - started,
        ),
        validity=assess(
            system, flight, options.validity, x, evaluation, stations, panels, stability
        ),
    )


# [rad] the largest bending rotation the exact beam's answers place streamwise sections at: 90
# deg less a round-off's margin (the section's span axis is the axis's y-z direction, which
# vanishes at 90 deg on an unswept wing).
_FOLDED = math.pi / 2 - 1e-6


def _representable(system: CoupledSystem, flight: OperatingPoint, x: np.ndarray) -> None:
    """Refuse an exact beam's state folded back on itself (`solver.errors.FoldedWing`), naming
    the first station whose |bending rotation| reaches 90 deg."""
    layout = system.layout
    if not layout.exact:
        return
    beyond = np.flatnonzero(np.abs(x[layout.slope]) >= _FOLDED)
    if beyond.size:
        i = int(beyond[0])
        rotation = math.degrees(float(x[layout.slope][i]))
        raise FoldedWing(flight.velocity, i, float(system.wing.y[i]), rotation)
