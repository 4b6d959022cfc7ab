"""solver.model.strip: strip theory's induced velocities, each strip a two-dimensional airfoil."""

from __future__ import annotations

import math

import numpy as np
import pytest

import solver
import solver.statics.jig
from solver.statics.system import CoupledSystem
from tests.solver.model.test_residual import _deformed_state, _swept_cambered_twisted


@pytest.mark.parametrize("k", [1, 2, 4])
def test_strip_theory_gives_a_flat_plate_the_thin_airfoils_lift(k: int):
    """Each strip a two-dimensional airfoil normal to its bound vortices: a rigid flat strip of a
    swept wing lifts 2 pi q c dy sin(alpha) cos(sweep), thin-airfoil theory (which the discrete
    vortex airfoil, vortices at the panels' quarter points, reproduces for a flat plate with any
    number of panels) with the independence principle's cos(sweep). The lattice's 3D lift on the
    same wing is 20 % lower. Round-off only: 1e-12. (On a tapered wing the chordwise panels'
    quarter lines are not parallel, and the strip is two-dimensional only to O(taper^2).)"""
    n, sweep = 9, 20.0
    wing = solver.Wing.create(np.linspace(0, 4, n), 0.8, 0.4, 1e4, 1e3, sweep=sweep)
    alpha = 3.0
    angle = math.radians(alpha)
    strip = CoupledSystem(wing, alpha, k, aerodynamics="strip")
    force = strip.panel_loads(solver.statics.jig.at_rest(strip).rigid_state(alpha))[0]  # per unit q
    strip_lift = (force[2] * math.cos(angle) - force[0] * math.sin(angle)).reshape(-1, k).sum(1)
    thin_airfoil = (
        2 * math.pi * 0.8 * np.diff(wing.y) * math.sin(angle) * math.cos(math.radians(sweep))
    )
    np.testing.assert_allclose(strip_lift, thin_airfoil, rtol=1e-12)
    lattice = CoupledSystem(wing, alpha, k)
    lattice_force = lattice.panel_loads(solver.statics.jig.at_rest(lattice).rigid_state(alpha))[0]
    lattice_lift = np.sum(lattice_force[2] * math.cos(angle) - lattice_force[0] * math.sin(angle))
    assert lattice_lift < 0.85 * thin_airfoil.sum()


def test_under_strip_theory_no_strip_sees_another():
    """The tangency rows of a strip involve only its own circulations, and the deformation of its
    own two stations and their neighbours (whose heave tilts the sections' local span axes, as
    AeroSandbox frames them): the influence block is block diagonal (k x k per strip), and
    nothing but the beam couples strips further apart."""
    system = CoupledSystem(_swept_cambered_twisted(), 4.0, 3, aerodynamics="strip")
    layout = system.layout
    jacobian = system.evaluate(_deformed_state(system, 5)).jacobian0
    tangency = jacobian[layout.tangency_rows]
    k = layout.chordwise
    for p in range(layout.n_panels):
        strip = p // k
        others = np.ones(layout.n_panels, dtype=bool)
        others[strip * k : strip * k + k] = False
        assert np.all(tangency[p, layout.circulation][others] == 0)
        assert np.any(tangency[p, layout.circulation][~others] != 0)
        stations = np.ones(layout.n, dtype=bool)
        stations[max(strip - 1, 0) : strip + 3] = False
        for part in (layout.heave, layout.slope, layout.twist):
            assert np.all(tangency[p, part][stations] == 0)
