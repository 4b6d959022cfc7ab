"""The coupled aeroelastic residual of one mesh, built symbolically once.

Unknowns, equations and parameters: `solver.model.layout`. The equations, with
h_i = (y_{i+1} - y_i) / cos(sweep) the beam's segment lengths along the elastic axis (EA):

    root clamps (3)          u_0 = 0, u'_0 = 0, phi_0 = 0
    heave kinematics (N-1)   u_{i+1} - u_i - h_i (u'_i + u'_{i+1}) / 2 = 0                   [m]
    bending (N-1)            u'_{i+1} - u'_i - h_i (M_i/EI_i + M_{i+1}/EI_{i+1}) / 2 = 0     [-]
    torsion (N-1)            phi_{i+1} - phi_i
                               - h_i (180/pi)(T_i/GJ_i + T_{i+1}/GJ_{i+1}) / 2 = 0           [deg]
    flow tangency (M)        (V_hat + induced_p) . n_p = 0                                   [-]

The trapezoidal rule is AeroSandbox's ``constrain_derivative``; the tangency rows are per unit V.
Internal loads by outboard sums over every panel p of the strips outboard of station i, with F_p
its force at its deformed force point r_p, e_s = (sin, cos, 0) of the sweep and r_i station i's
undeformed EA point (s_i = y_i / cos(sweep) along the EA):

    M_i = sum_p Fz_p (r_p . e_s) - s_i sum_p Fz_p
    T_i = sum_p (r_p x F_p) . e_s - d u_i sum_p (Fx_p cos(sweep) - Fy_p sin(sweep))

with d = 1 when the torque is taken about the heaved EA point (`deformed_axis`), else 0 (the
study's undeformed axis). At sweep 0, d = 0 and one chordwise panel these are the study's sums.

Aerodynamic loads scale with the dynamic pressure q = rho V^2 / 2 once the circulation is written
per unit V, so the residual is exactly affine in q:

    r(x; p, q) = r0(x; p) + q r1(x; p),   J = J0 + q J1.

The compiled function returns r0, r1, J0, J1 (their non-zero row blocks), and for trimmed
flight the derivatives of r0 and r1 in alpha and the lift per unit q with its derivatives.

The flow model (`flow=True` in the builders; control surfaces and roll: `solver.roll`,
`solver.controls.effectiveness`) is the same model with the image half's flow as parameters
(`solver.model.flow_vlm`'s kernels: the mirror or the rotation about x, and the image's derivatives
exact or turned), a steady roll rate p, which adds (p / V) (0, z, -y) to the unit freestream at
the collocation and force points (the air seen from a wing rolling about x), and more outputs:
the derivatives of r0, r1, the lift and the rolling moment along a control direction (a
d(camber)/d(deflection) parameter) and in the roll rate, the rolling moment's gradient, and
the panel loads' derivatives along a direction in the unknowns. Its functions are separate
(built with Python branches, so `flow=False` builds exactly the symmetric model's graph): the
flow kernels and the outputs would cost every symmetric Jacobian ~15 % (measured), and the flow
model lives in a library of its own (`solver.numerics.compiled`), compiled when first used. The
Jacobian is exact: CasADi differentiates the lattice geometry, the aerodynamic glue and the
horseshoe kernel (`vlm.pair_kernel` at the force points; `vlm.normal_pair_kernel` at the
collocation points, where tangency needs only the normal component); the O(M^2)
induced-velocity part is combined by the chain rule from the kernel's own derivatives, and the
beam's outboard sums are applied as running sums over a sparse panels-to-strips operator, which
keeps the work at O(M^2) instead of O(M^3).

Strip theory (`Layout.aerodynamics == "strip"`) is the same model with the lattice's induced
velocities replaced by each strip's own two-dimensional ones (`_strip_induced_function`): a
strip's tangency rows see only its own bound vortices, as infinite line vortices, and its
forces see the freestream alone. Every other row, the geometry and the beam are the lattice's,
so every static operation runs unchanged on it; it is O(N k^2).
"""

from __future__ import annotations

import ast
import functools
import hashlib
import inspect
import sys
from types import ModuleType

import casadi as ca
import numpy as np

import solver.model.flow_vlm as flow_vlm_module
import solver.model.geometry as geometry_module
import solver.model.horseshoe as horseshoe_module
import solver.model.layout as layout_module
import solver.model.vlm as vlm_module
from solver.model.flow_vlm import (
    flow_induced_velocities,
    flow_normal_source_columns,
    flow_source_columns,
)
from solver.model.geometry import DEG, Lattice, arc_length, axis_force, lattice, span_axis
from solver.model.layout import Layout
from solver.model.vlm import induced_velocities, normal_source_columns, source_columns

__all__ = [
    "MODEL_VERSION",
    "build_coupled_function",
    "build_full_span_function",
    "build_panel_loads_function",
    "build_residual_function",
    "model_tag",
]


def _graph_source_digest(*modules: ModuleType) -> str:
    """A digest of the code the compiled model's graph is generated from, docstrings left out
    (comments never reach the syntax tree): a change to the equations or to how they are
    written changes it, an edit of the documentation does not."""
    digest = hashlib.blake2b(digest_size=6)
    for module in modules:
        tree = ast.parse(inspect.getsource(module))
        for node in ast.walk(tree):
            body = getattr(node, "body", None)
            if isinstance(body, list) and body and _is_docstring(body[0]):
                node.body = body[1:] or [ast.Pass()]  # type: ignore[attr-defined]
        digest.update(ast.dump(tree).encode())
    return digest.hexdigest()


