"""The panels' aerodynamics given their induced velocities: the air's onset, flow tangency and the
Kutta-Joukowski loads with their moments about the elastic axis, as small CasADi SX functions
of one mesh (the "glue" between the lattice geometry and the O(M^2) induced velocities).

Each function takes the compiled model's whole parameter vector and reads what it needs by name
(`solver.model.layout.Layout.unpack`): the geometry its wing's slots, the loads alpha, the flow
model's functions the roll rate and the control direction. CasADi differentiates these
functions exactly (`ca.jacobian`); the induced velocities' derivatives come from the kernels
(`solver.model.induced`).

Per-panel loads, in this order, each M rows (`LOADS` of them): Fx, Fy, Fz [m^2 per unit q], the
normal force times its arm along the elastic axis, Fn (r . e_s), and the torque about the axis,
(r x F) . e_s [m^3 per unit q] (`solver.model.geometry`'s beam kinematics); the flow model adds
(r x F) . e_x [m^3 per unit q], the rolling moment about x (row block `ROLL`); the
geometrically exact beam's (`solver.model.exact_beam`) adds (r x F) . e_c and (r x F) . n, last.
"""

from __future__ import annotations

import functools
from typing import Any

import casadi as ca

from solver.model.geometry import (
    DEG,
    Lattice,
    along_span,
    in_wing_plane,
    lattice,
    normal_force,
    span_axis,
)
from solver.model.layout import Layout, Parameters

__all__ = [
    "LOADS",
    "ROLL",
    "aero_function",
    "lattice_function",
    "onset",
    "panel_forces_function",
    "panel_loads",
    "parameter_symbols",
    "stations_function",
    "wing_lattice",
]

LOADS = 5
ROLL = 5


def parameter_symbols(layout: Layout, flow: bool = False) -> tuple[ca.SX, Parameters]:
    """The model's parameter vector as one SX symbol (the flow model's with `flow`) and its slots
    by name."""
    size = layout.n_parameters + (layout.n_flow_parameters if flow else 0)
    p = ca.SX.sym("p", size)
    return p, layout.unpack(p)


def _freestream(alpha_deg: ca.SX) -> ca.SX:
    """Unit freestream velocity in geometry axes, (3,) [-]."""
    alpha = alpha_deg * DEG
    return ca.vertcat(ca.cos(alpha), 0, ca.sin(alpha))


def onset(alpha_deg: ca.SX, points: ca.SX, roll_rate: ca.SX | None) -> ca.SX:
    """(3, M) [-] the air's velocity per unit V at `points` (3, M) [m]: the freestream, plus
    (flow model) the roll rate's (p / V) (0, z, -y), the air seen from a wing rolling about x
    at p [rad/s] (x aft, y right, z up; positive p raises the right wing)."""
    m = points.shape[1]
    air = ca.repmat(_freestream(alpha_deg), 1, m)
    if roll_rate is None:
        return air
    return air + roll_rate * ca.vertcat(ca.DM.zeros(1, m), points[2, :], -points[1, :])


def _rows(matrix: ca.SX) -> tuple[ca.SX, ca.SX, ca.SX]:
    """A (3, M) matrix's three rows, a vector's components (`solver.model.geometry`)."""
    return matrix[0, :], matrix[1, :], matrix[2, :]


