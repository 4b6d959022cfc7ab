"""The gust model: the aircraft's plunge and the wing's elastic modes with unsteady strip
aerodynamics as aerodynamic states, linearised about the trimmed 1 g flight, as one linear
time-invariant system x' = A x + B g, y = C x + D g.

Structure (`solver.dynamics.modes`): the wing's equivalent strip loads f on its degrees of
freedom w = R c, the lowest r natural modes (R right, L left eigenvectors, L^T M R = I), and the
rigid plunge z of the whole aircraft (its mass W / g, half of it on this half wing), the wing
clamped to the fuselage at its root:

    c'' + Omega^2 c + L^T M_z z'' = L^T f,          M_z: the strips' inertia of a unit z''
    (W / 2 g) z'' + b_z . R c''  = sum of the strips' vertical forces,

b_z the vertical inertia force of the wing's elastic accelerations (the wing's mass is part of
W / g: a wing that only plunges moves as the rigid aircraft). Pitch is left out: it needs the
tail, the centre of gravity and the pitch inertia, none of which a wing describes, and Pratt's
K_g, the certification's reference, is of plunge alone (Pratt, NACA TN 2964, 1953). `clamped`
drops the plunge (a wind-tunnel model on its balance).

Aerodynamics (`solver.dynamics.unsteady`, as flutter's "strip" and "lattice"): the static
model's exact Jacobian at the trimmed state gives the quasi-steady circulations of each panel's
normalwash nu (its three-quarter-chord upwash per unit V: the deformation's angle, the motion's
-h'/V, the gust's w_g / V on the deformed panel's normal: the static model's own derivative in
alpha, a bent wing's dihedral included), Gamma = -T_g^{-1} nu (T_g the lattice's influence, or
strip theory's 2D one), and their loads q K_g Gamma on the strips. Lagged in time:

- the motion's normalwash (elastic and plunge) through Wagner's function, R. T. Jones'
  approximation, two states per panel with its strip's semichord (`solver.gusts.indicial`);
- the gust's through Kuessner's, Sears and Sparks' approximation, strip by strip, each strip
  meeting the gust when it reaches its leading edge (a swept wing's outer strips later): the
  input g (m,) is each strip's lagged gust angle, computed outside the state (it is a known
  function of time: `solver.gusts.discrete`; of frequency: `solver.gusts.turbulence`);
- Theodorsen's non-circulatory loads (apparent mass, pitch rate) of the elastic motion and of
  the plunge, at once.

With "lattice" the steady 3D loading (tip loss, induced downwash) is the lattice's, the lag
each strip's two-dimensional one: a quasi-3D model like flutter's `lattice` option (Yates'
modified strip analysis, NACA RM L57L10).

Outputs y (`OUTPUTS`): each station's incremental shear [N], bending moment [N m] and torque
[N m] (force summation: aerodynamic minus inertial strip loads), the load factor increment
Delta n = (lift increment of both halves) / W [-], the tip's elastic heave [m] and streamwise
twist [deg] relative to the root.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from solver.dynamics.modes import Structure, structure
from solver.dynamics.unsteady import UnsteadyAerodynamics, unsteady_aerodynamics
from solver.errors import DynamicInstability, InvalidInput
from solver.gusts.indicial import WAGNER
from solver.inputs.atmosphere import STANDARD_GRAVITY
from solver.inputs.flight import FlightCondition, dynamic_pressure
from solver.inputs.mass import section_inertia
from solver.inputs.options import SolverOptions
from solver.inputs.wing import Wing
from solver.model.geometry import DEG
from solver.results.equilibrium import Equilibrium
from solver.statics.solve import solve
from solver.statics.system import CoupledSystem

__all__ = ["GustModel", "gust_model"]

DEG_PER_RAD = 180.0 / math.pi
# A root grows when its real part exceeds this share of its modulus (round-off stays below).
_GROWING = 1e-9


@dataclass(frozen=True, eq=False)
class GustModel:
    """x' = A x + B g, y = C x + D g (module docstring); g (m,) the strips' Kuessner-lagged
    gust angles [rad]; y: shear (N,), bending moment (N,), torque (N,), Delta n, tip heave,
    tip twist (`output_slices`).

    wing, velocity [m/s], density [kg/m^3], weight [N] (the aircraft's), clamped; A (S, S),
    B (S, m), C (3N + 3, S), D (3N + 3, m); frequencies (r,) [rad/s] the modes' in vacuum;
    semichord (m,) [m] and delay (m,) [s] of each strip (when the gust reaches its leading
    edge, the first at 0); lift_slope [1/rad] of the half wing's lift against a uniform angle
    (its quasi-steady gust lift, over its area); area [m^2] the half wing's; equilibrium the
    1 g trimmed state linearised about.
    """

    wing: Wing
    velocity: float
    density: float
    weight: float
    clamped: bool
    a: np.ndarray
    b: np.ndarray
    c: np.ndarray
    d: np.ndarray
    frequencies: np.ndarray
    semichord: np.ndarray
    delay: np.ndarray
    lift_slope: float
    area: float
    equilibrium: Equilibrium

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

    @cached_property
    def eigen(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(roots (S,) [1/s], eigenvectors V (S, S), V^{-1}) of A."""
        roots, vectors = np.linalg.eig(self.a)
        return roots, vectors, np.linalg.inv(vectors)

    def check_stable(self) -> None:
        """Raise `DynamicInstability` if a root of A grows."""
        roots = self.eigen[0]
        worst = int(np.argmax(roots.real))
        if roots[worst].real > _GROWING * max(abs(roots[worst]), 1.0):
            raise DynamicInstability(
                self.velocity, float(roots[worst].real), float(abs(roots[worst].imag))
            )


def gust_model(
    wing: Wing,
    flight: FlightCondition,
    options: SolverOptions | None = None,
    modes: int | None = 8,
    clamped: bool = False,
) -> GustModel:
    """The gust model of `wing` (with its mass) in `flight` (trimmed to a weight: the
    aircraft's), linearised about the 1 g trim (or `flight`'s load factor), on its lowest
    `modes` natural modes (None: all); `clamped` at an angle of attack as well (a wind-tunnel
    model: n is then the lift against the equilibrium's). Raises `InvalidInput` without a
    weight (free) or a mass, `NoEquilibrium`/`ConvergenceError` without an equilibrium."""
    options = options or SolverOptions()
    if (flight.weight is None and not clamped) or flight.velocity is None:
        raise InvalidInput("flight.weight", "a gust analysis needs the aircraft's weight")
    if options.aerodynamics == "unsteady_lattice":
        raise InvalidInput(
            "options.aerodynamics",
            "gust loads take 'strip' or 'lattice' (the lattice's steady loading with the "
            "strips' Wagner and Kuessner lags)",
        )
    beam = structure(wing)
    equilibrium = solve(wing, flight, options=options)
    system = CoupledSystem.of(wing, equilibrium.totals.alpha, options)
    evaluation, alpha_terms = system.evaluate_with_alpha(equilibrium.state)
    layout = system.layout
    aero = unsteady_aerodynamics(beam, layout, evaluation)
    influence = evaluation.jacobian0[layout.tangency_rows, layout.circulation]
    # A vertical velocity w meets each panel as the stream turned by w / V: the tangency
    # rows' derivative in alpha (per radian) is its normalwash, the deformed panel's normal
    # (a bent wing's dihedral: cos of its slope) included.
    vertical = alpha_terms.r0[layout.tangency_rows] * DEG_PER_RAD
    return _assemble(
        beam, aero, influence, vertical, layout.chordwise, flight, equilibrium, modes, clamped
    )


def _assemble(
    beam: Structure,
    aero: UnsteadyAerodynamics,
    influence: np.ndarray,
    vertical: np.ndarray,
    chordwise: int,
    flight: FlightCondition,
    equilibrium: Equilibrium,
    modes: int | None,
    clamped: bool,
) -> GustModel:
    wing = beam.wing
    velocity, density = float(flight.velocity or 0.0), flight.density
    # Clamped at an angle of attack (a wind-tunnel model): the load factor is the lift's
    # increment against the lift the equilibrium carries (both halves).
    weight = float(flight.weight or abs(2 * equilibrium.stations.shear[0]) or 1.0)
    q = dynamic_pressure(density, velocity)
    m, n_dof = beam.n_strips, beam.n_dof
    r = n_dof if modes is None else min(modes, n_dof)
    omega2, right, left = beam.modes
    basis, project = right[:, :r], left[:, :r].T  # R (n, r), L^T (r, n)
    panels = m * chordwise
    to_panels = np.repeat(np.eye(m), chordwise, axis=0)  # (M, m)

    # Quasi-steady circulatory loads of a normalwash: f = q Q nu.
    loads_of_wash = -np.linalg.solve(influence.T, aero.circulation_loads.T).T
    wash_of_c = -influence @ aero.deformation @ basis
    wash_of_rate = -influence @ aero.motion @ basis / velocity
    wash_of_plunge = -vertical / velocity  # per unit z'
    geometric = aero.geometric @ basis
    apparent_mass = aero.apparent_mass @ basis
    apparent_damping = aero.apparent_damping @ basis

    rigid_inertia, elastic_vertical = _plunge_inertia(beam)
    plunge_apparent = _plunge_apparent_mass(beam)
    total_force = np.r_[np.ones(m), np.zeros(m)]  # the strips' vertical forces, summed

    # State x = (c, c', z' [free only], Wagner states per panel (2 M)).
    p = 0 if clamped else 1
    size = 2 * r + p + 2 * panels
    c_of, rate_of = slice(0, r), slice(r, 2 * r)
    lag_of = slice(2 * r + p, size)
    semichord = (wing.chord[1:] + wing.chord[:-1]) / 4
    panel_semichord = np.repeat(semichord, chordwise)
    poles = WAGNER.poles(velocity, panel_semichord)  # (M, 2)
    weights = WAGNER.output_weights(velocity, panel_semichord)

    # The motion's normalwash nu_m (M, S) and its lagged value (M, S).
    wash = np.zeros((panels, size))
    wash[:, c_of], wash[:, rate_of] = wash_of_c, wash_of_rate
    if not clamped:
        wash[:, 2 * r] = wash_of_plunge
    lagged = WAGNER.direct * wash
    lagged[:, lag_of] = np.hstack([np.diag(weights[:, 0]), np.diag(weights[:, 1])])

    # Strip loads of the state without accelerations, and of the input g (m,).
    loads_x = q * loads_of_wash @ lagged
    loads_x[:, c_of] += q * geometric
    loads_x[:, rate_of] += density * velocity * apparent_damping
    loads_g = q * loads_of_wash @ (vertical[:, None] * to_panels)

    # Accelerations a = (c'', z''): mass a = forces.
    acc = r + p
    mass = np.zeros((acc, acc))
    mass[:r, :r] = np.eye(r) - density * project @ apparent_mass
    forces_x = np.zeros((acc, size))
    forces_x[:r] = project @ loads_x
    forces_x[:r, c_of] -= np.diag(omega2[:r])
    forces_g = np.zeros((acc, m))
    forces_g[:r] = project @ loads_g
    if not clamped:
        mass[:r, r] = project @ (rigid_inertia - density * plunge_apparent)
        mass[r, :r] = elastic_vertical @ basis - density * total_force @ apparent_mass
        mass[r, r] = weight / (2 * STANDARD_GRAVITY) - density * total_force @ plunge_apparent
        forces_x[r] = total_force @ loads_x
        forces_g[r] = total_force @ loads_g
    acc_x = np.linalg.solve(mass, forces_x)
    acc_g = np.linalg.solve(mass, forces_g)

    a = np.zeros((size, size))
    b = np.zeros((size, m))
    a[c_of, rate_of] = np.eye(r)
    a[r : r + acc] = acc_x
    b[r : r + acc] = acc_g
    for i in range(2):
        rows = slice(2 * r + p + i * panels, 2 * r + p + (i + 1) * panels)
        a[rows] = wash
        a[rows, rows] -= np.diag(poles[:, i])

    # Net strip loads: aerodynamic (with the apparent mass of the accelerations) minus inertial.
    accel_loads = np.hstack(
        [
            density * apparent_mass - beam.mass @ basis,
            (density * plunge_apparent - rigid_inertia)[:, None],
        ]
    )[:, :acc]
    net_x = loads_x + accel_loads @ acc_x
    net_g = loads_g + accel_loads @ acc_g
    aero_x = (
        loads_x + density * np.hstack([apparent_mass, plunge_apparent[:, None]])[:, :acc] @ acc_x
    )
    aero_g = (
        loads_g + density * np.hstack([apparent_mass, plunge_apparent[:, None]])[:, :acc] @ acc_g
    )

    stations = _station_loads(beam)  # (3N, n)
    n = wing.n_stations
    heave, pitch = beam.section_motion
    tip = np.zeros((3, size))
    tip[0] = 2 * total_force @ aero_x / weight
    tip[1, c_of] = heave[-1] @ basis
    tip[2, c_of] = DEG_PER_RAD * pitch[-1] @ basis
    c = np.vstack([stations @ net_x, tip])
    d = np.vstack([stations @ net_g, 2 * total_force @ aero_g / weight, np.zeros((2, m))])
    assert c.shape[0] == 3 * n + 3

    # Quasi-steady lift of a uniform gust angle on the half wing, over its area.
    lift_slope = float(total_force @ loads_g @ np.ones(m)) / q / (wing.planform_area / 2)
    leading_x = wing.y * math.tan(wing.sweep * DEG) - wing.elastic_axis * wing.chord
    strip_leading = (leading_x[1:] + leading_x[:-1]) / 2
    return GustModel(
        wing=wing,
        velocity=velocity,
        density=density,
        weight=weight,
        clamped=clamped,
        a=a,
        b=b,
        c=c,
        d=d,
        frequencies=np.sqrt(omega2[:r]),
        semichord=semichord,
        delay=(strip_leading - strip_leading.min()) / velocity,
        lift_slope=lift_slope,
        area=wing.planform_area / 2,
        equilibrium=equilibrium,
    )


def _strip_motion(m: int) -> np.ndarray:
    """(2m, 2m) the strips' heave and pitch of w: the mean of their two stations' (the root's
    zero), as `solver.dynamics.modes` lumps them."""
    mean = np.zeros((m, m))
    mean[np.arange(m), np.arange(m)] = 0.5
    mean[np.arange(1, m), np.arange(m - 1)] = 0.5
    return np.kron(np.eye(2), mean)


def _plunge_inertia(beam: Structure) -> tuple[np.ndarray, np.ndarray]:
    """(n,) the equivalent strip loads of a unit plunge acceleration's inertia (the strips'
    mass and static moment, the concentrated masses') and (n,) the vertical inertia force of
    unit elastic accelerations w'' (the row b_z of the module docstring)."""
    wing = beam.wing
    assert wing.mass is not None
    m = beam.n_strips
    inertia = section_inertia(wing.mass, wing.chord, wing.elastic_axis, wing.sweep, wing.spar)
    h = np.diff(beam.arc)
    strip_mass = h * (inertia.mass[1:] + inertia.mass[:-1]) / 2
    strip_moment = h * (inertia.static_moment[1:] + inertia.static_moment[:-1]) / 2
    rigid = np.r_[strip_mass, -strip_moment]
    vertical = rigid @ _strip_motion(m)
    sweep = wing.sweep * DEG
    for item in wing.mass.concentrated:
        if item.station == 0:
            continue  # at the clamped root: it plunges with the fuselage, in W
        i = item.station
        x_ea = wing.y[i] * math.tan(sweep) + item.offset
        point = np.array([[x_ea, wing.y[i], 0.0]])
        force = np.array([[0.0, 0.0, item.mass]])
        rigid = rigid + beam.wing_plane_loads(point, force, np.array([i - 1]))[:, 0]
        vertical[i - 1] += item.mass
        vertical[m + i - 1] -= item.mass * item.offset
    return rigid, vertical


def _plunge_apparent_mass(beam: Structure) -> np.ndarray:
    """(n,) Theodorsen's non-circulatory loads of a unit plunge acceleration per unit density
    (lift -pi b^2, moment -pi b^3 a per unit span on each streamwise strip), as equivalent
    strip loads."""
    wing = beam.wing
    b = (wing.chord[1:] + wing.chord[:-1]) / 4
    a = wing.elastic_axis[1:] + wing.elastic_axis[:-1] - 1.0
    area = math.pi * b * b * np.diff(wing.y)
    lift, moment = -area, -area * b * a
    sweep = wing.sweep * DEG
    direct = np.r_[lift, math.cos(sweep) * moment]
    return direct + beam.couple_to_strip_loads @ (-math.sin(sweep) * moment)


def _station_loads(beam: Structure) -> np.ndarray:
    """(3N, n) each station's shear [N], bending moment [N m] and torque [N m] of equivalent
    strip loads (forces at the strips' midpoints, torques): outboard sums, as the static model
    sums its loads."""
    m, n = beam.n_strips, beam.wing.n_stations
    outboard = np.triu(np.ones((n, m)))  # station i sums strips j >= i
    midpoint = (beam.arc[1:] + beam.arc[:-1]) / 2
    arm = midpoint[None, :] - beam.arc[:, None]
    zeros = np.zeros((n, m))
    return np.vstack(
        [
            np.hstack([outboard, zeros]),
            np.hstack([outboard * arm, zeros]),
            np.hstack([zeros, outboard]),
        ]
    )
