"""The geometrically exact beam (`options.structure = "geometrically_exact"`): finite bending
rotations in the plane of the elastic axis and the wing's normal, and torsion about the deformed
axis, in the same unknowns, rows and CasADi Newton system as the linear beam
(`solver.model.beam`).

The formulation is the inextensible, unsheared limit of Reissner's finite-strain beam in the
plane (E. Reissner, "On one-dimensional finite-strain beam theory: the plane problem", ZAMP 23,
1972; the elastica of Bisshopp and Drucker, Q. Appl. Math. 3, 1945), displacement based, with
the torsion of the deformed axis added (as in Hodges, "Nonlinear Composite Beam Theory", AIAA
2006: the twist rate about the deformed tangent as the torsional strain, small warping):

- The slope unknown is the section's bending rotation beta [rad] (exactly u'(s) = sin beta; the
  linear model's du/ds to first order): the axis's tangent t = cos(beta) e_s + sin(beta) n, e_s
  the jig axis, n the wing plane's normal (`solver.model.geometry`). beta turns about
  e_c = e_s x n, which bending leaves fixed: the plane of bending is the jig's; the wing is
  rigid in its own plane (no lag bending), as the linear beam is.
- The reference line: each segment is the chord of a circular arc of its length h and its
  rotations at both ends, so that a piecewise-constant curvature is integrated exactly:
      r_{i+1} - r_i = h sinc(db/2) (cos(b) e_s + sin(b) n),   b = (beta_i + beta_{i+1})/2,
      db = beta_{i+1} - beta_i.
  The heave u_i = r_i . n is the unknown (its kinematics row is the n component); the
  foreshortened distance along the jig axis S_i = r_i . e_s follows from the rotations.
- Internal loads, exact statics about the deformed station point r_i of every force outboard of
  it (the loads follow the deformed lattice; gravity stays a dead load, `solver.statics.inertia`):
      M_i = (sum (r_p - r_i) x F_p) . e_c,   T_i = (sum (r_p - r_i) x F_p) . t_i,
  and the bending and torsion rows integrate the section's compliance exactly as the linear
  beam's: beta' = M/EI* - c T, phi' = T/GJ* - c M (`solver.model.beam.section_compliance`),
  with phi the twist about the deformed axis (the sections then turn as the linear model's
  kinematics say, about the deformed axis: `solver.model.geometry.lattice`).

In the small-deflection limit every term that differs from the linear beam (with the torque
about the heaved axis) is of second order in the deflection. A wing folded back on itself
(|beta| past 90 degrees at a station, the axis turning back toward the root) has no streamwise
sections: the answers refuse it naming the station (`solver.statics.verdict`,
`solver.errors.FoldedWing`).

Unknowns, rows and parameter slots are the linear beam's (`solver.model.layout`); the panel loads
carry two more rows for it, (r x F) . e_c and (r x F) . n per panel (`EXACT_LOADS`, after the
others: `solver.model.aerodynamics.panel_loads`).
"""

from __future__ import annotations

from typing import Any

import casadi as ca
import numpy as np

from solver.model.beam import Beam
from solver.model.geometry import (
    axis_force,
    in_wing_plane,
    reference_line,
    segment_chords,
    span_axis,
)
from solver.model.layout import Layout

__all__ = [
    "EXACT_LOADS",
    "ExactBeam",
    "axis_points",
    "exact_internal_loads",
    "exact_structure_rows",
]

EXACT_LOADS = 2  # per-panel rows the exact beam adds after the loads: (r x F) . e_c, (r x F) . n


def exact_structure_rows(layout: Layout, x: ca.MX, h: ca.MX) -> ca.MX:
    """Root clamps, the heave's exact kinematics u_{i+1} - u_i - h sinc(db/2) sin(b), and the
    load-free part of the bending and torsion rows (`solver.model.beam.structure_rows`'s)."""
    heave, beta, twist = x[layout.heave], x[layout.slope], x[layout.twist]
    _, normal = segment_chords(beta, h)
    return ca.vertcat(
        heave[0],
        beta[0],
        twist[0],
        heave[1:] - heave[:-1] - normal,
        beta[1:] - beta[:-1],
        twist[1:] - twist[:-1],
    )


def _scale(factors: ca.MX, matrix: ca.MX) -> ca.MX:
    return ca.repmat(factors, 1, matrix.size2()) * matrix


