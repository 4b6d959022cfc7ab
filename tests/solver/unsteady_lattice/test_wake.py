"""solver.unsteady_lattice.wake: the convected wake's normalwash, against the two-dimensional
wake in closed form, and its limits."""

from __future__ import annotations

import numpy as np
import scipy.special

import solver
import solver.unsteady_lattice.wake as wake_module
from solver.unsteady_lattice.panels import panels
from solver.unsteady_lattice.wake import shed_wake, wake_normalwash


def test_a_very_long_strips_wake_is_the_two_dimensional_wake():
    """A strip 400 chords wide, seen from its middle: its wake sheet, shed at distance d behind
    the collocation point with the spanwise vorticity -i kappa e^{-i kappa xi} per unit
    circulation, induces in 2D (Biot-Savart, integrated in closed form)

        w = -(i kappa / 2 pi) e^{i kappa d} E_1(i kappa d).

    Within 1e-2 for kappa d from 0.0125 to 1.25: the finite span's own share is ~ 1 / (kappa
    S) of the far wake (6e-3 at the lowest kappa), the quadrature's 3e-4."""
    semispan = 800.0
    wing = solver.Wing.create([0.0, semispan / 2, semispan], 1.0, 0.25, 1e6, 1e6)
    grid = panels(wing, 1)
    d = grid.shed_left[0, 0] - grid.collocation[0, 0]  # a quarter chord
    kappa = np.array([0.05, 0.2, 1.0, 5.0])
    wake = wake_normalwash(grid, kappa)[:, 0, :].sum(axis=1)  # the strip and its neighbour
    z = 1j * kappa * d
    exact = -1j * kappa / (2 * np.pi) * np.exp(z) * scipy.special.exp1(z)
    np.testing.assert_allclose(wake, exact, rtol=1e-2)
    assert abs(wake[-1] - exact[-1]) < 1e-3 * abs(exact[-1])  # the near wake: quadrature alone


def test_the_wake_adds_nothing_at_zero_frequency_and_cancels_its_legs_at_infinity():
    """W(0) = 0 exactly (the steady wake is the horseshoes' own); as kappa grows W tends to
    -n . H(0), the strip's horseshoe from its trailing edge (the shed vorticity cancels the
    trailing legs at once), as 1 / (kappa d) with d the nearest collocation point's distance
    to the trailing edge (an eighth of the chord here): within 1e-3 of the limit at kappa d =
    2.5e4."""
    wing = solver.Wing.create(np.linspace(0, 3, 7), 1.0, 0.3, 1e5, 1e4)
    grid = panels(wing, 2)
    zero, fast, infinite = shed_wake(grid, np.array([0.0, 2e5, np.inf])).influence
    assert np.all(zero == 0)
    np.testing.assert_allclose(fast, infinite, rtol=0, atol=1e-3 * np.abs(infinite).max())


def test_the_wake_quadrature_is_converged(monkeypatch):
    """Intervals growing by 1.01 instead of 1.04, starting four times smaller, and the wake
    sampled twice as far aft move W by less than 1e-3 of its largest value at kappa c = 0.1
    to 10, on a swept wing whose wakes pass beside each other's collocation points (measured
    5e-4: the linear interpolation between samples, ~ (growth - 1)^2 / 8 of their curvature;
    the Goland wing's flutter speed moves by 1e-5, tests/solver/dynamics/test_flutter.py)."""
    wing = solver.Wing.create(np.linspace(0, 3, 7), 1.0, 0.3, 1e5, 1e4, sweep=20.0)
    grid = panels(wing, 3)
    kappa = np.array([0.1, 1.0, 10.0])
    coarse = wake_normalwash(grid, kappa)
    monkeypatch.setattr(wake_module, "_GROWTH", 1.01)
    monkeypatch.setattr(wake_module, "_FIRST", wake_module._FIRST / 4)
    monkeypatch.setattr(wake_module, "_LENGTH", 2 * wake_module._LENGTH)
    fine = wake_normalwash(grid, kappa)
    for a, b in zip(coarse, fine, strict=True):
        np.testing.assert_allclose(a, b, rtol=0, atol=1e-3 * np.abs(b).max())
