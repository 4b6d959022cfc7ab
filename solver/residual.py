"""The coupled aeroelastic residual of one mesh size N, built symbolically once.

Unknowns x (4N - 1), in this order:
    u (N) [m]        heave at stations
    du (N) [-]       slope u' at stations
    theta (N) [deg]  twist at stations
    g (N - 1) [m]    circulation per unit airspeed of each right-half panel, Gamma / V
Parameters p (5N + 1): y, chord, elastic_axis, EI, GJ (N each), alpha [deg].

Equations (4N - 1), in this order:
    root clamps (3)          u_0 = 0, u'_0 = 0, theta_0 = 0
    heave kinematics (N-1)   u_{i+1} - u_i - h_i (u'_i + u'_{i+1}) / 2 = 0                   [m]
    bending (N-1)            u'_{i+1} - u'_i - h_i (M_i/EI_i + M_{i+1}/EI_{i+1}) / 2 = 0     [-]
    torsion (N-1)            theta_{i+1} - theta_i
                               - h_i (180/pi)(T_i/GJ_i + T_{i+1}/GJ_{i+1}) / 2 = 0           [deg]
    flow tangency (N-1)      (V_hat + induced_i) . n_i = 0                                   [-]
The trapezoidal rule is AeroSandbox's ``constrain_derivative``; the tangency rows are per unit V.

Aerodynamic loads scale with the dynamic pressure q = rho V^2 / 2 once the circulation is written
per unit V, so the residual is exactly affine in q:

    r(x; p, q) = r0(x; p) + q r1(x; p),   J = J0 + q J1.

The compiled function returns r0, r1, J0, J1. Newton combines them for any q; a stored
Jacobian is re-targeted to a new airspeed for free; and J0 v = -lambda J1 v is the divergence
eigenproblem.

The Jacobian is exact: CasADi differentiates the geometry, the aerodynamic glue and the
horseshoe kernel (`vlm.pair_kernel`); the O(N^2) induced-velocity part is combined by the chain
rule from the kernel's own derivatives, and the beam's outboard sums are applied as
running sums, which keeps the work at O(N^2) instead of O(N^3).
"""

from __future__ import annotations

import casadi as ca
import numpy as np

from solver.geometry import panel_geometry, station_points
from solver.layout import Layout
from solver.vlm import induced_velocities, source_columns

__all__ = [
    "build_coupled_function",
    "build_panel_loads_function",
    "build_residual_function",
    "MODEL_VERSION",
]

# Bump when the equations change: compiled libraries on disk are keyed by it.
MODEL_VERSION = "3"

DEG_PER_RAD = 180.0 / np.pi


def _split_parameters(p: ca.MX | ca.SX, n: int) -> tuple:
    """y, chord, elastic_axis, EI, GJ (N each) and alpha [deg] from p."""
    return (
        p[0:n],
        p[n : 2 * n],
        p[2 * n : 3 * n],
        p[3 * n : 4 * n],
        p[4 * n : 5 * n],
        p[5 * n],
    )


def _freestream_direction(alpha_deg: ca.SX) -> ca.SX:
    """Unit freestream velocity in geometry axes, (3,) [-]."""
    alpha = alpha_deg * (np.pi / 180.0)
    return ca.vertcat(ca.cos(alpha), 0, ca.sin(alpha))


def _geometry_function(n: int) -> ca.Function:
    """(heave, twist, y, chord, elastic_axis) -> points and their derivatives w.r.t. [u; theta]."""
    heave, twist, y, chord, ea = (ca.SX.sym(name, n) for name in ("u", "theta", "y", "c", "ea"))
    deformation = ca.vertcat(heave, twist)
    points = station_points(heave, twist, y, chord, ea)
    panels = panel_geometry(points)
    outputs = [points.vortex_vertex, panels.collocation, panels.vortex_center]
    jacobians = [ca.jacobian(ca.vec(out), deformation) for out in outputs]
    return ca.Function(
        "wing_geometry",
        [heave, twist, y, chord, ea],
        outputs + jacobians,
    )


