"""Horseshoe vortex lattice of a symmetric wing: the O(N^2) part of the model, as one small kernel.

Each right-half panel k carries a horseshoe vortex (`solver.model.horseshoe`) of strength
Gamma_k = V g_k: a bound leg from its inboard quarter-chord vertex A to its outboard vertex B,
and two trailing legs running to +x infinity. The left half is the mirror image in y with the
same circulation, so its horseshoe runs from m(B) to m(A), m = diag(1, -1, 1).

`pair_kernel` returns both halves' velocity and its exact derivatives with respect to the three
points, so the full Jacobian of the coupled residual is assembled from O(N^2) kernel values by
the chain rule instead of by differentiating through a dense O(N^2) expression graph. Flow
tangency reads only the normal component n . v at a collocation point: `normal_pair_kernel`
gives it and its derivatives as rows, a third of the derivative work of the full kernel. The
source columns map a kernel over every field point and every source panel.

The flow model's kernels, with the image half's flow as parameters, are separate
(`solver.model.flow_vlm`): their weights cost the kernel ~10 % of a Jacobian.
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
    "induced_velocities",
    "normal_pair_kernel",
    "normal_source_columns",
    "pair_kernel",
    "source_columns",
]

_MIRROR = ca.DM([1.0, -1.0, 1.0])


def _halves(field: ca.SX, weight: ca.SX, left: ca.SX, right: ca.SX) -> tuple[Horseshoe, Horseshoe]:
    """The right half's horseshoe at `field` (its bound leg weighted) and its mirror image on
    the left half, which runs from m(right) to m(left)."""
    return (
        Horseshoe(field - left, field - right, weight),
        Horseshoe(field - _MIRROR * right, field - _MIRROR * left, 1.0),
    )


def _velocity(right_half: Horseshoe, left_half: Horseshoe) -> ca.SX:
    """(3,) [-] both halves' induced velocity per unit g (their 4 pi v summed, divided by 4 pi)."""
    return (right_half.velocity() + left_half.velocity()) * INV_4PI


def _vertex_derivatives(
    right_da: ca.SX, right_db: ca.SX, left_da: ca.SX, left_db: ca.SX
) -> tuple[ca.SX, ca.SX, ca.SX]:
    """d/d(field), d/d(left), d/d(right) of both halves from their derivatives in a = field -
    first vertex and b = field - second vertex. The left half's vertices are mirrored
    (m = m^-1): its a moves with m(right), its b with m(left)."""
    mirror = ca.diag(_MIRROR)
    d_field = right_da + right_db + left_da + left_db
    d_left = -right_da - ca.mtimes(left_db, mirror)
    d_right = -right_db - ca.mtimes(left_da, mirror)
    return d_field, d_left, d_right


def pair_kernel() -> ca.Function:
    """Both halves' horseshoes of one right-half panel seen from one field point.

    Inputs: field (3,) [m], bound_weight (1,) [-], left (3,) [m], right (3,) [m], g (1,) [m].
    Outputs, all per unit V:
        velocity (3,) [-]: induced velocity per unit g.
        g_dfield (3, 3): g * d(velocity)/d(field), transposed ([d, c] = d v_c / d field_d).
        g_dleft, g_dright (3, 3): the same for the two bound-vortex vertices.
    """
    field, weight, left, right, g = pair_symbols()
    right_half, left_half = _halves(field, weight, left, right)
    d_field, d_left, d_right = _vertex_derivatives(
        *right_half.derivatives(), *left_half.derivatives()
    )
    velocity = _velocity(right_half, left_half)
    scaled = g * INV_4PI
    outputs = ca.cse([velocity, scaled * d_field.T, scaled * d_left.T, scaled * d_right.T])
    return ca.Function(
        "vlm_pair",
        [field, weight, left, right, g],
        outputs,
        ["field", "bound_weight", "left", "right", "g"],
        ["velocity", "g_dfield", "g_dleft", "g_dright"],
    )


def normal_pair_kernel() -> ca.Function:
    """`pair_kernel` seen along a field point's unit normal n: what flow tangency needs.

    Tangency reads only n . v, so its derivatives are rows n^T dv (1, 3) instead of 3 x 3
    blocks: a third of the kernel's derivative work and of the O(M^2) chain rule after it.

    Inputs: field, bound_weight, left, right, g as `pair_kernel`; normal (3,) [-], held
    constant (how the normal itself moves with the geometry is the caller's part).
    Outputs, per unit V:
        velocity (3,) [-]: induced velocity per unit g.
        normal_velocity (1,) [-]: n . velocity.
        g_dfield, g_dleft, g_dright (1, 3): g n^T d(velocity)/d(point).
    """
    field, weight, left, right, g = pair_symbols()
    normal = ca.SX.sym("normal", 3)
    right_half, left_half = _halves(field, weight, left, right)
    d_field, d_left, d_right = _vertex_derivatives(
        *right_half.normal_derivatives(normal), *left_half.normal_derivatives(normal)
    )
    velocity = _velocity(right_half, left_half)
    scaled = g * INV_4PI
    outputs = ca.cse(
        [velocity, ca.dot(normal, velocity), scaled * d_field, scaled * d_left, scaled * d_right]
    )
    return ca.Function(
        "vlm_normal_pair",
        [field, weight, left, right, g, normal],
        outputs,
        ["field", "bound_weight", "left", "right", "g", "normal"],
        ["velocity", "normal_velocity", "g_dfield", "g_dleft", "g_dright"],
    )


