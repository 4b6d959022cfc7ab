"""solver.dynamics.pk: the p-k fixed point of each root, followed up the airspeeds."""

from __future__ import annotations

import numpy as np

import solver
from solver.dynamics.flutter import flutter
from solver.inputs.mass import MassModel
from tests.study import DENSITY, study_wing


def test_a_heavily_damped_slow_root_reaches_its_fixed_point():
    """The study's light wing under the unsteady lattice, just below its divergence (24.2 m/s):
    its first root, damped 0.995 and oscillating at ~2 rad/s before it turns real, has
    d(Im s - omega)/d omega ~ -0.1: a plain fixed-point step leaves 0.9 of the mismatch, 230
    steps to 1e-10, more than the default 100. The secant takes it there in a few, at every
    airspeed (each point solved), and the divergence is the lattice's static one."""
    n = 30
    wing = study_wing(n)
    mass = MassModel.create(n, 1.0, 0.42, 0.02)
    options = solver.SolverOptions(aerodynamics="unsteady_lattice")
    result = flutter(wing, mass, np.linspace(1.0, 40.0, 50), DENSITY, options=options)
    assert all(point.status == "solved" for point in result.points)
    static = solver.linear_divergence(wing, DENSITY, solver.SolverOptions())
    assert result.divergence is not None and static.velocity is not None
    assert result.divergence.velocity == static.velocity


class _Springs:
    """Undamped unit masses on the springs `stiffness` (n, n) [N/m], lightly damped (1e-3 of
    each root's frequency) so that every root lies in the upper half-plane: the p-k interface
    (`solver.dynamics.reduced.Equations`) with loads of no frequency."""

    def __init__(self, stiffness: np.ndarray) -> None:
        self.stiffness = stiffness

    def roots(
        self, frequencies: np.ndarray, velocity: float, density: float, lagged: bool
    ) -> np.ndarray:
        omega = np.sqrt(np.linalg.eigvalsh(self.stiffness))
        upper = np.concatenate([-1e-3 * omega + 1j * omega, -1e-3 * omega - 1j * omega])
        return np.tile(upper, (len(frequencies), 1))

    def blend(self, other: _Springs, weight: float) -> _Springs:
        return _Springs((1 - weight) * self.stiffness + weight * other.stiffness)


def test_pk1_a_pair_of_near_roots_split_by_a_load_stays_two_roots():
    """The bent HALE wing's case in miniature: roots at 30.16 and 31.76 rad/s (torsion and lag
    straight) that the load couples into 24.5 and 50, the upper one crossing a third root at
    39.3 on its way. Followed through the blended equations (`Follower._blend`), each ends on
    its own root: a step on which two roots would become one is halved, and each root starts
    where its last two head (at four plain steps the pair fell on one root)."""
    from solver.dynamics.pk import Follower, Tracking

    straight = np.diag([30.157**2, 31.757**2, 39.3**2])
    a = 30.157**2
    b = 24.5**2 + 50.0**2 - a
    c = np.sqrt(a * b - (24.5 * 50.0) ** 2)
    bent = np.array([[a, c, 0.0], [c, b, 0.0], [0.0, 0.0, 39.3**2]])
    follower = Follower(_Springs(straight), 1.0, Tracking(False, 1e-9, 10), 1.0)
    start = follower.history[0][1]  # still air: 30.16, 31.76, 39.3 rad/s
    ends = follower._blend(_Springs(straight), _Springs(bent), start, 1.0)
    np.testing.assert_allclose(ends.imag, [24.5, 50.0, 39.3], rtol=1e-9)
