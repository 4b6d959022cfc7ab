"""The induced velocities of the compiled model and their exact derivatives, by the chain rule.

The O(M^2) induced-velocity part of the Jacobian is never differentiated through as one dense
graph: the kernels (`solver.model.vlm`, `solver.model.flow_vlm`) give each horseshoe's velocity
and its derivatives with respect to its field point and its two vertices (along the collocation
points' normals for flow tangency, where only n . v counts), and those are combined with the
lattice's own derivatives with respect to the beam's unknowns (`solver.model.aerodynamics
.lattice_function`). Strip theory's induced velocities (`solver.model.strip`) take the same
form.
"""

from __future__ import annotations

import casadi as ca

from solver.model.flow_vlm import flow_induced_velocities
from solver.model.strip import strip_induced_function
from solver.model.symbols import Symbols
from solver.model.vlm import induced_velocities

__all__ = [
    "Kernel",
    "induced_at_points",
    "induced_derivative",
    "induced_values",
    "lattice_induced",
    "strip_induced",
]

Kernel = tuple[ca.MX, ca.MX, ca.MX]  # the induced velocities' d/d(field, left, right points)


def induced_derivative(
    g_dfield: ca.MX,
    g_dleft: ca.MX,
    g_dright: ca.MX,
    field_z: ca.MX,
    left_z: ca.MX,
    right_z: ca.MX,
    m: int,
    rows_per_point: int = 3,
) -> ca.MX:
    """d(induced velocity)/dz by the chain rule through field points and vortex vertices.

    g_dfield (R, 3), g_dleft/g_dright (R, 3M) from `vlm.source_columns` (R = 3M, rows 3i + c:
    field point i's component c) or `vlm.normal_source_columns` (R = M, rows_per_point = 1: the
    normal component); field_z, left_z, right_z (3M, 3N) the lattice's derivatives (rows
    3p + c: point p's coordinate c). The field points' term is one sparse product
    (`_per_field_point`), not a product through a diagonal matrix per coordinate: 1.05x faster
    Jacobians at N = 30.
    """
    result = ca.mtimes(g_dleft, left_z) + ca.mtimes(g_dright, right_z)
    return result + ca.mtimes(_per_field_point(g_dfield, m, rows_per_point), field_z)


def _per_field_point(g_dfield: ca.MX, m: int, rows_per_point: int) -> ca.MX:
    """(R, 3M) sparse: row r of field point i holds g_dfield[r, :] in columns 3 i .. 3 i + 2, so
    that its product with field_z (3M, 3N) applies each row's field-point derivative in one
    sparse product (R = rows_per_point M)."""
    r = rows_per_point * m
    rows, columns, order = [], [], []
    for i in range(m):
        for c in range(3):  # column 3 i + c, rows in increasing order (compressed columns)
            for d in range(rows_per_point):
                row = rows_per_point * i + d
                rows.append(row)
                columns.append(3 * i + c)
                order.append(c * r + row)  # g_dfield (R, 3) is stored column-major
    pattern = ca.Sparsity.triplet(r, 3 * m, rows, columns)
    values = ca.vec(g_dfield)[order]
    return ca.MX(pattern, values)


def lattice_induced(
    sym: Symbols,
    left: ca.MX,
    right: ca.MX,
    collocation: ca.MX,
    center: ca.MX,
    normal: ca.MX,
    left_z: ca.MX,
    right_z: ca.MX,
    collocation_z: ca.MX,
    center_z: ca.MX,
) -> tuple[ca.MX, ca.MX, ca.MX, ca.MX, Kernel, Kernel]:
    """The lattice's induced velocities and their derivatives w.r.t. x = [z; g]: at the
    collocation points (3M,) with the normal component's derivative (M, nx), at the force
    points (3M,) with theirs (3M, nx); and the kernels' point derivatives at both (the flow
    model's control direction moves the points too)."""
    m = sym.m
    ind_t, infl_t, dfield_t, dleft_t, dright_t = sym.sources(
        collocation, sym.all_bound_legs, left, right, normal
    )
    ind_f, infl_f, dfield_f, dleft_f, dright_f = sym.sources(
        center, sym.no_self_bound_leg, left, right
    )
    # Normal induced velocities at the collocation points and induced velocities at the force
    # points, w.r.t. x = [z; g].
    normal_ind_t_x = ca.horzcat(
        induced_derivative(dfield_t, dleft_t, dright_t, collocation_z, left_z, right_z, m, 1),
        infl_t,
    )
    ind_f_x = ca.horzcat(
        induced_derivative(dfield_f, dleft_f, dright_f, center_z, left_z, right_z, m), infl_f
    )
    kernels = (dfield_t, dleft_t, dright_t), (dfield_f, dleft_f, dright_f)
    return ind_t, normal_ind_t_x, ind_f, ind_f_x, *kernels


def strip_induced(sym: Symbols) -> tuple[ca.MX, ca.MX, ca.MX, ca.MX]:
    """Strip theory's induced velocities (`solver.model.strip`) in the form of
    `lattice_induced`: none at the force points, so the loads see the freestream alone."""
    m, nx = sym.m, sym.layout.n_unknowns
    ind_t, normal_ind_t_x = strip_induced_function(sym.layout, True)(sym.z, sym.circulation, sym.p)
    return ind_t, normal_ind_t_x, ca.MX(3 * m, 1), ca.MX(3 * m, nx)


def induced_values(sym: Symbols, left: ca.MX, right: ca.MX, field: ca.MX, weights: ca.DM) -> ca.MX:
    """The horseshoes' induced velocities at `field` (3M,), without derivatives."""
    if sym.flow:
        return flow_induced_velocities(sym.m)(
            field, weights, left, right, sym.circulation.T, sym.parameters.image
        )
    induced = induced_velocities(sym.m)
    return induced(field, weights, left, right, sym.circulation.T)


def induced_at_points(
    sym: Symbols, left: ca.MX, right: ca.MX, collocation: ca.MX, center: ca.MX
) -> tuple[ca.MX, ca.MX]:
    """Induced velocities (values only) at the collocation and the force points, (3M,) each."""
    if sym.layout.aerodynamics == "strip":
        induced = strip_induced_function(sym.layout, False)(sym.z, sym.circulation, sym.p)
        return induced, ca.MX(3 * sym.m, 1)
    ind_t = induced_values(sym, left, right, collocation, sym.all_bound_legs)
    ind_f = induced_values(sym, left, right, center, sym.no_self_bound_leg)
    return ind_t, ind_f
