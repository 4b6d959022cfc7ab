"""Unsteady aerodynamics of a vibrating wing: Theodorsen's function and the loads of small
oscillations about a state of the static model, on the structure's degrees of freedom.

Strip theory (Theodorsen 1935, NACA Report 496; Bisplinghoff, Ashley and Halfman 1955, section
5-6; Hodges and Pierce 2011, section 5.4). A section of semichord b whose elastic axis lies a b
aft of mid-chord, heaving h (up) and pitching alpha (nose-up) at frequency omega in a stream V,
carries per unit span the lift (up) and moment about the elastic axis (nose-up)

    L = pi rho b^2 (-h'' + V alpha' - b a alpha'') + 2 pi rho V b C(k) w
    M = pi rho b^2 (-b a h'' - V b (1/2 - a) alpha' - b^2 (1/8 + a^2) alpha'')
        + 2 pi rho V b^2 (a + 1/2) C(k) w,
    w = V alpha - h' + b (1/2 - a) alpha'    (the upwash at the three-quarter chord)

with k = omega b / V and C(k) = H1(k) / (H1(k) + i H0(k)) (Hankel functions of the second
kind). The first group is the apparent mass and the pitch rate's camber (non-circulatory: it
follows the motion at once); the second the circulatory lift at the quarter chord, the
quasi-steady lift of the three-quarter-chord upwash lagged by the wake, C(k).

Here the circulatory loads come from the static model itself, from its exact Jacobian at the
state (J0 + q J1 of `solver.model.residual`), with the circulations eliminated:

    quasi-steady circulation   g = -T_g^{-1} (T_s z + (s / V) N z)
    circulatory loads          q (K_s z + K_g C(k) g)

T_s, T_g the flow-tangency rows' derivatives in the structure's unknowns and the circulations,
K_s, K_g the load rows', N the motion's upwash: each collocation point's vertical velocity
relative to the stream, per unit V, taken at its strip's three-quarter chord (the upwash w
above, for every chordwise panel, so that a pitch rate's camber is counted once, in the
non-circulatory group). C(k) lags each strip's circulations with the strip's own semichord. The
non-circulatory loads are Theodorsen's, per streamwise strip.

What the two aerodynamics are (`SolverOptions.aerodynamics`):

- "strip": each strip a two-dimensional airfoil, so the above is exactly Theodorsen's strip
  theory, the classical model behind the published beam-wing flutter results.
- "lattice": the same with the lattice's steady 3D circulation response: the induced downwash
  of the whole steady wake (tip loss, 3D lift slope) in T_g, the lag of a two-dimensional wake
  C(k) per strip. It is a quasi-steady 3D lattice with a strip-theory lag (the "modified strip
  analysis" idea of Yates, NACA RM L57L10, with the lattice in place of a lifting-line
  loading), not an unsteady lattice: the wake's oscillating vorticity is felt only through
  C(k), section by section. At k -> 0 both are exactly the static model, so the zero-frequency
  root is the static divergence of the same aerodynamics.

The unsteady lattice ("unsteady_lattice"), whose wake is shed and convected in 3D, is
`solver.dynamics.lattice_loads`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.special

from solver.dynamics.modes import Structure
from solver.inputs.flight import dynamic_pressure
from solver.model.geometry import DEG
from solver.model.layout import Layout
from solver.numerics.evaluation import Evaluation

__all__ = ["UnsteadyAerodynamics", "theodorsen", "theodorsen_section", "unsteady_aerodynamics"]


def theodorsen(k: np.ndarray | float) -> np.ndarray:
    """Theodorsen's function C(k) = F + i G of the reduced frequency k >= 0 (array or number):
    C(0) = 1 (quasi-steady), C -> 1/2 as k -> infinity."""
    k = np.asarray(k, dtype=float)
    result = np.ones(k.shape, dtype=complex)
    positive = k > 0
    h1 = scipy.special.hankel2(1, k[positive])
    h0 = scipy.special.hankel2(0, k[positive])
    result[positive] = h1 / (h1 + 1j * h0)
    return result


def theodorsen_section(
    frequency: float, velocity: float, density: float, semichord: float, a: float
) -> np.ndarray:
    """(2, 2) complex: the section's lift [N/m] (up) and moment about its elastic axis [N m/m]
    (nose-up) per unit heave [m] (up) and pitch [rad] (nose-up) in harmonic motion at
    `frequency` omega [rad/s] (Theodorsen's, module docstring); `a`: the elastic axis's position
    aft of mid-chord in semichords."""
    s = 1j * frequency
    b, v = semichord, velocity
    lag = theodorsen(frequency * b / v)[()] if v > 0 else 0.0
    apparent = math.pi * density * b * b
    circulatory = 2 * math.pi * density * v * b * lag
    upwash = np.array([-s, v + b * (0.5 - a) * s])  # w per unit h and alpha
    lift = apparent * np.array([-s * s, v * s - b * a * s * s]) + circulatory * upwash
    moment = (
        apparent
        * np.array([-b * a * s * s, -v * b * (0.5 - a) * s - b * b * (0.125 + a * a) * s * s])
        + circulatory * b * (a + 0.5) * upwash
    )
    return np.vstack([lift, moment])


@dataclass(frozen=True)
class UnsteadyAerodynamics:
    """The aerodynamic loads of small oscillations w e^{st} about one state, as equivalent
    strip loads (`solver.dynamics.modes.Structure`) on the degrees of freedom w (n = 2 (N - 1)):

        f(s) = q (geometric + circulation_loads C (deformation + (s / V) motion)) w
               + density (s^2 apparent_mass + V s apparent_damping) w

    geometric: (n, n) [m^2 ...] per unit q, the loads' change with the geometry at fixed
    circulation; circulation_loads: (n, M) per unit q, of the panels' circulations per unit V;
    deformation: (M, n) the quasi-steady circulations of a deformation; motion: (M, n) of the
    deformation's rate per unit s / V; apparent_mass, apparent_damping: (n, n) Theodorsen's
    non-circulatory loads per unit density (times s^2, and V s); semichord: (M,) [m] each
    panel's strip's semichord, which C(k) of the panel's circulation is evaluated with.
    """

    geometric: np.ndarray
    circulation_loads: np.ndarray
    deformation: np.ndarray
    motion: np.ndarray
    apparent_mass: np.ndarray
    apparent_damping: np.ndarray
    semichord: np.ndarray

    def stiffness(self) -> np.ndarray:
        """(n, n) per unit q: the quasi-steady, zero-frequency loads of w (the static
        model's aerodynamic stiffness: K w = q this w is its divergence)."""
        return self.geometric + self.circulation_loads @ self.deformation

    def loads(
        self, s: complex, velocity: float, density: float, lag: np.ndarray | None = None
    ) -> np.ndarray:
        """(n, n) complex: f(s) per unit w at root s [1/s], airspeed [m/s], density [kg/m^3];
        `lag` (M,) C(k) of each panel's circulation (default: Theodorsen's at k = |Im s| b / V)."""
        if lag is None:
            lag = theodorsen(abs(s.imag) * self.semichord / velocity)
        q = dynamic_pressure(density, velocity)
        circulation = self.deformation + (s / velocity) * self.motion
        return q * (self.geometric + (self.circulation_loads * lag) @ circulation) + density * (
            s * s * self.apparent_mass + velocity * s * self.apparent_damping
        )


def unsteady_aerodynamics(
    structure: Structure, layout: Layout, evaluation: Evaluation
) -> UnsteadyAerodynamics:
    """The loads of small oscillations about the state whose exact Jacobians `evaluation`
    holds (J0, J1 of the static model on `layout`, aerodynamics as the layout says). With lag
    (a structure bending in the wing's plane, `solver.dynamics.modes`) a lag displacement
    moves no collocation point across the plane and carries no non-circulatory load; about a
    bent state a lag rotation pitches the section (`_upwash`), and the static model's
    Jacobian couples the rest."""
    wing = structure.wing
    z_of_w = structure.states  # (3N, n); (5N, n) with lag
    j0, j1 = evaluation.jacobian0, evaluation.jacobian1
    tangency, circulation = layout.tangency_rows, layout.circulation
    load_rows = j1[layout.load_rows]
    solve = np.linalg.solve
    influence = j0[tangency, circulation]
    deformation = -solve(influence, j0[tangency, layout.structure] @ z_of_w)
    motion = -solve(influence, _upwash(structure, layout))
    geometric = structure.strip_loads_of(load_rows[:, layout.structure] @ z_of_w)
    circulation_loads = structure.strip_loads_of(load_rows[:, circulation])
    mass, damping = _apparent_loads(structure)
    strip_semichord = (wing.chord[1:] + wing.chord[:-1]) / 4
    return UnsteadyAerodynamics(
        geometric=geometric,
        circulation_loads=circulation_loads,
        deformation=deformation,
        motion=motion,
        apparent_mass=mass,
        apparent_damping=damping,
        semichord=np.repeat(strip_semichord, layout.chordwise),
    )


def _upwash(structure: Structure, layout: Layout) -> np.ndarray:
    """(M, n): N of the module docstring on w, each panel's upwash per unit s / V: minus the
    vertical displacement of its strip's three-quarter-chord line (the mean of its two
    stations', at (3/4 - x_ea) c aft of the elastic axis, turned about it by the section's
    streamwise pitch, `Structure.section_motion`). A lag displacement moves no collocation
    point across the wing's plane; a lag rotation of a bent section turns its chord across
    the bent surface, a pitch a_z psi (`solver.dynamics.modes`), as the unsteady lattice's
    `solver.dynamics.lattice_loads` takes it too."""
    strips = structure.strip_points_motion(np.array([0.75]))[:, 0]  # (N - 1, n)
    return -np.repeat(strips, layout.chordwise, axis=0)


def _apparent_loads(structure: Structure) -> tuple[np.ndarray, np.ndarray]:
    """(n, n) each: Theodorsen's non-circulatory loads per unit density on each streamwise strip
    (lift at the elastic axis, moment about it), as equivalent strip loads of w: the
    coefficients of s^2 and of V s."""
    wing = structure.wing
    heave, pitch = structure.section_motion
    mean_heave, mean_pitch = (heave[:-1] + heave[1:]) / 2, (pitch[:-1] + pitch[1:]) / 2
    b = ((wing.chord[1:] + wing.chord[:-1]) / 4)[:, None]
    a = (wing.elastic_axis[1:] + wing.elastic_axis[:-1] - 1.0)[:, None]  # 2 x_ea - 1, mean
    area = math.pi * b * b * np.diff(wing.y)[:, None]  # pi b^2 per strip's span [m^3]
    lift_s2 = area * (-mean_heave - b * a * mean_pitch)
    moment_s2 = area * (-b * a * mean_heave - b * b * (0.125 + a * a) * mean_pitch)
    lift_vs = area * mean_pitch
    moment_vs = area * (-b * (0.5 - a) * mean_pitch)
    sweep = wing.sweep * DEG

    def equivalent(lift: np.ndarray, moment: np.ndarray) -> np.ndarray:
        # A streamwise moment is a torque about the swept axis and a bending couple; the
        # sections' non-circulatory loads have no part in the wing's plane (lag rows zero).
        direct = np.zeros((structure.n_dof, lift.shape[1]))
        direct[: 2 * lift.shape[0]] = np.vstack([lift, math.cos(sweep) * moment])
        return direct + structure.couple_to_strip_loads @ (-math.sin(sweep) * moment)

    return equivalent(lift_s2, moment_s2), equivalent(lift_vs, moment_vs)
