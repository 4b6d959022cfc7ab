"""Lag (in-plane) bending in the geometrically exact beam (`solver.model.exact_beam`): the
reference line bends in three dimensions, in the plane of the jig axis e_s and the wing's
normal n (flap, beta) and in the wing's own plane (lag, psi), with torsion about the deformed
tangent. Taken when the wing has `in_plane_bending_stiffness` under
`options.structure = "geometrically_exact"` (`solver.model.layout.Layout.lag`); the design:
docs/design/lag_bending.md.

Unknowns per station (`Layout`): u [m], beta [rad], phi [deg] as the exact beam's, and
v [m], the displacement along e_c = e_s x n (aft at zero sweep), and psi [rad], the lag
rotation about n (positive turns the axis forward, toward -e_c).

Kinematics: R = R_n(psi) R_ec(beta) R_es(phi) (lag, then flap, then twist; Hodges,
"Nonlinear Composite Beam Theory", AIAA 2006, ch. 4), in the right-handed frame (e_s, n, e_c):

    t    = cos(beta) (cos(psi) e_s - sin(psi) e_c) + sin(beta) n     (the tangent)
    e_c' = cos(psi) e_c + sin(psi) e_s                                (the flap axis)
    n''  = -sin(beta) (cos(psi) e_s - sin(psi) e_c) + cos(beta) n    (the lag axis)

Each segment the chord of an arc in each plane (`solver.model.geometry.lag_segment_chords`).
The curvatures, the axial vector of R^T R': k_t = phi' + psi' sin(beta) (torsion),
k_f = beta' (about e_c'), k_l = psi' cos(beta) (about n''), and in the twisted section's axes
(chord cos(phi) e_c' - sin(phi) n'', normal cos(phi) n'' + sin(phi) e_c'):
k_f^s = cos(phi) k_f - sin(phi) k_l, k_l^s = sin(phi) k_f + cos(phi) k_l.

Constitutive law in the section's axes: T = GJ k_t + K k_f^s, M_f^s = EI k_f^s + K k_t
(`solver.model.beam.section_compliance`), M_l^s = EI_lag k_l^s. The internal moment at the
deformed station r_i of every force outboard, M_i = sum_p (r_p - r_i) x F_p (r_p on the
deformed lattice), projected: T = M . t, M_f = M . e_c', M_l = M . n'', M_f^s, M_l^s turned
by phi. The rows integrate by the trapezoid, as the exact beam's, the rates the moments give:

    bending (N-1)      beta_{i+1} - beta_i - h_i/2 (beta'_i + beta'_{i+1})
                       beta' = cos(phi) k_f^s + sin(phi) k_l^s
    torsion (N-1)      phi_{i+1} - phi_i + sin(b_i) (psi_{i+1} - psi_i) - h_i/2 (k_t,i + k_t,i+1)
                       (degrees; b_i the segment's mean flap rotation: the midpoint rule of
                       psi' sin(beta), second order as the trapezoid)
    lag clamps (2)     v_0 = 0, psi_0 = 0
    lag kinematics     v_{i+1} - v_i - (r_{i+1} - r_i) . e_c
    lag bending (N-1)  psi_{i+1} - psi_i - h_i/2 (psi'_i + psi'_{i+1}),
                       psi' = (-sin(phi) k_f^s + cos(phi) k_l^s) / cos(beta)

with k_f^s = M_f^s/EI* - c T, k_l^s = M_l^s/EI_lag, k_t = T/GJ* - c M_f^s. The loads' rows
are linear in the loads at fixed z (their q-proportional part), as the exact beam's; the term
sin(b) dpsi of the torsion rows is load-free (J0's).

The limit EI_lag -> infinity is not the planar exact beam: a twisted section is rigid in its
own lag direction and bends in its weak plane (psi' cos(beta) = -tan(phi) beta'); the two
differ at second order (phi beta'). Without the field, the planar beam is taken, bit for bit.
"""

from __future__ import annotations

from typing import Any

import casadi as ca
import numpy as np

from solver.model.beam import DEG_PER_RAD, section_compliance
from solver.model.exact_beam import EXACT_LOADS, ExactBeam
from solver.model.geometry import (
    DEG,
    axis_force,
    in_wing_plane,
    lag_reference_line,
    lag_segment_chords,
    span_axis,
)
from solver.model.layout import Layout

