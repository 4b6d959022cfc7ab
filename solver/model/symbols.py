"""The compiled functions' symbols: the unknowns x and the parameters p of one mesh as CasADi MX
symbols, their parts by name, and the pieces every compiled function is assembled from (the
lattice, the aerodynamic glue, the horseshoes' induced velocities, the beam's rows, and the
whole wing's lift, drag and rolling moment from the per-panel loads).

Aerodynamic loads scale with the dynamic pressure q = rho V^2 / 2 once the circulation is written
per unit V, so the residual is exactly affine in q: r(x; p, q) = r0(x; p) + q r1(x; p).
"""

from __future__ import annotations

import casadi as ca

from solver.model.aerodynamics import ROLL, aero_function, lattice_function
from solver.model.beam import Beam, structure_rows
from solver.model.exact_beam import ExactBeam, exact_structure_rows
from solver.model.flow_vlm import flow_normal_source_columns, flow_source_columns
from solver.model.geometry import DEG
from solver.model.lag_beam import LagBeam, lag_structure_rows
from solver.model.layout import Layout
from solver.model.vlm import normal_source_columns, source_columns

__all__ = ["Symbols"]


class Symbols:
    """Symbolic unknowns and parameters of one mesh, split into named parts (the flow model's
    too, with `flow`): `parameters` holds every slot by name (`Layout.unpack`)."""

    def __init__(self, layout: Layout, flow: bool = False) -> None:
        self.layout = layout
        self.flow = flow
        self.m = layout.n_panels
        self.x = ca.MX.sym("x", layout.n_unknowns)
        n_parameters = layout.n_parameters + (layout.n_flow_parameters if flow else 0)
        self.p = ca.MX.sym("p", n_parameters)
        self.parameters = layout.unpack(self.p)
        self.z = self.x[layout.structure]
        self.heave = self.x[layout.heave]
        self.circulation = self.x[layout.circulation]
        self.beam: Beam
        if layout.lag:
            self.beam = LagBeam(layout, self.p, self.z)
        elif layout.exact:
            self.beam = ExactBeam(layout, self.p, self.z)
        else:
            self.beam = Beam(layout, self.parameters)
        # The horseshoe of panel p induces nothing of its bound leg at its own force point.
        self.all_bound_legs = ca.DM.ones(self.m, self.m)
        self.no_self_bound_leg = ca.DM.ones(self.m, self.m) - ca.DM.eye(self.m)

    def lattice(self) -> tuple[ca.MX, ...]:
        """left, right, collocation, center, normal, and the point sets' derivatives w.r.t. z
        (the flow model's outputs too, `solver.model.aerodynamics.lattice_function`)."""
        return tuple(lattice_function(self.layout, self.flow)(self.z, self.p))  # type: ignore[arg-type]

    def aero(self, with_jacobians: bool, induced_tangency: ca.MX, induced_forces: ca.MX):  # type: ignore[no-untyped-def]
        """`solver.model.aerodynamics.aero_function`'s outputs at these symbols."""
        return aero_function(self.layout, with_jacobians, self.flow)(
            self.z, self.circulation, self.p, induced_tangency, induced_forces
        )

    def sources(self, field: ca.MX, weights: ca.DM, left: ca.MX, right: ca.MX, normal=None):  # type: ignore[no-untyped-def]
        """The horseshoes' induced velocities and derivatives at `field`: along the normals
        (`vlm.normal_source_columns`) when given, else the full vectors; the flow model's with
        the image's parameters."""
        m, g_row = self.m, self.circulation.T
        image = [self.parameters.image, self.parameters.image_jacobian] if self.flow else []
        if normal is not None:
            columns = flow_normal_source_columns(m) if self.flow else normal_source_columns(m)
            return columns(field, normal, weights, left, right, g_row, *image)
        columns = flow_source_columns(m) if self.flow else source_columns(m)
        return columns(field, weights, left, right, g_row, *image)

    def structure_rows(self) -> ca.MX:
        """The beam's load-free rows (n_structure,): the linear beam's, the exact beam's, or
        with lag the lag beam's."""
        if self.layout.lag:
            return lag_structure_rows(self.layout, self.x, self.beam.h)
        rows = exact_structure_rows if self.layout.exact else structure_rows
        return rows(self.layout, self.x, self.beam.h)

    def placed(self, load_rows: ca.MX) -> ca.MX:
        """(n_unknowns, c) the beam's load rows (`Beam.load_rows`) at their places among
        zeros (`Layout.load_rows`): bending and torsion, and with lag the lag bending rows."""
        layout, n_strips, c = self.layout, self.layout.n_strips, load_rows.size2()
        if not layout.lag:
            return ca.vertcat(ca.MX(3 + n_strips, c), load_rows, ca.MX(self.m, c))
        return ca.vertcat(
            ca.MX(3 + n_strips, c),
            load_rows[: 2 * n_strips, :],
            ca.MX(2 + n_strips, c),
            load_rows[2 * n_strips :, :],
            ca.MX(self.m, c),
        )

    def residual(self, tangency: ca.MX, loads: ca.MX) -> tuple[ca.MX, ca.MX]:
        """r0 and r1 from the aerodynamic outputs."""
        r0 = ca.vertcat(self.structure_rows(), tangency)
        r1 = self.placed(
            self.beam.load_rows(loads, self.heave, self.parameters.deformed_axis),
        )
        return r0, r1

    def drag(self, loads: ca.MX) -> ca.MX:
        """Near-field induced drag of both halves per unit q [m^2]: 2 sum (Fx cos + Fz sin)."""
        m, alpha = self.m, self.parameters.alpha * DEG
        return 2 * (
            ca.cos(alpha) * ca.sum1(loads[:m, :]) + ca.sin(alpha) * ca.sum1(loads[2 * m : 3 * m, :])
        )

    def lift(self, loads: ca.MX) -> ca.MX:
        """Lift of both halves per unit q [m^2]: 2 sum (Fz cos(alpha) - Fx sin(alpha))."""
        m, alpha = self.m, self.parameters.alpha * DEG
        return 2 * (
            ca.cos(alpha) * ca.sum1(loads[2 * m : 3 * m, :]) - ca.sin(alpha) * ca.sum1(loads[:m, :])
        )

    def roll(self, loads: ca.MX) -> ca.MX:
        """Twice the right half's rolling moment about x per unit q [m^3], 2 sum (y Fz - z Fy)
        (flow model): both halves' in the antisymmetric flow (image -1), where the image rolls
        as the right half does; with image_jacobian -1 about a symmetric state, the derivatives
        of both halves' for the antisymmetric disturbance (`solver.model.flow_vlm`)."""
        m = self.m
        return 2 * ca.sum1(loads[ROLL * m : (ROLL + 1) * m, :])