def normal_source_columns(n_panels: int) -> ca.Function:
    """`source_columns` along the field points' normals (flow tangency's view).

    Inputs: field (3, M) [m], normal (3, M) [-] (the field points' unit normals), then
    bound_weight, left, right and g as `source_columns`.
    Outputs, per unit V (field point i, source k):
        induced (3M, 1) [-]: sum_k g_k v_ik, rows 3 i + c (the full vector).
        influence (M, M) [-]: n_i . v_ik, column k (per unit g_k): the influence matrix.
        g_dfield (M, 3): sum_k g_k n_i^T d v_ik / d field_i, column d.
        g_dleft, g_dright (M, 3M): g_k n_i^T d v_ik / d left_k, column 3 k + d (likewise
            right_k).
    """
    m = n_panels
    pair = normal_pair_kernel()
    field, weight, left, right, g = column_symbols(m)
    normal = ca.MX.sym("normal", 3, m)
    over_fields = pair.map("vlm_normal_over_fields", "serial", m, [2, 3, 4], [])
    velocity, normal_velocity, g_dfield, g_dleft, g_dright = over_fields(
        field, weight.T, left, right, g, normal
    )
    column = ca.Function(
        "vlm_normal_column",
        [field, normal, weight, left, right, g],
        [
            g * ca.vec(velocity),
            normal_velocity.T,
            ca.reshape(g_dfield, 3, m).T,
            ca.reshape(g_dleft, 3, m).T,
            ca.reshape(g_dright, 3, m).T,
        ],
    )
    # All sources: field points and normals shared, the g-weighted sums reduced.
    over_sources = column.map("vlm_normal_over_sources", "serial", m, [0, 1], [0, 2])
    field_all, weight_all, left_all, right_all, g_all = all_symbols(m)
    normal_all = ca.MX.sym("normal", 3, m)
    return ca.Function(
        "vlm_normal_sources",
        [field_all, normal_all, weight_all, left_all, right_all, g_all],
        list(over_sources(field_all, normal_all, weight_all, left_all, right_all, g_all)),
        ["field", "normal", "bound_weight", "left", "right", "g"],
        ["induced", "influence", "g_dfield", "g_dleft", "g_dright"],
    )


def source_columns(n_panels: int) -> ca.Function:
    """Every source panel against every field point, as two nested maps of `pair_kernel`.

    Inputs (M = n_panels):
        field (3, M) [m]: field points, shared by all sources.
        bound_weight (M, M) [-]: column k holds the weights the field points see for source k.
        left, right (3, M) [m]: source bound-vortex vertices.
        g (1, M) [m]: source circulations per unit V.
    Outputs, rows indexed 3 i + c (field point i, velocity component c), per unit V:
        induced (3M, 1) [-]: sum_k g_k v_ik, the induced velocity at each field point.
        influence (3M, M) [-]: v_ik, column k (per unit g_k).
        g_dfield (3M, 3): sum_k g_k d v_ik / d field_i, column d.
        g_dleft, g_dright (3M, 3M): g_k d v_ik / d left_k, column 3 k + d (likewise right_k).
    """
    m = n_panels
    pair = pair_kernel()
    field, weight, left, right, g = column_symbols(m)
    # Inner map: one source against all field points (source inputs shared).
    over_fields = pair.map("vlm_over_fields", "serial", m, [2, 3, 4], [])
    velocity, g_dfield, g_dleft, g_dright = over_fields(field, weight.T, left, right, g)
    column = ca.Function(
        "vlm_column",
        [field, weight, left, right, g],
        [
            ca.vec(velocity),
            g * ca.vec(velocity),
            g_dfield.T,
            g_dleft.T,
            g_dright.T,
        ],
    )
    # Outer map: all sources; field points shared, the g-weighted sums reduced.
    over_sources = column.map("vlm_over_sources", "serial", m, [0], [1, 2])
    field_all, weight_all, left_all, right_all, g_all = all_symbols(m)
    influence, induced, g_dfield_sum, g_dleft_all, g_dright_all = over_sources(
        field_all, weight_all, left_all, right_all, g_all
    )
    return ca.Function(
        "vlm_sources",
        [field_all, weight_all, left_all, right_all, g_all],
        [induced, influence, g_dfield_sum, g_dleft_all, g_dright_all],
        ["field", "bound_weight", "left", "right", "g"],
        ["induced", "influence", "g_dfield", "g_dleft", "g_dright"],
    )


def induced_velocities(n_panels: int) -> ca.Function:
    """Values only: sum_k g_k v_ik at every field point, without derivatives (4x cheaper).

    Inputs as `source_columns`; output induced (3M, 1) [-] per unit V, rows 3 i + c.
    """
    m = n_panels
    field, weight, left, right, g = pair_symbols()
    right_half, left_half = _halves(field, weight, left, right)
    velocity = _velocity(right_half, left_half)
    pair = ca.Function("vlm_pair_value", [field, weight, left, right, g], [g * velocity])
    over_fields = pair.map("vlm_value_over_fields", "serial", m, [2, 3, 4], [])
    field_mx, weight_mx, left_mx, right_mx, g_mx = column_symbols(m)
    column = ca.Function(
        "vlm_value_column",
        [field_mx, weight_mx, left_mx, right_mx, g_mx],
        [ca.vec(over_fields(field_mx, weight_mx.T, left_mx, right_mx, g_mx))],
    )
    over_sources = column.map("vlm_value_over_sources", "serial", m, [0], [0])
    field_all, weight_all, left_all, right_all, g_all = all_symbols(m)
    return ca.Function(
        "vlm_induced",
        [field_all, weight_all, left_all, right_all, g_all],
        [over_sources(field_all, weight_all, left_all, right_all, g_all)],
        ["field", "bound_weight", "left", "right", "g"],
        ["induced"],
    )