class ExactBeam(Beam):
    """The exact beam's load rows (module docstring): the linear beam's trapezoids of the
    section's compliance, of the exact internal loads at the deformed stations. `z` (3N,) the
    beam's unknowns [u; beta; phi], `p` the parameter vector `wing` unpacks."""

    def __init__(self, layout: Layout, p: ca.MX, z: ca.MX) -> None:
        super().__init__(layout, layout.unpack(p))
        self.p, self.z = p, z

    def _internal(self, loads: ca.MX, z: ca.MX) -> tuple[ca.MX, ca.MX]:
        """(N, c) M_i and T_i of per-panel loads (rows as `solver.model.aerodynamics`'s, the
        exact rows last) at the beam's unknowns z."""
        n, m = self.layout.n, self.layout.n_panels
        exact = loads.size1() // m - EXACT_LOADS
        e_x, e_y = span_axis(self.wing)
        fx, fy, fz = self._force(loads)
        # The outboard force in the wing's frame: along the axis, across it (e_c), normal.
        x, y, f_normal = in_wing_plane((fx, fy, fz), self.wing)
        f_along = e_x * x + e_y * y
        f_across = axis_force((fx, fy, fz), self.wing)
        m_along = self.outboard(loads, 4)
        m_across = self.outboard(loads, exact)
        m_normal = self.outboard(loads, exact + 1)
        beta = z[n : 2 * n]
        along, heave = reference_line(beta, self.h)
        bending = m_across - _scale(along, f_normal) + _scale(heave, f_along)
        about_axis = m_along - _scale(heave, f_across)
        about_normal = m_normal + _scale(along, f_across)
        torque = _scale(ca.cos(beta), about_axis) + _scale(ca.sin(beta), about_normal)
        return bending, torque

    def load_rows(self, loads: ca.MX, heave: ca.MX, deformed: ca.MX) -> ca.MX:
        """(2(N-1), c) the q-proportional part of the bending and torsion rows, or its
        derivative along a parameter z does not depend on (`Beam.load_rows`; the torque is
        always about the deformed axis, `deformed` is not read)."""
        return self.rows(*self._internal(loads, self.z))

    def load_rows_jacobian(
        self, loads: ca.MX, loads_x: ca.MX, heave: ca.MX, deformed: ca.MX, heave_columns: ca.DM
    ) -> ca.MX:
        """(2(N-1), nx) d(load_rows)/dx: linear in the loads at fixed z (their derivative rows
        loads_x), plus the explicit derivative through the deformed stations and axis."""
        n3, nx = 3 * self.layout.n, self.layout.n_unknowns
        # On symbols of their own: CasADi differentiates the rows in z alone, the loads held.
        z, held, p = (
            ca.MX.sym("z", n3),
            ca.MX.sym("loads", loads.shape),
            ca.MX.sym("p", self.p.shape),
        )
        inner = ExactBeam(self.layout, p, z)
        rows_at = inner.rows(*inner._internal(held, z))
        explicit = ca.Function("exact_beam_z", [z, held, p], [ca.jacobian(rows_at, z)])
        through_z = ca.horzcat(explicit(self.z, loads, self.p), ca.MX(rows_at.size1(), nx - n3))
        return self.rows(*self._internal(loads_x, self.z)) + through_z


def exact_internal_loads(
    wing: Any, force: np.ndarray, center: np.ndarray, beta: np.ndarray, k: int
) -> tuple[np.ndarray, np.ndarray]:
    """Numpy, for the answers: (N,) M_i and T_i [N m] (module docstring) of the panels' forces
    (3, M) [N] at their deformed force points (3, M) [m] (geometry axes), at the rotations
    beta (N,) [rad]; `wing` the numeric `solver.inputs.wing.Wing`."""
    e_x, e_y = span_axis(wing)
    f_x, f_y, f_normal = in_wing_plane(force, wing)
    r_x, r_y, r_normal = in_wing_plane(center, wing)
    f_along, f_across = e_x * f_x + e_y * f_y, e_y * f_x - e_x * f_y
    r_along, r_across = e_x * r_x + e_y * r_y, e_y * r_x - e_x * r_y
    # r x F in the right-handed frame (e_s, n, e_c).
    m_along = r_normal * f_across - r_across * f_normal
    m_normal = r_across * f_along - r_along * f_across
    m_across = r_along * f_normal - r_normal * f_along

    def outboard(values: np.ndarray) -> np.ndarray:
        strips = values.reshape(-1, k).sum(axis=1)
        return np.concatenate([np.cumsum(strips[::-1])[::-1], [0.0]])

    arc = np.asarray(wing.arc_length, dtype=float)
    along, heave = reference_line(beta, np.diff(arc))
    f_along_sum, f_normal_sum, f_across_sum = (outboard(f) for f in (f_along, f_normal, f_across))
    bending = outboard(m_across) - along * f_normal_sum + heave * f_along_sum
    about_axis = outboard(m_along) - heave * f_across_sum
    about_normal = outboard(m_normal) + along * f_across_sum
    return bending, np.cos(beta) * about_axis + np.sin(beta) * about_normal


def axis_points(wing: Any, heave: np.ndarray, rotation: np.ndarray, exact: bool) -> np.ndarray:
    """Numpy, for the answers: (3, N) [m] the deformed elastic axis's points in geometry axes:
    on the exact beam's reference line (`rotation` beta [rad]), or the linear beam's jig axis
    heaved normal to the wing's plane; the plane turned by the dihedral."""
    arc = np.asarray(wing.arc_length, dtype=float)
    along, normal = reference_line(rotation, np.diff(arc)) if exact else (arc, heave)
    e_x, e_y = span_axis(wing)
    x, y = e_x * along, e_y * along
    cos, sin = np.cos(np.radians(wing.dihedral)), np.sin(np.radians(wing.dihedral))
    return np.vstack([x, y * cos - normal * sin, y * sin + normal * cos])