def _aero_loads(n: int, heave, twist, circulation, y, chord, ea, alpha_deg, induced_forces):
    """Per-panel forces per unit q from the induced velocity at the vortex centres.

    Returns (force (3, M) [m^2], torque (1, M) [m^3], panel geometry). Kutta-Joukowski:
    F = rho (V_local x l) Gamma = 2 q (V_hat_local x l) g.
    """
    m = n - 1
    points = station_points(heave, twist, y, chord, ea)
    panels = panel_geometry(points)
    v_local = ca.repmat(_freestream_direction(alpha_deg), 1, m) + ca.reshape(induced_forces, 3, m)
    leg = panels.bound_leg
    g_row = circulation.T
    force = 2 * ca.vertcat(
        (v_local[1, :] * leg[2, :] - v_local[2, :] * leg[1, :]) * g_row,
        (v_local[2, :] * leg[0, :] - v_local[0, :] * leg[2, :]) * g_row,
        (v_local[0, :] * leg[1, :] - v_local[1, :] * leg[0, :]) * g_row,
    )
    center = panels.vortex_center
    # y-moment about the origin = torque about the elastic axis (which lies on the y axis).
    torque = center[2, :] * force[0, :] - center[0, :] * force[2, :]
    return force, torque, points, panels


def _aero_function(n: int, with_jacobians: bool) -> ca.Function:
    """Tangency residuals and beam loads given the induced velocities.

    Outputs: tangency (M,) [-]; loads (3M,) per unit q: vertical force Fz [m^2], its moment
    Fz * y_load about the root [m^3], torque about the elastic axis [m^3]. With `with_jacobians`
    also their partial derivatives w.r.t. z = [u; theta; g] and w.r.t. the induced velocities.
    """
    m = n - 1
    heave, twist, y, chord, ea = (ca.SX.sym(name, n) for name in ("u", "theta", "y", "c", "ea"))
    circulation = ca.SX.sym("g", m)
    alpha_deg = ca.SX.sym("alpha")
    induced_tangency = ca.SX.sym("induced_tangency", 3 * m)
    induced_forces = ca.SX.sym("induced_forces", 3 * m)
    force, torque, _, panels = _aero_loads(
        n, heave, twist, circulation, y, chord, ea, alpha_deg, induced_forces
    )
    v_collocation = ca.repmat(_freestream_direction(alpha_deg), 1, m) + ca.reshape(
        induced_tangency, 3, m
    )
    tangency = ca.sum1(v_collocation * panels.normal).T
    lift_force = force[2, :]
    loads = ca.vertcat(lift_force.T, (lift_force * panels.vortex_center[1, :]).T, torque.T)
    outputs = [tangency, loads]
    if with_jacobians:
        z = ca.vertcat(heave, twist, circulation)
        outputs += [
            ca.jacobian(tangency, z),
            ca.jacobian(tangency, induced_tangency),
            ca.jacobian(loads, z),
            ca.jacobian(loads, induced_forces),
        ]
    return ca.Function(
        "aero_glue" if with_jacobians else "aero_glue_values",
        [heave, twist, circulation, y, chord, ea, alpha_deg, induced_tangency, induced_forces],
        outputs,
    )


def _outboard_sum(panel_rows: ca.MX) -> ca.MX:
    """(N-1, k) per-panel rows -> (N, k): row i sums panels j >= i (zero at the tip).

    A running sum from the tip, O(N k), where a triangular matrix product would be O(N^2 k).
    """
    m, k = panel_rows.shape
    running = ca.MX(1, k)
    rows = [running]
    for j in reversed(range(m)):
        running = running + panel_rows[j, :]
        rows.append(running)
    return ca.vertcat(*reversed(rows))


def _beam_load_rows(loads: ca.MX, y: ca.MX, ei: ca.MX, gj: ca.MX) -> ca.MX:
    """The q-proportional part of the bending and torsion equations, (2(N-1), k).

    `loads` (3M, k) holds per-panel [Fz; Fz y_load; torque] per unit q, or their derivative
    rows (k = number of unknowns): every operation here is linear, so the same code gives the
    r1 rows and the J1 rows. Internal loads by outboard sums (study section 14.3):
    M_i = sum_{j>=i} Fz_j y_j - y_i S_i, T_i = sum_{j>=i} tau_j; then the trapezoidal rule.
    """
    m = loads.shape[0] // 3
    shear = _outboard_sum(loads[:m, :])
    bending = _outboard_sum(loads[m : 2 * m, :]) - ca.mtimes(ca.diag(y), shear)
    torsion = _outboard_sum(loads[2 * m :, :])
    h = y[1:] - y[:-1]

    def trapezoid(integrand: ca.MX, stiffness: ca.MX, scale: float) -> ca.MX:
        """-scale h_i/2 (f_i/K_i + f_{i+1}/K_{i+1}), row by row."""
        inner = ca.diag(-scale * h / (2 * stiffness[:-1]))
        outer = ca.diag(-scale * h / (2 * stiffness[1:]))
        return ca.mtimes(inner, integrand[:-1, :]) + ca.mtimes(outer, integrand[1:, :])

    return ca.vertcat(trapezoid(bending, ei, 1.0), trapezoid(torsion, gj, DEG_PER_RAD))


