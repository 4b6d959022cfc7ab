"""solver.dynamics.modes with in-plane (lag) bending: the cantilever bending in the wing's plane
too (`docs/design/lag_bending.md`, step 3), about the jig, against closed forms and the flap
bending that the same stiffness gives."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from scipy.optimize import brentq

import solver
from solver.dynamics.modes import natural_modes, structure
from tests.solver.dynamics.test_modes import (
    BETA,
    EI,
    LENGTH,
    MASS,
    MESHES,
    _second_order,
    uniform_mass,
    uniform_wing,
)

EI_LAG = 9 * EI  # the in-plane modes 3 times the flap ones: clear of the torsion ones


def lagging(wing: solver.Wing, stiffness: float = EI_LAG) -> solver.Wing:
    """`wing` bending in its plane with a uniform in-plane stiffness [N m^2]."""
    return dataclasses.replace(wing, in_plane_bending_stiffness=np.full(wing.n_stations, stiffness))


def _lag_frequencies(n: int, **store) -> tuple[np.ndarray, np.ndarray]:
    """(lag, other) natural frequencies [rad/s] of the uniform wing with EI_LAG: the modes
    whose kinetic energy is in-plane and the others."""
    modes = natural_modes(lagging(uniform_wing(n)), uniform_mass(n, **store))
    lag = np.array([m.frequency for m in modes.modes if m.lag_share > 0.5])
    other = np.array([m.frequency for m in modes.modes if m.lag_share <= 0.5])
    return lag, other


def test_ml1_the_in_plane_modes_converge_to_the_cantilevers_at_second_order():
    """The in-plane bending of the uniform cantilever: beta_k^2 sqrt(EI_lag / (m L^4)), from
    above at second order as the flap bending (the same rows turned into the plane)."""
    exact = [b**2 * math.sqrt(EI_LAG / (MASS * LENGTH**4)) for b in BETA]
    errors = np.array([_lag_frequencies(n)[0][:2] / exact - 1 for n in MESHES])
    assert np.all(errors[-1] > 0) and np.all(errors[-1] < 3e-3)
    for mode in range(2):
        _second_order(list(errors[:, mode]))


def test_ml2_about_the_jig_the_other_modes_are_the_planar_beams():
    """Straight, nothing couples the plane's bending with the rest (centre of gravity on the
    chord line): every other mode is the beam without lag, to round-off (the non-symmetric
    eigenproblem, now half as large again: measured 7.5e-9, held to 1e-7); each in-plane mode
    is purely in-plane."""
    n = 21
    wing, mass = uniform_wing(n), uniform_mass(n, center_of_gravity=0.45)
    planar = [m.frequency for m in natural_modes(wing, mass).modes]
    modes = natural_modes(lagging(wing), mass).modes
    assert len(modes) == 3 * (n - 1)
    other = [m for m in modes if m.lag_share < 0.5]
    lag = [m for m in modes if m.lag_share >= 0.5]
    assert np.array([m.frequency for m in other]) == pytest.approx(planar, rel=1e-7)
    for mode in lag:
        assert mode.lag_share == pytest.approx(1.0, abs=1e-12)
        assert np.abs(mode.heave).max() < 1e-9 and np.abs(mode.twist).max() < 1e-9
        assert np.abs(mode.lag).max() == pytest.approx(1.0)
    for mode in other:
        assert np.abs(mode.lag).max() < 1e-9


def test_ml3_a_tip_store_lowers_the_in_plane_modes_as_blevins_formula():
    """A concentrated mass M = 2 m L at the tip moves in the plane with the axis: the in-plane
    frequency obeys the flap's equation, 1 + cos cosh + (M / (m L)) bL (cos sinh - sin cosh) = 0
    (Blevins table 8-1, case 4), with EI_lag. Second order, within 5e-4 at N = 41."""
    ratio = 2.0
    store = {"mass": ratio * MASS * LENGTH, "inertia": 1.0, "offset": 0.0}

    def equation(x: float) -> float:
        return (
            1
            + math.cos(x) * math.cosh(x)
            + ratio * x * (math.cos(x) * math.sinh(x) - math.sin(x) * math.cosh(x))
        )

    exact = brentq(equation, 0.5, BETA[0]) ** 2 * math.sqrt(EI_LAG / (MASS * LENGTH**4))
    errors = [abs(_lag_frequencies(n, **store)[0][0] / exact - 1) for n in MESHES]
    assert errors[-1] < 5e-4
    _second_order(errors)


def test_ml4_an_aft_force_bends_the_axis_aft_as_an_upward_force_bends_it_up():
    """With EI_lag = EI, a force across the axis in the wing's plane at a point on the axis
    displaces it in the plane as the same force normal to the plane displaces it in heave
    (the rows are the flap rows turned by 90 degrees about the axis): to round-off (1e-9 of the
    largest; the two solve through different rows), and aft
    (v > 0) for a force aft."""
    n = 15
    wing, mass = uniform_wing(n, sweep=20.0), uniform_mass(n)
    beam = structure(wing, mass, in_plane_bending_stiffness=np.full(n, EI))
    sweep = math.radians(20.0)
    along = np.array([math.sin(sweep), math.cos(sweep), 0.0])
    across = np.array([[math.cos(sweep), -math.sin(sweep), 0.0]])  # e_c = e_s x n
    normal = np.array([[0.0, 0.0, 1.0]])
    point = 0.3 * beam.arc[-1] * along[None, :]  # on the axis, in strip 4's span
    strip = np.array([int(np.searchsorted(beam.arc, 0.3 * beam.arc[-1])) - 1])
    up = np.linalg.solve(beam.stiffness, beam.wing_plane_loads(point, 1e3 * normal, strip))
    aft = np.linalg.solve(beam.stiffness, beam.wing_plane_loads(point, 1e3 * across, strip))
    z_up, z_aft = beam.states @ up[:, 0], beam.states @ aft[:, 0]
    heave, lag = z_up[:n], z_aft[3 * n : 4 * n]
    assert lag == pytest.approx(heave, abs=1e-9 * np.abs(heave).max())
    assert lag[-1] > 0
    assert np.abs(z_aft[:n]).max() < 1e-15 and np.abs(z_up[3 * n :]).max() < 1e-15
