"""solver.statics.system: one wing at one alpha as modelled, keyed canonically, sharing what it
can."""

from __future__ import annotations

import numpy as np
import pytest

import solver
from solver import SolverOptions
from solver.statics.system import CoupledSystem
from tests.study import study_arrays, study_wing


def test_equal_wings_and_alphas_have_one_key_whatever_the_sign_of_zero():
    wing = study_wing(12)
    assert CoupledSystem(wing, 0.0).key == CoupledSystem(study_wing(12), -0.0).key
    assert CoupledSystem(wing, 5.0).key != CoupledSystem(wing, 5.0, chordwise=2).key
    assert CoupledSystem(wing, 5.0).key != CoupledSystem(wing, 5.0, deformed_axis=True).key
    assert CoupledSystem(wing, 5.0).key != CoupledSystem(wing, 5.0, aerodynamics="strip").key
    options = SolverOptions(chordwise_panels=3, torque_axis="deformed", aerodynamics="strip")
    system = CoupledSystem.of(wing, 5.0, options)
    assert system.key == (wing.key, 5.0, 3, True, "strip")
    assert system.model_key == (wing.key, 3, True, "strip")  # what the wing at rest keys
    assert system.at_alpha(1.0).model_key == system.model_key


def test_at_another_alpha_only_alpha_changes_and_the_model_is_shared():
    system = CoupledSystem(study_wing(12), 5.0)
    other = system.at_alpha(-2.0)
    assert other.model is system.model and other.layout is system.layout
    changed = np.flatnonzero(other.parameters != system.parameters)
    assert changed.tolist() == [system.layout.slot("alpha").start]
    assert other.parameters[system.layout.slot("alpha")] == -2.0
    np.testing.assert_array_equal(other.parameters, CoupledSystem(study_wing(12), -2.0).parameters)


def test_the_parameter_vector_is_read_only():
    parameters = CoupledSystem(study_wing(12), 5.0).parameters
    with pytest.raises(ValueError, match="read-only"):
        parameters[0] = 1.0


def test_the_residual_alone_is_the_evaluations_residual():
    system = CoupledSystem(study_wing(12), 5.0)
    state = np.random.default_rng(5).normal(scale=0.01, size=system.layout.n_unknowns)
    r0, r1 = system.residual(state)
    evaluation = system.evaluate(state)
    # Two compiled functions (the residual alone, and with its Jacobians) sum the same terms
    # in their own orders: equal to round-off, not to the bit.
    np.testing.assert_allclose(r0, evaluation.r0, rtol=1e-13, atol=1e-15)
    np.testing.assert_allclose(r1, evaluation.r1, rtol=1e-13, atol=1e-15)


@pytest.mark.parametrize(
    "ask",
    [
        lambda wing, strip: solver.roll(wing, solver.FlightCondition(12.0, 5.0), strip),
        lambda wing, strip: solver.control_sweep(wing, [12.0], 5.0, 1.225, strip),
    ],
    ids=["roll", "control_sweep"],
)
def test_strip_theory_has_no_flow_model_and_says_so_naming_the_option(ask) -> None:
    """Found by the operation x option matrix: /roll and /controls under strip theory were a
    500 (the residual's builder refused the flow model with a ValueError). Control
    derivatives, roll and the antisymmetric flow are the lattice's: the refusal names
    `options.aerodynamics`."""
    aileron = {"name": "aileron", "start": 0.55, "end": 0.95, "hinge": 0.5, "kind": "aileron"}
    wing = solver.Wing.create(**study_arrays(), control_surfaces=[aileron | {"deflection": 5.0}])
    strip = solver.SolverOptions(aerodynamics="strip", chordwise_panels=2)
    with pytest.raises(solver.InvalidInput) as raised:
        ask(wing, strip)
    assert raised.value.field == "options.aerodynamics"