def _structure_rows(layout: Layout, x: ca.MX, y: ca.MX) -> ca.MX:
    """Root clamps, heave kinematics and the load-free part of bending and torsion rows."""
    heave, slope, twist = x[layout.heave], x[layout.slope], x[layout.twist]
    h = y[1:] - y[:-1]
    return ca.vertcat(
        heave[0],
        slope[0],
        twist[0],
        heave[1:] - heave[:-1] - h * (slope[:-1] + slope[1:]) / 2,
        slope[1:] - slope[:-1],
        twist[1:] - twist[:-1],
    )


def _induced_derivative(
    g_dfield: ca.MX, g_dleft: ca.MX, g_dright: ca.MX, field_d: ca.MX, vertex_d: ca.MX, m: int
) -> ca.MX:
    """d(induced velocity)/d[u; theta] by the chain rule through field points and vertices.

    g_dfield (3M, 3), g_dleft/g_dright (3M, 3M) from `vlm.source_columns`; field_d (3M, 2N) and
    vertex_d (3N, 2N) the geometry derivatives. Panel k's left vertex is station k, its right
    vertex station k + 1.
    """
    pad = ca.MX(3 * m, 3)
    d_vertices = ca.horzcat(g_dleft, pad) + ca.horzcat(pad, g_dright)
    result = ca.mtimes(d_vertices, vertex_d)
    for component in range(3):
        # Row 3i + c of the field derivative uses field point i's coordinate `component`.
        rows = [3 * i + component for i in range(m) for _ in range(3)]
        result += ca.mtimes(ca.diag(g_dfield[:, component]), field_d[rows, :])
    return result


class _Symbols:
    """Symbolic unknowns and parameters of one mesh, split into named parts."""

    def __init__(self, n: int) -> None:
        self.layout = Layout(n)
        self.m = n - 1
        self.x = ca.MX.sym("x", self.layout.n_unknowns)
        self.p = ca.MX.sym("p", self.layout.n_parameters)
        self.heave = self.x[self.layout.heave]
        self.twist = self.x[self.layout.twist]
        self.circulation = self.x[self.layout.circulation]
        self.y, self.chord, self.ea, self.ei, self.gj, self.alpha_deg = _split_parameters(self.p, n)
        # The horseshoe of panel k induces nothing of its bound leg at its own vortex centre.
        self.all_bound_legs = ca.DM.ones(self.m, self.m)
        self.no_self_bound_leg = ca.DM.ones(self.m, self.m) - ca.DM.eye(self.m)

    def geometry(self) -> tuple[ca.MX, ...]:
        """vertex, collocation, center and their derivatives w.r.t. [u; theta]."""
        geometry = _geometry_function(self.layout.n)
        return tuple(geometry(self.heave, self.twist, self.y, self.chord, self.ea))  # type: ignore[arg-type]

    def aero(self, with_jacobians: bool, induced_tangency: ca.MX, induced_forces: ca.MX):
        return _aero_function(self.layout.n, with_jacobians)(
            self.heave,
            self.twist,
            self.circulation,
            self.y,
            self.chord,
            self.ea,
            self.alpha_deg,
            induced_tangency,
            induced_forces,
        )

    def residual(self, tangency: ca.MX, loads: ca.MX) -> tuple[ca.MX, ca.MX]:
        """r0 and r1 from the aerodynamic outputs."""
        m = self.m
        r0 = ca.vertcat(_structure_rows(self.layout, self.x, self.y), tangency)
        r1 = ca.vertcat(
            ca.MX(3 + m, 1), _beam_load_rows(loads, self.y, self.ei, self.gj), ca.MX(m, 1)
        )
        return r0, r1


