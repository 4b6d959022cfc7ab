"""solver.model.horseshoe: one horseshoe vortex against Biot-Savart's law, written out
independently."""

from __future__ import annotations

import casadi as ca
import numpy as np
import pytest

from solver.model.horseshoe import horseshoe_velocity
from tests.solver.model.biot_savart import horseshoe, segment


def _kernel() -> ca.Function:
    field, left, right = (ca.SX.sym(name, 3) for name in ("field", "left", "right"))
    weight = ca.SX.sym("weight")
    return ca.Function(
        "hs", [field, left, right, weight], [horseshoe_velocity(field, left, right, weight)]
    )


POINTS = [
    pytest.param(np.array([0.3, 0.2, 0.1]), id="behind-and-above"),
    pytest.param(np.array([-1.0, 0.7, -0.2]), id="ahead-and-below"),
    pytest.param(np.array([0.05, -0.4, 0.0]), id="in-plane-outboard"),
    pytest.param(np.array([2.0, 0.25, 0.3]), id="far-downstream"),
]


@pytest.mark.parametrize("point", POINTS)
def test_a_horseshoe_induces_what_biot_savart_says(point):
    left, right = np.array([0.0, 0.0, 0.0]), np.array([0.1, 0.5, 0.02])
    ours = np.array(_kernel()(point, left, right, 1.0)).ravel()
    theirs = horseshoe(point, left, right)
    # The 1e7 m legs stand for infinite ones: their far ends contribute ~1e-14 relative.
    np.testing.assert_allclose(ours, theirs, rtol=1e-9, atol=1e-12)


def test_a_bound_leg_induces_nothing_at_its_own_midpoint_once_masked():
    left, right = np.array([0.0, 0.0, 0.0]), np.array([0.0, 1.0, 0.0])
    midpoint = (left + right) / 2
    masked = np.array(_kernel()(midpoint, left, right, 0.0)).ravel()
    downstream = np.array([1e7, 0.0, 0.0])
    trailing_only = segment(midpoint, left + downstream, left) + segment(
        midpoint, right, right + downstream
    )
    np.testing.assert_allclose(masked, trailing_only, rtol=1e-9)
    assert np.all(np.isfinite(masked))
