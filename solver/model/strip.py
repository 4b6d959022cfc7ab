"""Strip theory's induced velocities (`Layout.aerodynamics == "strip"`): each strip a
two-dimensional airfoil.

The model is the lattice's with its induced velocities replaced by each strip's own
two-dimensional ones: a strip's tangency rows see only its own bound vortices, as infinite line
vortices, and its forces see the freestream alone. Every other row, the geometry and the beam
are the lattice's, so every static operation runs unchanged on it; it is O(N k^2).
"""

from __future__ import annotations

import functools

import casadi as ca
import numpy as np

from solver.model.aerodynamics import parameter_symbols, wing_lattice
from solver.model.layout import Layout

__all__ = ["strip_induced_function"]


def _cross_columns(a: ca.SX, b: ca.SX) -> ca.SX:
    """a x b of two (3, 1) columns."""
    return ca.vertcat(
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    )


@functools.lru_cache(maxsize=8)
def strip_induced_function(layout: Layout, with_jacobian: bool) -> ca.Function:
    """Strip theory: the velocity per unit V at each collocation point induced by the bound
    vortices of its own strip only, each an infinite (two-dimensional) line vortex along its leg,

        v_p = sum over panels p' of p's strip of g_p' / (2 pi) (l_p' x d) / |d|^2,

    with l_p' the unit leg and d the part of (collocation_p - center_p') normal to it; no
    trailing legs, no other strip, no mirrored half. One chordwise panel puts the collocation
    point half a chord behind the vortex, so tangency gives g = pi c sin(incidence): the thin
    airfoil's lift, slope 2 pi per radian, at the quarter chord. With k panels each strip is the
    two-dimensional discrete-vortex airfoil (vortices at the panels' quarter, tangency at their
    three-quarter points), which carries the camber's lift and moment.

    (z, g, p) -> induced (3M,) (rows 3 p + c), and with `with_jacobian` the normal component's
    derivative n_p . d(v_p)/dx (M, 3N + M)."""
    m, k = layout.n_panels, layout.chordwise
    p, wing = parameter_symbols(layout)
    z = ca.SX.sym("z", layout.n_structure)
    g = ca.SX.sym("g", m)
    lat = wing_lattice(layout, z, wing)
    columns = []
    for panel in range(m):
        first = (panel // k) * k
        velocity = ca.SX.zeros(3, 1)
        for q in range(first, first + k):
            unit = lat.leg[:, q] / ca.norm_2(lat.leg[:, q])
            offset = lat.collocation[:, panel] - lat.center[:, q]
            normal_offset = offset - ca.dot(offset, unit) * unit
            velocity += (
                g[q]
                / (2 * np.pi)
                * _cross_columns(unit, normal_offset)
                / ca.dot(normal_offset, normal_offset)
            )
        columns.append(velocity)
    induced = ca.vertcat(*columns)
    outputs = [induced]
    if with_jacobian:
        derivative = ca.jacobian(induced, ca.vertcat(z, g))
        outputs.append(
            ca.vertcat(
                *[
                    ca.mtimes(lat.normal[:, panel].T, derivative[3 * panel : 3 * panel + 3, :])
                    for panel in range(m)
                ]
            )
        )
    return ca.Function(
        "strip_induced" if with_jacobian else "strip_induced_values", [z, g, p], outputs
    )
