"""The horseshoe lattice with its image half's flow as parameters: the flow model's kernels (control
surfaces and roll, `solver.model.flow`).

The left half is then the image of the right half under T = diag(1, -1, s), its horseshoe
(`solver.model.horseshoe`) running from T(B) to T(A) with strength s Gamma_k (the `image`
input s):

- s = +1, T the mirror in y: the symmetric flow of `solver.model.vlm`;
- s = -1, T the rotation by 180 deg about x: the exactly antisymmetric flow (an aileron, a roll
  rate) of a wing whose sections are symmetric in z, at zero incidence. A rotated filament with
  the same circulation induces R v(R^-1 P) (vorticity is a pseudovector), which is the horseshoe
  from T(A) to T(B), i.e. -1 times the one from T(B) to T(A).

`image_jacobian` weights the image's part of the derivatives in its own vertices and circulation
(its part at the field point keeps the weight s of its value). Equal to s, the derivatives are
exact. With s = +1 and image_jacobian = -1 at a symmetric state they are the antisymmetric block
of the full-span Jacobian there: the derivatives of the right half's equations when the left half
moves opposite to it (its heave, twist and circulation the negatives of the right half's
changes), the linearisation of an antisymmetric disturbance about a symmetric equilibrium
(`solver.controls.roll`). The weights cost the kernel ~40 multiplications per pair, ~10 % of a
Jacobian: the symmetric model keeps `solver.model.vlm`'s kernels, and these are separate
functions, the flow model's.
"""

from __future__ import annotations

import casadi as ca

from solver.model.horseshoe import (
    INV_4PI,
    Horseshoe,
    all_symbols,
    column_symbols,
    pair_symbols,
)

__all__ = [
    "flow_induced_velocities",
    "flow_normal_pair_kernel",
    "flow_normal_source_columns",
    "flow_pair_kernel",
    "flow_source_columns",
]


def _image_of(point: ca.SX, image: ca.SX) -> ca.SX:
    """T(point) = diag(1, -1, image) point."""
    return ca.vertcat(point[0], -point[1], image * point[2])


def _image_symbols() -> tuple[ca.SX, ca.SX]:
    """The image's sign s (its geometry T = diag(1, -1, s) and the weight of its value) and the
    weight of its derivatives in its own vertices and circulation (module docstring)."""
    return ca.SX.sym("image"), ca.SX.sym("image_jacobian")


def _flow_halves(
    field: ca.SX, weight: ca.SX, left: ca.SX, right: ca.SX, image: ca.SX
) -> tuple[Horseshoe, Horseshoe]:
    """The right half's horseshoe at `field` (its bound leg weighted) and its image on the left
    half, which runs from T(right) to T(left) (its weight s is the caller's)."""
    return (
        Horseshoe(field - left, field - right, weight),
        Horseshoe(field - _image_of(right, image), field - _image_of(left, image), 1.0),
    )


def _weighted_velocity(right_half: Horseshoe, left_half: Horseshoe, weight: ca.SX) -> ca.SX:
    """(3,) [-] both halves' induced velocity per unit g, the image's weighted."""
    return (right_half.velocity() + weight * left_half.velocity()) * INV_4PI


def _flow_vertex_derivatives(
    right_da: ca.SX,
    right_db: ca.SX,
    left_da: ca.SX,
    left_db: ca.SX,
    image: ca.SX,
    image_jacobian: ca.SX,
) -> tuple[ca.SX, ca.SX, ca.SX]:
    """`_vertex_derivatives` with the image at T(right), T(left) (T = T^-1): its part in its
    vertices weighted `image_jacobian`, its part at the field point `image`."""
    transform = ca.diag(ca.vertcat(1, -1, image))
    d_field = right_da + right_db + image * (left_da + left_db)
    d_left = -right_da - image_jacobian * ca.mtimes(left_db, transform)
    d_right = -right_db - image_jacobian * ca.mtimes(left_da, transform)
    return d_field, d_left, d_right