def _is_docstring(statement: ast.stmt) -> bool:
    return (
        isinstance(statement, ast.Expr)
        and isinstance(statement.value, ast.Constant)
        and isinstance(statement.value.value, str)
    )


# Compiled libraries on disk are keyed by it (the flow model's too, `solver.numerics.compiled`): it
# changes by itself with the equations or the graph they are generated from (this module and the
# modules below it that build the graph).
MODEL_VERSION = _graph_source_digest(
    sys.modules[__name__],
    layout_module,
    geometry_module,
    horseshoe_module,
    vlm_module,
    flow_vlm_module,
)

DEG_PER_RAD = 180.0 / np.pi
# Per-panel loads, in this order, each M rows: Fx, Fy, Fz [m^2 per unit q], Fz (r . e_s) and
# (r x F) . e_s [m^3 per unit q]; the flow model adds (r x F) . e_x [m^3 per unit q], the
# rolling moment about x.
_LOADS = 5
_ROLL = 5


def _freestream(alpha_deg: ca.SX) -> ca.SX:
    """Unit freestream velocity in geometry axes, (3,) [-]."""
    alpha = alpha_deg * DEG
    return ca.vertcat(ca.cos(alpha), 0, ca.sin(alpha))


def _onset(alpha_deg: ca.SX, points: ca.SX, roll_rate: ca.SX | None) -> ca.SX:
    """(3, M) [-] the air's velocity per unit V at `points` (3, M) [m]: the freestream, plus
    (flow model) the roll rate's (p / V) (0, z, -y), the air seen from a wing rolling about x
    at p [rad/s] (x aft, y right, z up; positive p raises the right wing)."""
    m = points.shape[1]
    onset = ca.repmat(_freestream(alpha_deg), 1, m)
    if roll_rate is None:
        return onset
    return onset + roll_rate * ca.vertcat(ca.DM.zeros(1, m), points[2, :], -points[1, :])


class _Parameters:
    """The parameter vector's parts, as SX symbols of the glue functions."""

    def __init__(self, layout: Layout) -> None:
        n, k1 = layout.n, layout.chordwise + 1
        self.layout = layout
        self.y, self.chord, self.ea, self.jig = (ca.SX.sym(s, n) for s in ("y", "c", "ea", "jig"))
        self.camber = ca.SX.sym("camber", n * k1)
        self.sweep = ca.SX.sym("sweep")

    @property
    def inputs(self) -> list[ca.SX]:
        return [self.y, self.chord, self.ea, self.jig, self.camber, self.sweep]

    def lattice(self, z: ca.SX) -> Lattice:
        n = self.layout.n
        camber = ca.reshape(self.camber, self.layout.chordwise + 1, n).T
        return lattice(
            z[:n],
            z[n : 2 * n],
            z[2 * n :],
            self.y,
            self.chord,
            self.ea,
            self.jig,
            camber,
            self.sweep,
            self.layout.chordwise,
        )


# The symbolic pieces are pure functions of the mesh: each of the three compiled functions uses
# them, so they are built once per mesh, not three times.
@functools.lru_cache(maxsize=16)
def _lattice_function(layout: Layout, flow: bool = False) -> ca.Function:
    """(z, parameters) -> vortex vertices, collocation and force points, the panels' unit
    normals, and the four point sets' derivatives w.r.t. z = [u; u'; phi] (3N). The flow model
    adds the input control (N (k + 1)) and the four point sets' derivatives along it (3M, 1),
    and the stations' leading edges' and quarter-chord points' derivatives w.r.t. z."""
    params = _Parameters(layout)
    z = ca.SX.sym("z", 3 * layout.n)
    lat = params.lattice(z)
    outputs = [lat.left, lat.right, lat.collocation, lat.center]
    jacobians = [ca.jacobian(ca.vec(out), z) for out in outputs]
    if not flow:
        return ca.Function("wing_lattice", [z, *params.inputs], [*outputs, lat.normal, *jacobians])
    control = ca.SX.sym("control", params.camber.shape[0])
    along = [ca.jtimes(ca.vec(out), params.camber, control) for out in outputs]
    stations = [ca.jacobian(ca.vec(out), z) for out in (lat.leading_edge, lat.quarter_chord)]
    return ca.Function(
        "wing_flow_lattice",
        [z, *params.inputs, control],
        [*outputs, lat.normal, *jacobians, *along, *stations],
    )


def _panel_loads(
    lat: Lattice,
    g: ca.SX,
    alpha_deg: ca.SX,
    induced: ca.SX,
    sweep: ca.SX,
    roll_rate: ca.SX | None = None,
):
    """Per-panel forces per unit q (Kutta-Joukowski F = rho (V_local x l) Gamma = 2 q (V_hat_local
    x l) g) and their moments about the elastic axis: ((3, M) force [m^2], (5M,) loads); with a
    roll rate (the flow model) its onset and the moments about x too ((6M,) loads)."""
    m = lat.leg.shape[1]
    v_local = _onset(alpha_deg, lat.center, roll_rate) + ca.reshape(induced, 3, m)
    leg, g_row = lat.leg, g.T
    force = 2 * ca.vertcat(
        (v_local[1, :] * leg[2, :] - v_local[2, :] * leg[1, :]) * g_row,
        (v_local[2, :] * leg[0, :] - v_local[0, :] * leg[2, :]) * g_row,
        (v_local[0, :] * leg[1, :] - v_local[1, :] * leg[0, :]) * g_row,
    )
    e_s = span_axis(sweep)
    center = lat.center
    arm = e_s[0] * center[0, :] + e_s[1] * center[1, :]
    moment = ca.vertcat(
        center[1, :] * force[2, :] - center[2, :] * force[1, :],
        center[2, :] * force[0, :] - center[0, :] * force[2, :],
        center[0, :] * force[1, :] - center[1, :] * force[0, :],
    )
    torque = e_s[0] * moment[0, :] + e_s[1] * moment[1, :]
    loads = ca.vertcat(force[0, :].T, force[1, :].T, force[2, :].T, (force[2, :] * arm).T, torque.T)
    if roll_rate is not None:
        loads = ca.vertcat(loads, moment[0, :].T)
    return force, loads


