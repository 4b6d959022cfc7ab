"""The coupled aeroelastic residual of one mesh, built symbolically once: the compiled model's
functions and the version that names their libraries.

Unknowns, equations and parameters: `solver.model.layout`. The equations: the beam's rows
(`solver.model.beam`: root clamps, heave kinematics, bending, torsion) and flow tangency,
(V_hat + induced_p) . n_p = 0 at each panel's collocation point (per unit V; M rows). The loads
are the panels' Kutta-Joukowski forces (`solver.model.aerodynamics`) on the deformed lattice
(`solver.model.geometry`). Written per unit V, the residual is exactly affine in the dynamic
pressure q:

    r(x; p, q) = r0(x; p) + q r1(x; p),   J = J0 + q J1.

The coupled function returns r0, r1, J0, J1 (their non-zero row blocks), and for trimmed flight
the derivatives of r0 and r1 in alpha and the lift per unit q with its derivatives; the flow
model's (`flow=True`: control surfaces and roll, `solver.model.flow`) adds its outputs. The
Jacobian is exact: CasADi differentiates the lattice geometry, the aerodynamic glue and the
horseshoe kernel (`vlm.pair_kernel` at the force points; `vlm.normal_pair_kernel` at the
collocation points, where tangency needs only the normal component); the O(M^2)
induced-velocity part is combined by the chain rule from the kernel's own derivatives
(`solver.model.induced`), and the beam's outboard sums are applied as running sums over a sparse
panels-to-strips operator, which keeps the work at O(M^2) instead of O(M^3).

Strip theory (`Layout.aerodynamics == "strip"`, `solver.model.strip`) is the same model with the
lattice's induced velocities replaced by each strip's own two-dimensional ones.
"""

from __future__ import annotations

import ast
import hashlib
import inspect
import sys
from types import ModuleType

import casadi as ca
import numpy as np

import solver.model.aerodynamics as aerodynamics_module
import solver.model.beam as beam_module
import solver.model.exact_beam as exact_beam_module
import solver.model.flow as flow_module
import solver.model.flow_vlm as flow_vlm_module
import solver.model.geometry as geometry_module
import solver.model.horseshoe as horseshoe_module
import solver.model.induced as induced_module
import solver.model.lag_beam as lag_beam_module
import solver.model.layout as layout_module
import solver.model.strip as strip_module
import solver.model.symbols as symbols_module
import solver.model.vlm as vlm_module
from solver.model.aerodynamics import (
    ROLL,
    lattice_function,
    panel_forces_function,
    stations_function,
)
from solver.model.beam import DEG_PER_RAD
from solver.model.flow import flow_outputs
from solver.model.flow_vlm import flow_induced_velocities
from solver.model.geometry import DEG
from solver.model.induced import induced_at_points, induced_values, lattice_induced, strip_induced
from solver.model.layout import Layout
from solver.model.symbols import Symbols

__all__ = [
    "DEG_PER_RAD",
    "MODEL_VERSION",
    "build_coupled_function",
    "build_full_span_function",
    "build_panel_loads_function",
    "build_residual_function",
    "model_tag",
]


def _graph_source_digest(*modules: ModuleType, table: tuple[object, ...] = ()) -> str:
    """A digest of the code the compiled model's graph is generated from, docstrings left out
    (comments never reach the syntax tree): a change to the equations or to how they are
    written changes it, an edit of the documentation does not. `table`: what else decides the
    graph (the parameter slots' names and sizes, in order)."""
    digest = hashlib.blake2b(digest_size=6)
    for module in modules:
        tree = ast.parse(inspect.getsource(module))
        for node in ast.walk(tree):
            body = getattr(node, "body", None)
            if isinstance(body, list) and body and _is_docstring(body[0]):
                node.body = body[1:] or [ast.Pass()]  # type: ignore[attr-defined]
        digest.update(ast.dump(tree).encode())
    digest.update(repr(table).encode())
    return digest.hexdigest()


def _is_docstring(statement: ast.stmt) -> bool:
    return (
        isinstance(statement, ast.Expr)
        and isinstance(statement.value, ast.Constant)
        and isinstance(statement.value.value, str)
    )


# Compiled libraries on disk are keyed by it (the flow model's too, `solver.numerics.compiled`): it
# changes by itself with the equations or the graph they are generated from (this module and the
# modules below it that build the graph) and with the parameter table, whose order a new compiled
# wing field changes without a line of the model changing.
MODEL_VERSION = _graph_source_digest(
    sys.modules[__name__],
    layout_module,
    geometry_module,
    horseshoe_module,
    vlm_module,
    flow_vlm_module,
    aerodynamics_module,
    beam_module,
    exact_beam_module,
    lag_beam_module,
    strip_module,
    symbols_module,
    induced_module,
    flow_module,
    table=tuple(
        (slot.name, slot.size)
        for layout in (Layout(3), Layout(3, beam="geometrically_exact", lag=True))
        for slot in layout.table(flow=True)
    ),
)


def model_tag(layout: Layout) -> str:
    """The mesh's name in the compiled functions' names (`Layout.tag`)."""
    return layout.tag


def _kind(flow: bool) -> str:
    """The functions' name prefix: the flow model's are `flexwing_flow_*`."""
    return "flow_" if flow else ""


