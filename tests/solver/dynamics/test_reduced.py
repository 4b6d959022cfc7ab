"""solver.dynamics.reduced: the equations on the flutter basis; the unsteady lattice's tabulated
in reduced frequency, interpolated between its nodes."""

from __future__ import annotations

import numpy as np

import solver
from solver.dynamics.flutter import FlutterOptions, _model
from solver.dynamics.lattice_loads import lattice_loads
from solver.dynamics.linearisation import States
from solver.dynamics.modes import structure
from solver.dynamics.reduced import LatticeEquations, reduced_frequency_nodes
from solver.statics.jig import at_rest
from solver.unsteady_lattice.panels import panels
from solver.unsteady_lattice.wake import shed_wake
from tests.flutter_reference import SEA_LEVEL, goland_mass, goland_wing


def test_the_nodes_run_from_zero_to_the_largest_then_infinity():
    nodes = reduced_frequency_nodes(2.0, 12)
    assert nodes.shape == (13,) and nodes[0] == 0.0 and abs(nodes[-2] - 2.0) < 1e-12
    assert np.isinf(nodes[-1]) and np.all(np.diff(nodes[:-1]) > 0)
    assert nodes[1] < nodes[-2] / 20  # denser at low k


def test_between_its_nodes_the_lattice_is_interpolated_closely():
    """The tabulated matrices (12 nodes to k = 2) against the lattice solved at reduced
    frequencies between them, on the Goland wing's basis: within 5e-4 of the largest entry up
    to k = 2 (measured 1.6e-4 at k = 0.01, where the wake's lag grows as k log k; 5e-7 at the
    flutter's k = 0.3, where the flutter speed moves by 1e-6, tests/solver/dynamics/
    test_flutter.py), within 5e-3 beyond, towards the infinite-frequency limit (3.7e-3 at k =
    3: low airspeeds, where the air's loads are small beside the structure's); exactly that
    limit in still air (to round-off)."""
    wing, mass = goland_wing(12), goland_mass(12)
    options = solver.SolverOptions(aerodynamics="unsteady_lattice", chordwise_panels=2)
    beam = structure(wing, mass)
    states = States(wing, SEA_LEVEL, None, None, options)
    basis, build = _model(beam, states, options, FlutterOptions(), 6)
    equations = states.equations(0.0, build)
    assert isinstance(equations, LatticeEquations)
    between = np.array([0.01, 0.07, 0.3, 0.8, 1.7, 3.0])
    b = equations.semichord
    jig = panels(wing, 2)
    loads = lattice_loads(beam, states.rest.layout, at_rest(states.rest).evaluation, jig)
    exact = loads.modal(shed_wake(jig, between / b), basis.right, basis.left)
    interpolated = equations.aerodynamics(between)
    for ours, theirs in zip(
        interpolated, (exact.stiffness, exact.damping, exact.inertia), strict=True
    ):
        scale = np.abs(theirs).max()
        np.testing.assert_allclose(ours[:5], theirs[:5], rtol=0, atol=5e-4 * scale)
        np.testing.assert_allclose(ours[5], theirs[5], rtol=0, atol=5e-3 * scale)
    still = equations.aerodynamics(np.array([np.inf]))[2][0]  # the spline at its last node
    limit = equations.lattice_inertia[-1]
    np.testing.assert_allclose(still, limit, rtol=0, atol=1e-14 * np.abs(limit).max())
