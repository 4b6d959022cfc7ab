"""Exact references for the vibration and flutter tests: the continuous uniform cantilever,
bending (Euler-Bernoulli) and torsion (St Venant) coupled by the centre of gravity's offset,
with Theodorsen's strip loads and an optional tip store, solved without discretising anything.

For a uniform strip the equations are an ODE in the span with constant coefficients, so the
state z = (h, h', h'', h''', alpha, alpha') obeys z' = A(s, V) z exactly and z(L) = e^{AL} z(0)
(ContourRoots, Tutorial 11, "Flutter of a continuous wing", 2025: the same formulation). The
root clamps and the tip's conditions make a 3 x 3 determinant, zero at the roots s. With
Theodorsen's lag at k = Im(s) b / V its zeros on the imaginary axis are the flutter points.

Checked here against ContourRoots' published values for its Goland parameters (validation
record of its continuous Goland wing): 136.983977449 m/s, 70.033012953 rad/s at sea-level air
(tests/solver/test_flutter.py).

Conventions as flexwing's: heave h up, pitch alpha nose-up about the elastic axis, the centre of
gravity d aft of it (static moment S = m d), inertia I about the elastic axis.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.linalg
import scipy.optimize
import scipy.special

import solver
from solver.inputs.mass import ConcentratedMass, MassModel

# The Goland wing (Goland 1945, J. Appl. Mech. 12, A197-A208), SI as usually quoted: semispan
# 20 ft, chord 6 ft, elastic axis at 33 % chord, centre of gravity at 43 %, EI 23.65e6 lb ft^2,
# GJ 2.39e6 lb ft^2, 0.746 slug/ft, 1.943 slug ft^2/ft about the elastic axis (Eastep's
# tabulation, as used by Allen and Camberos 2009).
GOLAND = {
    "semispan": 6.096,  # [m]
    "chord": 1.8288,  # [m]
    "elastic_axis": 0.33,
    "center_of_gravity": 0.43,
    "bending_stiffness": 9.77e6,  # [N m^2]
    "torsional_stiffness": 0.987e6,  # [N m^2]
    "mass": 35.71,  # [kg/m]
    "inertia_about_elastic_axis": 8.64,  # [kg m]
}
SEA_LEVEL = 1.225  # [kg/m^3] Goland's air (0.002378 slug/ft^3)


@dataclass(frozen=True)
class UniformWing:
    """A uniform cantilever with its section and, optionally, a tip store."""

    semispan: float  # [m]
    semichord: float  # [m]
    a: float  # elastic axis aft of mid-chord [semichords]
    bending_stiffness: float  # [N m^2]
    torsional_stiffness: float  # [N m^2]
    mass: float  # [kg/m]
    static_moment: float  # [kg] mass times the centre of gravity's distance aft of the axis
    inertia: float  # [kg m] about the elastic axis
    store_mass: float = 0.0  # [kg]
    store_offset: float = 0.0  # [m] aft of the elastic axis
    store_inertia: float = 0.0  # [kg m^2] about the store's own centre of gravity
    quasi_steady: bool = False  # C = 1: no wake lag

    def root_matrix(self, s: complex, velocity: float, density: float) -> np.ndarray:
        """(3, 3) whose determinant vanishes at a root s."""
        a_matrix = np.zeros((6, 6), dtype=complex)
        a_matrix[0, 1] = a_matrix[1, 2] = a_matrix[2, 3] = a_matrix[4, 5] = 1.0
        (lift_h, lift_a), (moment_h, moment_a) = _theodorsen_loads(
            s, velocity, density, self.semichord, self.a, not self.quasi_steady
        )
        ei, gj = self.bending_stiffness, self.torsional_stiffness
        # EI h'''' = L - s^2 (m h - S alpha);  GJ alpha'' = s^2 (-S h + I alpha) - M
        a_matrix[3, 0] = (lift_h - s * s * self.mass) / ei
        a_matrix[3, 4] = (lift_a + s * s * self.static_moment) / ei
        a_matrix[5, 0] = (-s * s * self.static_moment - moment_h) / gj
        a_matrix[5, 4] = (s * s * self.inertia - moment_a) / gj
        tip = scipy.linalg.expm(a_matrix * self.semispan)[:, [2, 3, 5]]
        # Tip: no bending moment; the shear and the torque balance the store's inertia, its
        # vertical force -M s^2 (h - d alpha) and torque -s^2 (-M d h + (I_s + M d^2) alpha).
        m_s, d = self.store_mass, self.store_offset
        force = -s * s * np.array([m_s, -m_s * d])  # on (h, alpha) at the tip
        torque = -s * s * np.array([-m_s * d, self.store_inertia + m_s * d * d])
        conditions = np.zeros((3, 6), dtype=complex)
        conditions[0, 2] = 1.0
        conditions[1, 3] = ei
        conditions[1, [0, 4]] = force  # EI h''' = -F
        conditions[2, 5] = gj
        conditions[2, [0, 4]] = -torque  # GJ alpha' = tau
        return conditions @ tip

    def determinant(self, s: complex, velocity: float = 0.0, density: float = 0.0) -> complex:
        return complex(np.linalg.det(self.root_matrix(s, velocity, density)))

    def vacuum_frequencies(self, highest: float, points: int = 20000) -> list[float]:
        """[rad/s] every natural frequency below `highest`, by sign changes of the (real)
        vacuum determinant, refined by Brent's method."""
        grid = np.linspace(highest * 1e-3, highest, points)
        values = np.array([self.determinant(1j * w).real for w in grid])
        roots = []
        for i in np.flatnonzero(np.sign(values[:-1]) != np.sign(values[1:])):
            roots.append(
                scipy.optimize.brentq(
                    lambda w: self.determinant(1j * w).real, grid[i], grid[i + 1], xtol=1e-13
                )
            )
        return roots

    def flutter(self, density: float, guess: tuple[float, float]) -> tuple[float, float]:
        """(V [m/s], omega [rad/s]) where the determinant vanishes on the imaginary axis, from
        a guess (Newton's method on its real and imaginary parts)."""

        def parts(x: np.ndarray) -> list[float]:
            value = self.determinant(1j * x[1], x[0], density)
            return [value.real, value.imag]

        solution = scipy.optimize.fsolve(parts, np.array(guess), xtol=1e-13)
        return float(solution[0]), float(solution[1])


