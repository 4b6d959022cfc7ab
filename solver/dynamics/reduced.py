"""The equations of motion on the flutter basis, with each aerodynamic model's loads.

Small oscillations w = R c e^{st} about a state obey, taken along the basis's left vectors L,

    (s^2 mass(omega) + s damping(omega) + stiffness(omega)) c = 0,

the aerodynamic loads evaluated at the root's own frequency omega = Im s (the p-k method,
`solver.dynamics.pk`), each coefficient a real matrix plus the aerodynamic one:

- `TheodorsenEquations` (options.aerodynamics "strip" and "lattice"): the loads of
  `solver.dynamics.unsteady`, the circulatory terms grouped by the strips' semichords, each group
  lagged by Theodorsen's C(k) of its own reduced frequency k = omega b / V.
- `LatticeEquations` ("unsteady_lattice"): the loads of `solver.dynamics.lattice_loads`,
  tabulated at a few reduced frequencies and interpolated between them (as Nastran's MKAERO1
  lists are; MSC Nastran Aeroelastic Analysis User's Guide, section 2.6), up to the
  infinite-frequency limit.

Either also gives the zero-frequency equations' real roots (`divergence_rate`) and blends into
another state's equations (`blend`). `companion` and `condense` turn the coefficients into one
eigenvalue problem per frequency.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from functools import cached_property

import numpy as np
import scipy.interpolate

from solver.dynamics.lattice_loads import LatticeLoads
from solver.dynamics.modes import Structure
from solver.dynamics.unsteady import UnsteadyAerodynamics, theodorsen
from solver.inputs.flight import dynamic_pressure
from solver.unsteady_lattice.wake import ShedWake

__all__ = [
    "OSCILLATING",
    "Basis",
    "Equations",
    "LatticeEquations",
    "TheodorsenEquations",
    "companion",
    "condense",
    "reduced_frequency_nodes",
]

# A root is oscillating when its frequency exceeds this fraction of its modulus.
OSCILLATING = 1e-6


@dataclass(frozen=True)
class Basis:
    """The reduced degrees of freedom: w = right c, equations projected on left; the last
    column, with `condensed`, the divergence shape's remainder (statically condensed)."""

    right: np.ndarray  # (n, r)
    left: np.ndarray  # (n, r)
    vacuum: np.ndarray  # (modes,) [rad/s] the natural modes' frequencies in vacuum
    divergence_pressure: float | None  # [Pa] of the unloaded wing
    condensed: bool  # the last column is the divergence shape's remainder
    structural_damping: float = 0.0  # [-] zeta, each natural mode's fraction of critical

    def structural(self, mass: np.ndarray) -> np.ndarray:
        """(r, r) the structure's own damping on the basis with the reduced `mass` (r, r):
        viscous, 2 zeta omega_i m_ii on each natural mode i (Nastran's modal damping, TABDMP1
        of type CRIT), none on the condensed remainder (it has no frequency of its own)."""
        modes = self.vacuum.shape[0]
        diagonal = np.zeros(mass.shape[0])
        diagonal[:modes] = 2 * self.structural_damping * self.vacuum * np.diag(mass)[:modes]
        return np.diag(diagonal)


