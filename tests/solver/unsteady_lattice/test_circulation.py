"""solver.unsteady_lattice.circulation: the circulation of harmonic motion, whose zero-frequency
limit is the static lattice's."""

from __future__ import annotations

import math

import numpy as np
import pytest

import solver
from solver.statics.jig import at_rest
from solver.statics.system import CoupledSystem
from solver.unsteady_lattice.circulation import gust_normalwash, harmonic_lattice
from solver.unsteady_lattice.panels import panels
from solver.unsteady_lattice.wake import shed_wake

DENSITY, SPEED = 1.225, 30.0


def _rigid_wing(**given) -> solver.Wing:
    """Stiff enough that the equilibria below are the jig to 1e-9 of their circulation."""
    return solver.Wing.create(
        np.linspace(0, 4, 13), np.linspace(1.2, 0.6, 13), 0.35, 1e12, 1e12, **given
    )


@pytest.mark.parametrize(
    ("given", "chordwise"),
    [({}, 1), ({"sweep": 20.0, "jig_twist": 2.0, "airfoil": "naca2412"}, 4)],
    ids=["flat", "swept-twisted-cambered"],
)
def test_at_zero_frequency_a_gust_is_the_static_lattices_change_of_incidence(given, chordwise):
    """A slow gust of angle w_g / V tilts the flow as alpha does: the unsteady lattice's
    circulation at kappa -> 0 is d(circulation)/d(sin alpha) of `solver.solve`'s equilibria
    (central difference at +-0.5 deg: the rigid jig's circulation is exactly cos(alpha) g_cos
    + sin(alpha) g_sin, so the difference over 2 sin(0.5 deg) is g_sin to round-off): within
    1e-6 of the largest, the issue's steady limit (measured ~1e-9, the solves' tolerance)."""
    wing = _rigid_wing(**given)
    options = solver.SolverOptions(chordwise_panels=chordwise)
    system = CoupledSystem.of(wing, 0.0, options)
    layout = system.layout
    influence = at_rest(system).evaluation.jacobian0[layout.tangency_rows, layout.circulation]
    grid = panels(wing, chordwise)
    flow = harmonic_lattice(influence, shed_wake(grid, np.array([1e-9])))
    unsteady = flow.circulation(0, gust_normalwash(grid, 1e-9))
    delta = 0.5
    states = [
        solver.solve(wing, solver.FlightCondition(SPEED, a, DENSITY), options=options).state
        for a in (delta, -delta)
    ]
    static = (states[0] - states[1])[layout.circulation] / (2 * math.sin(math.radians(delta)))
    np.testing.assert_allclose(unsteady, static, rtol=0, atol=1e-6 * np.abs(static).max())
    assert np.abs(unsteady.imag).max() < 1e-6 * np.abs(static).max()


def test_statics_with_the_unsteady_lattice_are_the_lattices():
    """The unsteady lattice's steady limit is the lattice: a static answer with it is the
    lattice's, bit for bit, on the lattice's compiled model (no model of its own)."""
    wing = solver.Wing.create(np.linspace(0, 5, 12), 1.0, 0.4, 2e4, 1e3)
    flight = solver.FlightCondition(12.0, 4.0, DENSITY)
    lattice = solver.solve(wing, flight, options=solver.SolverOptions())
    unsteady = solver.solve(
        wing, flight, options=solver.SolverOptions(aerodynamics="unsteady_lattice")
    )
    np.testing.assert_array_equal(unsteady.state, lattice.state)
    assert unsteady.totals.lift == lattice.totals.lift
    system = CoupledSystem.of(wing, 4.0, solver.SolverOptions(aerodynamics="unsteady_lattice"))
    assert system.layout == CoupledSystem.of(wing, 4.0, solver.SolverOptions()).layout