def panel_loads(
    lat: Lattice,
    g: ca.SX,
    wing: Any,
    induced: ca.SX,
    roll_rate: ca.SX | None = None,
    exact: bool = False,
) -> tuple[ca.SX, ca.SX]:
    """Per-panel forces per unit q (Kutta-Joukowski F = rho (V_local x l) Gamma = 2 q (V_hat_local
    x l) g) and their moments about the elastic axis: ((3, M) force [m^2], (5M,) loads); with a
    roll rate (the flow model) its onset and the moments about x too ((6M,) loads). `wing`:
    the parameters by name (alpha and the beam's axis)."""
    m = lat.leg.shape[1]
    v_local = onset(wing.alpha, lat.center, roll_rate) + ca.reshape(induced, 3, m)
    leg, g_row = lat.leg, g.T
    force = 2 * ca.vertcat(
        (v_local[1, :] * leg[2, :] - v_local[2, :] * leg[1, :]) * g_row,
        (v_local[2, :] * leg[0, :] - v_local[0, :] * leg[2, :]) * g_row,
        (v_local[0, :] * leg[1, :] - v_local[1, :] * leg[0, :]) * g_row,
    )
    center = lat.center
    arm = along_span(_rows(center), wing)
    moment = ca.vertcat(
        center[1, :] * force[2, :] - center[2, :] * force[1, :],
        center[2, :] * force[0, :] - center[0, :] * force[2, :],
        center[0, :] * force[1, :] - center[1, :] * force[0, :],
    )
    torque = along_span(_rows(moment), wing)
    loads = ca.vertcat(
        force[0, :].T,
        force[1, :].T,
        force[2, :].T,
        (normal_force(_rows(force), wing) * arm).T,
        torque.T,
    )
    if roll_rate is not None:
        loads = ca.vertcat(loads, moment[0, :].T)
    if exact:
        # The geometrically exact beam's two more moments (`solver.model.exact_beam`), last:
        # about e_c = e_s x n (across the axis, in the wing's plane) and about the normal n.
        m_x, m_y, m_normal = in_wing_plane(_rows(moment), wing)
        cos, sin = span_axis(wing)[1], span_axis(wing)[0]
        loads = ca.vertcat(loads, (m_x * cos - m_y * sin).T, m_normal.T)
    return force, loads


def wing_lattice(layout: Layout, z: ca.SX, wing: Any) -> Lattice:
    """The lattice at the beam's unknowns z = [u; u'; phi] (3N,), with lag [u; beta; phi; v;
    psi] (5N,)."""
    n = layout.n
    if layout.lag:
        lag = (z[3 * n : 4 * n], z[4 * n : 5 * n])
        return lattice(z[:n], z[n : 2 * n], z[2 * n : 3 * n], wing, layout.chordwise, True, lag)
    return lattice(z[:n], z[n : 2 * n], z[2 * n :], wing, layout.chordwise, exact=layout.exact)


# The symbolic pieces are pure functions of the mesh: each of the three compiled functions uses
# them, so they are built once per mesh, not three times.
@functools.lru_cache(maxsize=16)
def lattice_function(layout: Layout, flow: bool = False) -> ca.Function:
    """(z, p) -> vortex vertices, collocation and force points, the panels' unit normals, and the
    four point sets' derivatives w.r.t. z = [u; u'; phi] (3N). The flow model's (p its
    parameters) adds the four point sets' derivatives along its control direction (3M, 1), and
    the stations' leading edges' and quarter-chord points' derivatives w.r.t. z."""
    p, wing = parameter_symbols(layout, flow)
    z = ca.SX.sym("z", layout.n_structure)
    lat = wing_lattice(layout, z, wing)
    outputs = [lat.left, lat.right, lat.collocation, lat.center]
    jacobians = [ca.jacobian(ca.vec(out), z) for out in outputs]
    if not flow:
        return ca.Function("wing_lattice", [z, p], [*outputs, lat.normal, *jacobians])
    along = [ca.jtimes(ca.vec(out), wing.camber, wing.control) for out in outputs]
    stations = [ca.jacobian(ca.vec(out), z) for out in (lat.leading_edge, lat.quarter_chord)]
    return ca.Function(
        "wing_flow_lattice", [z, p], [*outputs, lat.normal, *jacobians, *along, *stations]
    )