@dataclass(frozen=True)
class TheodorsenEquations:
    """The equations on the basis at one state (`solver.dynamics.unsteady.UnsteadyAerodynamics`),
    the circulatory terms grouped by the strips' semichords (one lag per group):

        (s^2 mass + s damping(C) + stiffness(C)) c = 0,
        stiffness(C) = stiffness - q (geometric + sum_g C_g lagged_deformation_g),
        damping(C) = -(q / V) sum_g C_g lagged_motion_g - density V apparent_damping,
        mass = mass - density apparent_mass.
    """

    stiffness: np.ndarray  # (r, r)
    mass: np.ndarray  # (r, r)
    geometric: np.ndarray  # (r, r)
    lagged_deformation: np.ndarray  # (groups, r, r)
    lagged_motion: np.ndarray  # (groups, r, r)
    apparent_mass: np.ndarray  # (r, r)
    apparent_damping: np.ndarray  # (r, r)
    semichord: np.ndarray  # (groups,) [m]
    condensed: bool  # the last degree of freedom is condensed statically (`condense`)
    structural: np.ndarray  # (r, r) the structure's own damping (`Basis.structural`)

    @classmethod
    def of(cls, beam: Structure, basis: Basis, aero: UnsteadyAerodynamics) -> TheodorsenEquations:
        left, right = basis.left.T, basis.right
        loads = left @ aero.circulation_loads  # (r, M)
        deformation, motion = aero.deformation @ right, aero.motion @ right
        semichord, group = np.unique(aero.semichord, return_inverse=True)
        members = [np.flatnonzero(group == g) for g in range(semichord.size)]
        mass = left @ beam.mass @ right
        return cls(
            stiffness=left @ beam.stiffness @ right,
            mass=mass,
            geometric=left @ aero.geometric @ right,
            lagged_deformation=np.array([loads[:, p] @ deformation[p] for p in members]),
            lagged_motion=np.array([loads[:, p] @ motion[p] for p in members]),
            apparent_mass=left @ aero.apparent_mass @ right,
            apparent_damping=left @ aero.apparent_damping @ right,
            semichord=semichord,
            condensed=basis.condensed,
            structural=basis.structural(mass),
        )

    def divergence_rate(self, velocity: float, density: float) -> float | None:
        """[1/s] the largest real root of the equations at zero reduced frequency (C = 1, the
        p-k root of a non-oscillating motion), or None when they have no real root; positive
        beyond divergence. At s = 0 the equations are the static model's, K w = q Q w."""
        if velocity == 0:
            return None
        q = dynamic_pressure(density, velocity)
        # No lag: real coefficients, a real eigenvalue problem (half the work of a complex one).
        stiffness = self.stiffness - q * (self.geometric + self.lagged_deformation.sum(axis=0).real)
        damping = -(q / velocity) * self.lagged_motion.sum(axis=0).real
        damping = damping - density * velocity * self.apparent_damping + self.structural
        mass = self.mass - density * self.apparent_mass
        return _largest_real_root(mass, damping, stiffness, self.condensed)

    def blend(self, other: TheodorsenEquations, weight: float) -> TheodorsenEquations:
        """The equations (1 - weight) self + weight other (the same basis and strips)."""
        names = [n for n in self.__dataclass_fields__ if n not in ("semichord", "condensed")]
        mixed = {
            name: (1 - weight) * getattr(self, name) + weight * getattr(other, name)
            for name in names
        }
        return TheodorsenEquations(**mixed, semichord=self.semichord, condensed=self.condensed)

    def roots(
        self, frequency: np.ndarray, velocity: float, density: float, lagged: bool
    ) -> np.ndarray:
        """(t, 2r) the roots s [1/s] of the equations with the lag of each of the t
        `frequency` [rad/s] (C = 1 without `lagged`, or in still air)."""
        r, t = self.stiffness.shape[0], frequency.shape[0]
        q = dynamic_pressure(density, velocity)
        if velocity > 0 and lagged:
            lag = theodorsen(frequency[:, None] * self.semichord[None, :] / velocity)
        else:
            lag = np.ones((t, self.semichord.shape[0]), dtype=complex)
        circulatory = np.tensordot(lag, self.lagged_deformation, axes=1)  # (t, r, r)
        stiffness = self.stiffness - q * (self.geometric + circulatory)
        damping = np.broadcast_to(
            self.structural - density * velocity * self.apparent_damping, (t, r, r)
        )
        if velocity > 0:
            damping = damping - (q / velocity) * np.tensordot(lag, self.lagged_motion, axes=1)
        mass = np.broadcast_to(self.mass - density * self.apparent_mass, (t, r, r))
        if self.condensed:
            mass, damping, stiffness = condense(mass, damping, stiffness)
        return np.linalg.eigvals(companion(mass, damping, stiffness))


