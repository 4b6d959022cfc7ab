"""solver.model.vlm: the symmetric wing's pair kernels (both halves) against Biot-Savart's law and
CasADi's differentiation, and the source columns mapped over every panel."""

from __future__ import annotations

import casadi as ca
import numpy as np
import pytest

from solver.model.horseshoe import horseshoe_velocity
from solver.model.vlm import normal_pair_kernel, normal_source_columns, pair_kernel, source_columns
from tests.solver.model.biot_savart import horseshoe


def test_the_pair_kernel_adds_the_mirrored_left_half_and_its_derivatives_are_exact():
    """Both halves' horseshoes of one right-half panel, and g times their exact derivatives:
    central differences with a 1e-6 step agree to ~1e-8 (truncation ~h^2)."""
    kernel = pair_kernel()
    field, left, right = (
        np.array([0.4, 0.3, 0.05]),
        np.array([0.0, 0.1, 0.0]),
        np.array([0.1, 0.6, 0.02]),
    )
    g = 0.7
    velocity, g_dfield, g_dleft, g_dright = (
        np.array(v) for v in kernel(field, 1.0, left, right, g)
    )
    mirror = np.array([1.0, -1.0, 1.0])
    expected = horseshoe(field, left, right) + horseshoe(field, mirror * right, mirror * left)
    np.testing.assert_allclose(velocity.ravel(), expected, rtol=1e-9)
    step = 1e-6
    for derivative, moved in ((g_dfield, "field"), (g_dleft, "left"), (g_dright, "right")):
        for d in range(3):
            args = {"field": field.copy(), "left": left.copy(), "right": right.copy()}
            plus, minus = dict(args), dict(args)
            plus[moved] = args[moved] + step * np.eye(3)[d]
            minus[moved] = args[moved] - step * np.eye(3)[d]
            v_plus = np.array(kernel(plus["field"], 1.0, plus["left"], plus["right"], g)[0]).ravel()
            v_minus = np.array(
                kernel(minus["field"], 1.0, minus["left"], minus["right"], g)[0]
            ).ravel()
            finite = g * (v_plus - v_minus) / (2 * step)
            np.testing.assert_allclose(derivative[d], finite, rtol=1e-6, atol=1e-9)


@pytest.mark.parametrize("bound_weight", [1.0, 0.0], ids=["with_bound_leg", "bound_leg_masked"])
@pytest.mark.parametrize("seed", [1, 2, 3])
def test_the_pair_kernels_written_out_derivatives_are_casadis_to_round_off(
    bound_weight: float, seed: int
):
    """The kernel's derivatives are written by hand (no divisions); CasADi's automatic
    differentiation of `horseshoe_velocity` for both halves gives the same numbers to ~1e-13."""
    rng = np.random.default_rng(seed)
    field, left, right = rng.normal(size=3), rng.normal(size=3), rng.normal(size=3)
    g = 0.7
    points = [ca.SX.sym(name, 3) for name in ("field", "left", "right")]
    at, start, end = points
    mirror = ca.DM([1.0, -1.0, 1.0])
    both_halves = horseshoe_velocity(at, start, end, bound_weight) + horseshoe_velocity(
        at, mirror * end, mirror * start
    )
    automatic = ca.Function(
        "automatic", points, [both_halves] + [g * ca.jacobian(both_halves, p).T for p in points]
    )
    expected = [np.array(v) for v in automatic(field, left, right)]
    ours = [np.array(v) for v in pair_kernel()(field, bound_weight, left, right, g)]
    for mine, theirs in zip(ours, expected, strict=True):
        scale = np.max(np.abs(theirs))
        np.testing.assert_allclose(mine, theirs, rtol=0, atol=1e-13 * scale)


@pytest.mark.parametrize("bound_weight", [1.0, 0.0], ids=["with_bound_leg", "bound_leg_masked"])
def test_the_normal_pair_kernel_is_the_pair_kernel_seen_along_the_normal(bound_weight: float):
    """Tangency's kernel: n . v and n^T times each 3 x 3 derivative block, to round-off."""
    rng = np.random.default_rng(7)
    field, left, right = rng.normal(size=3), rng.normal(size=3), rng.normal(size=3)
    normal = rng.normal(size=3)
    normal /= np.linalg.norm(normal)
    g = 0.7
    velocity, g_dfield, g_dleft, g_dright = (
        np.array(v) for v in pair_kernel()(field, bound_weight, left, right, g)
    )
    seen = [np.array(v) for v in normal_pair_kernel()(field, bound_weight, left, right, g, normal)]
    np.testing.assert_array_equal(seen[0].ravel(), velocity.ravel())
    np.testing.assert_allclose(seen[1].item(), normal @ velocity.ravel(), rtol=1e-13)
    # pair_kernel's blocks are transposed: [d, c] = g d v_c / d point_d.
    for along, block in zip(seen[2:], (g_dfield, g_dleft, g_dright), strict=True):
        np.testing.assert_allclose(along.ravel(), block @ normal, rtol=1e-12, atol=1e-15)


def test_the_normal_source_columns_are_the_source_columns_seen_along_the_normals():
    """Every output of the tangency map is the full map's, contracted with n_i at field
    point i (4 panels, the self-induced bound legs masked on the diagonal)."""
    m = 4
    rng = np.random.default_rng(3)
    field = rng.normal(size=(3, m))
    normal = rng.normal(size=(3, m))
    normal /= np.linalg.norm(normal, axis=0)
    weights = np.ones((m, m)) - np.eye(m)
    left, right, g = rng.normal(size=(3, m)), rng.normal(size=(3, m)), rng.normal(size=(1, m))
    induced, influence, g_dfield, g_dleft, g_dright = (
        np.array(v) for v in source_columns(m)(field, weights, left, right, g)
    )
    seen = [np.array(v) for v in normal_source_columns(m)(field, normal, weights, left, right, g)]
    # Row 3 i + c of the full outputs -> row i, contracted with n_i.
    along = np.zeros((m, 3 * m))
    for i in range(m):
        along[i, 3 * i : 3 * i + 3] = normal[:, i]
    np.testing.assert_allclose(seen[0], induced, rtol=1e-13, atol=1e-15)
    for contracted, full in zip(seen[1:], (influence, g_dfield, g_dleft, g_dright), strict=True):
        np.testing.assert_allclose(contracted, along @ full, rtol=1e-12, atol=1e-14)