__all__ = [
    "LagBeam",
    "bent_station_load_rows",
    "bent_strip_load_rows",
    "lag_axis_points",
    "lag_internal_loads",
    "lag_structure_rows",
    "section_moments",
]


def lag_structure_rows(layout: Layout, x: ca.MX, h: ca.MX) -> ca.MX:
    """(5N,) the load-free rows (module docstring): the exact beam's root clamps, heave
    kinematics on the 3D chords, bending, torsion with its sin(b) dpsi term, then the lag
    clamps, kinematics and bending."""
    heave, beta, twist = x[layout.heave], x[layout.slope], x[layout.twist]
    lag, psi = x[layout.lag_displacement], x[layout.lag_rotation]
    _, normal, across = lag_segment_chords(beta, psi, h)
    flap = (beta[:-1] + beta[1:]) / 2
    return ca.vertcat(
        heave[0],
        beta[0],
        twist[0],
        heave[1:] - heave[:-1] - normal,
        beta[1:] - beta[:-1],
        twist[1:] - twist[:-1] + DEG_PER_RAD * ca.sin(flap) * (psi[1:] - psi[:-1]),
        lag[0],
        psi[0],
        lag[1:] - lag[:-1] - across,
        psi[1:] - psi[:-1],
    )


def section_moments(
    moment: tuple[Any, Any, Any],
    force: tuple[Any, Any, Any],
    line: tuple[Any, Any, Any],
    beta: Any,
    psi: Any,
    scale: Any,
) -> tuple[Any, Any, Any]:
    """T = M . t, M_f = M . e_c', M_l = M . n'' [N m] at the stations (module docstring), of
    the outboard sums of the panels' moments about the root `moment` (along e_s, n, e_c) and
    forces `force` (along e_s, n, e_c), about the stations' points `line` (S, u, v (N,) [m]):
    M_i = sum r_p x F_p - r_i x sum F_p. `scale(factors, values)` multiplies each station's
    row (numpy broadcasting or a CasADi column times a matrix)."""
    m_s, m_n, m_c = moment
    f_s, f_n, f_c = force
    along, heave, lag = line
    # r_i x F in (e_s, n, e_c): (u F_c - v F_n, v F_s - S F_c, S F_n - u F_s).
    about_s = m_s - scale(heave, f_c) + scale(lag, f_n)
    about_n = m_n - scale(lag, f_s) + scale(along, f_c)
    about_c = m_c - scale(along, f_n) + scale(heave, f_s)
    cos_b, sin_b = _cos(beta), _sin(beta)
    cos_p, sin_p = _cos(psi), _sin(psi)
    torque = scale(cos_b * cos_p, about_s) + scale(sin_b, about_n) - scale(cos_b * sin_p, about_c)
    flap = scale(sin_p, about_s) + scale(cos_p, about_c)
    lag_moment = (
        scale(-sin_b * cos_p, about_s) + scale(cos_b, about_n) + scale(sin_b * sin_p, about_c)
    )
    return torque, flap, lag_moment


def _cos(angle: Any) -> Any:
    return ca.cos(angle) if isinstance(angle, ca.SX | ca.MX | ca.DM) else np.cos(angle)


def _sin(angle: Any) -> Any:
    return ca.sin(angle) if isinstance(angle, ca.SX | ca.MX | ca.DM) else np.sin(angle)


def _scale(factors: ca.MX, matrix: ca.MX) -> ca.MX:
    return ca.repmat(factors, 1, matrix.size2()) * matrix


