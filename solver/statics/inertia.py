"""Inertia relief: the wing's own mass under the aircraft's load factor.

In steady flight at load factor n the aircraft accelerates at (n - 1) g upward while gravity
pulls g down: in its frame every mass of the wing weighs n g, downward. The wing's distributed
mass (`wing.mass`: the non-structural mass, plus a tube spar's own, density times its wall's
area), and its concentrated masses (stores, engines, balance weights), so load the beam
against the lift: the section loads are the aerodynamic loads minus the inertial ones. The
weight the lift carries is the aircraft's, the wing's own mass part of it (`FlightCondition`).

Sign convention, as the reported loads: z up, a force up positive; the inertial force of a mass
m is m n g against the lift, normal to the flight path (the load factor is the lift over the
weight, n = L / W), so the wing's plane, at an angle of attack alpha to the path, carries
-m n g cos(alpha) of it (down, for n > 0; what `InertialLoads` holds is the one-g load at
alpha 0, and the model scales it by n cos(alpha)); a centre of gravity a distance d aft of the
elastic axis (EA) turns that force into a torque +m n g d cos(alpha) about the EA (nose up: the
trailing edge pulled down), so a mass ahead of the EA twists the wing nose down. On a dihedral
wing the beam carries the component normal to the wing's plane (cos(dihedral) of it). The
components along the plane (sin(alpha) chordwise, sin(dihedral) spanwise) are what the linear
beam leaves out, as it leaves out the lift's.

Lumping, as the vibration model lumps it (`solver.dynamics.modes`): each strip's mass, and its
static moment about the EA, integrated between its stations along the EA (trapezoids), act at
the strip's middle on the EA; a concentrated mass acts at its station, its offset aft of the EA
giving its torque. A load at a station counts in the cut just inboard of it (the tip's store is
carried by the whole last segment); a mass at the root station sits on the clamp and loads only
the root's reaction.

The beam's rows of these loads (the residual's bending and torsion rows,
`solver.model.beam`) enter the residual beside the aerodynamic ones
(`solver.statics.system.CoupledSystem.load_per_q`). On the linear beam they are constant (the
jig's arms, `InertialLoads.rows`). On the geometrically exact beam (`solver.model.exact_beam`)
the weight is a dead load taken about the deformed stations, as the beam's exact statics take
every force (`deformed_loads`): each mass point sits on the deformed reference line, at the
middle of its segment's chord for a strip, at its station for a concentrated mass, and

    M_i = sum_p W_p (S_p - S_i),   T_i = cos(beta_i) T_jig,i

with S the stations' foreshortened distances along the jig axis
(`solver.model.geometry.reference_line`), W_p the one-g weights normal to the jig's plane,
and T_jig the static moments' torque about the jig axis: the weight (normal to the plane)
has no moment about the deformed axis t_i but through the mass's offset across it, along
e_c, which bending about e_c leaves fixed ((d e_c x W n) . t_i = -d W cos(beta_i)). These rows
depend on the rotations; `deformed_rows` gives them with their exact derivative.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from typing import Any

import casadi as ca
import numpy as np

from solver.inputs.mass import MassModel
from solver.inputs.wing import Wing
from solver.model.beam import DEG_PER_RAD, coupled_trapezoid, section_compliance
from solver.model.geometry import DEG, arc_length, in_wing_plane, lag_reference_line, reference_line
from solver.model.layout import Layout
from solver.numerics.cache import cached

__all__ = [
    "GRAVITY",
    "DeformedInertialLoads",
    "InertialLoads",
    "deformed_loads",
    "deformed_rows",
    "lag_deformed_loads",
    "lag_deformed_rows",
    "deformed_stations",
    "inertial_loads",
    "strip_station_weights",
]

GRAVITY = 9.80665  # [m/s^2] standard gravity (3rd CGPM, 1901; ISO 80000-3)


@dataclass(frozen=True)
class InertialLoads:
    """The loads of the wing's own mass at one g (load factor 1): a load factor n multiplies
    them.

    shear, bending_moment, torque: (N,) [N], [N m], [N m] at each station, as the reported
    loads are (z up, torque nose-up about the EA); rows: (n_unknowns,) their terms in the
    residual's bending and torsion rows (its units, `solver.model.beam`; zero elsewhere);
    mass: [kg] of both halves, concentrated masses included; station_weights: (N, N) [N] the
    bending moment's weights on the stations' positions along the axis, bending_moment =
    station_weights @ S for stations S [m] along it (the jig's arc length, or the exact beam's
    foreshortened reference line: `deformed_loads`).
    """

    shear: np.ndarray
    bending_moment: np.ndarray
    torque: np.ndarray
    rows: np.ndarray
    mass: float
    station_weights: np.ndarray


@dataclass(frozen=True)
class DeformedInertialLoads:
    """The one-g inertial loads about the exact beam's deformed stations (module docstring) at
    rotations beta (N,) [rad]: bending_moment, torque (N,) [N m]; their derivatives in beta,
    bending_beta, torque_beta (N, N) [N m/rad]."""

    bending_moment: np.ndarray
    torque: np.ndarray
    bending_beta: np.ndarray
    torque_beta: np.ndarray


def inertial_loads(wing: Wing, layout: Layout) -> InertialLoads | None:
    """The wing's inertial loads at one g (`InertialLoads`), None without `wing.mass`; kept in
    the solver's cache (a deterministic function of the wing and the mesh)."""
    if wing.mass is None:
        return None
    key = ("inertial_loads", wing.key, layout)
    return cached(key, lambda: _inertial_loads(wing, wing.mass, layout), _size)  # type: ignore[arg-type]


