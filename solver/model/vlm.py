"""Horseshoe vortex lattice of a symmetric wing: the O(N^2) part of the model, as one small kernel.

Each right-half panel k carries a horseshoe vortex of strength Gamma_k = V g_k: a bound leg from its
inboard quarter-chord vertex A to its outboard vertex B, and two trailing legs running to +x
infinity (geometry axes, not along the freestream: AeroSandbox's default). The left half is the
mirror image in y with the same circulation, so its horseshoe runs from m(B) to m(A),
m = diag(1, -1, 1).

The induced velocity of a unit horseshoe at a field point (Drela's form, as in AeroSandbox's
``calculate_induced_velocity_horseshoe``), with a = P - A, b = P - B and u = [1, 0, 0]:

    v = 1/(4 pi) [ (a x b)(1/|a| + 1/|b|) / (|a||b| + a.b) + (a x u)/(|a|(|a| - a.u))
                   - (b x u)/(|b|(|b| - b.u)) ]

A bound leg induces nothing at its own midpoint, where the first term is 0/0: the `bound_weight`
input masks it exactly (AeroSandbox's 1e-8 m core radius gives the same numbers).

`pair_kernel` returns the velocity and its exact derivatives with respect to the three points, so
the full Jacobian of the coupled residual is assembled from O(N^2) kernel values by the chain
rule instead of by differentiating through a dense O(N^2) expression graph.

The image as a parameter (`flow_*`, for control surfaces and roll): the left half is then the
image of the right half under T = diag(1, -1, s), its horseshoe running from T(B) to T(A) with
strength s Gamma_k (the `image` input s):

- s = +1, T the mirror in y: the symmetric flow above;
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
(`solver.roll`). The weights cost the kernel ~40 multiplications per pair, ~10 % of a Jacobian:
the symmetric model keeps the kernels above, and the flow kernels are separate functions (the
flow model's, `solver.model.residual`). Flow tangency reads
only the normal component n . v at a collocation point: `normal_pair_kernel` gives it and its
derivatives as rows, a third of the derivative work of the full kernel.

The kernels are most of the Jacobian's cost, so their derivatives are written out by hand
(`_Horseshoe`) from reciprocals computed once per horseshoe: no division and no square root in
the derivative graph, where CasADi's differentiation rules put ~80 divisions into each pair
(1.1-1.4x faster kernels; tests/solver/test_vlm.py checks them against CasADi's differentiation
to round-off).
"""

from __future__ import annotations

import casadi as ca
import numpy as np

__all__ = [
    "flow_induced_velocities",
    "flow_normal_pair_kernel",
    "flow_normal_source_columns",
    "flow_pair_kernel",
    "flow_source_columns",
    "horseshoe_velocity",
    "induced_velocities",
    "normal_pair_kernel",
    "normal_source_columns",
    "pair_kernel",
    "source_columns",
]

_MIRROR = ca.DM([1.0, -1.0, 1.0])


def _cross(a: ca.SX, b: ca.SX) -> ca.SX:
    return ca.vertcat(
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    )


_INV_4PI = 1.0 / (4 * np.pi)
_E_X = ca.DM([1.0, 0.0, 0.0])


def _skew(v: ca.SX) -> ca.SX:
    """(3, 3) the cross-product matrix: _skew(v) w = v x w."""
    zero = ca.SX(1, 1)
    return ca.vertcat(
        ca.horzcat(zero, -v[2], v[1]),
        ca.horzcat(v[2], zero, -v[0]),
        ca.horzcat(-v[1], v[0], zero),
    )


