"""The undeformed wing: its rigid solution at any alpha, and its linear divergence pressure.

At q = 0 the structure stays undeformed and the residual is linear in the circulation, whose
right-hand side is the freestream (cos alpha, 0, sin alpha) through the panels' normals. So one
evaluation of the wing at rest (zero circulation, alpha = 0) gives the rigid solution at every
alpha and every airspeed (loads scale with q) by superposition:

    x_rigid(alpha) = cos(alpha) x_cos + sin(alpha) x_sin,
    x_cos = -J0^{-1} r0,   x_sin = -J0^{-1} dr0/dalpha   (at rest).

It is where every branch, every path and the rigid lift start. The same evaluation gives the
classical linear divergence pressure and the beam's response used by every stability verdict
(the structure's rows do not depend on the state). Everything is cached per wing
(`solver.numerics.cache`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from solver.model.geometry import DEG
from solver.numerics.cache import cached
from solver.numerics.evaluation import Evaluation
from solver.numerics.stability import beam_response, divergence_pressure
from solver.statics.loads import RigidLoads, rigid_loads
from solver.statics.system import CoupledSystem

__all__ = ["NEGLIGIBLE_INCIDENCE", "AtRest", "Jig", "at_rest", "jig", "linear_pressure"]

# [rad] The incidence below which a jig counts as unloaded: thin-airfoil circulation per unit
# speed is g ~ pi c alpha, so the test is max |g| <= pi c_mean NEGLIGIBLE_INCIDENCE. Such an
# imperfect bifurcation folds within ~alpha^(2/3) ~ 1e-7 of the linear divergence pressure.
NEGLIGIBLE_INCIDENCE = 1e-10


@dataclass(frozen=True)
class AtRest:
    """The undeformed wing carrying no circulation, at alpha = 0: what every alpha shares.

    evaluation: r0, r1, J0, J1 at x = 0; cos_state, sin_state: (n,) the rigid states x_cos and
    x_sin of the module docstring; beam: the clamped beam's response to its load rows
    (`solver.numerics.stability.beam_response`), the same at every state and alpha; lift_gradient:
    (n,) [m^2] the lift per unit q's gradient in x at rest: the linear lattice's lift,
    l(alpha) = lift_gradient . x_rigid(alpha) to first order in the circulation.
    """

    evaluation: Evaluation
    cos_state: np.ndarray
    sin_state: np.ndarray
    beam: np.ndarray
    lift_gradient: np.ndarray

    def rigid_state(self, alpha: float) -> np.ndarray:
        """(n,) the rigid jig's state at `alpha` [deg]: u = u' = phi = 0, its circulations."""
        angle = alpha * DEG
        return math.cos(angle) * self.cos_state + math.sin(angle) * self.sin_state

    @property
    def nbytes(self) -> int:
        return (
            self.evaluation.nbytes
            + self.cos_state.nbytes
            + self.sin_state.nbytes
            + self.beam.nbytes
            + self.lift_gradient.nbytes
        )


def _evaluate_at_rest(system: CoupledSystem) -> AtRest:
    evaluation, terms = system.at_alpha(0.0).evaluate_with_alpha(np.zeros(system.layout.n_unknowns))
    states = np.linalg.solve(evaluation.jacobian0, -np.column_stack([evaluation.r0, terms.r0]))
    beam = beam_response(evaluation, system.layout)
    beam.setflags(write=False)
    return AtRest(
        evaluation.read_only(), states[:, 0].copy(), states[:, 1] / DEG, beam, terms.lift_x
    )


def at_rest(system: CoupledSystem) -> AtRest:
    """The wing of `system` at rest (cached per wing and model; alpha plays no part)."""
    key = ("at_rest", *system.model_key)
    return cached(key, lambda: _evaluate_at_rest(system.unloaded), lambda r: r.nbytes)


def is_unloaded(system: CoupledSystem, state: np.ndarray) -> bool:
    """Whether the rigid `state` carries no load worth the name (see `Jig.unloaded`)."""
    circulation = state[system.layout.circulation]
    limit = math.pi * system.wing.mean_chord * NEGLIGIBLE_INCIDENCE
    return bool(np.max(np.abs(circulation)) <= limit)


@dataclass(frozen=True)
class Jig:
    """The rigid jig of a wing at one alpha.

    state: (n,) u = u' = phi = 0 with the rigid wing's circulations.
    evaluation: r0, r1, J0, J1 at `state` (r0 = 0 there to round-off).
    rigid: the rigid wing's loads per unit q.
    unloaded: the jig carries no load worth the name: its circulation is below what
        `NEGLIGIBLE_INCIDENCE` of incidence would give (alpha = 0 on an uncambered, untwisted
        wing, or within round-off of it). It stays an equilibrium, to the tolerance, at every q
        below the linear divergence, where it loses stability at a bifurcation that a load of
        this size cannot resolve into a fold.
    """

    state: np.ndarray
    evaluation: Evaluation
    rigid: RigidLoads
    unloaded: bool

    @property
    def nbytes(self) -> int:
        return self.state.nbytes + self.evaluation.nbytes + self.rigid.strip_lift.nbytes


def _solve_jig(system: CoupledSystem) -> Jig:
    state = at_rest(system).rigid_state(system.alpha)
    state.setflags(write=False)
    evaluation = system.evaluate(state).read_only()
    return Jig(state, evaluation, rigid_loads(system, state), is_unloaded(system, state))


def jig(system: CoupledSystem) -> Jig:
    """The rigid jig of `system` (cached per wing and alpha)."""
    return cached(("jig", *system.key), lambda: _solve_jig(system), lambda j: j.nbytes)


def linear_pressure(system: CoupledSystem) -> float | None:
    """[Pa] the classical linear divergence dynamic pressure of the undeformed, unloaded wing,
    or None if the wing cannot diverge (cached per wing and model; alpha plays no part).

    Linearised about the undeformed wing carrying no circulation: the classical problem (for an
    uncambered, untwisted wing it is the jig at alpha = 0)."""
    key = ("linear_divergence", *system.model_key)
    try:
        rest = at_rest(system)
    except np.linalg.LinAlgError:
        return None  # a degenerate wing: its solves end in a typed error, not here
    box = cached(
        key, lambda: [divergence_pressure(rest.evaluation, system.layout, rest.beam)], lambda _: 64
    )
    return box[0]
