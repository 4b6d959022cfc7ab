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
from solver.loads import lift_and_drag, panel_loads
from solver.stability import beam_response, divergence_pressure
from solver.system import CoupledSystem

__all__ = ["NEGLIGIBLE_INCIDENCE", "Jig", "jig", "linear_pressure"]

# [rad] The incidence below which a jig counts as unloaded: thin-airfoil circulation per unit
# speed is g ~ pi c alpha, so the test is max |g| <= pi c_mean NEGLIGIBLE_INCIDENCE. Such an
# imperfect bifurcation folds within ~alpha^(2/3) ~ 1e-7 of the linear divergence pressure.
NEGLIGIBLE_INCIDENCE = 1e-10


@dataclass(frozen=True)
class Jig:
    """The rigid jig of a wing at one alpha.

    state: (n,) u = u' = phi = 0 with the rigid wing's circulations.
    evaluation: r0, r1, J0, J1 at `state` (r0 = 0 there to round-off).
    rigid_lift_per_q: [m^2] the rigid wing's lift over q.
    rigid_strip_lift_per_q: (N-1,) [m^2] its strips' vertical forces over q.
    beam: the clamped beam's response to its load rows (`solver.stability.beam_response`),
        the same at every state: what every stability verdict of this wing reuses.
    unloaded: the jig carries no load worth the name: its circulation is below what
        `NEGLIGIBLE_INCIDENCE` of incidence would give (alpha = 0 on an uncambered, untwisted
        wing, or within round-off of it). It stays an equilibrium, to the tolerance, at every q
        below the linear divergence, where it loses stability at a bifurcation that a load of
        this size cannot resolve into a fold.
    """

    state: np.ndarray
    evaluation: Evaluation
    rigid_lift_per_q: float
    rigid_strip_lift_per_q: np.ndarray
    unloaded: bool
    beam: np.ndarray

    @property
    def nbytes(self) -> int:
        return self.state.nbytes + self.evaluation.nbytes + self.beam.nbytes


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
    evaluation = system.evaluate(state)
    beam = beam_response(evaluation, system.layout)
    strips = per_q.per_strip(per_q.force[2], system.chordwise)
    return Jig(state, evaluation, lift_per_q, strips, unloaded, beam)


def jig(system: CoupledSystem) -> Jig:
    """The rigid jig of `system` (cached per wing and alpha)."""
    return cached(("jig", *system.key), lambda: _solve_jig(system), lambda j: j.nbytes)


def _linear_divergence(system: CoupledSystem) -> float | None:
    # Linearised about the undeformed wing carrying no circulation: the classical problem (for
    # an uncambered, untwisted wing it is the jig at alpha = 0).
    at_rest = system.at_alpha(0.0).evaluate(np.zeros(system.layout.n_unknowns))
    return divergence_pressure(at_rest, system.layout)


def linear_pressure(system: CoupledSystem) -> float | None:
    """[Pa] the classical linear divergence dynamic pressure of the undeformed, unloaded wing,
    or None if the wing cannot diverge (cached per wing and model; alpha plays no part)."""
    key = ("linear_divergence", system.wing.key, system.chordwise, system.deformed_axis)
    box = cached(key, lambda: [_linear_divergence(system)], lambda _: 64)
    return box[0]
