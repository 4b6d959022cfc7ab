"""solver.model.layout: where each unknown, equation and parameter sits."""

from __future__ import annotations

import numpy as np
import pytest

from solver import Layout


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


def test_the_parameter_vector_splits_back_into_its_parts():
    layout = Layout(3, 2)
    arrays = tuple(np.full(3, float(k)) for k in range(6))
    camber = np.arange(9.0).reshape(3, 3)
    p = layout.parameters(arrays, camber, 7.5, 20.0, True)
    assert p.shape == (layout.n_parameters,)
    *parts, camber_part, alpha, sweep, deformed = layout.split(p)
    for k, part in enumerate(parts):
        np.testing.assert_array_equal(part, np.full(3, float(k)))
    np.testing.assert_array_equal(camber_part, camber.ravel())  # station-major
    assert (alpha, sweep, deformed) == (7.5, 20.0, 1.0)


def test_the_flow_models_parameters_follow_the_models_and_split_back():
    layout = Layout(3, 2)
    arrays = tuple(np.full(3, float(k)) for k in range(6))
    control = -np.arange(9.0).reshape(3, 3)
    direction = np.arange(float(layout.n_unknowns))
    p = np.concatenate(
        [
            layout.parameters(arrays, np.zeros((3, 3)), 7.5, 20.0, True),
            layout.flow_parameters(-1.0, 1.0, 0.25, control, direction),
        ]
    )
    assert p.shape == (layout.n_parameters + layout.n_flow_parameters,)
    assert p[layout.alpha_index] == 7.5 and p[layout.roll_rate_index] == 0.25
    image, image_jacobian, roll_rate, control_part, direction_part = layout.split_flow(p)
    assert (image, image_jacobian, roll_rate) == (-1.0, 1.0, 0.25)
    np.testing.assert_array_equal(control_part, control.ravel())
    np.testing.assert_array_equal(direction_part, direction)
    np.testing.assert_array_equal(p[layout.direction_slice], direction)
    np.testing.assert_array_equal(p[layout.control_slice], control.ravel())


def test_the_default_flow_is_the_symmetric_one_without_disturbance():
    layout = Layout(4, 1)
    image, image_jacobian, roll_rate, control, direction = layout.split_flow(
        np.concatenate([np.zeros(layout.n_parameters), layout.flow_parameters()])
    )
    assert (image, image_jacobian, roll_rate) == (1.0, 1.0, 0.0)
    assert not np.any(control) and not np.any(direction)
