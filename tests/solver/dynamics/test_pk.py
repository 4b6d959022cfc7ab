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
