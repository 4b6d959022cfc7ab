"""The beam's rows of the residual: the root clamps, the heave kinematics, and bending and torsion
by the trapezoidal rule along the elastic axis (AeroSandbox's ``constrain_derivative``), with
h_i = s_{i+1} - s_i the segment lengths along the axis (`solver.model.geometry.arc_length`):

    root clamps (3)          u_0 = 0, u'_0 = 0, phi_0 = 0
    heave kinematics (N-1)   u_{i+1} - u_i - h_i (u'_i + u'_{i+1}) / 2 = 0                   [m]
    bending (N-1)            u'_{i+1} - u'_i - h_i (M_i/EI_i + M_{i+1}/EI_{i+1}) / 2 = 0     [-]
    torsion (N-1)            phi_{i+1} - phi_i
                               - h_i (180/pi)(T_i/GJ_i + T_{i+1}/GJ_{i+1}) / 2 = 0           [deg]

With a bending-torsion coupling stiffness K_i (`Wing.bending_torsion_coupling`) the section's
moments are [M; T] = [[EI, K], [K, GJ]] [u''; phi'] (phi' in rad/m), and the rows integrate its
compliance instead: u'' = M/EI* - c T, phi' = T/GJ* - c M, with EI* = EI - K^2/GJ,
GJ* = GJ - K^2/EI and c = K/(EI GJ - K^2) (`section_compliance`). Positive K: bending the tip up
(M > 0) twists the section nose down, a washout. At K = 0, EI* and GJ* are EI and GJ to the
bit and the coupling terms add signed zeros: the rows are the uncoupled ones to the last digit.

Internal loads by outboard sums over every panel p of the strips outboard of station i, with F_p
its force at its deformed force point r_p, Fn_p its component normal to the wing's plane, e_s
the elastic axis's direction and s_i station i's distance along it (the beam's kinematics,
`solver.model.geometry`):

    M_i = sum_p Fn_p (r_p . e_s) - s_i sum_p Fn_p
    T_i = sum_p (r_p x F_p) . e_s - d u_i sum_p F_p . (e_s x n)

with d = 1 when the torque is taken about the heaved elastic-axis point (`deformed_axis`), else
0 (the study's undeformed axis). At sweep 0, d = 0 and one chordwise panel these are the study's
sums. The per-panel loads (`solver.model.aerodynamics`) are applied as running sums over a
sparse panels-to-strips operator, which keeps the work at O(M) per column.
"""

from __future__ import annotations

from typing import Any

import casadi as ca
import numpy as np

from solver.model.geometry import arc_length, axis_force, normal_force
from solver.model.layout import Layout

__all__ = [
    "DEG_PER_RAD",
    "Beam",
    "coupled_trapezoid",
    "outboard_sum",
    "section_compliance",
    "structure_rows",
]

DEG_PER_RAD = 180.0 / np.pi


def outboard_sum(strip_rows: ca.MX) -> ca.MX:
    """(N-1, c) per-strip rows -> (N, c): row i sums strips j >= i (zero at the tip).

    A running sum from the tip, O(N c), where a triangular matrix product would be O(N^2 c).
    """
    m, c = strip_rows.shape
    running = ca.MX(1, c)
    rows = [running]
    for j in reversed(range(m)):
        running = running + strip_rows[j, :]
        rows.append(running)
    return ca.vertcat(*reversed(rows))


def section_compliance(ei: Any, gj: Any, coupling: Any) -> tuple[Any, Any, Any]:
    """The section's compliance [[EI, K], [K, GJ]]^-1 as (EI*, GJ*, c): its diagonal's
    inverses EI* = EI - K^2/GJ and GJ* = GJ - K^2/EI [N m^2] and its off-diagonal's negative
    c = K/(EI GJ - K^2) [1/(N m^2)], so that u'' = M/EI* - c T and phi' = T/GJ* - c M. Numpy
    arrays or CasADi columns (N,) alike; at K = 0, EI* and GJ* are EI and GJ to the bit."""
    square = coupling * coupling
    return ei - square / gj, gj - square / ei, coupling / (ei * gj - square)


def coupled_trapezoid(
    h: Any, bending: Any, torque: Any, wing_stiffness: tuple[Any, Any, Any]
) -> tuple[Any, Any]:
    """Numpy: the bending and torsion rows' load terms (N-1, ...) of station moments and torques
    (N, ...) [N m]: -h_i/2 (f_i + f_{i+1}) of f = M/EI* - c T and degrees(T/GJ* - c M)
    (`section_compliance`; `wing_stiffness` its EI, GJ, K (N,)). Each uncoupled part is
    evaluated as the uncoupled rows are, the coupling's added after: at K = 0 the rows are
    the uncoupled ones to the bit."""
    ei, gj, coupling = wing_stiffness
    ei_eff, gj_eff, cross = section_compliance(ei, gj, coupling)
    shape = (-1,) + (1,) * (np.ndim(bending) - 1)

    def trapezoid(values: Any, stiffness: Any, scale: float) -> Any:
        per = values / np.reshape(stiffness, shape)
        return -scale * np.reshape(h, shape) / 2 * (per[:-1] + per[1:])

    def cross_term(values: Any, scale: float) -> Any:
        per = values * np.reshape(cross, shape)
        return scale * np.reshape(h, shape) / 2 * (per[:-1] + per[1:])

    return (
        trapezoid(bending, ei_eff, 1.0) + cross_term(torque, 1.0),
        trapezoid(torque, gj_eff, DEG_PER_RAD) + cross_term(bending, DEG_PER_RAD),
    )