class _Horseshoe:
    """One horseshoe (bound leg left -> right, trailing legs to +x infinity) seen from one
    field point, through a = field - left and b = field - right, times 4 pi.

    The velocity is written with its reciprocals computed once,

        4 pi v = k (a x b) + f_a (a x u) - f_b (b x u),
        k = w (1/|a| + 1/|b|) / (|a||b| + a.b + 1 - w),   f_a = 1/(|a| (|a| - a_x)),

    and its derivatives in a and b are written out by hand from the same reciprocals: the
    derivative graph has no division and no square root, where CasADi's own differentiation
    rules put ~40 divisions into each horseshoe's. tests/solver/test_vlm.py checks them against
    CasADi's differentiation of `horseshoe_velocity`.
    """

    def __init__(self, a: ca.SX, b: ca.SX, bound_weight: ca.SX | float) -> None:
        self.a, self.b = a, b
        self.norm_a = ca.sqrt(ca.dot(a, a))
        self.norm_b = ca.sqrt(ca.dot(b, b))
        # Every reciprocal below is positive: fabs changes no value, but keeps CasADi from
        # folding x * (1/y) back into a division at each use.
        self.inv_a = ca.fabs(1 / self.norm_a)
        self.inv_b = ca.fabs(1 / self.norm_b)
        self.trailing_a = ca.fabs(1 / (self.norm_a * (self.norm_a - a[0])))
        self.trailing_b = ca.fabs(1 / (self.norm_b * (self.norm_b - b[0])))
        # With weight 0 (a field point on the bound leg itself) the denominator is shifted away
        # from 0 and the bound leg's factor multiplied by 0: value and derivatives see no 0/0.
        bound = ca.fabs(1 / (self.norm_a * self.norm_b + ca.dot(a, b) + (1 - bound_weight)))
        self.weighted = bound_weight * bound
        self.inv_sum = self.inv_a + self.inv_b
        self.bound_factor = self.weighted * self.inv_sum  # k
        self.cross = _cross(a, b)
        self.bound_share = self.inv_sum * bound  # k / w, what differentiating 1/den leaves

    def velocity(self) -> ca.SX:
        """(3,) 4 pi v."""
        a, b = self.a, self.b
        return (
            self.bound_factor * self.cross
            + self.trailing_a * ca.vertcat(0, a[2], -a[1])
            - self.trailing_b * ca.vertcat(0, b[2], -b[1])
        )

    def _bound_factor_gradients(self) -> tuple[ca.SX, ca.SX]:
        """dk/da, dk/db (3,): k = w s / D with s = 1/|a| + 1/|b|, D = |a||b| + a.b + 1 - w,
        ds/da = -a/|a|^3 and dD/da = |b| a/|a| + b (likewise in b)."""
        a, b, share = self.a, self.b, self.bound_share
        along_a = self.inv_a * self.inv_a * self.inv_a + share * self.norm_b * self.inv_a
        along_b = self.inv_b * self.inv_b * self.inv_b + share * self.norm_a * self.inv_b
        return (
            -self.weighted * (along_a * a + share * b),
            -self.weighted * (along_b * b + share * a),
        )

    @staticmethod
    def _trailing_gradient(v: ca.SX, norm: ca.SX, inv: ca.SX, factor: ca.SX) -> ca.SX:
        """d f/dv (3,) of f = 1/(|v|^2 - |v| v_x): -f^2 ((2 - v_x/|v|) v - |v| e_x)."""
        squared = factor * factor
        return -squared * ((2 - v[0] * inv) * v) + (squared * norm) * _E_X

    def derivatives(self) -> tuple[ca.SX, ca.SX]:
        """(3, 3) d(4 pi v)/da and d(4 pi v)/db, [c, d] = d v_c / d a_d."""
        a, b = self.a, self.b
        k_a, k_b = self._bound_factor_gradients()
        f_a = self._trailing_gradient(a, self.norm_a, self.inv_a, self.trailing_a)
        f_b = self._trailing_gradient(b, self.norm_b, self.inv_b, self.trailing_b)
        zero = ca.SX(1, 3)
        trailing_da = ca.vertcat(
            zero,
            a[2] * f_a.T + ca.horzcat(0, 0, self.trailing_a),
            -a[1] * f_a.T - ca.horzcat(0, self.trailing_a, 0),
        )
        trailing_db = ca.vertcat(
            zero,
            -b[2] * f_b.T - ca.horzcat(0, 0, self.trailing_b),
            b[1] * f_b.T + ca.horzcat(0, self.trailing_b, 0),
        )
        # d(a x b)/da = -[b]x, d(a x b)/db = [a]x.
        k = self.bound_factor
        d_a = -k * _skew(b) + ca.mtimes(self.cross, k_a.T) + trailing_da
        d_b = k * _skew(a) + ca.mtimes(self.cross, k_b.T) + trailing_db
        return d_a, d_b

    def normal_derivatives(self, normal: ca.SX) -> tuple[ca.SX, ca.SX]:
        """(1, 3) n^T d(4 pi v)/da and n^T d(4 pi v)/db, without the 3 x 3 blocks:
        n^T [b]x = -(b x n)^T, n^T [a]x = -(a x n)^T = (n x a)^T."""
        a, b = self.a, self.b
        k_a, k_b = self._bound_factor_gradients()
        f_a = self._trailing_gradient(a, self.norm_a, self.inv_a, self.trailing_a)
        f_b = self._trailing_gradient(b, self.norm_b, self.inv_b, self.trailing_b)
        along_cross = ca.dot(normal, self.cross)
        # n . (v x u) for u = e_x: n_y v_z - n_z v_y.
        seen_a = normal[1] * a[2] - normal[2] * a[1]
        seen_b = normal[1] * b[2] - normal[2] * b[1]
        sideways = ca.horzcat(0, -normal[2], normal[1])  # n^T d(v x u)/dv
        k = self.bound_factor
        d_a = (
            k * _cross(b, normal).T
            + along_cross * k_a.T
            + seen_a * f_a.T
            + self.trailing_a * sideways
        )
        d_b = (
            k * _cross(normal, a).T
            + along_cross * k_b.T
            - seen_b * f_b.T
            - self.trailing_b * sideways
        )
        return d_a, d_b


