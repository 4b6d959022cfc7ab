"""The equilibrium branch from the jig shape, and its fold.

One branch per wing and alpha, traced lazily by pseudo-arclength continuation
(`solver.numerics.continuation.BranchTracer`) and kept in the solver's cache: a request that needs
it further extends it. Its points depend on the wing and alpha only (the continuation's scaled
coordinates use an intrinsic pressure scale, never the limit asked for), so what a request reads
from it is the same whether the branch was traced for it or long before: `Branch` views are
canonical prefixes.
"""

from __future__ import annotations

import math
import threading

import numpy as np

from solver.inputs.flight import dynamic_pressure, velocity_for
from solver.numerics.branch_points import Branch
from solver.numerics.cache import cached, resize
from solver.numerics.continuation import BranchTracer
from solver.results.equilibrium import Fold
from solver.statics.jig import jig, linear_pressure
from solver.statics.loads import lift_and_drag, panel_loads
from solver.statics.system import CoupledSystem

__all__ = ["branch", "fold", "pressure_scale", "search_velocity_limit"]

# Past the linear divergence speed by this factor the search goes on: with a load on the jig the
# fold can lie above the alpha = 0 eigenvalue (the z Fx torque term makes it alpha-dependent).
_PAST_LINEAR = 1.25
# ... and at least this multiple of the largest requested speed.
_PAST_REQUESTED = 1.5
# The deformation that marks the pressure scale of a wing without linear divergence.
_SCALE_HEAVE = 0.1  # [-] of the semispan
_SCALE_TWIST = math.degrees(0.1)  # [deg]


def search_velocity_limit(system: CoupledSystem, density: float, velocity: float) -> float:
    """[m/s] how far to follow the branch when `velocity` is the largest speed asked for."""
    limit = _PAST_REQUESTED * velocity
    q_div = linear_pressure(system)
    if q_div is not None:
        limit = max(limit, _PAST_LINEAR * velocity_for(q_div, density))
    return limit


def default_search_limit(system: CoupledSystem, density: float) -> float:
    """[m/s] how far to follow the branch when no speed is asked for: past the linear
    divergence speed, or, for a wing without one, past the speed of its pressure scale."""
    return _PAST_LINEAR * velocity_for(pressure_scale(system), density)


def pressure_scale(system: CoupledSystem) -> float:
    """[Pa] the wing's intrinsic pressure scale: its linear divergence pressure, or, for a wing
    that cannot diverge, where the linear theory's deformation reaches a tenth of the semispan
    or 0.1 rad of twist."""
    q_div = linear_pressure(system)
    if q_div is not None:
        return q_div
    start = jig(system)
    layout = system.layout
    rate = np.linalg.solve(start.evaluation.jacobian0, -start.evaluation.r1)  # dx/dq at q = 0
    heave_rate = float(np.max(np.abs(rate[layout.heave])))
    twist_rate = float(np.max(np.abs(rate[layout.twist])))
    candidates = [
        _SCALE_HEAVE * system.wing.semispan / heave_rate if heave_rate > 0 else math.inf,
        _SCALE_TWIST / twist_rate if twist_rate > 0 else math.inf,
    ]
    scale = min(candidates)
    return scale if math.isfinite(scale) and scale > 0 else 1.0


class _CachedTracer:
    """A tracer with the lock that serialises its extensions."""

    def __init__(self, system: CoupledSystem) -> None:
        start = jig(system)
        self.tracer = BranchTracer(
            system.evaluate,
            system.residual,
            np.array(start.state),
            system.scale(pressure_scale(system)),
            jig_evaluation=start.evaluation,
        )
        self.lock = threading.Lock()


def branch(system: CoupledSystem, q_limit: float) -> Branch:
    """The branch from the jig of `system`, to its fold or to q_limit [Pa] (canonical prefix)."""
    key = ("branch", *system.key)
    entry = cached(key, lambda: _CachedTracer(system), lambda e: e.tracer.nbytes)
    with entry.lock:
        traced = len(entry.tracer.points)
        view = entry.tracer.view(q_limit)
        if len(entry.tracer.points) != traced:  # traced further: record its new size
            resize(key, entry, entry.tracer.nbytes)
    return view


def fold(system: CoupledSystem, density: float, velocity_limit: float) -> Fold:
    """The fold of the branch from the jig at `density` [kg/m^3], searched to velocity_limit."""
    if velocity_limit <= 0:
        return Fold(None, None, None, None, 0.0, "no search limit: no speed requested")
    if jig(system).unloaded:
        return _bifurcation(system, density, velocity_limit)
    found = branch(system, dynamic_pressure(density, velocity_limit))
    reached = velocity_for(found.reached_pressure, density)
    point = found.fold
    if point is None:
        reason = found.reason or (
            f"no fold up to {reached:.4g} m/s: the branch from the jig shape continues"
        )
        return Fold(None, None, None, None, reached, reason, evaluations=found.evaluations)
    layout = system.layout
    lift, _ = lift_and_drag(panel_loads(system, point.state, point.dynamic_pressure), system.alpha)
    return Fold(
        velocity=velocity_for(point.dynamic_pressure, density),
        dynamic_pressure=point.dynamic_pressure,
        tip_twist=float(point.state[layout.twist][-1]),
        lift=lift,
        searched_to_velocity=reached,
        tip_heave=float(point.state[layout.heave][-1]),
        evaluations=found.evaluations,
    )


def _bifurcation(system: CoupledSystem, density: float, velocity_limit: float) -> Fold:
    """An unloaded jig stays an equilibrium at every q and loses stability at the eigenvalue."""
    q_div = linear_pressure(system)
    if q_div is None:
        return Fold(
            None,
            None,
            None,
            None,
            velocity_limit,
            "the unloaded jig is a stable equilibrium at every speed",
        )
    velocity = velocity_for(q_div, density)
    return Fold(
        velocity=velocity,
        dynamic_pressure=q_div,
        tip_twist=0.0,
        lift=0.0,
        searched_to_velocity=velocity,
        reason=(
            "the jig carries no load at this angle of attack: it stays an equilibrium but loses "
            "stability at the linear divergence (a bifurcation, not a fold)"
        ),
        tip_heave=0.0,
    )