def _size(loads: InertialLoads | None) -> int:
    return 0 if loads is None else 4 * loads.rows.nbytes + loads.station_weights.nbytes


def _inertial_loads(wing: Wing, mass: MassModel, layout: Layout) -> InertialLoads:
    arc = arc_length(wing)  # [m] along the EA, in the wing's plane
    h = np.diff(arc)
    per_length = mass.mass_per_length.astype(float)
    offset = (mass.center_of_gravity - wing.elastic_axis) * wing.chord
    offset = offset * math.cos(math.radians(wing.sweep))  # normal to the EA, in the plane
    moment_per_length = per_length * offset  # [kg] static moment about the EA
    if wing.spar is not None:  # on the EA: mass, no static moment
        per_length = per_length + wing.spar.material.density * wing.spar.area
    # The weight of a unit mass at one g, in the wing's frame: its component normal to the plane.
    weight = float(in_wing_plane((0.0, 0.0, -GRAVITY), wing)[2])
    strip_mass = h * (per_length[:-1] + per_length[1:]) / 2  # [kg]
    strip_moment = h * (moment_per_length[:-1] + moment_per_length[1:]) / 2  # [kg m]
    middle = (arc[:-1] + arc[1:]) / 2
    n = wing.n_stations
    shear, bending, torque = np.zeros(n), np.zeros(n), np.zeros(n)
    for i in range(n):
        outboard = slice(i, None)
        force = weight * strip_mass[outboard]
        shear[i] = force.sum()
        bending[i] = force @ (middle[outboard] - arc[i])
        torque[i] = -weight * strip_moment[outboard].sum()
    total = float(2 * strip_mass.sum())
    for item in mass.concentrated:
        k = item.station
        inboard = slice(0, k + 1)  # every cut inboard of the mass, its station's own included
        shear[inboard] += weight * item.mass
        bending[inboard] += weight * item.mass * (arc[k] - arc[inboard])
        torque[inboard] += -weight * item.mass * item.offset
        total += 2 * item.mass
    station_weights = _station_weights(weight * strip_mass, mass, weight)
    rows = np.zeros(layout.n_unknowns)
    stiffness = (wing.bending_stiffness, wing.torsional_stiffness, wing.bending_torsion_coupling)
    rows[layout.bending_rows], rows[layout.torsion_rows] = coupled_trapezoid(
        h, bending, torque, stiffness
    )
    for array in (shear, bending, torque, rows, station_weights):
        array.setflags(write=False)
    return InertialLoads(shear, bending, torque, rows, total, station_weights)


def strip_station_weights(strip_force: np.ndarray) -> np.ndarray:
    """(N, N) [N] the station weights (`InertialLoads.station_weights`) of the strips' forces
    normal to the plane (N-1,) [N], each at its chord's middle: M_i = sum_{j >= i} F_j
    ((S_j + S_{j+1}) / 2 - S_i), half of F_j on either station, less the outboard force at
    S_i. Linear in the forces."""
    n = strip_force.size + 1
    weights = np.zeros((n, n))
    for i in range(n - 1):
        weights[i, i:-1] += strip_force[i:] / 2
        weights[i, i + 1 :] += strip_force[i:] / 2
        weights[i, i] -= strip_force[i:].sum()
    return weights


def _station_weights(strip_force: np.ndarray, mass: MassModel, weight: float) -> np.ndarray:
    """(N, N) [N]: the strips' (`strip_station_weights`) and each concentrated mass's, at its
    station, less its weight at S_i for every station inboard of it."""
    weights = strip_station_weights(strip_force)
    for item in mass.concentrated:
        k = item.station
        force = weight * item.mass
        weights[: k + 1, k] += force
        weights[np.arange(k + 1), np.arange(k + 1)] -= force
    return weights