def horseshoe_velocity(
    field: ca.SX, left: ca.SX, right: ca.SX, bound_weight: ca.SX | float = 1.0
) -> ca.SX:
    """Velocity [m/s per (m^2/s)] induced at `field` by a unit horseshoe with bound leg left->right.

    All points are (3,) [m]. `bound_weight` is 1, or 0 to drop the bound leg's contribution
    (for a field point on the bound leg itself).
    """
    return _Horseshoe(field - left, field - right, bound_weight).velocity() * _INV_4PI


def _pair_symbols() -> tuple[ca.SX, ca.SX, ca.SX, ca.SX, ca.SX]:
    """One field point and one source panel: field (3,), bound_weight, left (3,), right (3,), g."""
    return (
        ca.SX.sym("field", 3),
        ca.SX.sym("bound_weight"),
        ca.SX.sym("left", 3),
        ca.SX.sym("right", 3),
        ca.SX.sym("g"),
    )


def _halves(
    field: ca.SX, weight: ca.SX, left: ca.SX, right: ca.SX
) -> tuple[_Horseshoe, _Horseshoe]:
    """The right half's horseshoe at `field` (its bound leg weighted) and its mirror image on
    the left half, which runs from m(right) to m(left)."""
    return (
        _Horseshoe(field - left, field - right, weight),
        _Horseshoe(field - _MIRROR * right, field - _MIRROR * left, 1.0),
    )


def _velocity(right_half: _Horseshoe, left_half: _Horseshoe) -> ca.SX:
    """(3,) [-] both halves' induced velocity per unit g (their 4 pi v summed, divided by 4 pi)."""
    return (right_half.velocity() + left_half.velocity()) * _INV_4PI


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
    field, weight, left, right, g = _pair_symbols()
    right_half, left_half = _halves(field, weight, left, right)
    d_field, d_left, d_right = _vertex_derivatives(
        *right_half.derivatives(), *left_half.derivatives()
    )
    velocity = _velocity(right_half, left_half)
    scaled = g * _INV_4PI
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
    field, weight, left, right, g = _pair_symbols()
    normal = ca.SX.sym("normal", 3)
    right_half, left_half = _halves(field, weight, left, right)
    d_field, d_left, d_right = _vertex_derivatives(
        *right_half.normal_derivatives(normal), *left_half.normal_derivatives(normal)
    )
    velocity = _velocity(right_half, left_half)
    scaled = g * _INV_4PI
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


def _column_symbols(m: int) -> tuple[ca.MX, ca.MX, ca.MX, ca.MX, ca.MX]:
    """One source against M field points: field (3, M), bound_weight (M, 1), left (3, 1),
    right (3, 1), g."""
    return (
        ca.MX.sym("field", 3, m),
        ca.MX.sym("bound_weight", m, 1),
        ca.MX.sym("left", 3, 1),
        ca.MX.sym("right", 3, 1),
        ca.MX.sym("g"),
    )


