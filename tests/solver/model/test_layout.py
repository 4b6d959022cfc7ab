"""solver.model.layout: where each unknown, equation and named parameter slot sits."""

from __future__ import annotations

import casadi as ca
import numpy as np
import pytest

import solver
from solver import Layout
from solver.model.layout import FLOW_SLOTS, MODEL_SLOTS, WING_SLOTS


@pytest.mark.parametrize(("n", "k"), [(3, 1), (30, 1), (150, 1), (30, 4)])
def test_unknowns_and_equations_tile_the_system(n: int, k: int):
    layout = Layout(n, k)
    assert layout.n_unknowns == 3 * n + (n - 1) * k
    unknowns = np.zeros(layout.n_unknowns, dtype=int)
    for part in (layout.heave, layout.slope, layout.twist, layout.circulation):
        unknowns[part] += 1
    assert np.all(unknowns == 1)
    equations = np.zeros(layout.n_unknowns, dtype=int)
    equations[:3] += 1  # root clamps
    equations[3 : 3 + layout.n_strips] += 1  # heave kinematics
    for rows in (layout.bending_rows, layout.torsion_rows, layout.tangency_rows):
        equations[rows] += 1
    assert np.all(equations == 1)


def test_the_load_rows_are_the_bending_and_torsion_rows():
    layout = Layout(5)
    rows = np.arange(layout.n_unknowns)
    expected = np.r_[rows[layout.bending_rows], rows[layout.torsion_rows]]
    np.testing.assert_array_equal(layout.load_rows, expected)


def _wing() -> solver.Wing:
    return solver.Wing.create([0.0, 1.0, 2.0], [1.0, 0.8, 0.6], 0.4, 2e3, 3e2, sweep=20.0)


def _values(layout: Layout) -> dict[str, object]:
    """Every slot of the model's table by name: a wing's fields, camber, alpha, torque axis."""
    camber = np.arange(float(layout.length("camber"))).reshape(layout.n, -1)
    return layout.wing_values(_wing()) | {"camber": camber, "alpha": 7.5, "deformed_axis": True}


def test_the_wings_slots_are_its_compiled_fields_in_declaration_order():
    compiled = [name for name, spec in solver.specs(solver.Wing).items() if spec.compiled]
    assert [slot.name for slot in WING_SLOTS] == compiled
    assert {"y", "chord", "elastic_axis", "sweep", "jig_twist"} <= set(compiled)
    assert not {"airfoil", "spar", "mass", "control_surfaces", "cl_max"} & set(compiled)
    sizes = {slot.name: slot.size for slot in WING_SLOTS}
    assert sizes["chord"] == "station" and sizes["sweep"] == "scalar"


@pytest.mark.parametrize(("n", "k"), [(3, 1), (3, 2), (30, 4)])
def test_the_slots_tile_the_parameter_vectors_the_flow_models_after_the_models(n: int, k: int):
    layout = Layout(n, k)
    covered = np.zeros(layout.n_parameters + layout.n_flow_parameters, dtype=int)
    for slot in layout.table(flow=True):
        covered[layout.slot(slot.name)] += 1
        assert layout.length(slot.name) == layout.size(slot)
    assert np.all(covered == 1)
    assert all(layout.slot(slot.name).stop <= layout.n_parameters for slot in MODEL_SLOTS)
    assert all(layout.slot(slot.name).start >= layout.n_parameters for slot in FLOW_SLOTS)
    assert layout.length("camber") == layout.length("control") == n * (k + 1)
    assert layout.length("direction") == layout.n_unknowns


def test_a_packed_vector_unpacks_to_the_values_by_name():
    layout = Layout(3, 2)
    values = _values(layout)
    p = layout.pack(values)
    assert p.shape == (layout.n_parameters,)
    part = layout.unpack(p)
    wing = _wing()
    for name in ("y", "chord", "elastic_axis", "bending_stiffness", "jig_twist"):
        np.testing.assert_array_equal(getattr(part, name), getattr(wing, name))
    np.testing.assert_array_equal(part.camber, np.ravel(values["camber"]))  # station-major
    assert (part.alpha, part.sweep, part.deformed_axis) == (7.5, 20.0, 1.0)
    with pytest.raises(AttributeError, match="image"):
        _ = part.image  # the model's vector has no flow slots