class LagBeam(ExactBeam):
    """The lag beam's load rows (module docstring): (3(N-1), c) the bending, torsion and lag
    bending rows' q-proportional part. `z` (5N,) the beam's unknowns [u; beta; phi; v; psi],
    `p` the lag layout's parameter vector."""

    def __init__(self, layout: Layout, p: ca.MX, z: ca.MX) -> None:
        super().__init__(layout, p, z)
        self.ei_lag = self.wing.in_plane_bending_stiffness

    def _rates(self, loads: ca.MX, z: ca.MX) -> tuple[ca.MX, ca.MX, ca.MX]:
        """(N, c) beta' [1/m], k_t [1/m] and psi' [1/m] of per-panel loads (rows as
        `solver.model.aerodynamics`'s, the exact rows last) at the beam's unknowns z."""
        n, m = self.layout.n, self.layout.n_panels
        exact = loads.size1() // m - EXACT_LOADS
        e_x, e_y = span_axis(self.wing)
        fx, fy, fz = self._force(loads)
        x, y, f_normal = in_wing_plane((fx, fy, fz), self.wing)
        force = (e_x * x + e_y * y, f_normal, axis_force((fx, fy, fz), self.wing))
        moment = (
            self.outboard(loads, 4),
            self.outboard(loads, exact + 1),
            self.outboard(loads, exact),
        )
        beta, psi = z[n : 2 * n], z[4 * n : 5 * n]
        line = lag_reference_line(beta, psi, self.h)
        return self.rates_of(section_moments(moment, force, line, beta, psi, _scale), z)

    def rates_of(self, moments: tuple[ca.MX, ca.MX, ca.MX], z: ca.MX) -> tuple[ca.MX, ca.MX, ca.MX]:
        """(N, c) beta', k_t and psi' [1/m] of the stations' T, M_f and M_l (N, c) [N m]
        (`section_moments`) at the beam's unknowns z: the constitutive law in the twisted
        section's axes (module docstring)."""
        n = self.layout.n
        torque, flap, lag = moments
        beta, phi = z[n : 2 * n], z[2 * n : 3 * n] * DEG
        cos_t, sin_t = ca.cos(phi), ca.sin(phi)
        flap_s = _scale(cos_t, flap) - _scale(sin_t, lag)
        lag_s = _scale(sin_t, flap) + _scale(cos_t, lag)
        # The section's curvatures: about its chord, its normal, and the twist rate.
        kappa_f = _scale(1 / self.ei, flap_s) - _scale(self.cross, torque)
        kappa_l = _scale(1 / self.ei_lag, lag_s)
        twist_rate = _scale(1 / self.gj, torque) - _scale(self.cross, flap_s)
        beta_rate = _scale(cos_t, kappa_f) + _scale(sin_t, kappa_l)
        psi_rate = _scale(1 / ca.cos(beta), _scale(-sin_t, kappa_f) + _scale(cos_t, kappa_l))
        return beta_rate, twist_rate, psi_rate

    def lag_rows(self, rates: tuple[ca.MX, ca.MX, ca.MX]) -> ca.MX:
        """(3(N-1), c) -h_i/2 (f_i + f_{i+1}) of beta', degrees(k_t) and psi'."""

        def trapezoid(rate: ca.MX, scale: float) -> ca.MX:
            return _scale(-scale * self.h / 2, rate[:-1, :] + rate[1:, :])

        beta_rate, twist_rate, psi_rate = rates
        return ca.vertcat(
            trapezoid(beta_rate, 1.0), trapezoid(twist_rate, DEG_PER_RAD), trapezoid(psi_rate, 1.0)
        )

    def load_rows(self, loads: ca.MX, heave: ca.MX, deformed: ca.MX) -> ca.MX:
        """(3(N-1), c) the q-proportional part of the bending, torsion and lag bending rows, or
        its derivative along a parameter z does not depend on (`deformed` is not read)."""
        return self.lag_rows(self._rates(loads, self.z))

    def load_rows_jacobian(
        self, loads: ca.MX, loads_x: ca.MX, heave: ca.MX, deformed: ca.MX, heave_columns: ca.DM
    ) -> ca.MX:
        """(3(N-1), nx) d(load_rows)/dx: linear in the loads at fixed z, plus the explicit
        derivative through the deformed stations, axes and the section's twist."""
        nz, nx = self.layout.n_structure, self.layout.n_unknowns
        z, held, p = (
            ca.MX.sym("z", nz),
            ca.MX.sym("loads", loads.shape),
            ca.MX.sym("p", self.p.shape),
        )
        inner = LagBeam(self.layout, p, z)
        rows_at = inner.lag_rows(inner._rates(held, z))
        explicit = ca.Function("lag_beam_z", [z, held, p], [ca.jacobian(rows_at, z)])
        through_z = ca.horzcat(explicit(self.z, loads, self.p), ca.MX(rows_at.size1(), nx - nz))
        return self.lag_rows(self._rates(loads_x, self.z)) + through_z


def _outboard(values: np.ndarray, k: int) -> np.ndarray:
    strips = values.reshape(-1, k).sum(axis=1)
    return np.concatenate([np.cumsum(strips[::-1])[::-1], [0.0]])