def _all_symbols(m: int) -> tuple[ca.MX, ca.MX, ca.MX, ca.MX, ca.MX]:
    """M sources against M field points: field (3, M), bound_weight (M, M), left (3, M),
    right (3, M), g (1, M)."""
    return (
        ca.MX.sym("field", 3, m),
        ca.MX.sym("bound_weight", m, m),
        ca.MX.sym("left", 3, m),
        ca.MX.sym("right", 3, m),
        ca.MX.sym("g", 1, m),
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
    field, weight, left, right, g = _column_symbols(m)
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
    field_all, weight_all, left_all, right_all, g_all = _all_symbols(m)
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
    field, weight, left, right, g = _column_symbols(m)
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
    field_all, weight_all, left_all, right_all, g_all = _all_symbols(m)
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
    field, weight, left, right, g = _pair_symbols()
    right_half, left_half = _halves(field, weight, left, right)
    velocity = _velocity(right_half, left_half)
    pair = ca.Function("vlm_pair_value", [field, weight, left, right, g], [g * velocity])
    over_fields = pair.map("vlm_value_over_fields", "serial", m, [2, 3, 4], [])
    field_mx, weight_mx, left_mx, right_mx, g_mx = _column_symbols(m)
    column = ca.Function(
        "vlm_value_column",
        [field_mx, weight_mx, left_mx, right_mx, g_mx],
        [ca.vec(over_fields(field_mx, weight_mx.T, left_mx, right_mx, g_mx))],
    )
    over_sources = column.map("vlm_value_over_sources", "serial", m, [0], [0])
    field_all, weight_all, left_all, right_all, g_all = _all_symbols(m)
    return ca.Function(
        "vlm_induced",
        [field_all, weight_all, left_all, right_all, g_all],
        [over_sources(field_all, weight_all, left_all, right_all, g_all)],
        ["field", "bound_weight", "left", "right", "g"],
        ["induced"],
    )


# ------------------------------------------------------------------ the image as a parameter


def _image_of(point: ca.SX, image: ca.SX) -> ca.SX:
    """T(point) = diag(1, -1, image) point."""
    return ca.vertcat(point[0], -point[1], image * point[2])


def _image_symbols() -> tuple[ca.SX, ca.SX]:
    """The image's sign s (its geometry T = diag(1, -1, s) and the weight of its value) and the
    weight of its derivatives in its own vertices and circulation (module docstring)."""
    return ca.SX.sym("image"), ca.SX.sym("image_jacobian")


def _flow_halves(
    field: ca.SX, weight: ca.SX, left: ca.SX, right: ca.SX, image: ca.SX
) -> tuple[_Horseshoe, _Horseshoe]:
    """The right half's horseshoe at `field` (its bound leg weighted) and its image on the left
    half, which runs from T(right) to T(left) (its weight s is the caller's)."""
    return (
        _Horseshoe(field - left, field - right, weight),
        _Horseshoe(field - _image_of(right, image), field - _image_of(left, image), 1.0),
    )


def _weighted_velocity(right_half: _Horseshoe, left_half: _Horseshoe, weight: ca.SX) -> ca.SX:
    """(3,) [-] both halves' induced velocity per unit g, the image's weighted."""
    return (right_half.velocity() + weight * left_half.velocity()) * _INV_4PI


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
    field, weight, left, right, g = _pair_symbols()
    image, image_jacobian = _image_symbols()
    right_half, left_half = _flow_halves(field, weight, left, right, image)
    d_field, d_left, d_right = _flow_vertex_derivatives(
        *right_half.derivatives(), *left_half.derivatives(), image, image_jacobian
    )
    velocity = _weighted_velocity(right_half, left_half, image)
    influence = _weighted_velocity(right_half, left_half, image_jacobian)
    scaled = g * _INV_4PI
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
    field, weight, left, right, g = _pair_symbols()
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
    scaled = g * _INV_4PI
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
    field, weight, left, right, g = _column_symbols(m)
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
    field_all, weight_all, left_all, right_all, g_all = _all_symbols(m)
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
    field, weight, left, right, g = _column_symbols(m)
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
    field_all, weight_all, left_all, right_all, g_all = _all_symbols(m)
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
    field, weight, left, right, g = _pair_symbols()
    image = ca.SX.sym("image")
    if with_image:
        velocity = _weighted_velocity(*_flow_halves(field, weight, left, right, image), image)
    else:
        velocity = _Horseshoe(field - left, field - right, weight).velocity() * _INV_4PI
    pair = ca.Function(
        "vlm_flow_pair_value", [field, weight, left, right, g, image], [g * velocity]
    )
    over_fields = pair.map("vlm_flow_value_over_fields", "serial", m, [2, 3, 4, 5], [])
    field_mx, weight_mx, left_mx, right_mx, g_mx = _column_symbols(m)
    image_mx = ca.MX.sym("image")
    column = ca.Function(
        "vlm_flow_value_column",
        [field_mx, weight_mx, left_mx, right_mx, g_mx, image_mx],
        [ca.vec(over_fields(field_mx, weight_mx.T, left_mx, right_mx, g_mx, image_mx))],
    )
    over_sources = column.map("vlm_flow_value_over_sources", "serial", m, [0, 5], [0])
    field_all, weight_all, left_all, right_all, g_all = _all_symbols(m)
    return ca.Function(
        "vlm_flow_induced",
        [field_all, weight_all, left_all, right_all, g_all, image_mx],
        [over_sources(field_all, weight_all, left_all, right_all, g_all, image_mx)],
        ["field", "bound_weight", "left", "right", "g", "image"],
        ["induced"],
    )