def _scale_rows(factors: ca.MX, matrix: ca.MX) -> ca.MX:
    """diag(factors) matrix, for a (r, 1) column of factors and a dense (r, c) matrix: an
    elementwise product, where CasADi's sparse product through a diagonal matrix goes through
    index arrays and a dense work column for every column."""
    return ca.repmat(factors, 1, matrix.size2()) * matrix


class Beam:
    """The beam's load rows from per-panel loads (values or derivative rows: all linear but the
    deformed-axis term, which the Jacobian adds by hand). `wing`: the model's parameters by name
    (the stations, the stiffnesses, the axis's direction)."""

    def __init__(self, layout: Layout, wing: Any) -> None:
        self.layout = layout
        self.wing = wing
        self.s = arc_length(wing)  # [m] along the EA
        self.h = self.s[1:] - self.s[:-1]
        self.ei, self.gj, self.cross = section_compliance(
            wing.bending_stiffness, wing.torsional_stiffness, wing.bending_torsion_coupling
        )
        k, strips = layout.chordwise, layout.n_strips
        # Panels to strips: strip i holds panels i k .. i k + k - 1.
        self.strips = ca.sparsify(ca.DM(np.kron(np.eye(strips), np.ones((1, k)))))

    def outboard(self, loads: ca.MX, part: int) -> ca.MX:
        """(N, c) the outboard sums of the loads' `part` (`solver.model.aerodynamics`)."""
        m = self.layout.n_panels
        return outboard_sum(ca.mtimes(self.strips, loads[part * m : (part + 1) * m, :]))

    def _force(self, loads: ca.MX) -> tuple[ca.MX, ca.MX, ca.MX]:
        """The outboard sums of the force's three components (those unused leave the graph)."""
        return self.outboard(loads, 0), self.outboard(loads, 1), self.outboard(loads, 2)

    def bending(self, loads: ca.MX) -> ca.MX:
        """(N, c) M_i, linear in the loads."""
        normal = normal_force(self._force(loads), self.wing)
        return self.outboard(loads, 3) - _scale_rows(self.s, normal)

    def axis_force(self, loads: ca.MX) -> ca.MX:
        """(N, c) outboard sum of F . (e_s x n) (`solver.model.geometry.axis_force`)."""
        return axis_force(self._force(loads), self.wing)

    def torque(self, loads: ca.MX, heave: ca.MX, deformed: ca.MX) -> ca.MX:
        """(N, c) T_i for loads along a parameter the heave does not depend on (values, alpha,
        the control direction, the roll rate)."""
        return self.outboard(loads, 4) - deformed * heave * self.axis_force(loads)

    def rows(self, bending: ca.MX, torque: ca.MX) -> ca.MX:
        """(2(N-1), c): -h_i/2 (f_i/K_i + f_{i+1}/K_{i+1}) for M/EI* and degrees(T/GJ*), and
        the coupling's +h_i/2 (c_i g_i + c_{i+1} g_{i+1}) of the other load (T in the bending
        rows, M in the torsion rows; `section_compliance`)."""

        def trapezoid(integrand: ca.MX, stiffness: ca.MX, scale: float) -> ca.MX:
            inner = -scale * self.h / (2 * stiffness[:-1])
            outer = -scale * self.h / (2 * stiffness[1:])
            return _scale_rows(inner, integrand[:-1, :]) + _scale_rows(outer, integrand[1:, :])

        def coupling(other: ca.MX, scale: float) -> ca.MX:
            # Signed zeros at K = 0: added to the uncoupled rows, they leave them to the bit.
            inner = scale * self.h * self.cross[:-1] / 2
            outer = scale * self.h * self.cross[1:] / 2
            return _scale_rows(inner, other[:-1, :]) + _scale_rows(outer, other[1:, :])

        return ca.vertcat(
            trapezoid(bending, self.ei, 1.0) + coupling(torque, 1.0),
            trapezoid(torque, self.gj, DEG_PER_RAD) + coupling(bending, DEG_PER_RAD),
        )

    def load_rows(self, loads: ca.MX, heave: ca.MX, deformed: ca.MX) -> ca.MX:
        """(2(N-1), c) the q-proportional part of the bending and torsion equations, or
        d(load_rows) along a parameter the heave does not depend on (alpha, the control
        direction, the roll rate), from the loads' derivative along it."""
        return self.rows(self.bending(loads), self.torque(loads, heave, deformed))

    def load_rows_jacobian(
        self, loads: ca.MX, loads_x: ca.MX, heave: ca.MX, deformed: ca.MX, heave_columns: ca.DM
    ) -> ca.MX:
        """(2(N-1), nx) d(load_rows)/dx from the loads and their derivative rows (5M, nx)."""
        torque_x = self.outboard(loads_x, 4) - deformed * (
            _scale_rows(heave, self.axis_force(loads_x))
            + ca.mtimes(ca.diag(self.axis_force(loads)), heave_columns)
        )
        return self.rows(self.bending(loads_x), torque_x)


def structure_rows(layout: Layout, x: ca.MX, h: ca.MX) -> ca.MX:
    """Root clamps, heave kinematics and the load-free part of bending and torsion rows."""
    heave, slope, twist = x[layout.heave], x[layout.slope], x[layout.twist]
    return ca.vertcat(
        heave[0],
        slope[0],
        twist[0],
        heave[1:] - heave[:-1] - h * (slope[:-1] + slope[1:]) / 2,
        slope[1:] - slope[:-1],
        twist[1:] - twist[:-1],
    )