@functools.lru_cache(maxsize=16)
def aero_function(layout: Layout, with_jacobians: bool, flow: bool = False) -> ca.Function:
    """(z, g, p, induced_tangency, induced_forces) -> tangency residuals and per-panel loads given
    the induced velocities.

    Outputs: tangency (M,) [-]; loads (5M,) per unit q (module docstring). With
    `with_jacobians` also their partial derivatives w.r.t. w = [u; u'; phi; g] (the induced
    velocities held fixed: for tangency that leaves the normal's rotation), the loads' w.r.t.
    the induced velocities at the force points, and both w.r.t. alpha. (Tangency's derivative
    through the induced velocity is n . d(induced), which `vlm.normal_source_columns` gives
    directly.) The flow model's (p its parameters) adds the rolling moments (loads 6M), and
    with `with_jacobians` both outputs' derivatives along the control and w.r.t. the roll rate.
    """
    m = layout.n_panels
    p, wing = parameter_symbols(layout, flow)
    z = ca.SX.sym("z", layout.n_structure)
    g = ca.SX.sym("g", m)
    induced_tangency = ca.SX.sym("induced_tangency", 3 * m)
    induced_forces = ca.SX.sym("induced_forces", 3 * m)
    lat = wing_lattice(layout, z, wing)
    rate = wing.roll_rate if flow else None
    _, loads = panel_loads(lat, g, wing, induced_forces, rate, layout.exact)
    v_collocation = onset(wing.alpha, lat.collocation, rate) + ca.reshape(induced_tangency, 3, m)
    tangency = ca.sum1(v_collocation * lat.normal).T
    outputs = [tangency, loads]
    if with_jacobians:
        w = ca.vertcat(z, g)
        outputs += [
            ca.jacobian(tangency, w),
            ca.jacobian(loads, w),
            ca.jacobian(loads, induced_forces),
            ca.jacobian(tangency, wing.alpha),
            ca.jacobian(loads, wing.alpha),
        ]
        if flow:
            outputs += [
                ca.jtimes(tangency, wing.camber, wing.control),
                ca.jtimes(loads, wing.camber, wing.control),
                ca.jacobian(tangency, wing.roll_rate),
                ca.jacobian(loads, wing.roll_rate),
            ]
    name = "aero_glue" if with_jacobians else "aero_glue_values"
    if flow:
        name = f"flow_{name}"
    return ca.Function(name, [z, g, p, induced_tangency, induced_forces], outputs)


@functools.lru_cache(maxsize=16)
def panel_forces_function(layout: Layout, flow: bool = False) -> ca.Function:
    """(z, g, p, induced) -> force (3, M) [m^2 per unit q], torque (1, M) [m^3 per unit q] about
    the undeformed elastic axis, the stations' quarter-chord points (3, N) [m] and, the flow
    model's (its roll rate's onset), their leading edges (3, N) [m]."""
    m = layout.n_panels
    p, wing = parameter_symbols(layout, flow)
    z, g = ca.SX.sym("z", layout.n_structure), ca.SX.sym("g", m)
    induced = ca.SX.sym("induced", 3 * m)
    lat = wing_lattice(layout, z, wing)
    rate = wing.roll_rate if flow else None
    force, loads = panel_loads(lat, g, wing, induced, rate, layout.exact)
    outputs = [force, loads[4 * m : 5 * m].T, lat.quarter_chord]
    if flow:
        outputs.append(lat.leading_edge)
    return ca.Function("flow_panel_forces" if flow else "panel_forces", [z, g, p, induced], outputs)


@functools.lru_cache(maxsize=16)
def stations_function(layout: Layout, flow: bool = False) -> ca.Function:
    """(z, p) -> the stations' quarter-chord points and leading edges (3, N) [m] (p the flow
    model's parameters with `flow`)."""
    p, wing = parameter_symbols(layout, flow)
    z = ca.SX.sym("z", layout.n_structure)
    lat = wing_lattice(layout, z, wing)
    return ca.Function("stations", [z, p], [lat.quarter_chord, lat.leading_edge])
