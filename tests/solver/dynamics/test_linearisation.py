"""solver.dynamics.linearisation: the state flutter linearises about, and what it carries."""

from __future__ import annotations

import numpy as np

import solver
from solver.dynamics.linearisation import States
from solver.statics.system import CoupledSystem
from tests.solver.model.test_hale_wing import hale_wing

EXACT = solver.SolverOptions(structure="geometrically_exact", aerodynamics="strip")


def test_li1_a_trimmed_exact_wing_is_linearised_with_its_weights_geometric_stiffness():
    """The HALE wing (its own 0.75 kg/m) trimmed to 150 N at 25 m/s carries its weight at 1 g,
    a dead load about the deformed stations under the exact beam: the Jacobians flutter takes
    about that equilibrium are those of the system with the weight (J1 holds the weight's
    derivative, its geometric stiffness), which differ from the weightless system's in the load
    rows by more than round-off (measured: 2.3e-3 of J1's largest load-row entry; held above
    1e-4)."""
    wing = hale_wing(9)
    states = States(wing, 0.0889, None, 150.0, EXACT)
    system, evaluation = states.evaluation(25.0)
    equilibrium = states.equilibria[25.0]
    assert not isinstance(equilibrium, Exception)
    q = 0.5 * 0.0889 * 25.0**2
    loaded = CoupledSystem.of(wing, equilibrium.totals.alpha, EXACT).with_inertia(1.0, q)
    expected = loaded.evaluate(equilibrium.state)
    rows = system.layout.load_rows
    scale = np.abs(expected.jacobian1).max()
    np.testing.assert_allclose(evaluation.jacobian1, expected.jacobian1, rtol=0, atol=1e-12 * scale)
    weightless = CoupledSystem.of(wing, equilibrium.totals.alpha, EXACT).evaluate(equilibrium.state)
    difference = np.abs(evaluation.jacobian1[rows] - weightless.jacobian1[rows]).max()
    assert difference > 1e-4 * np.abs(evaluation.jacobian1[rows]).max()
