"""The undeformed wing: its rigid solution at one alpha, and its linear divergence pressure.

At q = 0 the structure stays undeformed and the residual is linear in the circulation, so one
Newton step from zero circulation is the exact rigid solution, for every airspeed (loads scale
with q). It is where every branch, every path and the rigid lift start. Both are cached per wing
(`solver.cache`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from solver.cache import cached
from solver.evaluation import Evaluation
from solver.inputs import Wing
from solver.loads import lift_and_drag, panel_loads
from solver.stability import divergence_pressure
from solver.system import CoupledSystem

__all__ = ["NEGLIGIBLE_INCIDENCE", "Jig", "jig", "linear_divergence_pressure"]

# [rad] The incidence below which a jig counts as unloaded: thin-airfoil circulation per unit
# speed is g ~ pi c alpha, so the test is max |g| <= pi c_mean NEGLIGIBLE_INCIDENCE. Such an
# imperfect bifurcation folds within ~alpha^(2/3) ~ 1e-7 of the linear divergence pressure.
NEGLIGIBLE_INCIDENCE = 1e-10


@dataclass(frozen=True)
class Jig:
    """The rigid jig of a wing at one alpha.

    state: (n,) u = u' = theta = 0 with the rigid wing's circulations.
    evaluation: r0, r1, J0, J1 at `state` (r0 = 0 there to round-off).
    rigid_lift_per_q: [m^2] the rigid wing's lift over q.
    rigid_panel_lift_per_q: (N-1,) [m^2] its panels' vertical forces over q.
    unloaded: the jig carries no load worth the name: its circulation is below what
        `NEGLIGIBLE_INCIDENCE` of incidence would give (alpha = 0 on an uncambered, untwisted
        wing, or within round-off of it). It stays an equilibrium, to the tolerance, at every q
        below the linear divergence, where it loses stability at a bifurcation that a load of
        this size cannot resolve into a fold.
    """

    state: np.ndarray
    evaluation: Evaluation
    rigid_lift_per_q: float
    rigid_panel_lift_per_q: np.ndarray
    unloaded: bool

    @property
    def nbytes(self) -> int:
        return self.state.nbytes + self.evaluation.nbytes


def _solve_jig(system: CoupledSystem) -> Jig:
    zero = np.zeros(system.layout.n_unknowns)
    at_zero = system.evaluate(zero)
    state = -np.linalg.solve(at_zero.jacobian0, at_zero.r0)
    state.setflags(write=False)
    per_q = panel_loads(system, state, 1.0)
    lift_per_q, _ = lift_and_drag(per_q, system.alpha)
    circulation = state[system.layout.circulation]
    unloaded = bool(
        np.max(np.abs(circulation)) <= math.pi * system.wing.mean_chord * NEGLIGIBLE_INCIDENCE
    )
    return Jig(state, system.evaluate(state), lift_per_q, per_q.force[2].copy(), unloaded)


def jig(system: CoupledSystem) -> Jig:
    """The rigid jig of `system` (cached per wing and alpha)."""
    return cached(("jig", *system.key), lambda: _solve_jig(system), lambda j: j.nbytes)


def _linear_divergence(wing: Wing) -> float | None:
    system = CoupledSystem(wing, 0.0)
    # At alpha = 0 an uncambered jig carries no circulation: the classical linear problem.
    at_rest = system.evaluate(np.zeros(system.layout.n_unknowns))
    return divergence_pressure(at_rest, system.layout.load_rows)


def linear_divergence_pressure(wing: Wing) -> float | None:
    """[Pa] the classical linear divergence dynamic pressure of the unloaded jig (alpha = 0),
    or None if the wing cannot diverge (cached per wing)."""
    box = cached(("linear_divergence", wing.key), lambda: [_linear_divergence(wing)], lambda _: 64)
    return box[0]