def flow_pair_kernel() -> ca.Function:
    """`pair_kernel` with the image as a parameter (module docstring).

    Inputs: field, bound_weight, left, right, g as `pair_kernel`; image, image_jacobian (1,).
    Outputs, all per unit V:
        velocity (3,) [-]: induced velocity per unit g (the image's part weighted image).
        influence (3,) [-]: d(g velocity)/dg, the image's part weighted image_jacobian.
        g_dfield, g_dleft, g_dright (3, 3): as `pair_kernel`'s.
    """
    field, weight, left, right, g = pair_symbols()
    image, image_jacobian = _image_symbols()
    right_half, left_half = _flow_halves(field, weight, left, right, image)
    d_field, d_left, d_right = _flow_vertex_derivatives(
        *right_half.derivatives(), *left_half.derivatives(), image, image_jacobian
    )
    velocity = _weighted_velocity(right_half, left_half, image)
    influence = _weighted_velocity(right_half, left_half, image_jacobian)
    scaled = g * INV_4PI
    outputs = ca.cse(
        [velocity, influence, scaled * d_field.T, scaled * d_left.T, scaled * d_right.T]
    )
    return ca.Function(
        "vlm_flow_pair",
        [field, weight, left, right, g, image, image_jacobian],
        outputs,
        ["field", "bound_weight", "left", "right", "g", "image", "image_jacobian"],
        ["velocity", "influence", "g_dfield", "g_dleft", "g_dright"],
    )


def flow_normal_pair_kernel() -> ca.Function:
    """`normal_pair_kernel` with the image as a parameter.

    Inputs: field, bound_weight, left, right, g, normal as `normal_pair_kernel`; image,
    image_jacobian (1,).
    Outputs, per unit V: velocity (3,) as `flow_pair_kernel`'s; normal_influence (1,) [-]:
    n . d(g velocity)/dg (the image's part weighted image_jacobian); g_dfield, g_dleft, g_dright
    (1, 3).
    """
    field, weight, left, right, g = pair_symbols()
    normal = ca.SX.sym("normal", 3)
    image, image_jacobian = _image_symbols()
    right_half, left_half = _flow_halves(field, weight, left, right, image)
    d_field, d_left, d_right = _flow_vertex_derivatives(
        *right_half.normal_derivatives(normal),
        *left_half.normal_derivatives(normal),
        image,
        image_jacobian,
    )
    velocity = _weighted_velocity(right_half, left_half, image)
    influence = _weighted_velocity(right_half, left_half, image_jacobian)
    scaled = g * INV_4PI
    outputs = ca.cse(
        [velocity, ca.dot(normal, influence), scaled * d_field, scaled * d_left, scaled * d_right]
    )
    return ca.Function(
        "vlm_flow_normal_pair",
        [field, weight, left, right, g, normal, image, image_jacobian],
        outputs,
        ["field", "bound_weight", "left", "right", "g", "normal", "image", "image_jacobian"],
        ["velocity", "normal_influence", "g_dfield", "g_dleft", "g_dright"],
    )


def flow_normal_source_columns(n_panels: int) -> ca.Function:
    """`normal_source_columns` of `flow_normal_pair_kernel`: inputs field, normal,
    bound_weight, left, right, g as there, then image and image_jacobian (1,); outputs as
    there (influence: the image's part weighted image_jacobian)."""
    m = n_panels
    pair = flow_normal_pair_kernel()
    field, weight, left, right, g = column_symbols(m)
    normal = ca.MX.sym("normal", 3, m)
    image, image_jacobian = ca.MX.sym("image"), ca.MX.sym("image_jacobian")
    over_fields = pair.map("vlm_flow_normal_over_fields", "serial", m, [2, 3, 4, 6, 7], [])
    velocity, normal_influence, g_dfield, g_dleft, g_dright = over_fields(
        field, weight.T, left, right, g, normal, image, image_jacobian
    )
    column = ca.Function(
        "vlm_flow_normal_column",
        [field, normal, weight, left, right, g, image, image_jacobian],
        [
            g * ca.vec(velocity),
            normal_influence.T,
            ca.reshape(g_dfield, 3, m).T,
            ca.reshape(g_dleft, 3, m).T,
            ca.reshape(g_dright, 3, m).T,
        ],
    )
    over_sources = column.map("vlm_flow_normal_over_sources", "serial", m, [0, 1, 6, 7], [0, 2])
    field_all, weight_all, left_all, right_all, g_all = all_symbols(m)
    normal_all = ca.MX.sym("normal", 3, m)
    inputs = [field_all, normal_all, weight_all, left_all, right_all, g_all]
    return ca.Function(
        "vlm_flow_normal_sources",
        [*inputs, image, image_jacobian],
        list(over_sources(*inputs, image, image_jacobian)),
        ["field", "normal", "bound_weight", "left", "right", "g", "image", "image_jacobian"],
        ["induced", "influence", "g_dfield", "g_dleft", "g_dright"],
    )


