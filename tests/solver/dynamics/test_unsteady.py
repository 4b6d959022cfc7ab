"""solver.dynamics.unsteady: Theodorsen's function and section loads, and the loads of small
oscillations taken from the static model's exact Jacobian: Theodorsen's strip theory exactly
under strip aerodynamics, the static model itself at zero frequency under either."""

from __future__ import annotations

import math

import numpy as np
import pytest

import solver
from solver import SolverOptions
from solver.dynamics.modes import structure
from solver.dynamics.unsteady import (
    _upwash,
    theodorsen,
    theodorsen_section,
    unsteady_aerodynamics,
)
from solver.inputs.mass import MassModel
from solver.model.layout import Layout
from solver.statics.jig import at_rest
from solver.statics.system import CoupledSystem
from tests.flutter_reference import goland_mass, goland_wing
from tests.solver.dynamics.test_modes_lag import lagging

# Theodorsen 1935 (NACA Report 496), F and G of C(k) = F + i G to 4 decimals, as reproduced in
# Bisplinghoff, Ashley and Halfman 1955 and Fung 1955 (their tables round the last digit).
TABULATED = {
    0.1: (0.8319, -0.1723),
    0.2: (0.7276, -0.1886),
    0.5: (0.5979, -0.1507),
    1.0: (0.5394, -0.1003),
}


@pytest.mark.parametrize("k", list(TABULATED), ids=[f"k={k}" for k in TABULATED])
def test_theodorsens_function_is_the_tabulated_one(k: float):
    value = complex(theodorsen(k))
    f, g = TABULATED[k]
    assert value.real == pytest.approx(f, abs=1e-4)
    assert value.imag == pytest.approx(g, abs=1e-4)


def test_theodorsens_function_is_quasi_steady_at_zero_and_halved_at_infinity():
    values = theodorsen(np.array([0.0, 1e-8, 1e4]))
    assert values[0] == 1.0
    assert abs(values[1] - 1) < 1e-6  # C -> 1 as k -> 0 (like 1 + k log k)
    assert abs(values[2] - 0.5) < 1e-4  # C = 1/2 + O(1/k)


def test_a_section_in_slow_motion_carries_the_steady_thin_airfoil_loads():
    """As omega -> 0 the lift per pitch is 2 pi q c and acts at the quarter chord: the moment
    about the elastic axis is the lift times its lever (a + 1/2) b (Theodorsen 1935)."""
    velocity, density, b, a = 50.0, 1.1, 0.6, -0.2
    loads = theodorsen_section(1e-9, velocity, density, b, a)
    q = 0.5 * density * velocity**2
    assert loads[0, 1] == pytest.approx(2 * math.pi * q * 2 * b, rel=1e-8)
    assert loads[1, 1] == pytest.approx((a + 0.5) * b * loads[0, 1], rel=1e-8)
    assert abs(loads[0, 0]) < 1e-6 * abs(loads[0, 1])  # a slow heave carries nothing


@pytest.fixture(scope="module")
def goland_strip():
    wing, mass = goland_wing(12), goland_mass(12)
    beam = structure(wing, mass)
    system = CoupledSystem.of(wing, 0.0, SolverOptions(aerodynamics="strip"))
    return wing, beam, unsteady_aerodynamics(beam, system.layout, at_rest(system).evaluation)


@pytest.mark.parametrize("frequency", [5.0, 70.0, 400.0], ids=["k=0.04", "k=0.5", "k=2.9"])
def test_under_strip_theory_the_loads_are_theodorsens_strip_by_strip(goland_strip, frequency):
    """Every strip carries Theodorsen's lift and moment of its own mean heave and pitch, from
    reduced frequency 0.04 to 2.9: the static model's Jacobian (its circulatory part), the
    three-quarter-chord upwash and the apparent mass together are exactly the section theory.
    Round-off: 1e-9 of the largest load."""
    wing, beam, aero = goland_strip
    velocity, density = 130.0, 1.225
    deformation = np.random.default_rng(11).normal(size=beam.n_dof)
    loads = aero.loads(1j * frequency, velocity, density) @ deformation
    z = beam.states @ deformation
    n = wing.n_stations
    heave, pitch = z[:n], np.radians(z[2 * n :])
    mean_heave, mean_pitch = (heave[1:] + heave[:-1]) / 2, (pitch[1:] + pitch[:-1]) / 2
    section = theodorsen_section(frequency, velocity, density, wing.chord[0] / 2, 2 * 0.33 - 1)
    width = np.diff(wing.y)
    expected = np.concatenate(
        [
            (section[0, 0] * mean_heave + section[0, 1] * mean_pitch) * width,
            (section[1, 0] * mean_heave + section[1, 1] * mean_pitch) * width,
        ]
    )
    np.testing.assert_allclose(loads, expected, rtol=0, atol=1e-9 * np.abs(expected).max())


