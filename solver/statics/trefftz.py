"""Far-field (Trefftz-plane) induced drag of the wake in the wing's plane: what a zigzag twist
cannot lower.

The near-field drag of the vortex lattice over free station twists runs away (a zigzag between
stations costs it nothing); the Trefftz-plane drag of the planar wake, its trailing vortices at
the stations, does not (the design study's closing sketch, made well-posed in
`solver.optimize`).

Strip theory's sections are two-dimensional: they see no downwash, so their near-field drag is
zero by construction. Its induced drag is the Trefftz-plane drag of its lift distribution, the
drag that lift distribution sheds into its wake (`far_field_drag`); `solver.statics.loads` reports
it as the induced drag under strip theory, and the design objectives use it.
"""

from __future__ import annotations

import math

import numpy as np

from solver.results.equilibrium import Equilibrium
from solver.statics.system import CoupledSystem

__all__ = ["far_field_drag", "strip_sum", "trefftz_drag", "trefftz_matrix"]


def trefftz_matrix(y: np.ndarray, dihedral: float = 0.0) -> np.ndarray:
    """(N-1, N-1) [-] A with D_T / q = G^T A G for strip circulations G (N-1,) [m] per unit
    airspeed (both halves): the Trefftz-plane drag of the wake in the wing's plane, its trailing
    vortices at the stations, y along the plane (z = 0 at dihedral 0; a V of the dihedral
    [deg] otherwise), the normalwash taken at the strips' middles.

    A trailing vortex on the same half induces normalwash G / (2 pi (m - y)) at the distance
    m - y along the plane, whatever the dihedral; its mirror image on the other half, at
    (-y cos, y sin) seen from (m cos, m sin), induces -G / (2 pi) (c^2 A + s^2 B) / (c^2 A^2 +
    s^2 B^2) with A = m + y, B = m - y (c, s of the dihedral): -G / (2 pi A) at dihedral 0,
    written as 1/A times a factor that is exactly 1 there."""
    middle, width = (y[1:] + y[:-1]) / 2, np.diff(y)
    cos, sin = math.cos(math.radians(dihedral)), math.sin(math.radians(dihedral))
    n = y.size
    shed = np.zeros((n, n - 1))  # trailing strengths at the stations: inboard minus outboard
    shed[np.arange(1, n), np.arange(n - 1)] = 1.0
    shed[np.arange(1, n - 1), np.arange(1, n - 1)] = -1.0
    with np.errstate(divide="ignore"):
        apart, across = middle[:, None] + y[None, :], middle[:, None] - y[None, :]
        turned = (cos**2 * apart**2 + sin**2 * across * apart) / (
            cos**2 * apart**2 + sin**2 * across**2
        )
        kernel = (1 / across - 1 / apart * turned) / (2 * math.pi)
    kernel[:, 0] = 0.0  # the root's trailing vortex and its mirror image cancel
    return -2 * np.diag(width) @ kernel @ shed


def far_field_drag(system: CoupledSystem, x: np.ndarray, q: float) -> float:
    """[N] the Trefftz-plane induced drag of the state x (3N + M,) at dynamic pressure q [Pa]."""
    strips = strip_sum(system) @ x[system.layout.circulation]
    return float(q * strips @ trefftz_matrix(system.wing.y, system.wing.dihedral) @ strips)


def trefftz_drag(equilibrium: Equilibrium) -> float:
    """[N] the far-field induced drag of an equilibrium (the wake in the wing's plane,
    `trefftz_matrix`)."""
    system = CoupledSystem.of(equilibrium.wing, equilibrium.flight.alpha, equilibrium.options)
    return far_field_drag(system, equilibrium.state, equilibrium.dynamic_pressure)


def strip_sum(system: CoupledSystem) -> np.ndarray:
    """(N-1, M) panels to strips."""
    return np.kron(np.eye(system.layout.n_strips), np.ones((1, system.chordwise)))