def _theodorsen_loads(
    s: complex, velocity: float, density: float, b: float, a: float, lagged: bool = True
) -> tuple[tuple[complex, complex], tuple[complex, complex]]:
    """Lift and moment per unit h and alpha (Theodorsen 1935), the lag at k = Im(s) b / V
    (none, C = 1, unless `lagged`)."""
    if velocity > 0 and not lagged:
        lag: complex | float = 1.0
    elif velocity > 0:
        k = abs(s.imag) * b / velocity
        h1, h0 = scipy.special.hankel2(1, k), scipy.special.hankel2(0, k)
        lag = complex(h1 / (h1 + 1j * h0))
    else:
        lag = 0.0
    apparent = math.pi * density * b * b
    circulatory = 2 * math.pi * density * velocity * b * lag
    upwash_h, upwash_a = -s, velocity + b * (0.5 - a) * s
    lift = (
        apparent * -s * s + circulatory * upwash_h,
        apparent * (velocity * s - b * a * s * s) + circulatory * upwash_a,
    )
    moment = (
        apparent * -b * a * s * s + circulatory * b * (a + 0.5) * upwash_h,
        apparent * (-velocity * b * (0.5 - a) * s - b * b * (0.125 + a * a) * s * s)
        + circulatory * b * (a + 0.5) * upwash_a,
    )
    return lift, moment


def goland_continuous(**store: float) -> UniformWing:
    g = GOLAND
    offset = (g["center_of_gravity"] - g["elastic_axis"]) * g["chord"]
    return UniformWing(
        semispan=g["semispan"],
        semichord=g["chord"] / 2,
        a=2 * g["elastic_axis"] - 1,
        bending_stiffness=g["bending_stiffness"],
        torsional_stiffness=g["torsional_stiffness"],
        mass=g["mass"],
        static_moment=g["mass"] * offset,
        inertia=g["inertia_about_elastic_axis"],
        **store,
    )


def goland_wing(n: int = 30, stiffness_scale: float = 1.0) -> solver.Wing:
    g = GOLAND
    return solver.Wing.create(
        np.linspace(0, g["semispan"], n),
        g["chord"],
        g["elastic_axis"],
        g["bending_stiffness"] * stiffness_scale,
        g["torsional_stiffness"] * stiffness_scale,
    )


def goland_mass(n: int = 30, concentrated: tuple[ConcentratedMass, ...] = ()) -> MassModel:
    """Goland's inertia about the elastic axis, stated about the centre of gravity as
    `MassModel` takes it: 8.64 - 35.71 (0.1 c)^2 = 7.446 kg m (radius of gyration 0.2497 c)."""
    g = GOLAND
    offset = (g["center_of_gravity"] - g["elastic_axis"]) * g["chord"]
    about_cg = g["inertia_about_elastic_axis"] - g["mass"] * offset**2
    return MassModel.create(n, g["mass"], g["center_of_gravity"], about_cg, concentrated)