@functools.cache
def _stations_function(n: int) -> ca.Function:
    """(beta (N,), h (N-1,)) -> S (N,) and dS/dbeta (N, N): the exact beam's stations along the
    jig axis (`solver.model.geometry.reference_line`, its own formula), differentiated by
    CasADi."""
    beta, h = ca.SX.sym("beta", n), ca.SX.sym("h", n - 1)
    along, _ = reference_line(beta, h)
    return ca.Function("dead_load_stations", [beta, h], [along, ca.jacobian(along, beta)])


def deformed_stations(wing: Wing, beta: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(N,) [m] the exact beam's stations along the jig axis at rotations beta (N,) [rad]
    (its foreshortened reference line, `solver.model.geometry.reference_line`), and their
    derivative in beta (N, N) [m/rad]."""
    along, along_beta = _stations_function(wing.n_stations)(beta, np.diff(arc_length(wing)))
    return np.asarray(along).ravel(), np.asarray(along_beta)


def deformed_loads(inertia: InertialLoads, wing: Wing, beta: np.ndarray) -> DeformedInertialLoads:
    """The one-g inertial loads about the exact beam's deformed stations at rotations beta (N,)
    [rad] (module docstring), with their derivatives in beta."""
    along, along_beta = deformed_stations(wing, beta)
    return DeformedInertialLoads(
        bending_moment=inertia.station_weights @ along,
        torque=np.cos(beta) * inertia.torque,
        bending_beta=inertia.station_weights @ along_beta,
        torque_beta=np.diag(-np.sin(beta) * inertia.torque),
    )


def deformed_rows(
    inertia: InertialLoads, wing: Wing, layout: Layout, beta: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """The exact beam's one-g inertial rows at rotations beta (N,) [rad]: (n_unknowns,) as
    `InertialLoads.rows`, and their derivative in beta (n_unknowns, N) (zero but in the
    bending and torsion rows)."""
    loads = deformed_loads(inertia, wing, beta)
    h = np.diff(arc_length(wing))
    stiffness = (wing.bending_stiffness, wing.torsional_stiffness, wing.bending_torsion_coupling)
    rows = np.zeros(layout.n_unknowns)
    rows_beta = np.zeros((layout.n_unknowns, wing.n_stations))
    rows[layout.bending_rows], rows[layout.torsion_rows] = coupled_trapezoid(
        h, loads.bending_moment, loads.torque, stiffness
    )
    rows_beta[layout.bending_rows], rows_beta[layout.torsion_rows] = coupled_trapezoid(
        h, loads.bending_beta, loads.torque_beta, stiffness
    )
    return rows, rows_beta


# --- Lag layouts: the weight about the deformed stations in three dimensions ---------------------
#
# With lag bending (`solver.model.lag_beam`) each mass point sits on the 3D reference line
# (S, u, v): the weight F_p n (signed, one g, normal to the plane: `InertialLoads.
# station_weights`) at the middle of a strip's chord (a concentrated mass at its station) has
# the moment about the deformed station r_i, in (e_s, n, e_c),
#
#     M_i = sum_p (r_p - r_i) x F_p n = -sum_p F_p (v_p - v_i) e_s + sum_p F_p (S_p - S_i) e_c
#
# and the static moments' torque about the jig axis T_jig as the planar
# exact beam takes it (the offsets along e_c, which the rotations turn at second order only).
# Projected on the section's axes as the lag beam's loads (`solver.model.lag_beam.
# section_moments`) and integrated by its rows (`LagBeam.rates_of`, `lag_rows`): the weight of a
# lagged wing twists it through v (the first term), which is the coupling the lag model adds.


@functools.cache
def _lag_rows_function(n: int) -> ca.Function:
    """(beta, phi [deg], psi (N,), h (N-1,), station weights (N, N), T_jig (N,), EI*, GJ*, c,
    EI_lag (N,)) -> the lag beam's bending, torsion and lag rows (3(N-1),) of the one-g weight,
    their derivative in (beta, phi, psi) (3(N-1), 3N), and the stations' T, M_f, M_l (N,)."""
    beta, phi_deg, psi = (ca.SX.sym(name, n) for name in ("beta", "phi", "psi"))
    h = ca.SX.sym("h", n - 1)
    weights = ca.SX.sym("weights", n, n)
    torque_jig, ei, gj, cross, ei_lag = (
        ca.SX.sym(name, n) for name in ("torque_jig", "ei", "gj", "cross", "ei_lag")
    )
    along, _, lag = lag_reference_line(beta, psi, h)
    about_s = -ca.mtimes(weights, lag) + torque_jig
    about_c = ca.mtimes(weights, along)
    cos_b, sin_b, cos_p, sin_p = ca.cos(beta), ca.sin(beta), ca.cos(psi), ca.sin(psi)
    torque = cos_b * cos_p * about_s - cos_b * sin_p * about_c
    flap = sin_p * about_s + cos_p * about_c
    lag_moment = -sin_b * cos_p * about_s + sin_b * sin_p * about_c
    phi = phi_deg * DEG
    cos_t, sin_t = ca.cos(phi), ca.sin(phi)
    flap_s = cos_t * flap - sin_t * lag_moment
    lag_s = sin_t * flap + cos_t * lag_moment
    kappa_f = flap_s / ei - cross * torque
    kappa_l = lag_s / ei_lag
    twist_rate = torque / gj - cross * flap_s
    beta_rate = cos_t * kappa_f + sin_t * kappa_l
    psi_rate = (-sin_t * kappa_f + cos_t * kappa_l) / cos_b

    def trapezoid(rate: ca.SX, scale: float) -> ca.SX:
        return -scale * h / 2 * (rate[:-1] + rate[1:])

    rows = ca.vertcat(
        trapezoid(beta_rate, 1.0), trapezoid(twist_rate, DEG_PER_RAD), trapezoid(psi_rate, 1.0)
    )
    unknowns = ca.vertcat(beta, phi_deg, psi)
    return ca.Function(
        "lag_dead_load",
        [beta, phi_deg, psi, h, weights, torque_jig, ei, gj, cross, ei_lag],
        [rows, ca.jacobian(rows, unknowns), torque, flap, lag_moment],
    )


def _lag_evaluation(
    inertia: InertialLoads, wing: Wing, rotations: tuple[np.ndarray, ...]
) -> list[Any]:
    """`_lag_rows_function`'s outputs (rows, their Jacobian, torque, flap and lag moments, as
    CasADi DMs) for `wing` at the rotations (beta [rad], phi [deg], psi [rad]), each (N,)."""
    beta, phi, psi = rotations
    ei, gj, cross = section_compliance(
        wing.bending_stiffness, wing.torsional_stiffness, wing.bending_torsion_coupling
    )
    assert wing.in_plane_bending_stiffness is not None
    return _lag_rows_function(wing.n_stations)(
        beta,
        phi,
        psi,
        np.diff(arc_length(wing)),
        inertia.station_weights,
        inertia.torque,
        ei,
        gj,
        cross,
        wing.in_plane_bending_stiffness,
    )


def lag_deformed_rows(
    inertia: InertialLoads, wing: Wing, layout: Layout, x: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """A lag layout's one-g inertial rows at the state x (n_unknowns,) (the weight about the
    deformed stations in 3D, above): (n_unknowns,) as `InertialLoads.rows`, and their
    derivative in x (n_unknowns, n_unknowns) (zero but in the bending, torsion and lag bending
    rows' columns of beta, phi and psi)."""
    rotations = (x[layout.slope], x[layout.twist], x[layout.lag_rotation])
    values, derivative = (np.asarray(v) for v in _lag_evaluation(inertia, wing, rotations)[:2])
    rows = np.zeros(layout.n_unknowns)
    rows_x = np.zeros((layout.n_unknowns, layout.n_unknowns))
    where = layout.load_rows  # bending, torsion, lag bending (`Layout.load_rows`)
    rows[where] = values.ravel()
    columns = np.r_[
        np.arange(layout.n_unknowns)[layout.slope],
        np.arange(layout.n_unknowns)[layout.twist],
        np.arange(layout.n_unknowns)[layout.lag_rotation],
    ]
    rows_x[np.ix_(where, columns)] = derivative
    return rows, rows_x


def lag_deformed_loads(
    inertia: InertialLoads, wing: Wing, rotations: tuple[np.ndarray, ...]
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """For the answers: (N,) [N m] the one-g weight's flap moment M_f, torque T and lag moment
    M_l at the lag beam's deformed stations, at the rotations (beta [rad], phi [deg], psi [rad])
    (N,) each (as `solver.model.lag_beam.lag_internal_loads` reports the lift's)."""
    torque, flap, lag = (
        np.asarray(v).ravel() for v in _lag_evaluation(inertia, wing, rotations)[2:]
    )
    return flap, torque, lag