def build_coupled_function(layout: Layout, flow: bool = False) -> ca.Function:
    """(x, p) -> r0, r1, the non-zero row blocks of J0 and J1 (dense), and for trim r0_alpha,
    r1_alpha (per degree), lift (per unit q), lift_x (1, n) and lift_alpha; for design the
    near-field drag (per unit q) and drag_x (1, n). See the module docstring.

    The flow model (`flow`) takes the flow parameters after the model's (`solver.model.layout`) and
    adds, for control surfaces, r0_control, r1_control and lift_control along the control
    direction (per radian), the rolling moment (twice the right half's, per unit q,
    `Symbols.roll`), roll_x (1, n) and roll_control; for roll r0_rate, r1_rate and roll_rate,
    per unit roll rate p / V [rad/m]; and for a roll answer's linearised loads the panel loads'
    derivatives (6M, see `solver.model.aerodynamics`, per unit q) along the direction parameter
    in x, the control and the roll rate, the force points' (3M) along the direction and the
    control, and the stations' leading edges and quarter-chord points' (3N) along the direction
    (the camber moves neither).

    The Jacobians leave as row blocks (`solver.model.layout`): J0's structure rows (3N, n) and
    tangency rows (M, n), J1's load rows (2(N-1), n), its only non-zero ones. CasADi stores
    matrices by columns, so stacking row blocks into one matrix would transpose every block and
    the result; the caller places the blocks (`solver.numerics.compiled`), a plain copy."""
    sym = Symbols(layout, flow)
    m, n, nx = sym.m, layout.n, layout.n_unknowns
    deformed = sym.parameters.deformed_axis
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
        ind_t, normal_ind_t_x, ind_f, ind_f_x = strip_induced(sym)
        tangency_kernel = forces_kernel = (ca.MX(), ca.MX(), ca.MX())
    else:
        ind_t, normal_ind_t_x, ind_f, ind_f_x, tangency_kernel, forces_kernel = lattice_induced(
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
    structure = sym.structure_rows()
    heave_columns = ca.DM(np.eye(n, nx))
    j0_structure = ca.jacobian(structure, sym.x)
    j1_loads = sym.beam.load_rows_jacobian(loads, loads_x, sym.heave, deformed, heave_columns)
    r0_alpha = ca.vertcat(ca.MX(layout.n_structure, 1), tangency_a)
    r1_alpha = sym.placed(sym.beam.load_rows(loads_a, sym.heave, deformed))
    lift = sym.lift(loads)
    lift_x = sym.lift(loads_x)
    alpha = sym.parameters.alpha * DEG
    # d lift / d alpha [per degree]: through the loads, and through the wind axes' rotation.
    lift_alpha = sym.lift(loads_a) - 2 * DEG * (
        ca.sin(alpha) * ca.sum1(loads[2 * m : 3 * m]) + ca.cos(alpha) * ca.sum1(loads[:m])
    )
    drag = sym.drag(loads)
    drag_x = sym.drag(loads_x)
    flows = (
        flow_outputs(
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
        *flows.values(),
    ]
    return ca.Function(
        f"flexwing_{_kind(flow)}coupled_{layout.tag}",
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
            *flows,
        ],
    )


def build_residual_function(layout: Layout, flow: bool = False) -> ca.Function:
    """(x, p) -> (r0, r1, lift): the residual alone, without derivatives (path correctors,
    checks), and the lift per unit q [m^2] (the trimmed system's extra row). The flow model's
    adds the rolling moment per unit q [m^3] (`Symbols.roll`; the free-roll system's row)."""
    sym = Symbols(layout, flow)
    left, right, collocation, center, *_ = sym.lattice()
    ind_t, ind_f = induced_at_points(sym, left, right, collocation, center)
    tangency, loads = sym.aero(False, ind_t, ind_f)
    r0, r1 = sym.residual(tangency, loads)
    outputs = [ca.densify(r0), ca.densify(r1), ca.densify(sym.lift(loads))]
    names = ["r0", "r1", "lift"]
    if flow:
        outputs.append(ca.densify(sym.roll(loads)))
        names.append("roll")
    return ca.Function(
        f"flexwing_{_kind(flow)}residual_{layout.tag}",
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
    sym = Symbols(layout, flow)
    m = sym.m
    left, right, _, center, *_ = sym.lattice()
    if layout.aerodynamics == "strip":
        ind_f = ca.MX(3 * m, 1)  # strip theory's loads see the freestream alone
    else:
        ind_f = induced_values(sym, left, right, center, sym.no_self_bound_leg)
    names = ["force", "torque", "center", "quarter_chord"]
    if flow:
        names.append("leading_edge")
    panel = panel_forces_function(layout, flow)
    force, torque, *stations = panel(sym.z, sym.circulation, sym.p, ind_f)
    return ca.Function(
        f"flexwing_{_kind(flow)}panel_loads_{layout.tag}",
        [sym.x, sym.p],
        [force, torque, center, *stations],
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
    sym = Symbols(layout, flow=True)
    m = sym.m
    x_image = ca.MX.sym("x_image", layout.n_unknowns)
    camber_image = ca.MX.sym("camber_image", layout.length("camber"))
    left, right, collocation, center, *_ = sym.lattice()
    image = sym.parameters.replace(camber=camber_image)
    image_p = ca.vertcat(*(getattr(image, slot.name) for slot in layout.table()))
    image_left, image_right, *_ = lattice_function(layout)(x_image[layout.structure], image_p)
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
    quarter_chord, leading_edge = stations_function(layout, flow=True)(sym.z, sym.p)
    return ca.Function(
        f"flexwing_flow_full_span_{layout.tag}",
        [sym.x, x_image, sym.p, camber_image],
        [
            ca.densify(r0),
            ca.densify(r1),
            force,
            loads[4 * m : 5 * m].T,
            loads[ROLL * m : (ROLL + 1) * m].T,
            center,
            quarter_chord,
            leading_edge,
        ],
        ["x", "x_image", "p", "camber_image"],
        ["r0", "r1", "force", "torque", "roll", "center", "quarter_chord", "leading_edge"],
    )