def reduced_frequency_nodes(largest: float, count: int) -> np.ndarray:
    """(count + 1,) [-] the reduced frequencies the unsteady lattice is tabulated at: `count`
    from 0 to `largest`, evenly spaced in u = k / (k + largest / 4) (denser where the loads
    vary fastest, at low k), and the infinite-frequency limit (u = 1)."""
    scale = largest / 4
    top = largest / (largest + scale)
    u = np.linspace(0.0, top, count)
    return np.concatenate([scale * u / (1 - u), [np.inf]])


@dataclass(frozen=True, eq=False)
class LatticeEquations:
    """The equations on the basis at one state with the unsteady lattice's loads
    (`solver.dynamics.lattice_loads`), tabulated at the reduced frequencies `reduced` (the last
    one infinite) and interpolated between them:

        stiffness(k) = stiffness - q (geometric + A0(k)),
        damping(k) = -(q / V) A1(k),
        mass(k) = mass - (q / V^2) A2(k) = mass - (density / 2) A2(k),

    k = omega b / V; A0, A1, A2 the tabulated (K, r, r) (`lattice_stiffness`,
    `lattice_damping`, `lattice_inertia`), interpolated by cubic splines in u = k / (k + k_s)
    (`reduced_frequency_nodes`), which maps k = infinity to u = 1 (still air: the apparent mass
    alone)."""

    stiffness: np.ndarray  # (r, r)
    mass: np.ndarray  # (r, r)
    geometric: np.ndarray  # (r, r)
    lattice_stiffness: np.ndarray  # (K, r, r)
    lattice_damping: np.ndarray  # (K, r, r) [m]
    lattice_inertia: np.ndarray  # (K, r, r) [m^2]
    reduced: np.ndarray  # (K,) [-] the last one infinite
    semichord: float  # [m] b of the reduced frequency
    condensed: bool
    structural: np.ndarray  # (r, r) the structure's own damping (`Basis.structural`)

    @classmethod
    def of(
        cls,
        beam: Structure,
        basis: Basis,
        loads: LatticeLoads,
        wake: ShedWake,
        semichord: float,
    ) -> LatticeEquations:
        """The equations of `loads` with `wake` tabulated at kappa = k / b (`semichord` b)."""
        left, right = basis.left, basis.right
        modal = loads.modal(wake, right, left)
        mass = left.T @ beam.mass @ right
        return cls(
            stiffness=left.T @ beam.stiffness @ right,
            mass=mass,
            geometric=left.T @ loads.geometric @ right,
            lattice_stiffness=modal.stiffness,
            lattice_damping=modal.damping,
            lattice_inertia=modal.inertia,
            reduced=wake.kappa * semichord,
            semichord=semichord,
            condensed=basis.condensed,
            structural=basis.structural(mass),
        )

    @cached_property
    def _scale(self) -> float:
        finite = self.reduced[np.isfinite(self.reduced)]
        return float(finite.max()) / 4

    @cached_property
    def _splines(self) -> scipy.interpolate.CubicSpline:
        u = self._mapped(self.reduced)
        table = np.stack([self.lattice_stiffness, self.lattice_damping, self.lattice_inertia])
        return scipy.interpolate.CubicSpline(u, table, axis=1)

    def _mapped(self, reduced: np.ndarray) -> np.ndarray:
        with np.errstate(invalid="ignore"):
            u = reduced / (reduced + self._scale)
        return np.where(np.isinf(reduced), 1.0, u)

    def aerodynamics(self, reduced: np.ndarray) -> np.ndarray:
        """(3, t, r, r) complex: A0, A1, A2 at each of the t reduced frequencies (inf allowed)."""
        return self._splines(self._mapped(reduced))

    def divergence_rate(self, velocity: float, density: float) -> float | None:
        """[1/s] the largest real root of the equations at zero frequency (the wake without
        lag, the p-k root of a non-oscillating motion), or None when they have no real root;
        positive beyond divergence. At s = 0 they are the static model's, K w = q Q w."""
        if velocity == 0:
            return None
        q = dynamic_pressure(density, velocity)
        stiffness = self.stiffness - q * (self.geometric + self.lattice_stiffness[0].real)
        damping = self.structural - (q / velocity) * self.lattice_damping[0].real
        mass = self.mass - 0.5 * density * self.lattice_inertia[0].real
        return _largest_real_root(mass, damping, stiffness, self.condensed)

    def blend(self, other: LatticeEquations, weight: float) -> LatticeEquations:
        """The equations (1 - weight) self + weight other (the same basis and table)."""
        names = [
            "stiffness",
            "mass",
            "geometric",
            "lattice_stiffness",
            "lattice_damping",
            "lattice_inertia",
        ]
        mixed = {
            name: (1 - weight) * getattr(self, name) + weight * getattr(other, name)
            for name in names
        }
        return dataclasses.replace(self, **mixed)

    def roots(
        self, frequency: np.ndarray, velocity: float, density: float, lagged: bool
    ) -> np.ndarray:
        """(t, 2r) the roots s [1/s] of the equations with the loads of each of the t
        `frequency` [rad/s] (those of zero frequency without `lagged`; in still air the
        infinite-frequency limit, the apparent mass)."""
        t = frequency.shape[0]
        q = dynamic_pressure(density, velocity)
        if velocity == 0:
            reduced = np.full(t, np.inf)
        elif lagged:
            reduced = frequency * self.semichord / velocity
        else:
            reduced = np.zeros(t)
        a0, a1, a2 = self.aerodynamics(reduced)
        stiffness = self.stiffness - q * (self.geometric + a0)
        damping = -(q / velocity) * a1 if velocity > 0 else np.zeros_like(a1)
        damping = damping + self.structural
        mass = self.mass - 0.5 * density * a2
        if self.condensed:
            mass, damping, stiffness = condense(mass, damping, stiffness)
        return np.linalg.eigvals(companion(mass, damping, stiffness))