def flow_source_columns(n_panels: int) -> ca.Function:
    """`source_columns` of `flow_pair_kernel`: inputs as there, then image and image_jacobian
    (1,); outputs as there (influence: the image's part weighted image_jacobian)."""
    m = n_panels
    pair = flow_pair_kernel()
    field, weight, left, right, g = column_symbols(m)
    image, image_jacobian = ca.MX.sym("image"), ca.MX.sym("image_jacobian")
    over_fields = pair.map("vlm_flow_over_fields", "serial", m, [2, 3, 4, 5, 6], [])
    velocity, influence, g_dfield, g_dleft, g_dright = over_fields(
        field, weight.T, left, right, g, image, image_jacobian
    )
    column = ca.Function(
        "vlm_flow_column",
        [field, weight, left, right, g, image, image_jacobian],
        [ca.vec(influence), g * ca.vec(velocity), g_dfield.T, g_dleft.T, g_dright.T],
    )
    over_sources = column.map("vlm_flow_over_sources", "serial", m, [0, 5, 6], [1, 2])
    field_all, weight_all, left_all, right_all, g_all = all_symbols(m)
    influence, induced, g_dfield_sum, g_dleft_all, g_dright_all = over_sources(
        field_all, weight_all, left_all, right_all, g_all, image, image_jacobian
    )
    return ca.Function(
        "vlm_flow_sources",
        [field_all, weight_all, left_all, right_all, g_all, image, image_jacobian],
        [induced, influence, g_dfield_sum, g_dleft_all, g_dright_all],
        ["field", "bound_weight", "left", "right", "g", "image", "image_jacobian"],
        ["induced", "influence", "g_dfield", "g_dleft", "g_dright"],
    )


def flow_induced_velocities(n_panels: int, with_image: bool = True) -> ca.Function:
    """`induced_velocities` with the image as a parameter: inputs as there, then image (1,).
    Without the image (`with_image` False) the sources' horseshoes alone (image ignored): what a
    full-span wing whose halves move apart needs, its left half given as sources of its own
    (`solver.model.residual.build_full_span_function`)."""
    m = n_panels
    field, weight, left, right, g = pair_symbols()
    image = ca.SX.sym("image")
    if with_image:
        velocity = _weighted_velocity(*_flow_halves(field, weight, left, right, image), image)
    else:
        velocity = Horseshoe(field - left, field - right, weight).velocity() * INV_4PI
    pair = ca.Function(
        "vlm_flow_pair_value", [field, weight, left, right, g, image], [g * velocity]
    )
    over_fields = pair.map("vlm_flow_value_over_fields", "serial", m, [2, 3, 4, 5], [])
    field_mx, weight_mx, left_mx, right_mx, g_mx = column_symbols(m)
    image_mx = ca.MX.sym("image")
    column = ca.Function(
        "vlm_flow_value_column",
        [field_mx, weight_mx, left_mx, right_mx, g_mx, image_mx],
        [ca.vec(over_fields(field_mx, weight_mx.T, left_mx, right_mx, g_mx, image_mx))],
    )
    over_sources = column.map("vlm_flow_value_over_sources", "serial", m, [0, 5], [0])
    field_all, weight_all, left_all, right_all, g_all = all_symbols(m)
    return ca.Function(
        "vlm_flow_induced",
        [field_all, weight_all, left_all, right_all, g_all, image_mx],
        [over_sources(field_all, weight_all, left_all, right_all, g_all, image_mx)],
        ["field", "bound_weight", "left", "right", "g", "image"],
        ["induced"],
    )