@pytest.mark.parametrize("aerodynamics", ["strip", "lattice"])
def test_at_zero_frequency_the_loads_are_the_static_models(aerodynamics: str):
    """K w = q Q w, Q the quasi-steady loads: its smallest positive q is the static linear
    divergence pressure of the same aerodynamics (`solver.linear_divergence_pressure`), to
    round-off of the two eigenproblems (1e-10)."""
    wing = solver.Wing.create(np.linspace(0, 8, 13), np.linspace(1.2, 0.7, 13), 0.45, 3e5, 2e4)
    options = SolverOptions(aerodynamics=aerodynamics)
    beam = structure(wing, MassModel.create(13, 5.0, 0.45, 0.5))
    system = CoupledSystem.of(wing, 0.0, options)
    aero = unsteady_aerodynamics(beam, system.layout, at_rest(system).evaluation)
    mu = np.linalg.eigvals(np.linalg.solve(beam.stiffness, aero.stiffness()))
    real = mu[(np.abs(mu.imag) < 1e-9 * np.abs(mu).max()) & (mu.real > 0)].real
    static = solver.linear_divergence_pressure(wing, options)
    assert static is not None
    assert 1 / real.max() == pytest.approx(static, rel=1e-10)


def _pitch_lift(wing: solver.Wing, aerodynamics: str) -> float:
    """[N per Pa per rad] the quasi-steady lift of a uniform unit pitch of every strip."""
    n = wing.n_stations
    beam = structure(wing, MassModel.create(n, 10.0, 0.4, 1.0))
    system = CoupledSystem.of(wing, 0.0, SolverOptions(aerodynamics=aerodynamics))
    aero = unsteady_aerodynamics(beam, system.layout, at_rest(system).evaluation)
    pitch = np.concatenate([np.zeros(n - 1), np.ones(n - 1)])  # w: heave 0, twist 1 rad
    return float(np.sum((aero.stiffness() @ pitch)[: n - 1]))


def test_the_lattice_lifts_less_than_strips_by_the_wings_3d_loss():
    """The lattice's circulation answers a pitch with the 3D wing's lift, strip theory's 2 pi
    per strip times the spanwise loading's loss: on the Goland wing's planform (aspect ratio
    6.7) 0.694 of strip theory, 0.879 at aspect ratio 22 and 0.955 at 66 (measured; a
    lifting line's AR / (AR + 2) gives 0.77, 0.92, 0.97: the lattice's tip loss is larger), rising
    to 1 as the aspect ratio grows. This is what lifts the lattice's flutter speed above strip
    theory's (tests/solver/test_flutter.py)."""
    ratios = []
    for semispan in (6.096, 20.0, 60.0):
        wing = solver.Wing.create(np.linspace(0, semispan, 31), 1.8288, 0.33, 1e7, 1e6)
        ratios.append(_pitch_lift(wing, "lattice") / _pitch_lift(wing, "strip"))
    assert ratios == pytest.approx([0.694, 0.879, 0.955], abs=0.005)
    assert ratios[0] < ratios[1] < ratios[2] < 1


def test_a_lag_rotation_of_a_bent_section_is_upwash_at_its_three_quarter_chord():
    """A section bent up by beta (about the chord e_c) and turned in the wing's plane by psi
    (about the jig's normal n) moves its three-quarter-chord point r = x e_c, x aft of the
    elastic axis, by psi n x r = x psi e_s: across the bent surface (normal -sin(beta) e_s +
    cos(beta) n) by -x sin(beta) psi, the vertical displacement whose rate is upwash. The
    motion's upwash of every w is the straight wing's plus that, to 1e-12 (3D cross products,
    unswept wing); a lag displacement alone moves no point across the plane."""
    n = 9
    wing = lagging(solver.Wing.create(np.linspace(0, 6, n), 1.0, 0.4, 4e5, 3e5))
    mass = MassModel.create(n, 2.0, 0.45, 0.3)
    lag = wing.in_plane_bending_stiffness
    layout = Layout(n, 2)
    straight = structure(wing, mass, in_plane_bending_stiffness=lag)
    beta = np.linspace(0.0, 0.6, n)
    bent = structure(wing, mass, in_plane_bending_stiffness=lag, flap_rotation=beta)
    aft = (0.75 - wing.elastic_axis) * wing.chord  # [m]
    e_s, e_c, normal = np.eye(3)[1], np.eye(3)[0], np.eye(3)[2]
    across = np.array(
        [
            np.dot(-np.sin(b) * e_s + np.cos(b) * normal, np.cross(normal, x * e_c))
            for b, x in zip(beta, aft, strict=True)
        ]
    )  # [m] per unit psi
    psi = bent.states[4 * n : 5 * n]  # (N, n)
    displacement = across[:, None] * psi
    expected = -np.repeat((displacement[:-1] + displacement[1:]) / 2, 2, axis=0)
    difference = _upwash(bent, layout) - _upwash(straight, layout)
    scale = np.abs(_upwash(bent, layout)).max()
    np.testing.assert_allclose(difference, expected, rtol=0, atol=1e-12 * scale)
    assert np.abs(expected).max() > 0.01 * scale  # the term is there to be seen
    # The lag degrees of freedom (w's last N - 1) of the straight wing: no upwash at all.
    lag = slice(2 * (n - 1), None)
    assert np.abs(_upwash(straight, layout)[:, lag]).max() <= 1e-12 * scale
    assert np.abs(_upwash(bent, layout)[:, lag]).max() > 0.01 * scale