def test_the_flow_models_vector_holds_the_models_slots_then_its_own():
    layout = Layout(3, 2)
    control = -np.arange(9.0).reshape(3, 3)
    direction = np.arange(float(layout.n_unknowns))
    flow = {"image": -1.0, "image_jacobian": 1.0, "roll_rate": 0.25}
    p = layout.pack(_values(layout) | flow | {"control": control, "direction": direction}, True)
    assert p.shape == (layout.n_parameters + layout.n_flow_parameters,)
    np.testing.assert_array_equal(p[: layout.n_parameters], layout.pack(_values(layout)))
    part = layout.unpack(p)
    assert (part.image, part.image_jacobian, part.roll_rate, part.alpha) == (-1.0, 1.0, 0.25, 7.5)
    np.testing.assert_array_equal(part.control, control.ravel())
    np.testing.assert_array_equal(p[layout.slot("direction")], direction)


def test_packing_names_a_missing_an_unknown_or_a_misfit_slot():
    layout = Layout(3, 2)
    values = _values(layout)
    with pytest.raises(KeyError, match="'alpha' is not given"):
        layout.pack({k: v for k, v in values.items() if k != "alpha"})
    with pytest.raises(KeyError, match="'wingspan'"):
        layout.pack(values | {"wingspan": 4.0})
    with pytest.raises(KeyError, match="'image' is not given"):
        layout.pack(values, flow=True)
    with pytest.raises(ValueError, match="'chord' holds 3 numbers, given 2"):
        layout.pack(values | {"chord": [1.0, 2.0]})
    with pytest.raises(KeyError, match="'span'"):
        layout.slot("span")


def test_a_symbolic_vector_unpacks_to_symbols_by_name():
    """The compiled model reads its parameters by name from its symbol: the same slots."""
    layout = Layout(3, 2)
    p = ca.MX.sym("p", layout.n_parameters)
    part = layout.unpack(p)
    function = ca.Function("f", [p], [part.chord, part.camber, part.alpha, part.sweep])
    values = layout.pack(_values(layout))
    chord, camber, alpha, sweep = (np.array(v).ravel() for v in function(values))
    np.testing.assert_array_equal(chord, _wing().chord)
    np.testing.assert_array_equal(camber, np.ravel(_values(layout)["camber"]))
    assert (alpha.item(), sweep.item()) == (7.5, 20.0)


def test_the_positional_forms_are_deprecated_and_answer_as_the_named_ones():
    """Layout is public: its positional forms stay for a release (DeprecationWarning)."""
    layout = Layout(3, 2)
    wing = _wing()
    arrays = (wing.y, wing.chord, wing.elastic_axis, wing.bending_stiffness)
    arrays += (wing.torsional_stiffness, wing.jig_twist)
    camber = np.asarray(_values(layout)["camber"])
    with pytest.warns(DeprecationWarning, match="Layout.pack"):
        p = layout.parameters(arrays, camber, 7.5, 20.0, True)
    np.testing.assert_array_equal(p, layout.pack(_values(layout)))
    with pytest.warns(DeprecationWarning):
        *parts, camber_part, alpha, sweep, deformed = layout.split(p)
    np.testing.assert_array_equal(camber_part, camber.ravel())
    for part, array in zip(parts, arrays, strict=True):
        np.testing.assert_array_equal(part, array)
    assert (alpha, sweep, deformed) == (7.5, 20.0, 1.0)
    with pytest.warns(DeprecationWarning):
        flow = layout.flow_parameters(-1.0, 1.0, 0.25)
    full = np.concatenate([p, flow])
    with pytest.warns(DeprecationWarning):
        assert layout.split_flow(full)[:3] == (-1.0, 1.0, 0.25)
    with pytest.warns(DeprecationWarning):
        assert full[layout.alpha_index] == 7.5 and full[layout.roll_rate_index] == 0.25
    with pytest.warns(DeprecationWarning, match="Wing.arrays"):
        assert len(wing.arrays()) == 6
