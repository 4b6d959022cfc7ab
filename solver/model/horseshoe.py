"""One horseshoe vortex seen from one field point: the kernel every induced velocity of the
lattice is made of (`solver.model.vlm`, `solver.model.flow_vlm`), and the symbols those kernels
map over.

A horseshoe has a bound leg from its vertex A to its vertex B and two trailing legs running to
+x infinity (geometry axes, not along the freestream: AeroSandbox's default). Its induced
velocity at a field point (Drela's form, as in AeroSandbox's
``calculate_induced_velocity_horseshoe``), with a = P - A, b = P - B and u = [1, 0, 0]:

    v = 1/(4 pi) [ (a x b)(1/|a| + 1/|b|) / (|a||b| + a.b) + (a x u)/(|a|(|a| - a.u))
                   - (b x u)/(|b|(|b| - b.u)) ]

A bound leg induces nothing at its own midpoint, where the first term is 0/0: the `bound_weight`
input masks it exactly (AeroSandbox's 1e-8 m core radius gives the same numbers).

The kernels are most of the Jacobian's cost, so their derivatives are written out by hand
(`Horseshoe`) from reciprocals computed once per horseshoe: no division and no square root in
the derivative graph, where CasADi's differentiation rules put ~80 divisions into each pair
(1.1-1.4x faster kernels; tests/solver/model/test_horseshoe.py checks them against CasADi's
differentiation to round-off).
"""

from __future__ import annotations

import casadi as ca
import numpy as np

__all__ = [
    "INV_4PI",
    "Horseshoe",
    "all_symbols",
    "column_symbols",
    "horseshoe_velocity",
    "pair_symbols",
]


def _cross(a: ca.SX, b: ca.SX) -> ca.SX:
    return ca.vertcat(
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    )


INV_4PI = 1.0 / (4 * np.pi)
_E_X = ca.DM([1.0, 0.0, 0.0])


def _skew(v: ca.SX) -> ca.SX:
    """(3, 3) the cross-product matrix: _skew(v) w = v x w."""
    zero = ca.SX(1, 1)
    return ca.vertcat(
        ca.horzcat(zero, -v[2], v[1]),
        ca.horzcat(v[2], zero, -v[0]),
        ca.horzcat(-v[1], v[0], zero),
    )


class Horseshoe:
    """One horseshoe (bound leg left -> right, trailing legs to +x infinity) seen from one
    field point, through a = field - left and b = field - right, times 4 pi.

    The velocity is written with its reciprocals computed once,

        4 pi v = k (a x b) + f_a (a x u) - f_b (b x u),
        k = w (1/|a| + 1/|b|) / (|a||b| + a.b + 1 - w),   f_a = 1/(|a| (|a| - a_x)),

    and its derivatives in a and b are written out by hand from the same reciprocals: the
    derivative graph has no division and no square root, where CasADi's own differentiation
    rules put ~40 divisions into each horseshoe's. tests/solver/model/test_horseshoe.py checks
    them against CasADi's differentiation of `horseshoe_velocity`.
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
    return Horseshoe(field - left, field - right, bound_weight).velocity() * INV_4PI


def pair_symbols() -> tuple[ca.SX, ca.SX, ca.SX, ca.SX, ca.SX]:
    """One field point and one source panel: field (3,), bound_weight, left (3,), right (3,), g."""
    return (
        ca.SX.sym("field", 3),
        ca.SX.sym("bound_weight"),
        ca.SX.sym("left", 3),
        ca.SX.sym("right", 3),
        ca.SX.sym("g"),
    )


def column_symbols(m: int) -> tuple[ca.MX, ca.MX, ca.MX, ca.MX, ca.MX]:
    """One source against M field points: field (3, M), bound_weight (M, 1), left (3, 1),
    right (3, 1), g."""
    return (
        ca.MX.sym("field", 3, m),
        ca.MX.sym("bound_weight", m, 1),
        ca.MX.sym("left", 3, 1),
        ca.MX.sym("right", 3, 1),
        ca.MX.sym("g"),
    )


def all_symbols(m: int) -> tuple[ca.MX, ca.MX, ca.MX, ca.MX, ca.MX]:
    """M sources against M field points: field (3, M), bound_weight (M, M), left (3, M),
    right (3, M), g (1, M)."""
    return (
        ca.MX.sym("field", 3, m),
        ca.MX.sym("bound_weight", m, m),
        ca.MX.sym("left", 3, m),
        ca.MX.sym("right", 3, m),
        ca.MX.sym("g", 1, m),
    )