def build_coupled_function(n: int) -> ca.Function:
    """(x, p) -> (r0, r1, J0, J1), all dense, for N stations. See the module docstring."""
    sym = _Symbols(n)
    m, nx = sym.m, sym.layout.n_unknowns
    vertex, collocation, center, vertex_d, collocation_d, center_d = sym.geometry()
    sources = source_columns(m)
    left, right, g_row = vertex[:, :-1], vertex[:, 1:], sym.circulation.T
    ind_t, infl_t, dfield_t, dleft_t, dright_t = sources(
        collocation, sym.all_bound_legs, left, right, g_row
    )
    ind_f, infl_f, dfield_f, dleft_f, dright_f = sources(
        center, sym.no_self_bound_leg, left, right, g_row
    )
    # Induced velocities w.r.t. z = [u; theta; g].
    ind_t_z = ca.horzcat(
        _induced_derivative(dfield_t, dleft_t, dright_t, collocation_d, vertex_d, m), infl_t
    )
    ind_f_z = ca.horzcat(
        _induced_derivative(dfield_f, dleft_f, dright_f, center_d, vertex_d, m), infl_f
    )
    tangency, loads, tangency_z, tangency_ind, loads_z, loads_ind = sym.aero(True, ind_t, ind_f)
    tangency_z = tangency_z + ca.mtimes(tangency_ind, ind_t_z)
    loads_z = loads_z + ca.mtimes(loads_ind, ind_f_z)

    def z_to_x(rows_z: ca.MX) -> ca.MX:
        """Columns [u, theta, g] -> [u, u', theta, g] (aerodynamics never sees the slope)."""
        return ca.horzcat(rows_z[:, :n], ca.MX(rows_z.shape[0], n), rows_z[:, n:])

    r0, r1 = sym.residual(tangency, loads)
    structure = _structure_rows(sym.layout, sym.x, sym.y)
    j0 = ca.vertcat(ca.jacobian(structure, sym.x), z_to_x(tangency_z))
    j1 = ca.vertcat(
        ca.MX(3 + m, nx),
        _beam_load_rows(z_to_x(loads_z), sym.y, sym.ei, sym.gj),
        ca.MX(m, nx),
    )
    return ca.Function(
        f"flexwing_coupled_{n}",
        [sym.x, sym.p],
        [ca.densify(r0), ca.densify(r1), ca.densify(j0), ca.densify(j1)],
        ["x", "p"],
        ["r0", "r1", "J0", "J1"],
    )


def _induced_values(sym: _Symbols, vertex: ca.MX, field: ca.MX, weights: ca.DM) -> ca.MX:
    induced = induced_velocities(sym.m)
    return induced(field, weights, vertex[:, :-1], vertex[:, 1:], sym.circulation.T)


def build_residual_function(n: int) -> ca.Function:
    """(x, p) -> (r0, r1): the residual alone, without derivatives (line searches, checks)."""
    sym = _Symbols(n)
    vertex, collocation, center, *_ = sym.geometry()
    ind_t = _induced_values(sym, vertex, collocation, sym.all_bound_legs)
    ind_f = _induced_values(sym, vertex, center, sym.no_self_bound_leg)
    tangency, loads = sym.aero(False, ind_t, ind_f)
    r0, r1 = sym.residual(tangency, loads)
    return ca.Function(
        f"flexwing_residual_{n}",
        [sym.x, sym.p],
        [ca.densify(r0), ca.densify(r1)],
        ["x", "p"],
        ["r0", "r1"],
    )


def build_panel_loads_function(n: int) -> ca.Function:
    """(x, p) -> per-unit-q panel forces, torques, vortex centres and vortex vertices.

    Outputs: force (3, N-1) [m^2] (times q gives N), torque (1, N-1) [m^3] (times q gives N m),
    vortex_center (3, N-1) [m], vortex_vertex (3, N) [m]; right half-wing, root to tip.
    """
    sym = _Symbols(n)
    vertex, _, center, *_ = sym.geometry()
    induced = _induced_values(sym, vertex, center, sym.no_self_bound_leg)
    sx_args = [ca.SX.sym(name, n) for name in ("u", "theta", "y", "c", "ea")]
    g_sx, alpha_sx = ca.SX.sym("g", sym.m), ca.SX.sym("alpha")
    induced_sx = ca.SX.sym("induced", 3 * sym.m)
    force, torque, _, _ = _aero_loads(
        n, sx_args[0], sx_args[1], g_sx, sx_args[2], sx_args[3], sx_args[4], alpha_sx, induced_sx
    )
    loads = ca.Function(
        "panel_forces", [*sx_args[:2], g_sx, *sx_args[2:], alpha_sx, induced_sx], [force, torque]
    )
    force_mx, torque_mx = loads(
        sym.heave, sym.twist, sym.circulation, sym.y, sym.chord, sym.ea, sym.alpha_deg, induced
    )
    return ca.Function(
        f"flexwing_panel_loads_{n}",
        [sym.x, sym.p],
        [force_mx, torque_mx, center, vertex],
        ["x", "p"],
        ["force", "torque", "vortex_center", "vortex_vertex"],
    )