def lag_internal_loads(
    wing: Any,
    force: np.ndarray,
    center: np.ndarray,
    rotations: tuple[np.ndarray, np.ndarray],
    k: int,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Numpy, for the answers: (N,) M_f = M . e_c' (flap), T = M . t and M_l = M . n'' (lag)
    [N m] (module docstring) of the panels' forces (3, M) [N] at their deformed force points
    (3, M) [m] (geometry axes), at the rotations beta, psi (N,) [rad]; `wing` the numeric
    `solver.inputs.wing.Wing`."""
    beta, psi = rotations
    e_x, e_y = span_axis(wing)
    f_x, f_y, f_normal = in_wing_plane(force, wing)
    r_x, r_y, r_normal = in_wing_plane(center, wing)
    f_along, f_across = e_x * f_x + e_y * f_y, e_y * f_x - e_x * f_y
    r_along, r_across = e_x * r_x + e_y * r_y, e_y * r_x - e_x * r_y
    # r x F in the right-handed frame (e_s, n, e_c).
    m_along = r_normal * f_across - r_across * f_normal
    m_normal = r_across * f_along - r_along * f_across
    m_across = r_along * f_normal - r_normal * f_along
    moment = tuple(_outboard(part, k) for part in (m_along, m_normal, m_across))
    forces = tuple(_outboard(part, k) for part in (f_along, f_normal, f_across))
    arc = np.asarray(wing.arc_length, dtype=float)
    line = lag_reference_line(beta, psi, np.diff(arc))
    torque, flap, lag = section_moments(moment, forces, line, beta, psi, np.multiply)  # type: ignore[arg-type]
    return flap, torque, lag


def lag_axis_points(wing: Any, heave: np.ndarray, rotations: tuple[np.ndarray, ...]) -> np.ndarray:
    """Numpy, for the answers: (3, N) [m] the deformed elastic axis's points in geometry axes
    with lag: S e_s + v e_c + u n on the reference line of beta, psi [rad] (`rotations`), the
    heave u the unknown's, the plane turned by the dihedral."""
    beta, psi = rotations
    arc = np.asarray(wing.arc_length, dtype=float)
    along, _, lag = lag_reference_line(beta, psi, np.diff(arc))
    e_x, e_y = span_axis(wing)
    x, y = e_x * along + e_y * lag, e_y * along - e_x * lag
    cos, sin = np.cos(np.radians(wing.dihedral)), np.sin(np.radians(wing.dihedral))
    return np.vstack([x, y * cos - heave * sin, y * sin + heave * cos])


def bent_strip_load_rows(
    wing: Any, beta: np.ndarray, phi: np.ndarray, psi: np.ndarray
) -> np.ndarray:
    """Numpy, for the vibration model about a bent state: (3(N-1), 3(N-1)) the bending,
    torsion and lag bending rows' load terms (`LagBeam.lag_rows`' units) of unit strip loads
    at the rotations beta [rad], phi [deg], psi [rad] (N,): a force along n at each strip's
    middle on the deformed axis (the first N - 1 columns), a torque about the strip's tangent,
    a force along e_c (`solver.dynamics.modes`' strip loads, whose rows about the jig these
    are to the bit). On the bent wing a force across the axis in its plane, acting above the
    stations inboard, twists them: the geometric coupling of torsion with lag bending that
    lowers the torsion frequency of a bent wing (docs/design/lag_bending.md, step 3)."""
    n = wing.n_stations
    line = _deformed_line(wing, beta, psi)
    middle = (line[:-1] + line[1:]) / 2
    strip_tangent = _tangent((beta[:-1] + beta[1:]) / 2, (psi[:-1] + psi[1:]) / 2)
    moments = []
    for unit in (_NORMAL, None, _ACROSS):  # a force along n, a torque, a force along e_c
        for j in range(n - 1):
            # About each station; the stations outboard of the strip carry none.
            moment = np.zeros((n, 3))
            if unit is None:
                moment[: j + 1] = strip_tangent[j]
            else:
                moment[: j + 1] = np.cross(middle[j] - line[: j + 1], unit)
            moments.append(moment)
    return _rows_of_moments(wing, beta, phi, psi, np.array(moments))


def bent_station_load_rows(
    wing: Any, beta: np.ndarray, phi: np.ndarray, psi: np.ndarray
) -> np.ndarray:
    """Numpy, for the vibration model about a bent state: (N, 3(N-1), 3) at each station the
    bending, torsion and lag bending rows' load terms of a unit force along n at the station's
    deformed point, a unit torque about its tangent and a unit force along e_c (a concentrated
    mass's inertial loads; about the jig `solver.dynamics.modes`' station rows to the bit). The
    torque acts on the segments inboard of the station, each trapezoid taking it at both ends
    (as about the jig). On the bent wing the in-plane force at a raised station twists the
    stations inboard: a concentrated mass swings fore and aft as the wing twists."""
    n = wing.n_stations
    line = _deformed_line(wing, beta, psi)
    t = _tangent(beta, psi)
    rows = np.zeros((n, 3 * (n - 1), 3))
    for station in range(1, n):
        moments = np.zeros((3, n, 3))
        inboard = slice(0, station + 1)
        moments[0, inboard] = np.cross(line[station] - line[inboard], _NORMAL)
        moments[1, inboard] = t[station]
        moments[2, inboard] = np.cross(line[station] - line[inboard], _ACROSS)
        rows[station] = _rows_of_moments(wing, beta, phi, psi, moments)
        # The torque on the segments inboard only: the station's own segment outboard takes
        # none of it (its trapezoid would take half at the station's end).
        for group in range(3):
            rows[station, group * (n - 1) + station : (group + 1) * (n - 1), 1] = 0.0
    return rows


# Unit forces along n and e_c, in (e_s, n, e_c).
_NORMAL, _ACROSS = np.array([0.0, 1.0, 0.0]), np.array([0.0, 0.0, 1.0])


def _deformed_line(wing: Any, beta: np.ndarray, psi: np.ndarray) -> np.ndarray:
    """(N, 3) [m] the deformed axis's stations in (e_s, n, e_c)."""
    h = np.diff(np.asarray(wing.arc_length, dtype=float))
    return np.stack(lag_reference_line(beta, psi, h), axis=1)


def _tangent(b: np.ndarray, p: np.ndarray) -> np.ndarray:
    """(..., 3) the tangent t at flap and lag rotations b, p [rad], in (e_s, n, e_c)."""
    return np.stack([np.cos(b) * np.cos(p), np.sin(b), -np.cos(b) * np.sin(p)], axis=-1)


def _rows_of_moments(
    wing: Any, beta: np.ndarray, phi: np.ndarray, psi: np.ndarray, moments: np.ndarray
) -> np.ndarray:
    """(3(N-1), C) the bending, torsion and lag bending rows' load terms of C loads whose
    moments about each station are `moments` (C, N, 3) [N m per unit load] in (e_s, n, e_c):
    projected on the bent stations' axes and the twisted sections', through the compliance,
    integrated by the trapezoid (module docstring)."""
    n = wing.n_stations
    h = np.diff(np.asarray(wing.arc_length, dtype=float))
    t = _tangent(beta, psi)
    flap_axis = np.stack([np.sin(psi), np.zeros(n), np.cos(psi)], axis=-1)  # e_c'
    lag_axis = np.stack(
        [-np.sin(beta) * np.cos(psi), np.cos(beta), np.sin(beta) * np.sin(psi)], axis=-1
    )  # n''
    ei, gj, cross = section_compliance(
        wing.bending_stiffness, wing.torsional_stiffness, wing.bending_torsion_coupling
    )
    ei_lag = np.asarray(wing.in_plane_bending_stiffness, dtype=float)
    cos_t, sin_t = np.cos(phi * DEG), np.sin(phi * DEG)
    torque = np.einsum("cij,ij->ci", moments, t)
    flap = np.einsum("cij,ij->ci", moments, flap_axis)
    lag = np.einsum("cij,ij->ci", moments, lag_axis)
    flap_s, lag_s = cos_t * flap - sin_t * lag, sin_t * flap + cos_t * lag
    kappa_f = flap_s / ei - cross * torque
    kappa_l = lag_s / ei_lag
    twist_rate = torque / gj - cross * flap_s
    beta_rate = cos_t * kappa_f + sin_t * kappa_l
    psi_rate = (-sin_t * kappa_f + cos_t * kappa_l) / np.cos(beta)
    return np.vstack(
        [
            (-h / 2 * (beta_rate[:, :-1] + beta_rate[:, 1:])).T,
            (-DEG_PER_RAD * h / 2 * (twist_rate[:, :-1] + twist_rate[:, 1:])).T,
            (-h / 2 * (psi_rate[:, :-1] + psi_rate[:, 1:])).T,
        ]
    )
