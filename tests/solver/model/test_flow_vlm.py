"""solver.model.flow_vlm: the flow model's kernels, the image half's flow as parameters, against
Biot-Savart's law, CasADi's differentiation and the symmetric kernels."""

from __future__ import annotations

import casadi as ca
import numpy as np
import pytest

from solver.model.flow_vlm import (
    flow_normal_pair_kernel,
    flow_normal_source_columns,
    flow_pair_kernel,
    flow_source_columns,
)
from solver.model.horseshoe import horseshoe_velocity
from solver.model.vlm import normal_pair_kernel, pair_kernel
from tests.solver.model.biot_savart import horseshoe

# (image, image_jacobian): the mirror with exact derivatives (symmetric flow), the rotation
# about x with exact derivatives (antisymmetric flow), and the mirror whose own derivatives are
# turned (the antisymmetric block of the full-span Jacobian at a symmetric state).
IMAGES = [
    pytest.param(1.0, 1.0, id="mirror"),
    pytest.param(-1.0, -1.0, id="rotation"),
    pytest.param(1.0, -1.0, id="mirror-antisymmetric-jacobian"),
]


def _transformed(point: np.ndarray, image: float) -> np.ndarray:
    return np.array([point[0], -point[1], image * point[2]])


@pytest.mark.parametrize("image", [1.0, -1.0], ids=["mirror", "rotation"])
def test_the_flow_kernel_adds_the_image_and_its_derivatives_are_exact(image: float):
    """Both halves' horseshoes of one right-half panel: the image runs from T(right) to T(left)
    with weight s, T = diag(1, -1, s). Rotated (s = -1), that is the horseshoe from T(left) to
    T(right) (a rotated filament keeps its circulation). g times the exact derivatives against
    central differences with a 1e-6 step agree to ~1e-8 (truncation ~h^2)."""
    kernel = flow_pair_kernel()
    field, left, right = (
        np.array([0.4, 0.3, 0.05]),
        np.array([0.0, 0.1, 0.03]),
        np.array([0.1, 0.6, 0.02]),
    )
    g = 0.7

    def outputs(field, left, right):
        return [np.array(v) for v in kernel(field, 1.0, left, right, g, image, image)]

    velocity, influence, g_dfield, g_dleft, g_dright = outputs(field, left, right)
    rotated_image = horseshoe(field, _transformed(left, image), _transformed(right, image))
    mirrored_image = horseshoe(field, _transformed(right, image), _transformed(left, image))
    expected = horseshoe(field, left, right) + (mirrored_image if image > 0 else rotated_image)
    np.testing.assert_allclose(velocity.ravel(), expected, rtol=1e-9)
    np.testing.assert_array_equal(influence, velocity)  # exact derivatives: the same weights
    step = 1e-6
    for derivative, moved in ((g_dfield, "field"), (g_dleft, "left"), (g_dright, "right")):
        for d in range(3):
            args = {"field": field.copy(), "left": left.copy(), "right": right.copy()}
            plus, minus = dict(args), dict(args)
            plus[moved] = args[moved] + step * np.eye(3)[d]
            minus[moved] = args[moved] - step * np.eye(3)[d]
            v_plus = outputs(plus["field"], plus["left"], plus["right"])[0].ravel()
            v_minus = outputs(minus["field"], minus["left"], minus["right"])[0].ravel()
            finite = g * (v_plus - v_minus) / (2 * step)
            np.testing.assert_allclose(derivative[d], finite, rtol=1e-6, atol=1e-9)


@pytest.mark.parametrize(("image", "image_jacobian"), IMAGES)
@pytest.mark.parametrize("bound_weight", [1.0, 0.0], ids=["with_bound_leg", "bound_leg_masked"])
@pytest.mark.parametrize("seed", [1, 2, 3])
def test_the_flow_kernels_written_out_derivatives_are_casadis_to_round_off(
    bound_weight: float, seed: int, image: float, image_jacobian: float
):
    """The kernel's derivatives are written by hand (no divisions); CasADi's automatic
    differentiation of `horseshoe_velocity` for both halves gives the same numbers to ~1e-13:
    the value and the field point's derivative with the image weighted s, the derivatives in
    the source's vertices and circulation with the image weighted image_jacobian."""
    rng = np.random.default_rng(seed)
    field, left, right = rng.normal(size=3), rng.normal(size=3), rng.normal(size=3)
    g = 0.7
    points = [ca.SX.sym(name, 3) for name in ("field", "left", "right")]
    at, start, end = points
    transform = ca.DM([1.0, -1.0, image])
    own = horseshoe_velocity(at, start, end, bound_weight)
    other = horseshoe_velocity(at, transform * end, transform * start)
    value = own + image * other
    source = own + image_jacobian * other
    automatic = ca.Function(
        "automatic",
        points,
        [
            value,
            source,
            g * ca.jacobian(value, at).T,
            g * ca.jacobian(source, start).T,
            g * ca.jacobian(source, end).T,
        ],
    )
    expected = [np.array(v) for v in automatic(field, left, right)]
    ours = [
        np.array(v)
        for v in flow_pair_kernel()(field, bound_weight, left, right, g, image, image_jacobian)
    ]
    for mine, theirs in zip(ours, expected, strict=True):
        scale = np.max(np.abs(theirs))
        np.testing.assert_allclose(mine, theirs, rtol=0, atol=1e-13 * scale)