Equations = TheodorsenEquations | LatticeEquations


def _largest_real_root(
    mass: np.ndarray, damping: np.ndarray, stiffness: np.ndarray, condensed: bool
) -> float | None:
    """[1/s] the largest real root of real equations, None without one."""
    matrices = (mass[None], damping[None], stiffness[None])
    if condensed:
        matrices = condense(*matrices)
    roots = np.linalg.eigvals(companion(*matrices))[0]
    real = roots[np.abs(roots.imag) <= OSCILLATING * np.abs(roots)].real
    return float(real.max()) if real.size else None


def condense(
    mass: np.ndarray, damping: np.ndarray, stiffness: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(t, r - 1, r - 1) each: the equations with their last degree of freedom condensed
    statically (Guyan): it follows the others as the stiffness says, c_last = T c, and its
    equation is combined with theirs likewise. The condensed stiffness is the Schur
    complement, singular exactly when the whole is: the static divergence is kept; the last
    shape's own dynamics (a high-frequency remainder) are not, and it is no mode of its own."""
    k_last = stiffness[:, -1, -1]
    right = -stiffness[:, -1, :-1] / k_last[:, None]  # (t, r - 1)
    left = -stiffness[:, :-1, -1] / k_last[:, None]

    def apply(x: np.ndarray) -> np.ndarray:
        return (
            x[:, :-1, :-1]
            + x[:, :-1, -1:] * right[:, None, :]
            + left[:, :, None] * x[:, -1:, :-1]
            + x[:, -1:, -1:] * left[:, :, None] * right[:, None, :]
        )

    return apply(mass), apply(damping), apply(stiffness)


def companion(mass: np.ndarray, damping: np.ndarray, stiffness: np.ndarray) -> np.ndarray:
    """(t, 2r, 2r): the first-order form of (s^2 mass + s damping + stiffness) c = 0."""
    t, r = stiffness.shape[0], stiffness.shape[1]
    inverse = np.linalg.inv(mass)
    companion = np.zeros((t, 2 * r, 2 * r), dtype=np.result_type(stiffness, damping, mass))
    companion[:, :r, r:] = np.eye(r)
    companion[:, r:, :r] = -inverse @ stiffness
    companion[:, r:, r:] = -inverse @ damping
    return companion