@functools.lru_cache(maxsize=16)
def _aero_function(layout: Layout, with_jacobians: bool, flow: bool = False) -> ca.Function:
    """Tangency residuals and per-panel loads given the induced velocities.

    Outputs: tangency (M,) [-]; loads (5M,) per unit q (see _LOADS). With `with_jacobians` also
    their partial derivatives w.r.t. w = [u; u'; phi; g] (the induced velocities held fixed: for
    tangency that leaves the normal's rotation), the loads' w.r.t. the induced velocities at the
    force points, and both w.r.t. alpha. (Tangency's derivative through the induced velocity is
    n . d(induced), which `vlm.normal_source_columns` gives directly.) The flow model adds the
    inputs roll_rate and control, the rolling moments (loads 6M), and with `with_jacobians`
    both outputs' derivatives along the control and w.r.t. the roll rate.
    """
    m = layout.n_panels
    params = _Parameters(layout)
    z = ca.SX.sym("z", 3 * layout.n)
    g = ca.SX.sym("g", m)
    alpha_deg = ca.SX.sym("alpha")
    induced_tangency = ca.SX.sym("induced_tangency", 3 * m)
    induced_forces = ca.SX.sym("induced_forces", 3 * m)
    roll_rate = ca.SX.sym("roll_rate")
    control = ca.SX.sym("control", params.camber.shape[0])
    lat = params.lattice(z)
    rate = roll_rate if flow else None
    _, loads = _panel_loads(lat, g, alpha_deg, induced_forces, params.sweep, rate)
    v_collocation = _onset(alpha_deg, lat.collocation, rate) + ca.reshape(induced_tangency, 3, m)
    tangency = ca.sum1(v_collocation * lat.normal).T
    outputs = [tangency, loads]
    if with_jacobians:
        w = ca.vertcat(z, g)
        outputs += [
            ca.jacobian(tangency, w),
            ca.jacobian(loads, w),
            ca.jacobian(loads, induced_forces),
            ca.jacobian(tangency, alpha_deg),
            ca.jacobian(loads, alpha_deg),
        ]
        if flow:
            outputs += [
                ca.jtimes(tangency, params.camber, control),
                ca.jtimes(loads, params.camber, control),
                ca.jacobian(tangency, roll_rate),
                ca.jacobian(loads, roll_rate),
            ]
    inputs = [z, g, *params.inputs, alpha_deg, induced_tangency, induced_forces]
    name = "aero_glue" if with_jacobians else "aero_glue_values"
    if flow:
        return ca.Function(f"flow_{name}", [*inputs, roll_rate, control], outputs)
    return ca.Function(name, inputs, outputs)


def _outboard_sum(strip_rows: ca.MX) -> ca.MX:
    """(N-1, c) per-strip rows -> (N, c): row i sums strips j >= i (zero at the tip).

    A running sum from the tip, O(N c), where a triangular matrix product would be O(N^2 c).
    """
    m, c = strip_rows.shape
    running = ca.MX(1, c)
    rows = [running]
    for j in reversed(range(m)):
        running = running + strip_rows[j, :]
        rows.append(running)
    return ca.vertcat(*reversed(rows))


def _scale_rows(factors: ca.MX, matrix: ca.MX) -> ca.MX:
    """diag(factors) matrix, for a (r, 1) column of factors and a dense (r, c) matrix: an
    elementwise product, where CasADi's sparse product through a diagonal matrix goes through
    index arrays and a dense work column for every column."""
    return ca.repmat(factors, 1, matrix.size2()) * matrix


