"""The gust model with the unsteady lattice: the same aircraft as `solver.gusts.model` (the
rigid plunge with W / 2g on the half wing, or clamped; the wing's lowest natural modes), its
aerodynamics the unsteady vortex lattice's in the frequency domain
(`solver.dynamics.lattice_loads`), as MSC Nastran's SOL 146 builds its dynamic aeroelastic
response (MSC Nastran Aeroelastic Analysis User's Guide, ch. 7: modal frequency response with
the generalised aerodynamic forces Q_hh of the modes and Q_hj of the gust's downwash,
interpolated between the reduced frequencies of its MKAERO lists).

Unknowns at each frequency omega (s = i omega, kappa = omega / V, q the dynamic pressure): the
modal coordinates c (r,) and, free, the plunge velocity v = z' (the plunge z itself has a pole
at s = 0, a free aircraft riding a steady updraft out at v = w_g; its velocity has none: a
free aircraft's plunge is damped by its lift, and at omega = 0 its equation says that the
gust adds no lift). With the equations of `solver.gusts.model` in the frequency domain,

    (Omega^2 - omega^2) c + i omega L^T M_z v = L^T f,
    i omega (W / 2 g) v - omega^2 b_z . R c   = sum of the strips' vertical forces f,
    f = q [K_s + A0 + i kappa A1 - kappa^2 A2] R c + (q / V) Z(kappa) v + (q / V) G(omega) w_g,

R, L the modes (L^T M R = I), M_z and b_z the plunge's inertia (`solver.gusts.model`), A0, A1,
A2 the lattice's loads of deformation and motion grouped by powers of s / V, Z the loads of a
unit plunge velocity (normalwash -n_z / V on every panel), G those of a unit vertical gust
velocity (normalwash n_z e^{-i kappa (x_p - x_0)} / V: each panel meets it at its own delay,
time 0 when it reaches the foremost leading edge x_0). n_z is the static model's own
derivative of each panel's tangency in alpha (a bent wing's dihedral included), so at omega = 0
the gust's and the plunge's loads are the static lattice's d(load)/d(alpha) exactly.

Interpolation (as Nastran's Q_hj): the tables are computed at `_NODES` reduced frequencies
k = kappa b (b half the mean chord) from 0 to the largest the response needs, evenly spaced in
u = k / (k + k_max / 4) (`solver.dynamics.reduced.reduced_frequency_nodes`), plus the
infinite-frequency limit, and interpolated by cubic splines in u. The gust's loads are
tabulated strip by strip with the phase of the strip's mid-chord taken out (each strip's is
then Sears' smooth function, its delay e^{-i omega (x_j - x_0) / V} applied exactly at each
frequency): a swept wing's outer strips, met later, need no more nodes. Their
infinite-frequency limit is zero (Sears' function vanishes there: a gust shorter than the
panels lifts nothing).

Outputs per unit gust velocity (`GustModel.output_slices`): each station's shear, bending
moment and torque by force summation (aerodynamic f minus inertial -omega^2 (M R c) + i omega
M_z v), the load factor increment 2 sum(f_z) / W, the tip's elastic heave and twist.

Stability: no state matrix to take eigenvalues of. The argument principle instead: det D(i
omega) of the dynamic matrix above (polynomial of degree d = 2 r (+ 1 free) in s at large
|s|, analytic in the right half-plane, the aerodynamics being causal) turns by (d / 2 - p) pi
as omega goes from 0 to infinity, p its roots in the right half-plane: a turn short by pi or
more is flutter or divergence (`check_stable`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np
import scipy.interpolate

from solver.dynamics.aerodynamic_forces import MAX_REDUCED_FREQUENCY
from solver.dynamics.lattice_loads import lattice_loads
from solver.dynamics.modes import structure
from solver.dynamics.reduced import reduced_frequency_nodes
from solver.errors import DynamicInstability, InvalidInput, numerical_failures_as
from solver.gusts.model import _plunge_inertia, _station_loads
from solver.inputs.atmosphere import STANDARD_GRAVITY
from solver.inputs.flight import FlightCondition, dynamic_pressure
from solver.inputs.options import SolverOptions
from solver.inputs.wing import Wing
from solver.model.geometry import DEG
from solver.results.equilibrium import Equilibrium
from solver.statics.solve import solve
from solver.statics.system import CoupledSystem
from solver.unsteady_lattice.circulation import harmonic_lattice
from solver.unsteady_lattice.panels import panels
from solver.unsteady_lattice.wake import shed_wake

__all__ = ["LatticeGustModel", "lattice_gust_model"]

DEG_PER_RAD = 180.0 / math.pi
# Reduced frequencies the lattice is solved at (and the infinite-frequency limit): the
# transfer functions converge to 1e-3 of the peak loads with 16 (tests/solver/gusts/
# test_frequency_response.py); each one is one lattice solve.
_NODES = 16
# The largest reduced frequency tabulated: at least this (flutter's default), at most the
# lattice's limit.
_MIN_TOP = 2.0
# Stability: the determinant's phase is followed on this many frequencies per decade.
_PER_DECADE = 600


@dataclass(frozen=True, eq=False)
class LatticeGustModel:
    """The frequency-domain gust model (module docstring): the same fields as `GustModel` that
    the analysis reads (wing, velocity [m/s], density [kg/m^3], weight [N], clamped,
    frequencies (r,) [rad/s] in vacuum, semichord (m,) [m], delay (m,) [s] each strip's
    leading edge's, lift_slope [1/rad], area [m^2], equilibrium), the chordwise panels, the
    modes asked for but dropped (past the lattice's largest reduced frequency), and the
    tables.

    Tables, at the reduced frequencies `reduced` (K,) (the last infinite), rows
    (r [+1 free] generalised; 3N station loads; 1 total vertical force) per unit q:
    modal (3, K, rows, r) A0 + K_s, A1, A2 on the modes; plunge (2, K, rows) Z's parts
    (K_g g, P g of a normalwash -n_z) per unit plunge velocity / V; gust (K, rows, m) each
    strip's loads per unit gust velocity / V, its mid-chord's phase out; strip_phase (m,) [m]
    each strip's mid-chord less the foremost leading edge (x_j - x_0). Structure: omega2 (r,),
    plunge_inertia (r,) L^T M_z, elastic_vertical (r,) b_z . R, station_inertia (3N, r)
    stations of M R, station_plunge (3N,) stations of M_z, tip (2, r) heave [m] and twist
    [deg] per c."""

    wing: Wing
    velocity: float
    density: float
    weight: float
    clamped: bool
    frequencies: np.ndarray
    semichord: np.ndarray
    delay: np.ndarray
    lift_slope: float
    area: float
    equilibrium: Equilibrium
    chordwise: int
    dropped: int
    reference_semichord: float
    reduced: np.ndarray
    modal: np.ndarray
    plunge: np.ndarray
    gust: np.ndarray
    strip_phase: np.ndarray
    omega2: np.ndarray
    plunge_inertia: np.ndarray
    elastic_vertical: np.ndarray
    station_inertia: np.ndarray
    station_plunge: np.ndarray
    tip: np.ndarray

    @property
    def output_slices(self) -> dict[str, slice | int]:
        n = self.wing.n_stations
        return {
            "shear": slice(0, n),
            "bending_moment": slice(n, 2 * n),
            "torque": slice(2 * n, 3 * n),
            "load_factor": 3 * n,
            "tip_heave": 3 * n + 1,
            "tip_twist": 3 * n + 2,
        }

    @property
    def top_frequency(self) -> float:
        """[rad/s] the largest frequency tabulated (finite)."""
        return float(self.reduced[-2]) * self.velocity / self.reference_semichord

    @cached_property
    def _scale(self) -> float:
        return float(self.reduced[-2]) / 4

    def _u(self, omega: np.ndarray) -> np.ndarray:
        k = np.abs(omega) * self.reference_semichord / self.velocity
        return k / (k + self._scale)

    @cached_property
    def _splines(self) -> tuple[scipy.interpolate.CubicSpline, ...]:
        u = np.r_[self.reduced[:-1] / (self.reduced[:-1] + self._scale), 1.0]
        return (
            scipy.interpolate.CubicSpline(u, self.modal, axis=1),
            scipy.interpolate.CubicSpline(u, self.plunge, axis=1),
            scipy.interpolate.CubicSpline(u, self.gust, axis=0),
        )

    def _parts(self, omega: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The dynamic matrix D (F, p, p) and the loads' rows of the unknowns (F, rows, p) per
        unit q at frequencies `omega` (F,) [rad/s] >= 0 (unknowns c and, free, v)."""
        q = dynamic_pressure(self.density, self.velocity)
        v = self.velocity
        kappa = omega / v
        u = self._u(omega)
        a0, a1, a2 = self._splines[0](u)  # (F, rows, r)
        ik = (1j * kappa)[:, None, None]
        loads_c = a0 + ik * a1 + ik * ik * a2
        z0, z1 = self._splines[1](u)  # (F, rows)
        loads_v = (z0 + 1j * kappa[:, None] * z1) / v
        r = self.omega2.size
        p = r if self.clamped else r + 1
        loads = np.concatenate([loads_c, loads_v[:, :, None]], axis=2)[:, :, :p]
        w2 = (omega**2)[:, None, None]
        dynamic: np.ndarray = (-q * loads[:, :p, :]).astype(complex)
        dynamic[:, :r, :r] += np.diag(self.omega2)[None] - w2 * np.eye(r)[None]
        if not self.clamped:
            dynamic[:, :r, r] += 1j * omega[:, None] * self.plunge_inertia[None]
            dynamic[:, r, :r] -= (omega**2)[:, None] * self.elastic_vertical[None]
            dynamic[:, r, r] += 1j * omega * self.weight / (2 * STANDARD_GRAVITY)
        return dynamic, loads

    def _gust_loads(self, omega: np.ndarray) -> np.ndarray:
        """(F, rows) complex: the loads of a unit gust velocity [per m/s] per unit q."""
        table = self._splines[2](self._u(omega))  # (F, rows, m)
        phase = np.exp(-1j * np.outer(omega, self.strip_phase) / self.velocity)  # (F, m)
        return np.einsum("frm,fm->fr", table, phase) / self.velocity

    def response(self, omega: np.ndarray) -> np.ndarray:
        """(n_out, F) complex: the outputs per unit gust velocity [per m/s] at frequencies
        `omega` (F,) [rad/s] >= 0, time 0 when the gust reaches the foremost leading edge."""
        omega = np.asarray(omega, dtype=float)
        q = dynamic_pressure(self.density, self.velocity)
        r = self.omega2.size
        p = r if self.clamped else r + 1
        dynamic, loads = self._parts(omega)
        gust = self._gust_loads(omega)  # (F, rows)
        unknowns = np.linalg.solve(dynamic, q * gust[:, :p, None])[:, :, 0]  # (F, p)
        aero = q * (np.einsum("frp,fp->fr", loads[:, p:, :], unknowns) + gust[:, p:])
        n3 = 3 * self.wing.n_stations
        c = unknowns[:, :r]
        stations = aero[:, :n3] + (omega**2)[:, None] * (c @ self.station_inertia.T)
        if not self.clamped:
            stations -= 1j * omega[:, None] * unknowns[:, r : r + 1] * self.station_plunge[None]
        load_factor = 2 * aero[:, n3] / self.weight
        tip = c @ self.tip.T  # (F, 2)
        return np.concatenate([stations, load_factor[:, None], tip], axis=1).T

    def check_stable(self) -> None:
        """Raise `DynamicInstability` if the equations have a root in the right half-plane
        (module docstring): the determinant's phase followed from omega = 0 to well past the
        modes and the tabulated frequencies."""
        r = self.omega2.size
        degree = 2 * r + (0 if self.clamped else 1)
        low = 1e-4 * float(self.frequencies.min())
        high = 1e3 * max(float(self.frequencies.max()), self.top_frequency)
        count = int(_PER_DECADE * math.log10(high / low)) + 1
        omega = np.r_[0.0, np.geomspace(low, high, count)]
        dynamic, _ = self._parts(omega)
        scale = np.abs(np.diagonal(dynamic, axis1=1, axis2=2)).max(axis=1)
        det = np.linalg.det(dynamic / scale[:, None, None])
        turn = float(np.unwrap(np.angle(det))[-1] - np.angle(det[0]))
        right_half = round((degree * math.pi / 2 - turn) / math.pi)
        if right_half <= 0:
            return
        # The growing root: the frozen-aerodynamics root of largest real part near where the
        # determinant is smallest (the root's frequency).
        worst = int(np.argmin(np.abs(det)))
        rate, frequency = self._frozen_root(float(omega[worst]))
        raise DynamicInstability(self.velocity, max(rate, 0.0), frequency)

    def _frozen_root(self, omega: float) -> tuple[float, float]:
        """(growth rate [1/s], frequency [rad/s]) of the root of largest real part with the
        aerodynamics of `omega` frozen (one step of the p-k method)."""
        q = dynamic_pressure(self.density, self.velocity)
        r = self.omega2.size
        p = r if self.clamped else r + 1
        u = self._u(np.array([omega]))
        a0, a1, a2 = (part[0, :p] for part in self._splines[0](u))
        z0, z1 = (part[0, :p] for part in self._splines[1](u))
        v = self.velocity
        stiffness = np.zeros((p, p), dtype=complex)
        damping = np.zeros((p, p), dtype=complex)
        mass = np.zeros((p, p), dtype=complex)
        stiffness[:, :r] = -q * a0
        stiffness[:r, :r] += np.diag(self.omega2)
        damping[:, :r] = -q * a1 / v
        mass[:, :r] = -q * a2 / v**2
        mass[:r, :r] += np.eye(r)
        if not self.clamped:
            # v = s z: the plunge's column in z, its loads Z(kappa) s z / V.
            damping[:, r] = -q * z0 / v
            mass[:, r] = -q * z1 / v**2
            mass[:r, r] += self.plunge_inertia
            mass[r, :r] += self.elastic_vertical
            mass[r, r] += self.weight / (2 * STANDARD_GRAVITY)
        top = np.hstack([np.zeros((p, p)), np.eye(p)])
        bottom = np.linalg.solve(mass, np.hstack([-stiffness, -damping]))
        roots = np.linalg.eigvals(np.vstack([top, bottom]))
        roots = roots[np.abs(roots) > 1e-9 * max(1.0, float(np.abs(roots).max()))]
        best = roots[int(np.argmax(roots.real))]
        return float(best.real), float(abs(best.imag))


def lattice_gust_model(
    wing: Wing,
    flight: FlightCondition,
    options: SolverOptions | None = None,
    modes: int | None = 8,
    clamped: bool = False,
    top_frequency: float | None = None,
    nodes: int = _NODES,
) -> LatticeGustModel:
    """The frequency-domain gust model of `wing` (with its mass) in `flight` with the unsteady
    lattice, linearised about the 1 g trim as `solver.gusts.model.gust_model` is; tabulated up
    to `top_frequency` [rad/s] (default: twice the highest mode kept; at least reduced
    frequency 2, at most the lattice's 10) at `nodes` reduced frequencies and the infinite one.
    Raises as `gust_model`."""
    options = options or SolverOptions()
    if (flight.weight is None and not clamped) or flight.velocity is None:
        raise InvalidInput("flight.weight", "a gust analysis needs the aircraft's weight")
    beam = structure(wing)
    equilibrium = solve(wing, flight, options=options)
    system = CoupledSystem.of(wing, equilibrium.totals.alpha, options)
    evaluation, alpha_terms = system.evaluate_with_alpha(equilibrium.state)
    layout = system.layout
    velocity, density = float(flight.velocity), flight.density
    weight = float(flight.weight or abs(2 * equilibrium.stations.shear[0]) or 1.0)
    m, n_dof = beam.n_strips, beam.n_dof
    r = n_dof if modes is None else min(modes, n_dof)
    omega2, right, left = beam.modes
    reference = wing.mean_chord / 2
    # Modes past the lattice's largest reduced frequency have no aerodynamics it resolves (no
    # wave on the chord of 8 panels; its tables end there): they are left out, said so.
    within = int(
        np.sum(np.sqrt(np.maximum(omega2, 0.0)) * reference / velocity <= MAX_REDUCED_FREQUENCY)
    )
    asked, r = r, max(1, min(r, within))
    basis, project = right[:, :r], left[:, :r].T
    frequencies = np.sqrt(omega2[:r])
    wanted = 2 * float(frequencies.max()) if top_frequency is None else top_frequency
    top = min(max(_MIN_TOP, wanted * reference / velocity), MAX_REDUCED_FREQUENCY)
    reduced = reduced_frequency_nodes(top, nodes)
    kappa = reduced / reference

    # Rows kept of the strip loads: generalised (L^T, and the total vertical force when
    # free), the stations' loads and the total vertical force.
    stations = _station_loads(beam)
    total_force = np.r_[np.ones(m), np.zeros(m)]
    generalised = project if clamped else np.vstack([project, total_force])
    rows = np.vstack([generalised, stations, total_force])

    # The uniform vertical velocity's normalwash per unit w / V on the deformed panels: the
    # static model's derivative of tangency in alpha (per radian), as `gust_model`'s.
    vertical = alpha_terms.r0[layout.tangency_rows] * DEG_PER_RAD
    chordwise = layout.chordwise
    with numerical_failures_as(0.0):
        jig = panels(wing, chordwise)
        loads = lattice_loads(beam, layout, evaluation, jig)
        wake = shed_wake(jig, kappa)
        flow = harmonic_lattice(loads.influence, wake)
    strip = jig.strip
    x = jig.collocation[:, 0]
    leading_x = wing.y * math.tan(wing.sweep * DEG) - wing.elastic_axis * wing.chord
    strip_leading = (leading_x[1:] + leading_x[:-1]) / 2
    trailing_x = leading_x + wing.chord
    strip_middle = (leading_x[1:] + leading_x[:-1] + trailing_x[1:] + trailing_x[:-1]) / 4
    foremost = float(strip_leading.min())
    selector = np.zeros((x.size, m))
    selector[np.arange(x.size), strip] = 1.0

    deformation, motion = loads.deformation @ basis, loads.motion @ basis
    circulation = rows @ loads.circulation_loads
    pressure = rows @ loads.pressure_loads
    geometric = rows @ loads.geometric @ basis
    count = kappa.size
    modal = np.zeros((3, count, rows.shape[0], r), dtype=complex)
    plunge = np.zeros((2, count, rows.shape[0]), dtype=complex)
    gust = np.zeros((count, rows.shape[0], m), dtype=complex)
    for i, value in enumerate(flow.kappa):
        finite = np.isfinite(value)
        local = np.exp(-1j * value * (x - strip_middle[strip])) if finite else np.zeros(x.size)
        wash = (vertical * local)[:, None] * selector  # (M, m) each strip's own gust
        g = flow.circulation(i, np.hstack([deformation, motion, -vertical[:, None], wash]))
        g_def, g_mot, g_plunge, g_gust = g[:, :r], g[:, r : 2 * r], g[:, 2 * r], g[:, 2 * r + 1 :]
        modal[0, i] = geometric + circulation @ g_def
        modal[1, i] = circulation @ g_mot + pressure @ g_def
        modal[2, i] = pressure @ g_mot
        plunge[0, i] = circulation @ g_plunge
        plunge[1, i] = pressure @ g_plunge
        if finite:
            gust[i] = circulation @ g_gust + 1j * value * (pressure @ g_gust)

    assert wing.mass is not None
    rigid_inertia, elastic_vertical = _plunge_inertia(beam)
    heave, pitch = beam.section_motion
    semichord = (wing.chord[1:] + wing.chord[:-1]) / 4
    lift_slope = float(gust[0, -1].real.sum()) / (wing.planform_area / 2)
    return LatticeGustModel(
        wing=wing,
        velocity=velocity,
        density=density,
        weight=weight,
        clamped=clamped,
        frequencies=frequencies,
        semichord=semichord,
        delay=(strip_leading - foremost) / velocity,
        lift_slope=lift_slope,
        area=wing.planform_area / 2,
        equilibrium=equilibrium,
        chordwise=chordwise,
        dropped=asked - r,
        reference_semichord=reference,
        reduced=reduced,
        modal=modal,
        plunge=plunge,
        gust=gust,
        strip_phase=strip_middle - foremost,
        omega2=omega2[:r],
        plunge_inertia=project @ rigid_inertia,
        elastic_vertical=elastic_vertical @ basis,
        station_inertia=stations @ beam.mass @ basis,
        station_plunge=stations @ rigid_inertia,
        tip=np.vstack([heave[-1] @ basis, DEG_PER_RAD * pitch[-1] @ basis]),
    )
