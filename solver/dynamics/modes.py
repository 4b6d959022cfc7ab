"""Structural dynamics of the cantilever on the model's own mesh: stiffness, mass, natural modes.

The stiffness is the static model's own (`solver.model.residual`): the root clamps, the trapezoidal
heave kinematics and the trapezoid rows

    bending   u'_{i+1} - u'_i = h_i (M_i/EI_i + M_{i+1}/EI_{i+1}) / 2
    torsion   phi_{i+1} - phi_i = h_i (T_i/GJ_i + T_{i+1}/GJ_{i+1}) / 2

with M_i, T_i the outboard sums of the loads, are here matrices of numbers, in flexibility
form: loads -> load rows -> deformation. `tests/solver/test_modes.py` checks them against the
compiled model's own Jacobian rows and equilibria.

Degrees of freedom: w = (u_1 .. u_{N-1} [m], phi_1 .. phi_{N-1} [rad]), the heave and the twist
about the elastic axis (EA) at every station but the clamped root. Every deformation the beam
can take is fixed by them: the slopes follow (z = Z w, z = (u, u', phi [deg]) as the model's
unknowns).

Loads are taken as the static model takes its aerodynamic loads, per strip at the strip's
midpoint: a vertical force F_j and a torque tau_j about the EA. Such strip loads f give the
deformation w = G f; K = G^{-1} is the stiffness. Any other load (a concentrated mass at a
station, the lattice's panels, a streamwise pitching moment on a swept wing) enters as the strip
loads that give the same load rows, "equivalent strip loads", so the equations of motion are

    K w + M w'' = f_aero,

M the strips' inertia lumped at their midpoints (mass, static moment and inertia about the EA
integrated over the strip by the trapezoidal rule, moving as the mean of its two stations) and
the concentrated masses', as equivalent strip loads. K and M are not symmetric (the trapezoid
and the lumping are not variational), but K M^{-1} has real positive eigenvalues, the squares of
the natural frequencies, which converge to the continuous beam's at O(h^2) (tested against the
uniform cantilever's closed forms, 1.8751^2 sqrt(EI / (m L^4)) and (pi / 2) sqrt(GJ / (I L^2)),
and the exact coupled bending-torsion frequencies).

The same K is what makes a flutter solution's zero-frequency root the static divergence: at
zero frequency the equations are the static model's, K w = q Q w (`solver.flutter`).

In-plane (lag) bending: with an in-plane bending stiffness EI_lag (the geometrically exact
beam's, `docs/design/lag_bending.md`) the beam also bends in the wing's plane, and w gains the
lag displacements v_1 .. v_{N-1} [m] (along e_c = e_s x n, aft at zero sweep): n = 3 (N - 1),
the strip loads gain an in-plane force F_c per strip at its midpoint, the model's unknowns
z = (u, u', phi [deg], v, psi [rad]) (5N) and its rows the lag clamps, the lag kinematics
v_{i+1} - v_i + h_i (psi_i + psi_{i+1}) / 2 = 0 (straight) and the lag bending rows
psi_{i+1} - psi_i = h_i (M_l,i/EI_lag,i + M_l,i+1/EI_lag,i+1) / 2, M_l the in-plane moment
about the normal n (an aft force bends the axis aft: psi < 0, v > 0). The strips' mass moves
with v as with u; a centre of gravity on the chord line couples v with nothing. About the jig
the lag modes are the in-plane cantilever's, uncoupled; about a bent state the exact beam's
tangent rows couple them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np
import scipy.linalg

from solver.errors import ConvergenceError, InvalidInput
from solver.inputs.mass import MassModel, section_inertia
from solver.inputs.wing import Wing
from solver.model.beam import coupled_trapezoid, section_compliance
from solver.model.geometry import DEG, in_wing_plane
from solver.results.flutter import ModeShape, NaturalModes

__all__ = [
    "Structure",
    "largest_edge_displacement",
    "mode_shape",
    "natural_modes",
    "structure",
]

DEG_PER_RAD = 180.0 / math.pi
# An eigenvalue omega^2 counts as real when its imaginary part is this small relative to it:
# the non-symmetric discretisation moves real eigenvalues off the real axis by round-off only.
_REAL_TOLERANCE = 1e-6


def _lag_pitch(flap_rotation: np.ndarray, sweep: float) -> np.ndarray:
    """(N,) [-]: the streamwise pitch [rad] per unit lag rotation psi [rad] of sections bent by
    `flap_rotation` beta (N,) [rad] on an axis swept by `sweep` [rad]: a_z, the deformed axis's
    normal component in the y-z plane, as the lattice turns its sections
    (`solver.model.geometry.lattice`; sin(beta) unswept). A section yawed in a plane tilted by
    the bending meets the stream at an angle: the dihedral effect, local."""
    beta = np.asarray(flap_rotation, dtype=float)
    return np.sin(beta) / np.hypot(np.cos(beta) * math.cos(sweep), np.sin(beta))


def _outboard(strip_values: np.ndarray) -> np.ndarray:
    """(N-1, c) per strip -> (N, c): row i sums strips j >= i (zero at the tip)."""
    sums = np.cumsum(strip_values[::-1], axis=0)[::-1]
    return np.vstack([sums, np.zeros((1, strip_values.shape[1]))])


@dataclass(frozen=True, eq=False)
class Structure:
    """The cantilever of one wing with its mass, as matrices on the degrees of freedom w.

    wing: the wing; arc: (N,) [m] stations' distance from the root along the EA;
    stiffness: K (n, n), n = 2 (N - 1), 3 (N - 1) with lag; mass: M (n, n) (module docstring);
    kinetic_mass: (n, n) symmetric, w' . kinetic_mass w' / 2 is the kinetic energy [J];
    states: Z (3N, n), the model's structural unknowns z = (u [m], u' [-], phi [deg]) of w
    ((5N, n) with lag: v [m], psi [rad] after them);
    rows_to_strip_loads: (n, n), the equivalent strip loads of load rows (as the residual's
    bending and torsion rows: dimensionless and in degrees), `strip_loads_of`;
    couple_to_strip_loads: (n, N - 1), the equivalent strip loads of a bending couple [N m]
    about the axis normal to the EA on each strip (a streamwise moment on a swept wing has one);
    lag: whether the beam bends in the wing's plane (w ends with v); lag_couple_to_strip_loads:
    (n, N - 1) with lag, the equivalent strip loads of an in-plane couple [N m] about the normal
    n on each strip (None without lag); flap_rotation: (N,) [rad] with lag, the bent state's
    bending rotation beta the structure vibrates about (None: the jig's, zero).
    """

    wing: Wing
    arc: np.ndarray
    stiffness: np.ndarray
    mass: np.ndarray
    kinetic_mass: np.ndarray
    states: np.ndarray
    rows_to_strip_loads: np.ndarray
    couple_to_strip_loads: np.ndarray
    lag: bool = False
    lag_couple_to_strip_loads: np.ndarray | None = None
    flap_rotation: np.ndarray | None = None

    @property
    def n_strips(self) -> int:
        return self.wing.n_stations - 1

    @property
    def n_dof(self) -> int:
        return (3 if self.lag else 2) * self.n_strips

    def strip_loads_of(self, load_rows: np.ndarray) -> np.ndarray:
        """(n, c) equivalent strip loads (F_j [N], tau_j [N m]) of load rows (2(N-1), c) in the
        residual's units: the strip loads whose bending and torsion rows these are."""
        return self.rows_to_strip_loads @ load_rows

    @cached_property
    def section_motion(self) -> tuple[np.ndarray, np.ndarray]:
        """(N, n) each: the stations' heave [m] and streamwise pitch [rad] of w (the flow's
        twist phi cos(sweep) - u' sin(sweep), as the static model turns its sections; about a
        bent state with lag, plus a_z psi: `_lag_pitch`)."""
        n = self.wing.n_stations
        z = self.states
        sweep = self.wing.sweep * DEG
        heave = z[:n]
        pitch = math.cos(sweep) * DEG * z[2 * n : 3 * n] - math.sin(sweep) * z[n : 2 * n]
        if self.lag and self.flap_rotation is not None:
            pitch = pitch + _lag_pitch(self.flap_rotation, sweep)[:, None] * z[4 * n : 5 * n]
        return heave, pitch

    def strip_points_motion(self, place: np.ndarray) -> np.ndarray:
        """(N - 1, k, n) [m] per unit w: the vertical displacement of the points at chord
        fractions `place` (k,) of each strip (the mean of its two stations' sections, each turned
        about the elastic axis by its streamwise pitch, `section_motion`)."""
        heave, pitch = self.section_motion
        wing = self.wing
        aft = (place[None, :] - wing.elastic_axis[:, None]) * wing.chord[:, None]  # (N, k) [m]
        station = heave[:, None, :] - aft[:, :, None] * pitch[:, None, :]  # (N, k, n)
        return (station[:-1] + station[1:]) / 2

    def point_loads(self, points: np.ndarray, forces: np.ndarray, strips: np.ndarray) -> np.ndarray:
        """(n, P) the equivalent strip loads of the forces (P, 3) [N] at the points (P, 3) [m],
        both in geometry axes (the lattice's: a dihedral wing's plane turned about x), each on
        the strip `strips` (P,) holds: `wing_plane_loads` of their components in the wing's
        frame (`solver.model.geometry.in_wing_plane`), so that only the force normal to the
        wing's plane bends the beam, as in the static model."""
        return self.wing_plane_loads(
            np.array(in_wing_plane(points.T, self.wing)).T,
            np.array(in_wing_plane(forces.T, self.wing)).T,
            strips,
        )

    def wing_plane_loads(
        self, points: np.ndarray, forces: np.ndarray, strips: np.ndarray
    ) -> np.ndarray:
        """(n, P) the equivalent strip loads of the forces (P, 3) [N] at the points (P, 3) [m],
        both in the wing's frame (x, y in its plane, z normal to it), each on the strip
        `strips` (P,) holds, taken as the static model takes its panels'
        (`solver.model.residual`): the normal force bends the beam about the elastic axis from
        where it acts (a force at the strip's midpoint and a bending couple), the moment about
        the undeformed elastic axis twists it; with lag, the in-plane force across the axis
        (along e_c) bends it in the wing's plane the same way."""
        m, count = self.n_strips, points.shape[0]
        sweep = self.wing.sweep * DEG
        axis = np.array([math.sin(sweep), math.cos(sweep), 0.0])  # e_s
        midpoint = (self.arc[1:] + self.arc[:-1]) / 2
        columns = np.arange(count)
        loads = np.zeros((self.n_dof, count))
        loads[strips, columns] = forces[:, 2]
        loads[m + strips, columns] = np.cross(points, forces) @ axis
        arm = points @ axis - midpoint[strips]
        loads = loads + self.couple_to_strip_loads[:, strips] * (forces[:, 2] * arm)
        if self.lag_couple_to_strip_loads is not None:  # with lag
            across = forces @ np.array([math.cos(sweep), -math.sin(sweep), 0.0])  # F . e_c
            loads[2 * m + strips, columns] += across
            # (arm e_s) x (F_c e_c) = -arm F_c n: the in-plane couple about the normal.
            couples = self.lag_couple_to_strip_loads[:, strips]
            loads = loads + couples * (-across * arm)
        return loads

    @cached_property
    def modes(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(omega^2 (n,) ascending [rad^2/s^2], right eigenvectors (n, n), left eigenvectors
        (n, n)) of K v = omega^2 M v, the left ones scaled so that left.T M right = I."""
        values, left, right = scipy.linalg.eig(self.stiffness, self.mass, left=True, right=True)
        if not np.all(np.abs(values.imag) <= _REAL_TOLERANCE * np.abs(values)) or not np.all(
            values.real > 0
        ):
            raise ConvergenceError(
                0.0, 0, math.nan, "the structure's eigenvalues are not real and positive"
            )
        order = np.argsort(values.real)
        omega2 = values.real[order]
        right, left = right[:, order].real, left[:, order].real
        scale = np.einsum("ij,ik,kj->j", left, self.mass, right)
        return omega2, right, left / scale


def structure(
    wing: Wing,
    mass: MassModel | None = None,
    rows: np.ndarray | None = None,
    in_plane_bending_stiffness: np.ndarray | None = None,
    strip_load_rows: np.ndarray | None = None,
    flap_rotation: np.ndarray | None = None,
    station_load_rows: np.ndarray | None = None,
) -> Structure:
    """The cantilever of `wing` with `mass` (`Structure`); `rows` (3N, 3N), the structure rows'
    Jacobian to take instead of the linear beam's constant one (the geometrically exact beam's
    tangent about a bent state, `solver.model.exact_beam`); `in_plane_bending_stiffness` (N,)
    [N m^2], EI_lag: the beam bends in the wing's plane too (module docstring; `rows` then
    (5N, 5N)); `strip_load_rows` (n, n), the load rows of unit strip loads to take instead of
    the jig's (about a bent state, `solver.model.lag_beam.bent_strip_load_rows`);
    `station_load_rows` (N, n, 3) likewise each station's rows of a unit force along n, a
    unit torque and a unit force along e_c, a concentrated mass's inertial loads (about a bent
    state, `solver.model.lag_beam.bent_station_load_rows`: a mass raised above the stations
    inboard twists them as it swings fore and aft; None: the jig's);
    `flap_rotation` (N,) [rad], with lag, the bending rotation beta of
    that state: a lag rotation psi turns a bent section about its own tangent too (t . n =
    sin(beta)), so the sections' and the masses' rotary inertia is of phi + sin(beta) psi
    (R = R_n(psi) R_ec(beta) R_es(phi)'s angular velocity along t), and the flow's pitch is
    `Structure.section_motion`'s.

    Raises `InvalidInput` without a mass model (vibration needs one) or with sections that
    have no mass or no inertia."""
    mass = mass if mass is not None else wing.mass
    if mass is None:
        raise InvalidInput(
            "wing.mass",
            "vibration and flutter need the wing's mass: mass per unit length, centre of "
            "gravity and inertia per station",
        )
    if mass.mass_per_length.shape[0] != wing.n_stations:
        raise InvalidInput(
            "wing.mass", f"has {mass.mass_per_length.shape[0]} stations but y has {wing.n_stations}"
        )
    sweep = wing.sweep * DEG
    arc = wing.y / math.cos(sweep)
    beam = _Beam(
        arc,
        wing.bending_stiffness,
        wing.torsional_stiffness,
        wing.bending_torsion_coupling,
        rows,
        in_plane_bending_stiffness,
    )
    lag = in_plane_bending_stiffness is not None
    blocks = 3 if lag else 2
    inertia = section_inertia(mass, wing.chord, wing.elastic_axis, wing.sweep, wing.spar)
    strips = _strip_inertia(arc, inertia.mass, inertia.static_moment, inertia.inertia, lag)
    m = wing.n_stations - 1
    strip_rows = beam.strip_load_rows() if strip_load_rows is None else strip_load_rows
    flexibility = beam.flexibility()  # w per unit load row
    stiffness = np.linalg.inv(flexibility @ strip_rows)
    rows_to_strip_loads = np.linalg.inv(strip_rows)
    # Strips move as the mean of their two stations (the root's stays put).
    mean = np.zeros((m, m))
    mean[np.arange(m), np.arange(m)] = 0.5
    mean[np.arange(1, m), np.arange(m - 1)] = 0.5
    strip_motion = np.kron(np.eye(blocks), mean)
    states = beam.states(flexibility)
    turn = None  # (N, n) [rad] the sections' turn about their tangents by the lag, of w
    if lag and flap_rotation is not None:
        n = wing.n_stations
        turn = np.sin(np.asarray(flap_rotation, dtype=float))[:, None] * states[4 * n : 5 * n]
        strip_motion[m : 2 * m] += (turn[:-1] + turn[1:]) / 2
    mass_matrix = strips @ strip_motion
    kinetic = strip_motion.T @ strips @ strip_motion
    for item in mass.concentrated:
        if item.station == 0:
            continue  # the root is clamped: the mass never moves
        block = np.zeros((blocks, blocks))
        block[:2, :2] = [
            [item.mass, -item.mass * item.offset],
            [-item.mass * item.offset, item.inertia + item.mass * item.offset**2],
        ]
        if lag:
            block[2, 2] = item.mass  # moving in the wing's plane, coupled with nothing
        motion = np.zeros((blocks, blocks * m))
        for k in range(blocks):
            motion[k, k * m + item.station - 1] = 1.0
        if turn is not None:
            motion[1] += turn[item.station]
        at_station = (
            beam.station_load_rows(item.station)
            if station_load_rows is None
            else station_load_rows[item.station]
        )
        mass_matrix = mass_matrix + rows_to_strip_loads @ at_station @ (block @ motion)
        kinetic = kinetic + motion.T @ block @ motion
    lag_couples = rows_to_strip_loads @ beam.lag_couple_load_rows() if lag else None
    return Structure(
        wing=wing,
        arc=arc,
        stiffness=stiffness,
        mass=mass_matrix,
        kinetic_mass=kinetic,
        states=states,
        rows_to_strip_loads=rows_to_strip_loads,
        couple_to_strip_loads=rows_to_strip_loads @ beam.couple_load_rows(),
        lag=lag,
        lag_couple_to_strip_loads=lag_couples,
        flap_rotation=None if flap_rotation is None else np.asarray(flap_rotation, dtype=float),
    )


def _strip_inertia(
    arc: np.ndarray,
    mass: np.ndarray,
    static_moment: np.ndarray,
    inertia: np.ndarray,
    lag: bool = False,
) -> np.ndarray:
    """(n, n) strip inertia: (F, tau) = -this (u'', phi'') of the strips' midpoints (and F_c =
    -m v'' with lag); mass, static moment and inertia integrated over each strip (trapezoidal
    rule)."""
    h = np.diff(arc)

    def integral(per_length: np.ndarray) -> np.ndarray:
        return np.diag(h * (per_length[1:] + per_length[:-1]) / 2)

    moment = integral(static_moment)
    # Heave up with a centre of gravity d aft: the section's points move u - x phi, so the
    # kinetic energy is (m u'^2 - 2 S u' phi' + I phi'^2) / 2.
    blocks = np.block([[integral(mass), -moment], [-moment, integral(inertia)]])
    if not lag:
        return blocks
    # In the wing's plane every point of the section moves v (the twist moves the centre of
    # gravity across the plane at second order only).
    return scipy.linalg.block_diag(blocks, integral(mass))


class _Beam:
    """The static model's beam rows as matrices (`solver.model.residual._Beam` and
    `_structure_rows`): internal loads, load rows, deformation; with an in-plane bending
    stiffness, the lag rows after them (module docstring)."""

    def __init__(
        self,
        arc: np.ndarray,
        bending: np.ndarray,
        torsion: np.ndarray,
        coupling: np.ndarray | None = None,
        rows: np.ndarray | None = None,
        lag: np.ndarray | None = None,
    ) -> None:
        self.arc, self.h = arc, np.diff(arc)
        self.rows = rows
        coupling = np.zeros_like(bending) if coupling is None else coupling
        self.stiffness = (bending, torsion, coupling)
        self.torsion_compliance, self.cross = section_compliance(bending, torsion, coupling)[1:]
        self.lag = None if lag is None else np.asarray(lag, dtype=float)
        self.n = arc.shape[0]
        self.blocks = 2 if self.lag is None else 3  # load rows per segment

    def load_rows(
        self, moment: np.ndarray, torque: np.ndarray, lag_moment: np.ndarray | None = None
    ) -> np.ndarray:
        """(2(N-1), c) the bending and torsion rows' load terms of station moments and torques
        (N, c): -h_i/2 (M_i/EI_i + M_{i+1}/EI_{i+1}) and the same of T/GJ in degrees, with the
        bending-torsion coupling's (`solver.model.beam.coupled_trapezoid`); with lag
        (3(N-1), c), the lag rows' of the in-plane moments about n `lag_moment` (N, c) after
        them (default none)."""
        rows = np.vstack(coupled_trapezoid(self.h, moment, torque, self.stiffness))
        if self.lag is None:
            return rows
        if lag_moment is None:
            return np.vstack([rows, np.zeros((self.n - 1, rows.shape[1]))])
        per = lag_moment / self.lag[:, None]
        return np.vstack([rows, -self.h[:, None] / 2 * (per[:-1] + per[1:])])

    def strip_load_rows(self) -> np.ndarray:
        """(2(N-1), 2(N-1)) load rows of unit strip loads: a vertical force at each strip's
        midpoint on the EA (the first N - 1 columns), a torque about the EA on each strip; with
        lag (3(N-1), 3(N-1)), an in-plane force across the EA (along e_c) at each midpoint
        after them."""
        m = self.n - 1
        midpoint = (self.arc[1:] + self.arc[:-1]) / 2
        forces = np.eye(m)
        moment = _outboard(forces * midpoint[:, None]) - self.arc[:, None] * _outboard(forces)
        torque = _outboard(np.eye(m))
        zeros = np.zeros((self.n, m))
        columns = [self.load_rows(moment, zeros), self.load_rows(zeros, torque)]
        if self.lag is not None:
            # (r_p - r_i) x F_c e_c = -(s_p - s_i) F_c n: an aft force's moment about n is the
            # negative of an upward force's about e_c.
            columns.append(self.load_rows(zeros, zeros, -moment))
        return np.hstack(columns)

    def couple_load_rows(self) -> np.ndarray:
        """(2(N-1), N-1) load rows of a unit bending couple on each strip (3(N-1) rows with
        lag)."""
        m = self.n - 1
        return self.load_rows(_outboard(np.eye(m)), np.zeros((self.n, m)))

    def lag_couple_load_rows(self) -> np.ndarray:
        """(3(N-1), N-1) load rows of a unit in-plane couple about the normal n on each strip."""
        m = self.n - 1
        zeros = np.zeros((self.n, m))
        return self.load_rows(zeros, zeros, _outboard(np.eye(m)))

    def station_load_rows(self, station: int) -> np.ndarray:
        """(2(N-1), 2) load rows of a unit vertical force and a unit torque at `station` (with
        lag (3(N-1), 3), and a unit in-plane force across the EA).

        The force's moment is continuous there. The torque is not: it acts on the segments
        inboard of the station only (the trapezoid of each segment takes the torque on its own
        side of the station), which keeps the rows exact for a uniform torsional stiffness."""
        moment = np.maximum(self.arc[station] - self.arc, 0.0)[:, None]
        zero = np.zeros((self.n, 1))
        force_rows = self.load_rows(moment, zero)
        inboard = np.arange(self.n - 1) < station
        per = 1.0 / self.torsion_compliance
        torque_rows = np.zeros((self.n - 1, 1))
        torque_rows[inboard, 0] = -DEG_PER_RAD * self.h[inboard] / 2 * (per[:-1] + per[1:])[inboard]
        # The coupling's bending of the same torque, on the same segments (zero when uncoupled).
        bending_rows = np.zeros((self.n - 1, 1))
        cross = self.cross
        bending_rows[inboard, 0] = self.h[inboard] / 2 * (cross[:-1] + cross[1:])[inboard]
        if self.lag is None:
            return np.hstack([force_rows, np.vstack([bending_rows, torque_rows])])
        lag_rows = np.zeros((self.n - 1, 1))
        torque_column = np.vstack([bending_rows, torque_rows, lag_rows])
        return np.hstack([force_rows, torque_column, self.load_rows(zero, zero, -moment)])

    def structure_rows(self) -> np.ndarray:
        """(3N, 3N) A: the structure rows' load-free part on z = (u, u', phi [deg]) (the
        tangent given, if one was); with lag (5N, 5N), z = (u, u', phi [deg], v, psi), the lag
        clamps, kinematics and bending rows after the others."""
        if self.rows is not None:
            return np.array(self.rows, dtype=float)
        n, m, h = self.n, self.n - 1, self.h
        size = (3 if self.lag is None else 5) * n
        a = np.zeros((size, size))
        a[0, 0] = a[1, n] = a[2, 2 * n] = 1.0  # clamps
        i = np.arange(m)
        rows = 3 + i
        a[rows, i + 1], a[rows, i] = 1.0, -1.0
        a[rows, n + i], a[rows, n + i + 1] = -h / 2, -h / 2
        for block in (1, 2):  # slope and twist differences
            rows = 3 + block * m + i
            a[rows, block * n + i + 1], a[rows, block * n + i] = 1.0, -1.0
        if self.lag is not None:
            v, psi, first = 3 * n, 4 * n, 3 * n
            a[first, v] = a[first + 1, psi] = 1.0  # lag clamps
            # v' = -psi (a positive psi turns the axis forward, toward -e_c).
            rows = first + 2 + i
            a[rows, v + i + 1], a[rows, v + i] = 1.0, -1.0
            a[rows, psi + i], a[rows, psi + i + 1] = h / 2, h / 2
            rows = first + 2 + m + i
            a[rows, psi + i + 1], a[rows, psi + i] = 1.0, -1.0
        return a

    def _load_row_indices(self) -> np.ndarray:
        """(blocks (N-1),) the rows of A whose load terms the load rows are: bending, torsion
        (and lag bending)."""
        m = self.n - 1
        indices = 3 + m + np.arange(2 * m)
        if self.lag is None:
            return indices
        return np.concatenate([indices, 3 * self.n + 2 + m + np.arange(m)])

    def response(self) -> np.ndarray:
        """(3N, 2(N-1)) P = A^{-1} E: z = -P l for load rows l (`solver.numerics.stability`'s);
        (5N, 3(N-1)) with lag."""
        indices = self._load_row_indices()
        a = self.structure_rows()
        selector = np.zeros((a.shape[0], indices.shape[0]))
        selector[indices, np.arange(indices.shape[0])] = 1.0
        return np.linalg.solve(a, selector)

    def flexibility(self) -> np.ndarray:
        """(n, n): w of unit load rows, -S P (S picks u, phi [rad] (and v) off the root)."""
        m, n = self.n - 1, self.n
        response = self.response()
        pick = [np.arange(1, n), np.arange(2 * n + 1, 3 * n)]
        if self.lag is not None:
            pick.append(np.arange(3 * n + 1, 4 * n))
        flexibility = -response[np.concatenate(pick)]
        flexibility[m : 2 * m] *= DEG
        return flexibility

    def states(self, flexibility: np.ndarray) -> np.ndarray:
        """(3N, n) Z ((5N, n) with lag): the unknowns z of w, -P F^{-1}."""
        return -self.response() @ np.linalg.inv(flexibility)


def natural_modes(
    wing: Wing, mass: MassModel | None = None, count: int | None = None
) -> NaturalModes:
    """The lowest `count` natural modes of `wing` with `mass` in vacuum (default: all of them,
    2 (N - 1), 3 (N - 1) when the wing bends in its plane, `Wing.in_plane_bending_stiffness`),
    clamped at the root (about the jig, where the geometrically exact beam is the linear one).

    Each shape is scaled so that the largest vertical displacement of a leading or a trailing
    edge (or, with lag, the axis's in-plane displacement if larger) is 1 m, and that
    displacement is upward (aft). Raises `InvalidInput` without a mass model."""
    beam = structure(wing, mass, in_plane_bending_stiffness=wing.in_plane_bending_stiffness)
    if count is None:
        count = beam.n_dof
    if not (isinstance(count, int) and 1 <= count <= beam.n_dof):
        raise InvalidInput("modes", f"must be a whole number from 1 to {beam.n_dof}")
    omega2, right, _ = beam.modes
    shapes = [mode_shape(beam, right[:, i], math.sqrt(omega2[i])) for i in range(count)]
    return NaturalModes(y=wing.y, modes=shapes)


def largest_edge_displacement(beam: Structure, vector: np.ndarray) -> float:
    """[m] the vertical displacement of a leading or trailing edge of the degrees of freedom
    `vector` (n,) largest in magnitude (signed); with lag, or the in-plane displacement of the
    elastic axis if that is larger (an in-plane mode has no vertical one)."""
    edges = _edges(beam, vector)
    if beam.lag:
        edges = np.concatenate([edges, _lag(beam, vector)])
    return float(edges[np.argmax(np.abs(edges))])


def _edges(beam: Structure, vector: np.ndarray) -> np.ndarray:
    """(2N,) [m] the leading edges' and trailing edges' vertical displacements of `vector`."""
    wing = beam.wing
    z = beam.states @ vector
    n = wing.n_stations
    heave, slope, axis_twist = z[:n], z[n : 2 * n], z[2 * n : 3 * n]
    sweep = wing.sweep * DEG
    twist = axis_twist * math.cos(sweep) - np.degrees(slope) * math.sin(sweep)
    ahead = wing.elastic_axis * wing.chord
    return np.concatenate([heave + ahead * twist * DEG, heave - (wing.chord - ahead) * twist * DEG])


def _lag(beam: Structure, vector: np.ndarray) -> np.ndarray:
    """(N,) [m] the elastic axis's in-plane displacement v (along e_c, aft) of `vector`."""
    n = beam.wing.n_stations
    return (beam.states @ vector)[3 * n : 4 * n]


def mode_shape(beam: Structure, vector: np.ndarray, frequency: float) -> ModeShape:
    """The shape of the degrees of freedom `vector` (n,), at `frequency` [rad/s]: scaled as in
    `natural_modes`, with its bending share (and, with lag, its in-plane displacement and
    share)."""
    wing = beam.wing
    z = beam.states @ vector
    n = wing.n_stations
    heave, slope, axis_twist = z[:n], z[n : 2 * n], z[2 * n : 3 * n]
    sweep = wing.sweep * DEG
    twist = axis_twist * math.cos(sweep) - np.degrees(slope) * math.sin(sweep)
    scale = 1.0 / largest_edge_displacement(beam, vector)
    m, kinetic = beam.n_strips, beam.kinetic_mass
    heave_energy = vector[:m] @ kinetic[:m, :m] @ vector[:m]  # m u'^2 (times omega^2 / 2)
    twist_energy = vector[m : 2 * m] @ kinetic[m : 2 * m, m : 2 * m] @ vector[m : 2 * m]
    if not beam.lag:
        return ModeShape(
            frequency=frequency,
            heave=heave * scale,
            twist=twist * scale,
            axis_twist=axis_twist * scale,
            bending_share=float(heave_energy / (heave_energy + twist_energy)),
        )
    lag_energy = vector[2 * m :] @ kinetic[2 * m :, 2 * m :] @ vector[2 * m :]  # m v'^2
    total = heave_energy + twist_energy + lag_energy
    return ModeShape(
        frequency=frequency,
        heave=heave * scale,
        twist=twist * scale,
        axis_twist=axis_twist * scale,
        bending_share=float(heave_energy / total),
        lag=_lag(beam, vector) * scale,
        lag_share=float(lag_energy / total),
    )