class _Beam:
    """The beam's load rows from per-panel loads (values or derivative rows: all linear but the
    deformed-axis term, which the Jacobian adds by hand)."""

    def __init__(self, layout: Layout, y: ca.MX, ei: ca.MX, gj: ca.MX, sweep: ca.MX) -> None:
        self.layout = layout
        self.sweep = sweep
        self.s = arc_length(y, sweep)  # [m] along the EA
        self.h = self.s[1:] - self.s[:-1]
        self.ei, self.gj = ei, gj
        k, strips = layout.chordwise, layout.n_strips
        # Panels to strips: strip i holds panels i k .. i k + k - 1.
        self.strips = ca.sparsify(ca.DM(np.kron(np.eye(strips), np.ones((1, k)))))

    def _outboard(self, loads: ca.MX, part: int) -> ca.MX:
        m = self.layout.n_panels
        return _outboard_sum(ca.mtimes(self.strips, loads[part * m : (part + 1) * m, :]))

    def bending(self, loads: ca.MX) -> ca.MX:
        """(N, c) M_i, linear in the loads."""
        return self._outboard(loads, 3) - _scale_rows(self.s, self._outboard(loads, 2))

    def axis_force(self, loads: ca.MX) -> ca.MX:
        """(N, c) outboard sum of Fx cos(sweep) - Fy sin(sweep)."""
        return axis_force(self._outboard(loads, 0), self._outboard(loads, 1), self.sweep)

    def rows(self, bending: ca.MX, torque: ca.MX) -> ca.MX:
        """(2(N-1), c): -h_i/2 (f_i/K_i + f_{i+1}/K_{i+1}) for M/EI and degrees(T/GJ)."""

        def trapezoid(integrand: ca.MX, stiffness: ca.MX, scale: float) -> ca.MX:
            inner = -scale * self.h / (2 * stiffness[:-1])
            outer = -scale * self.h / (2 * stiffness[1:])
            return _scale_rows(inner, integrand[:-1, :]) + _scale_rows(outer, integrand[1:, :])

        return ca.vertcat(trapezoid(bending, self.ei, 1.0), trapezoid(torque, self.gj, DEG_PER_RAD))

    def load_rows(self, loads: ca.MX, heave: ca.MX, deformed: ca.MX) -> ca.MX:
        """(2(N-1), 1) the q-proportional part of the bending and torsion equations."""
        torque = self._outboard(loads, 4) - deformed * heave * self.axis_force(loads)
        return self.rows(self.bending(loads), torque)

    def load_rows_along(self, loads_along: ca.MX, heave: ca.MX, deformed: ca.MX) -> ca.MX:
        """(2(N-1), 1) d(load_rows) along a parameter the heave does not depend on (alpha, the
        control direction, the roll rate), from the loads' derivative along it."""
        torque = self._outboard(loads_along, 4) - deformed * heave * self.axis_force(loads_along)
        return self.rows(self.bending(loads_along), torque)

    def load_rows_jacobian(
        self, loads: ca.MX, loads_x: ca.MX, heave: ca.MX, deformed: ca.MX, heave_columns: ca.DM
    ) -> ca.MX:
        """(2(N-1), nx) d(load_rows)/dx from the loads and their derivative rows (5M, nx)."""
        torque_x = self._outboard(loads_x, 4) - deformed * (
            _scale_rows(heave, self.axis_force(loads_x))
            + ca.mtimes(ca.diag(self.axis_force(loads)), heave_columns)
        )
        return self.rows(self.bending(loads_x), torque_x)


def _structure_rows(layout: Layout, x: ca.MX, h: ca.MX) -> ca.MX:
    """Root clamps, heave kinematics and the load-free part of bending and torsion rows."""
    heave, slope, twist = x[layout.heave], x[layout.slope], x[layout.twist]
    return ca.vertcat(
        heave[0],
        slope[0],
        twist[0],
        heave[1:] - heave[:-1] - h * (slope[:-1] + slope[1:]) / 2,
        slope[1:] - slope[:-1],
        twist[1:] - twist[:-1],
    )


