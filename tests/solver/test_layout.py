"""solver.layout: where each unknown, equation and parameter sits."""

from __future__ import annotations

import numpy as np
import pytest

from solver import Layout


@pytest.mark.parametrize("n", [3, 30, 150])
def test_unknowns_and_equations_tile_the_system(n: int):
    layout = Layout(n)
    assert layout.n_unknowns == 4 * n - 1
    unknowns = np.zeros(layout.n_unknowns, dtype=int)
    for part in (layout.heave, layout.slope, layout.twist, layout.circulation):
        unknowns[part] += 1
    assert np.all(unknowns == 1)
    equations = np.zeros(layout.n_unknowns, dtype=int)
    equations[:3] += 1  # root clamps
    equations[3 : 3 + layout.n_panels] += 1  # heave kinematics
    for rows in (layout.bending_rows, layout.torsion_rows, layout.tangency_rows):
        equations[rows] += 1
    assert np.all(equations == 1)


def test_the_load_rows_are_the_bending_and_torsion_rows():
    layout = Layout(5)
    rows = np.arange(layout.n_unknowns)
    expected = np.r_[rows[layout.bending_rows], rows[layout.torsion_rows]]
    np.testing.assert_array_equal(layout.load_rows, expected)


def test_the_parameter_vector_ends_with_alpha():
    layout = Layout(3)
    arrays = tuple(np.full(3, float(k)) for k in range(5))
    p = layout.parameters(arrays, 7.5)
    assert p.shape == (layout.n_parameters,)
    assert p[-1] == 7.5
    np.testing.assert_array_equal(p[3:6], [1.0, 1.0, 1.0])