@pytest.mark.parametrize(("image", "image_jacobian"), IMAGES)
@pytest.mark.parametrize("bound_weight", [1.0, 0.0], ids=["with_bound_leg", "bound_leg_masked"])
def test_the_flow_normal_kernel_is_the_flow_kernel_seen_along_the_normal(
    bound_weight: float, image: float, image_jacobian: float
):
    """Tangency's kernel: n . v and n^T times each 3 x 3 derivative block, to round-off."""
    rng = np.random.default_rng(7)
    field, left, right = rng.normal(size=3), rng.normal(size=3), rng.normal(size=3)
    normal = rng.normal(size=3)
    normal /= np.linalg.norm(normal)
    g = 0.7
    flow = (image, image_jacobian)
    velocity, influence, g_dfield, g_dleft, g_dright = (
        np.array(v) for v in flow_pair_kernel()(field, bound_weight, left, right, g, *flow)
    )
    seen = [
        np.array(v)
        for v in flow_normal_pair_kernel()(field, bound_weight, left, right, g, normal, *flow)
    ]
    np.testing.assert_array_equal(seen[0].ravel(), velocity.ravel())
    np.testing.assert_allclose(seen[1].item(), normal @ influence.ravel(), rtol=1e-13)
    # pair_kernel's blocks are transposed: [d, c] = g d v_c / d point_d.
    for along, block in zip(seen[2:], (g_dfield, g_dleft, g_dright), strict=True):
        np.testing.assert_allclose(along.ravel(), block @ normal, rtol=1e-12, atol=1e-15)


@pytest.mark.parametrize(("image", "image_jacobian"), IMAGES)
def test_the_flow_normal_source_columns_are_the_flow_source_columns_seen_along_the_normals(
    image: float, image_jacobian: float
):
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
        np.array(v)
        for v in flow_source_columns(m)(field, weights, left, right, g, image, image_jacobian)
    )
    seen = [
        np.array(v)
        for v in flow_normal_source_columns(m)(
            field, normal, weights, left, right, g, image, image_jacobian
        )
    ]
    # Row 3 i + c of the full outputs -> row i, contracted with n_i.
    along = np.zeros((m, 3 * m))
    for i in range(m):
        along[i, 3 * i : 3 * i + 3] = normal[:, i]
    np.testing.assert_allclose(seen[0], induced, rtol=1e-13, atol=1e-15)
    for contracted, full in zip(seen[1:], (influence, g_dfield, g_dleft, g_dright), strict=True):
        np.testing.assert_allclose(contracted, along @ full, rtol=1e-12, atol=1e-14)


@pytest.mark.parametrize("normal", [False, True], ids=["full", "along-normal"])
def test_at_the_mirrors_weights_the_flow_kernel_is_the_mirrors(normal: bool):
    """image = image_jacobian = 1: the flow kernel gives the symmetric kernel's numbers to
    round-off (the symmetric model keeps its own: the weights cost ~10 % of a Jacobian)."""
    rng = np.random.default_rng(11)
    field, left, right = rng.normal(size=3), rng.normal(size=3), rng.normal(size=3)
    unit = rng.normal(size=3)
    args = (field, 1.0, left, right, 0.7) + ((unit / np.linalg.norm(unit),) if normal else ())
    flow = (flow_normal_pair_kernel if normal else flow_pair_kernel)()(*args, 1.0, 1.0)
    mirror = (normal_pair_kernel if normal else pair_kernel)()(*args)
    flow = [np.array(v) for v in flow]
    mirror = [np.array(v) for v in mirror]
    if not normal:  # one more output: the influence, the velocity itself here
        np.testing.assert_array_equal(flow[0], flow[1])
        flow = [flow[0], *flow[2:]]
    for ours, theirs in zip(flow, mirror, strict=True):
        np.testing.assert_allclose(ours, theirs, rtol=0, atol=1e-14 * np.max(np.abs(theirs)))