def _induced_derivative(
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


class _Symbols:
    """Symbolic unknowns and parameters of one mesh, split into named parts (the flow model's
    too, with `flow`)."""

    def __init__(self, layout: Layout, flow: bool = False) -> None:
        self.layout = layout
        self.flow = flow
        self.m = layout.n_panels
        self.x = ca.MX.sym("x", layout.n_unknowns)
        n_parameters = layout.n_parameters + (layout.n_flow_parameters if flow else 0)
        self.p = ca.MX.sym("p", n_parameters)
        self.z = self.x[layout.structure]
        self.heave = self.x[layout.heave]
        self.circulation = self.x[layout.circulation]
        (
            self.y,
            self.chord,
            self.ea,
            self.ei,
            self.gj,
            self.jig,
            self.camber,
            self.alpha_deg,
            self.sweep,
            self.deformed,
        ) = layout.split(self.p)
        self.geometry_inputs = [self.y, self.chord, self.ea, self.jig, self.camber, self.sweep]
        self.flow_inputs: list[ca.MX] = []
        if flow:
            (
                self.image,
                self.image_jacobian,
                self.roll_rate,
                self.control,
                self.direction,
            ) = layout.split_flow(self.p)
            self.flow_inputs = [self.roll_rate, self.control]
        self.beam = _Beam(layout, self.y, self.ei, self.gj, self.sweep)
        # The horseshoe of panel p induces nothing of its bound leg at its own force point.
        self.all_bound_legs = ca.DM.ones(self.m, self.m)
        self.no_self_bound_leg = ca.DM.ones(self.m, self.m) - ca.DM.eye(self.m)

    def lattice(self) -> tuple[ca.MX, ...]:
        """left, right, collocation, center, normal, and the point sets' derivatives w.r.t. z
        (the flow model's outputs too)."""
        inputs = [*self.geometry_inputs, *([self.control] if self.flow else [])]
        return tuple(_lattice_function(self.layout, self.flow)(self.z, *inputs))  # type: ignore[arg-type]

    def aero(self, with_jacobians: bool, induced_tangency: ca.MX, induced_forces: ca.MX):
        return _aero_function(self.layout, with_jacobians, self.flow)(
            self.z,
            self.circulation,
            *self.geometry_inputs,
            self.alpha_deg,
            induced_tangency,
            induced_forces,
            *self.flow_inputs,
        )

    def sources(self, field: ca.MX, weights: ca.DM, left: ca.MX, right: ca.MX, normal=None):
        """The horseshoes' induced velocities and derivatives at `field`: along the normals
        (`vlm.normal_source_columns`) when given, else the full vectors; the flow model's with
        the image's parameters."""
        m, g_row = self.m, self.circulation.T
        image = [self.image, self.image_jacobian] if self.flow else []
        if normal is not None:
            columns = flow_normal_source_columns(m) if self.flow else normal_source_columns(m)
            return columns(field, normal, weights, left, right, g_row, *image)
        columns = flow_source_columns(m) if self.flow else source_columns(m)
        return columns(field, weights, left, right, g_row, *image)

    def residual(self, tangency: ca.MX, loads: ca.MX) -> tuple[ca.MX, ca.MX]:
        """r0 and r1 from the aerodynamic outputs."""
        n_strips = self.layout.n_strips
        r0 = ca.vertcat(_structure_rows(self.layout, self.x, self.beam.h), tangency)
        r1 = ca.vertcat(
            ca.MX(3 + n_strips, 1),
            self.beam.load_rows(loads, self.heave, self.deformed),
            ca.MX(self.m, 1),
        )
        return r0, r1

    def drag(self, loads: ca.MX) -> ca.MX:
        """Near-field induced drag of both halves per unit q [m^2]: 2 sum (Fx cos + Fz sin)."""
        m, alpha = self.m, self.alpha_deg * DEG
        return 2 * (
            ca.cos(alpha) * ca.sum1(loads[:m, :]) + ca.sin(alpha) * ca.sum1(loads[2 * m : 3 * m, :])
        )

    def lift(self, loads: ca.MX) -> ca.MX:
        """Lift of both halves per unit q [m^2]: 2 sum (Fz cos(alpha) - Fx sin(alpha))."""
        m, alpha = self.m, self.alpha_deg * DEG
        return 2 * (
            ca.cos(alpha) * ca.sum1(loads[2 * m : 3 * m, :]) - ca.sin(alpha) * ca.sum1(loads[:m, :])
        )

    def roll(self, loads: ca.MX) -> ca.MX:
        """Twice the right half's rolling moment about x per unit q [m^3], 2 sum (y Fz - z Fy)
        (flow model): both halves' in the antisymmetric flow (image -1), where the image rolls
        as the right half does; with image_jacobian -1 about a symmetric state, the derivatives
        of both halves' for the antisymmetric disturbance (`solver.model.vlm`)."""
        m = self.m
        return 2 * ca.sum1(loads[_ROLL * m : (_ROLL + 1) * m, :])


_Kernel = tuple[ca.MX, ca.MX, ca.MX]  # the induced velocities' d/d(field, left, right points)


def _lattice_induced(
    sym: _Symbols,
    left: ca.MX,
    right: ca.MX,
    collocation: ca.MX,
    center: ca.MX,
    normal: ca.MX,
    left_z: ca.MX,
    right_z: ca.MX,
    collocation_z: ca.MX,
    center_z: ca.MX,
) -> tuple[ca.MX, ca.MX, ca.MX, ca.MX, _Kernel, _Kernel]:
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
        _induced_derivative(dfield_t, dleft_t, dright_t, collocation_z, left_z, right_z, m, 1),
        infl_t,
    )
    ind_f_x = ca.horzcat(
        _induced_derivative(dfield_f, dleft_f, dright_f, center_z, left_z, right_z, m), infl_f
    )
    kernels = (dfield_t, dleft_t, dright_t), (dfield_f, dleft_f, dright_f)
    return ind_t, normal_ind_t_x, ind_f, ind_f_x, *kernels


def _strip_induced(sym: _Symbols) -> tuple[ca.MX, ca.MX, ca.MX, ca.MX]:
    """Strip theory's induced velocities (`_strip_induced_function`) in the form of
    `_lattice_induced`: none at the force points, so the loads see the freestream alone."""
    m, nx = sym.m, sym.layout.n_unknowns
    ind_t, normal_ind_t_x = _strip_induced_function(sym.layout, True)(
        sym.z, sym.circulation, *sym.geometry_inputs
    )
    return ind_t, normal_ind_t_x, ca.MX(3 * m, 1), ca.MX(3 * m, nx)


