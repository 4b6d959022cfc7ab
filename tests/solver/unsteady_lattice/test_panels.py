"""solver.unsteady_lattice.panels: the statics' panels as numbers, their trailing edges and the
unsteady pressure's patches."""

from __future__ import annotations

import math

import numpy as np
import pytest

import solver
from solver.unsteady_lattice.panels import panels


def _wing(**given):
    return solver.Wing.create(
        np.linspace(0, 5, 11), np.linspace(2.0, 1.0, 11), 0.4, 1e5, 1e4, **given
    )


@pytest.mark.parametrize("sweep", [0.0, 30.0], ids=["unswept", "swept"])
def test_the_patches_cover_the_planform_and_a_bit_more(sweep):
    """The whole-panel patches tile the right half's planform (trapezoids between stations:
    the area is exact, 1e-12); the patches aft of each vortex add 3/4 of it."""
    wing = _wing(sweep=sweep)
    grid = panels(wing, 4)
    m = grid.n_panels
    half = wing.planform_area / 2
    assert grid.patch_area[:m, 2].sum() == pytest.approx(half, rel=1e-12)
    assert grid.patch_area[m:, 2].sum() == pytest.approx(0.75 * half, rel=1e-12)
    assert np.allclose(grid.patch_area[:, :2], 0, atol=1e-12)  # flat jig: vertical


def test_the_trailing_edges_are_the_chords_ends_turned_by_the_twist():
    """Each strip sheds from its stations' trailing edges: x = y tan(sweep) + (1 - x_ea) c
    cos(t) and z = -(1 - x_ea) c sin(t), t the jig twist (nose-up: the trailing edge drops).
    The sections turn about the local span axis, which the tapered wing's twisted leading edge
    tilts by ~7e-3 rad: z to 1e-4 (its cosine, 1 - 2.5e-5), x exactly."""
    twist = 4.0
    wing = _wing(sweep=10.0, jig_twist=twist)
    grid = panels(wing, 3)
    aft = (1 - 0.4) * wing.chord
    t = math.radians(twist)
    x = wing.y * math.tan(math.radians(10.0)) + aft * math.cos(t)
    np.testing.assert_allclose(grid.shed_left[:, 0], x[:-1], rtol=1e-12)
    np.testing.assert_allclose(grid.shed_right[:, 0], x[1:], rtol=1e-12)
    np.testing.assert_allclose(grid.shed_right[:, 2], -aft[1:] * math.sin(t), rtol=1e-4)


def test_each_patch_carries_the_circulation_bound_ahead_of_it():
    """The potential jump on a panel is the sum of its strip's circulations ahead of it, and
    aft of its own vortex its own circulation too: each strip's row sums 0, 1, ..., k - 1 for
    the whole-panel patches."""
    grid = panels(_wing(), 4)
    m = grid.n_panels
    np.testing.assert_array_equal(grid.patch_potential[:m].sum(axis=1), np.tile([0, 1, 2, 3], 10))
    np.testing.assert_array_equal(grid.patch_potential[m:], np.eye(m))