@functools.lru_cache(maxsize=8)
def _strip_induced_function(layout: Layout, with_jacobian: bool) -> ca.Function:
    """Strip theory: the velocity per unit V at each collocation point induced by the bound
    vortices of its own strip only, each an infinite (two-dimensional) line vortex along its leg,

        v_p = sum over panels p' of p's strip of g_p' / (2 pi) (l_p' x d) / |d|^2,

    with l_p' the unit leg and d the part of (collocation_p - center_p') normal to it; no
    trailing legs, no other strip, no mirrored half. One chordwise panel puts the collocation
    point half a chord behind the vortex, so tangency gives g = pi c sin(incidence): the thin
    airfoil's lift, slope 2 pi per radian, at the quarter chord. With k panels each strip is the
    two-dimensional discrete-vortex airfoil (vortices at the panels' quarter, tangency at their
    three-quarter points), which carries the camber's lift and moment.

    (z, g, parameters) -> induced (3M,) (rows 3 p + c), and with `with_jacobian` the normal
    component's derivative n_p . d(v_p)/dx (M, 3N + M)."""
    m, k = layout.n_panels, layout.chordwise
    params = _Parameters(layout)
    z = ca.SX.sym("z", 3 * layout.n)
    g = ca.SX.sym("g", m)
    lat = params.lattice(z)
    columns = []
    for p in range(m):
        first = (p // k) * k
        velocity = ca.SX.zeros(3, 1)
        for q in range(first, first + k):
            unit = lat.leg[:, q] / ca.norm_2(lat.leg[:, q])
            offset = lat.collocation[:, p] - lat.center[:, q]
            normal_offset = offset - ca.dot(offset, unit) * unit
            velocity += (
                g[q]
                / (2 * np.pi)
                * _cross_columns(unit, normal_offset)
                / ca.dot(normal_offset, normal_offset)
            )
        columns.append(velocity)
    induced = ca.vertcat(*columns)
    outputs = [induced]
    if with_jacobian:
        derivative = ca.jacobian(induced, ca.vertcat(z, g))
        outputs.append(
            ca.vertcat(
                *[ca.mtimes(lat.normal[:, p].T, derivative[3 * p : 3 * p + 3, :]) for p in range(m)]
            )
        )
    return ca.Function(
        "strip_induced" if with_jacobian else "strip_induced_values",
        [z, g, *params.inputs],
        outputs,
    )


def _cross_columns(a: ca.SX, b: ca.SX) -> ca.SX:
    """a x b of two (3, 1) columns."""
    return ca.vertcat(
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    )


def _induced_at_points(
    sym: _Symbols, left: ca.MX, right: ca.MX, collocation: ca.MX, center: ca.MX
) -> tuple[ca.MX, ca.MX]:
    """Induced velocities (values only) at the collocation and the force points, (3M,) each."""
    if sym.layout.aerodynamics == "strip":
        induced = _strip_induced_function(sym.layout, False)(
            sym.z, sym.circulation, *sym.geometry_inputs
        )
        return induced, ca.MX(3 * sym.m, 1)
    ind_t = _induced_values(sym, left, right, collocation, sym.all_bound_legs)
    ind_f = _induced_values(sym, left, right, center, sym.no_self_bound_leg)
    return ind_t, ind_f


def build_coupled_function(layout: Layout, flow: bool = False) -> ca.Function:
    """(x, p) -> r0, r1, the non-zero row blocks of J0 and J1 (dense), and for trim r0_alpha,
    r1_alpha (per degree), lift (per unit q), lift_x (1, n) and lift_alpha; for design the
    near-field drag (per unit q) and drag_x (1, n). See the module docstring.

    The flow model (`flow`) takes the flow parameters after the model's (`solver.model.layout`) and
    adds, for control surfaces, r0_control, r1_control and lift_control along the control
    direction (per radian), the rolling moment (twice the right half's, per unit q,
    `_Symbols.roll`), roll_x (1, n) and roll_control; for roll r0_rate, r1_rate and roll_rate,
    per unit roll rate p / V [rad/m]; and for a roll answer's linearised loads the panel loads'
    derivatives (6M, see _LOADS, per unit q) along the direction parameter in x, the control
    and the roll rate, the force points' (3M) along the direction and the control, and the
    stations' leading edges and quarter-chord points' (3N) along the direction (the camber
    moves neither).

    The Jacobians leave as row blocks (`solver.model.layout`): J0's structure rows (3N, n) and
    tangency rows (M, n), J1's load rows (2(N-1), n), its only non-zero ones. CasADi stores
    matrices by columns, so stacking row blocks into one matrix would transpose every block and
    the result; the caller places the blocks (`solver.numerics.compiled`), a plain copy."""
    sym = _Symbols(layout, flow)
    m, n, nx = sym.m, layout.n, layout.n_unknowns
    (
        left,
        right,
        collocation,
        center,
        normal,
        left_z,
        right_z,
        collocation_z,
        center_z,
        *flow_lattice,
    ) = sym.lattice()
    if layout.aerodynamics == "strip":
        if flow:
            raise ValueError("the flow model (control surfaces, roll) is the lattice's")
        ind_t, normal_ind_t_x, ind_f, ind_f_x = _strip_induced(sym)
        tangency_kernel = forces_kernel = (ca.MX(), ca.MX(), ca.MX())
    else:
        ind_t, normal_ind_t_x, ind_f, ind_f_x, tangency_kernel, forces_kernel = _lattice_induced(
            sym,
            left,
            right,
            collocation,
            center,
            normal,
            left_z,
            right_z,
            collocation_z,
            center_z,
        )
    tangency, loads, tangency_w, loads_w, loads_ind, tangency_a, loads_a, *flow_aero = sym.aero(
        True, ind_t, ind_f
    )
    tangency_x = tangency_w + normal_ind_t_x
    loads_x = loads_w + ca.mtimes(loads_ind, ind_f_x)
    r0, r1 = sym.residual(tangency, loads)
    structure = _structure_rows(layout, sym.x, sym.beam.h)
    heave_columns = ca.DM(np.eye(n, nx))
    j0_structure = ca.jacobian(structure, sym.x)
    j1_loads = sym.beam.load_rows_jacobian(loads, loads_x, sym.heave, sym.deformed, heave_columns)
    r0_alpha = ca.vertcat(ca.MX(3 * n, 1), tangency_a)
    r1_alpha = ca.vertcat(
        ca.MX(3 + layout.n_strips, 1),
        sym.beam.rows(
            sym.beam.bending(loads_a),
            sym.beam._outboard(loads_a, 4)
            - sym.deformed * sym.heave * sym.beam.axis_force(loads_a),
        ),
        ca.MX(m, 1),
    )
    lift = sym.lift(loads)
    lift_x = sym.lift(loads_x)
    alpha = sym.alpha_deg * DEG
    # d lift / d alpha [per degree]: through the loads, and through the wind axes' rotation.
    lift_alpha = sym.lift(loads_a) - 2 * DEG * (
        ca.sin(alpha) * ca.sum1(loads[2 * m : 3 * m]) + ca.cos(alpha) * ca.sum1(loads[:m])
    )
    drag = sym.drag(loads)
    drag_x = sym.drag(loads_x)
    flow_outputs = (
        _flow_outputs(
            sym,
            flow_lattice,
            flow_aero,
            loads,
            loads_x,
            loads_ind,
            tangency_kernel,
            forces_kernel,
            center_z,
        )
        if flow
        else {}
    )
    outputs = [
        r0,
        r1,
        j0_structure,
        tangency_x,
        j1_loads,
        r0_alpha,
        r1_alpha,
        lift,
        lift_x,
        lift_alpha,
        drag,
        drag_x,
        *flow_outputs.values(),
    ]
    return ca.Function(
        f"flexwing_{_kind(flow)}coupled_{model_tag(layout)}",
        [sym.x, sym.p],
        [ca.densify(out) for out in outputs],
        ["x", "p"],
        [
            "r0",
            "r1",
            "J0_structure_rows",
            "J0_tangency_rows",
            "J1_load_rows",
            "r0_alpha",
            "r1_alpha",
            "lift",
            "lift_x",
            "lift_alpha",
            "drag",
            "drag_x",
            *flow_outputs,
        ],
    )


def model_tag(layout: Layout) -> str:
    """The mesh's name in the compiled functions' names: N_k, and _strip for strip theory."""
    strip = "_strip" if layout.aerodynamics == "strip" else ""
    return f"{layout.n}_{layout.chordwise}{strip}"


def _flow_outputs(
    sym: _Symbols,
    flow_lattice: list[ca.MX],
    flow_aero: list[ca.MX],
    loads: ca.MX,
    loads_x: ca.MX,
    loads_ind: ca.MX,
    tangency_kernel: tuple[ca.MX, ca.MX, ca.MX],
    forces_kernel: tuple[ca.MX, ca.MX, ca.MX],
    center_z: ca.MX,
) -> dict[str, ca.MX]:
    """The flow model's outputs (`build_coupled_function`), by name."""
    layout, m, n = sym.layout, sym.m, sym.layout.n
    left_c, right_c, collocation_c, center_c, leading_edge_z, quarter_chord_z = flow_lattice
    tangency_c, loads_c, tangency_p, loads_p = flow_aero
    # Along the control direction: the geometry's own part, and the induced velocities' by the
    # chain rule through the lattice's points (as for z).
    tangency_c = tangency_c + _induced_derivative(
        *tangency_kernel, collocation_c, left_c, right_c, m, 1
    )
    loads_c = loads_c + ca.mtimes(
        loads_ind, _induced_derivative(*forces_kernel, center_c, left_c, right_c, m)
    )

    def r0_along(tangency_along: ca.MX) -> ca.MX:
        return ca.vertcat(ca.MX(3 * n, 1), tangency_along)

    def r1_along(loads_along: ca.MX) -> ca.MX:
        return ca.vertcat(
            ca.MX(3 + layout.n_strips, 1),
            sym.beam.load_rows_along(loads_along, sym.heave, sym.deformed),
            ca.MX(m, 1),
        )

    structure_direction = sym.direction[layout.structure]
    return {
        "r0_control": r0_along(tangency_c),
        "r1_control": r1_along(loads_c),
        "lift_control": sym.lift(loads_c),
        "roll": sym.roll(loads),
        "roll_x": sym.roll(loads_x),
        "roll_control": sym.roll(loads_c),
        "r0_rate": r0_along(tangency_p),
        "r1_rate": r1_along(loads_p),
        "roll_rate": sym.roll(loads_p),
        "loads_along": ca.mtimes(loads_x, sym.direction),
        "loads_control": loads_c,
        "loads_rate": loads_p,
        "center_along": ca.mtimes(center_z, structure_direction),
        "center_control": center_c,
        "leading_edge_along": ca.mtimes(leading_edge_z, structure_direction),
        "quarter_chord_along": ca.mtimes(quarter_chord_z, structure_direction),
    }


def _kind(flow: bool) -> str:
    """The functions' name prefix: the flow model's are `flexwing_flow_*`."""
    return "flow_" if flow else ""


def _induced_values(
    sym: _Symbols, left: ca.MX, right: ca.MX, field: ca.MX, weights: ca.DM
) -> ca.MX:
    if sym.flow:
        return flow_induced_velocities(sym.m)(
            field, weights, left, right, sym.circulation.T, sym.image
        )
    induced = induced_velocities(sym.m)
    return induced(field, weights, left, right, sym.circulation.T)


def build_residual_function(layout: Layout, flow: bool = False) -> ca.Function:
    """(x, p) -> (r0, r1, lift): the residual alone, without derivatives (path correctors,
    checks), and the lift per unit q [m^2] (the trimmed system's extra row). The flow model's
    adds the rolling moment per unit q [m^3] (`_Symbols.roll`; the free-roll system's row)."""
    sym = _Symbols(layout, flow)
    left, right, collocation, center, *_ = sym.lattice()
    ind_t, ind_f = _induced_at_points(sym, left, right, collocation, center)
    tangency, loads = sym.aero(False, ind_t, ind_f)
    r0, r1 = sym.residual(tangency, loads)
    outputs = [ca.densify(r0), ca.densify(r1), ca.densify(sym.lift(loads))]
    names = ["r0", "r1", "lift"]
    if flow:
        outputs.append(ca.densify(sym.roll(loads)))
        names.append("roll")
    return ca.Function(
        f"flexwing_{_kind(flow)}residual_{model_tag(layout)}",
        [sym.x, sym.p],
        outputs,
        ["x", "p"],
        names,
    )


def build_panel_loads_function(layout: Layout, flow: bool = False) -> ca.Function:
    """(x, p) -> per-unit-q panel forces and moments, force points and quarter-chord points.

    Outputs: force (3, M) [m^2] (times q gives N), torque (1, M) [m^3] ((r x F) . e_s about the
    undeformed EA, times q gives N m), center (3, M) [m] force points, quarter_chord (3, N) [m]
    stations' quarter-chord points; right half-wing, panels i k + j. The flow model's (its
    parameters, its roll rate's onset) adds leading_edge (3, N) [m], the stations' deformed
    leading edges (the chord axis is their difference over a quarter chord: hinge lines).
    """
    sym = _Symbols(layout, flow)
    m = sym.m
    left, right, _, center, *_ = sym.lattice()
    if layout.aerodynamics == "strip":
        ind_f = ca.MX(3 * m, 1)  # strip theory's loads see the freestream alone
    else:
        ind_f = _induced_values(sym, left, right, center, sym.no_self_bound_leg)
    params = _Parameters(layout)
    z, g, alpha = ca.SX.sym("z", 3 * layout.n), ca.SX.sym("g", m), ca.SX.sym("alpha")
    induced = ca.SX.sym("induced", 3 * m)
    roll_rate = ca.SX.sym("roll_rate")
    lat = params.lattice(z)
    force, loads = _panel_loads(lat, g, alpha, induced, params.sweep, roll_rate if flow else None)
    outputs = [force, loads[4 * m : 5 * m].T, lat.quarter_chord]
    names = ["force", "torque", "center", "quarter_chord"]
    inputs = [z, g, *params.inputs, alpha, induced]
    arguments = [sym.z, sym.circulation, *sym.geometry_inputs, sym.alpha_deg, ind_f]
    if flow:
        outputs.append(lat.leading_edge)
        names.append("leading_edge")
        inputs.append(roll_rate)
        arguments.append(sym.roll_rate)
    panel = ca.Function("flow_panel_forces" if flow else "panel_forces", inputs, outputs)
    force_mx, torque_mx, *stations = panel(*arguments)
    return ca.Function(
        f"flexwing_{_kind(flow)}panel_loads_{model_tag(layout)}",
        [sym.x, sym.p],
        [force_mx, torque_mx, center, *stations],
        ["x", "p"],
        names,
    )


def build_full_span_function(layout: Layout) -> ca.Function:
    """(x, x_image, p, camber_image) -> the right half's r0, r1 and panel loads when the left
    half moves on its own: its state x_image (n,) and camber camber_image (N (k + 1),) in the
    mirrored frame (its heave up, its twist nose-up, its circulation along the mirror image's
    horseshoes from m(B) to m(A)), the mirror m = diag(1, -1, 1) placing it.

    The full-span model's right half, evaluated without derivatives: with x_image = x and the
    same camber it is the symmetric model (`build_residual_function`, the parameters' image
    and image_jacobian ignored). Its derivative along (dx, -dx) at a symmetric state is the
    antisymmetric linearisation (`solver.model.flow_vlm`, image_jacobian -1): this function
    checks it, and the linearised loads of a roll answer, independently of the kernel's
    hand-written derivatives (tests/solver/model/test_residual.py). The virtual machine serves
    it.

    Outputs: r0, r1 (n,); force (3, M) [m^2 per unit q]; torque (1, M) [m^3 per unit q] about the
    undeformed elastic axis; roll (1, M) [m^3 per unit q] (r x F) . e_x; center (3, M) [m];
    quarter_chord, leading_edge (3, N) [m] (`build_panel_loads_function`).
    """
    sym = _Symbols(layout, flow=True)
    m = sym.m
    x_image = ca.MX.sym("x_image", layout.n_unknowns)
    camber_image = ca.MX.sym("camber_image", sym.camber.shape[0])
    left, right, collocation, center, *_ = sym.lattice()
    image_inputs = [sym.y, sym.chord, sym.ea, sym.jig, camber_image, sym.sweep]
    image_left, image_right, *_ = _lattice_function(layout)(
        x_image[layout.structure], *image_inputs
    )
    mirror = ca.DM([1.0, -1.0, 1.0])
    # The left half's horseshoes, as sources of their own: from m(B) to m(A).
    sources_left = ca.repmat(mirror, 1, m) * image_right
    sources_right = ca.repmat(mirror, 1, m) * image_left
    g_image = x_image[layout.circulation].T
    own = flow_induced_velocities(m, with_image=False)

    def induced(field: ca.MX, weights: ca.DM) -> ca.MX:
        return own(field, weights, left, right, sym.circulation.T, 0) + own(
            field, sym.all_bound_legs, sources_left, sources_right, g_image, 0
        )

    ind_t = induced(collocation, sym.all_bound_legs)
    ind_f = induced(center, sym.no_self_bound_leg)
    tangency, loads = sym.aero(False, ind_t, ind_f)
    r0, r1 = sym.residual(tangency, loads)
    force = ca.horzcat(*[loads[c * m : (c + 1) * m] for c in range(3)]).T
    params = _Parameters(layout)
    z = ca.SX.sym("z", 3 * layout.n)
    lat = params.lattice(z)
    stations = ca.Function("stations", [z, *params.inputs], [lat.quarter_chord, lat.leading_edge])
    quarter_chord, leading_edge = stations(sym.z, *sym.geometry_inputs)
    return ca.Function(
        f"flexwing_flow_full_span_{model_tag(layout)}",
        [sym.x, x_image, sym.p, camber_image],
        [
            ca.densify(r0),
            ca.densify(r1),
            force,
            loads[4 * m : 5 * m].T,
            loads[_ROLL * m : (_ROLL + 1) * m].T,
            center,
            quarter_chord,
            leading_edge,
        ],
        ["x", "x_image", "p", "camber_image"],
        ["r0", "r1", "force", "torque", "roll", "center", "quarter_chord", "leading_edge"],
    )
