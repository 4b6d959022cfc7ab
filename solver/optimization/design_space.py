"""The design space of a design problem: a design vector v -> the wing it describes, its
equilibrium, and every function the optimiser sees with its exact gradient.

v holds the jig-twist variables d (k control points, or every station) and, when the spar is
sized, the wall thickness t (N). Each design's equilibrium x(v) comes from Newton (warm-started
from the previous design's, in IPOPT's deterministic order), and every function's gradient from
one forward sensitivity at the equilibrium,

    dx/dv = -J^{-1} dr/dv,    dF/dv = F_x dx/dv + F_v,

with J the coupled Jacobian the solver already has. Design derivatives come for free from the
model's structure: the jig twist enters the lattice only through the streamwise twist
phi cos(sweep) - u' sin(sweep) + jig, so dr/d(jig) is the aerodynamic part of dr/dphi over
cos(sweep); EI and GJ enter only the beam's trapezoid rows, differentiated by hand.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import scipy.interpolate
import scipy.linalg

from solver.errors import ConvergenceError, InfeasibleDesign
from solver.inputs.design import DesignProblem
from solver.inputs.options import SolverOptions
from solver.inputs.spar import TubeSpar
from solver.inputs.wing import Wing
from solver.model.beam import DEG_PER_RAD
from solver.model.geometry import DEG
from solver.numerics.evaluation import AlphaTerms, Evaluation
from solver.numerics.newton import newton
from solver.statics.system import CoupledSystem
from solver.statics.trefftz import strip_sum, trefftz_matrix

__all__ = ["DesignPoint", "DesignSpace"]

_NEWTON_ITERATIONS = 20


def _twist_basis(wing: Wing, control_points: int | None) -> np.ndarray:
    """(N, k) jig twist at the stations per control point (identity for every station)."""
    n = wing.n_stations
    if control_points is None:
        return np.eye(n)
    where = np.linspace(0.0, 1.0, control_points)
    zero = np.zeros(control_points)
    spline = scipy.interpolate.CubicSpline(
        where, np.eye(control_points), bc_type=((1, zero), (2, zero))
    )
    return np.asarray(spline(wing.y / wing.semispan))


@dataclass
class DesignPoint:
    """One design's equilibrium and every function the optimiser sees, with gradients."""

    x: np.ndarray
    values: dict[str, np.ndarray]  # name -> (m,) values
    gradients: dict[str, np.ndarray]  # name -> (m, nv)


class DesignSpace:
    """The reduced functions of one problem: v -> equilibrium -> objective and constraints."""

    def __init__(
        self, wing: Wing, problem: DesignProblem, options: SolverOptions, rigid: bool
    ) -> None:
        self.wing, self.problem, self.options, self.rigid = wing, problem, options, rigid
        self.velocity = problem.velocity  # [m/s] names the flight in errors
        self.system = CoupledSystem.of(wing, problem.alpha, options)
        self.layout = self.system.layout
        self.q = problem.dynamic_pressure
        self.basis = _twist_basis(wing, problem.control_points)
        self.n_twist = self.basis.shape[1]
        n = wing.n_stations
        self.n_wall = n if problem.size_spar else 0
        self.cos_sweep = math.cos(wing.sweep * DEG)
        self.sin_sweep = math.sin(wing.sweep * DEG)
        self.arc = wing.arc_length
        self.h = np.diff(self.arc)
        self.spar = wing.spar
        self.strips = strip_sum(self.system)
        self.trefftz = trefftz_matrix(wing.y, wing.dihedral)
        self.x = np.zeros(self.layout.n_unknowns)
        self.evaluations = 0
        self._cache: dict[bytes, DesignPoint] = {}

    # --- the wing a design vector describes

    @property
    def n_design(self) -> int:
        return self.n_twist + self.n_wall

    @property
    def walls(self) -> slice:
        """Where the wall thicknesses sit in a design vector (after the twist variables)."""
        return slice(self.n_twist, self.n_twist + self.n_wall)

    def split(self, v: np.ndarray) -> tuple[np.ndarray, np.ndarray | None]:
        """(jig twist (N,) [deg], wall thickness (N,) [m] or None)."""
        jig = self.basis @ v[: self.n_twist]
        return jig, (v[self.walls] if self.n_wall else None)

    def variable_bounds(self) -> tuple[np.ndarray, np.ndarray]:
        """(nv,) lowest and highest design variables: the twist's free (its bounds are
        constraints, on the jig twist at the stations), the walls within the problem's bounds
        and the tube's radius. Raises `InfeasibleDesign` for walls no tube can have."""
        lower_v = np.full(self.n_design, -np.inf)
        upper_v = np.full(self.n_design, np.inf)
        if self.n_wall:
            tube = self.spar
            assert tube is not None
            low, high = self.problem.wall_thickness_bounds
            radius = tube.outer_diameter / 2
            if np.any(radius < low):
                thin = int(np.argmin(radius))
                raise InfeasibleDesign(
                    "wall_thickness",
                    f"the thinnest wall allowed, {low:g} m, is thicker than the tube's radius at "
                    f"station {thin} ({radius[thin]:.3g} m): no tube has such a wall",
                )
            lower_v[self.walls] = low
            upper_v[self.walls] = np.minimum(high, radius)
        return lower_v, upper_v

    def tube(self, wall: np.ndarray | None) -> TubeSpar | None:
        if self.spar is None:
            return None
        if wall is None:
            return self.spar
        return TubeSpar(self.spar.outer_diameter, wall, self.spar.material)

    def parameters(self, jig: np.ndarray, tube: TubeSpar | None) -> np.ndarray:
        """The model's parameter vector of a design: the problem's, its jig twist (and, sized,
        its spar's stiffnesses) set by slot (`solver.model.layout`)."""
        layout, p = self.layout, self.system.parameters.copy()
        p[layout.slot("jig_twist")] = jig
        if self.n_wall and tube is not None:
            p[layout.slot("bending_stiffness")] = tube.bending_stiffness
            p[layout.slot("torsional_stiffness")] = tube.torsional_stiffness
        return p

    def design_wing(self, v: np.ndarray) -> Wing:
        """The wing design `v` describes: the problem's wing with its jig twist (and, sized,
        its spar's walls and the stiffnesses they give), every other field as it was."""
        jig, wall = self.split(v)
        jig = np.array(jig)
        jig.setflags(write=False)
        tube = self.tube(wall)
        if tube is None or wall is None:
            return dataclasses.replace(self.wing, jig_twist=jig)
        return dataclasses.replace(
            self.wing,
            jig_twist=jig,
            spar=tube,
            bending_stiffness=tube.bending_stiffness,
            torsional_stiffness=tube.torsional_stiffness,
        )

    # --- the equilibrium of a design

    def _equilibrium(
        self,
        p: np.ndarray,
        load: Callable[[np.ndarray], tuple[np.ndarray, np.ndarray | None]] | None = None,
    ) -> np.ndarray:
        """The design's equilibrium from the last one; `load`: x -> what the wing's own mass
        adds to r1 (n_unknowns,) per unit q and its derivative in x (None: constant), or
        None (`_loaded`)."""
        model, q, layout = self.system.model, self.q, self.layout
        if self.rigid:
            # Undeformed: the tangency rows alone, linear in the circulation at z = 0.
            x = np.zeros(layout.n_unknowns)
            ev = model.evaluate(x, p)
            rows, cols = layout.tangency_rows, layout.circulation
            x[cols] = -np.linalg.solve(ev.jacobian0[rows, cols], ev.r0[rows])
            return x
        evaluate: Callable[[np.ndarray], Evaluation] = lambda x: model.evaluate(x, p)  # noqa: E731
        residual: Callable[[np.ndarray], tuple[np.ndarray, np.ndarray]] = (  # noqa: E731
            lambda x: model.residual(x, p)
        )
        if load is not None:
            evaluate, residual = _loaded(evaluate, residual, load)
        result = newton(evaluate, residual, self.x, q, self.options.tolerance, _NEWTON_ITERATIONS)
        if not result.converged:
            raise ConvergenceError(
                self.velocity, result.iterations, result.residual_norm, result.reason
            )
        return result.x

    def at(self, v: np.ndarray) -> DesignPoint:
        key = v.tobytes()
        point = self._cache.get(key)
        if point is None:
            point = self._evaluate(v)
            self._cache = {key: point}  # IPOPT asks for values, then gradients, of one point
        return point

    def _evaluate(self, v: np.ndarray) -> DesignPoint:
        jig, wall = self.split(v)
        tube = self.tube(wall)
        p = self.parameters(jig, tube)
        x = self._equilibrium(p)
        self.evaluations += 1
        if not self.rigid:
            self.x = x
        ev, terms = self.system.model.evaluate_with_alpha(x, p)
        return self._functions(v, x, ev, terms, tube)

    def _functions(self, v, x, ev, terms, tube) -> DesignPoint:
        layout, q, n = self.layout, self.q, self.wing.n_stations
        nx, nv = x.size, v.size
        twist_cols = layout.twist
        # dr/d(jig): the aerodynamic rows' phi columns, over cos(sweep).
        jig_rows = (
            np.vstack([q * ev.jacobian1[: 3 * n, twist_cols], ev.jacobian0[3 * n :, twist_cols]])
            / self.cos_sweep
        )
        r_v = np.zeros((nx, nv))
        r_v[:, : self.n_twist] = jig_rows @ self.basis
        moment, torque = self._internal_loads(ev.r1, tube)  # per unit q
        if self.n_wall:
            r_v[:, self.walls] = self._stiffness_rows(moment, torque, tube)
        self._explicit_rows(r_v, terms, tube)
        if self.rigid:
            sensitivity = np.zeros((nx, nv))
            rows, cols = layout.tangency_rows, layout.circulation
            sensitivity[cols] = -np.linalg.solve(ev.jacobian0[rows, cols], r_v[rows])
        else:
            sensitivity = -scipy.linalg.lu_solve(
                scipy.linalg.lu_factor(ev.jacobian(q), check_finite=False), r_v, check_finite=False
            )
        values: dict[str, np.ndarray] = {}
        gradients: dict[str, np.ndarray] = {}

        def record(name: str, value, value_x, value_v) -> None:
            values[name] = np.atleast_1d(value)
            gradients[name] = np.atleast_2d(value_x @ sensitivity + value_v)

        jig_v = np.zeros((n, nv))
        jig_v[:, : self.n_twist] = self.basis
        lift_v = np.zeros(nv)
        lift_v[: self.n_twist] = terms.lift_x[twist_cols] / self.cos_sweep @ self.basis
        self._explicit_lift(lift_v, terms)
        record("lift", q * terms.lift, q * terms.lift_x, q * lift_v)
        strips = self.strips @ x[layout.circulation]
        trefftz_x = np.zeros(nx)
        trefftz_x[layout.circulation] = q * (self.trefftz + self.trefftz.T) @ strips @ self.strips
        record("trefftz_drag", q * strips @ self.trefftz @ strips, trefftz_x, np.zeros(nv))
        if self.system.aerodynamics == "strip":
            # Two-dimensional sections have no near field: their induced drag is the far
            # field's (`solver.statics.trefftz`).
            record("induced_drag", values["trefftz_drag"], trefftz_x, np.zeros(nv))
        else:
            drag_v = np.zeros(nv)
            drag_v[: self.n_twist] = terms.drag_x[twist_cols] / self.cos_sweep @ self.basis
            record("induced_drag", q * terms.drag, q * terms.drag_x, q * drag_v)
        # Total streamwise twist (elastic + jig) [deg] and its smoothness penalty [N]: the rows of
        # twist_x are the derivatives of `geometry.streamwise_twist`.
        twist_x = np.zeros((n, nx))
        twist_x[:, layout.twist] = self.cos_sweep * np.eye(n)
        twist_x[:, layout.slope] = -self.sin_sweep * DEG_PER_RAD * np.eye(n)
        total = twist_x @ x + self.split(v)[0]
        second = np.diff(total, 2)
        second_op = np.diff(np.eye(n), 2, axis=0)
        w = self.problem.smoothness_weight
        record(
            "penalty",
            w * float(second @ second),
            2 * w * second @ second_op @ twist_x,
            2 * w * second @ second_op @ jig_v,
        )
        record(
            "root_twist_slope", total[0] - total[1], twist_x[0] - twist_x[1], jig_v[0] - jig_v[1]
        )
        record("jig_twist", self.split(v)[0], np.zeros((n, nx)), jig_v)
        heave_x = np.zeros(nx)
        heave_x[layout.heave.stop - 1] = 1.0
        record("tip_heave", x[layout.heave][-1], heave_x, np.zeros(nv))
        if tube is not None:
            self._spar_functions(record, tube, moment, torque, ev, terms, nv, nx)
        return DesignPoint(x, values, gradients)

    # What a design vector changes beyond the twist and the stiffnesses (a load case's angle of
    # attack, the spar's own mass): nothing here (`solver.optimization.case_space`).

    def _explicit_rows(self, r_v: np.ndarray, terms: AlphaTerms, tube: TubeSpar | None) -> None:
        """Add to r_v (n_unknowns, nv) the residual's other explicit derivatives."""

    def _explicit_lift(self, lift_v: np.ndarray, terms: AlphaTerms) -> None:
        """Add to lift_v (nv,) [m^2] the lift per unit q's other explicit derivatives."""

    def _explicit_loads(
        self,
        moment_v: np.ndarray,
        torque_v: np.ndarray,
        terms: AlphaTerms,
        tube: TubeSpar | None,
    ) -> None:
        """Add to moment_v, torque_v (N, nv) [m^3] the internal loads' (per unit q) other
        explicit derivatives."""

    def _internal_loads(
        self, r1: np.ndarray, tube: TubeSpar | None
    ) -> tuple[np.ndarray, np.ndarray]:
        """(N,) bending moment and torque per unit q [m^3], from the beam's trapezoid rows."""
        layout = self.layout
        ei, gj = self._stiffness(tube)
        return (
            self._back_substitute(r1[layout.bending_rows], ei, 1.0),
            self._back_substitute(r1[layout.torsion_rows], gj, DEG_PER_RAD),
        )

    def _stiffness(self, tube: TubeSpar | None) -> tuple[np.ndarray, np.ndarray]:
        if tube is not None and self.n_wall:
            return tube.bending_stiffness, tube.torsional_stiffness
        return self.wing.bending_stiffness, self.wing.torsional_stiffness

    def _back_substitute(self, rows: np.ndarray, stiffness: np.ndarray, scale: float) -> np.ndarray:
        """Invert rows_j = -scale h_j / 2 (f_j / K_j + f_{j+1} / K_{j+1}) with f = 0 at the tip.

        Linear in `rows` (a vector, or a matrix of derivative rows)."""
        out = np.zeros((stiffness.size, *rows.shape[1:]))
        for j in reversed(range(stiffness.size - 1)):
            out[j] = stiffness[j] * (
                -2 * rows[j] / (scale * self.h[j]) - out[j + 1] / stiffness[j + 1]
            )
        return out

    def _stiffness_rows(self, moment, torque, tube) -> np.ndarray:
        """(n, N) d(q r1)/d(wall thickness): EI and GJ enter the trapezoid rows only."""
        layout, q, n = self.layout, self.q, self.wing.n_stations
        outer, wall = tube.outer_diameter, tube.wall_thickness
        d_second = math.pi / 64 * 4 * (outer - 2 * wall) ** 3 * 2  # dI/dt [m^3]
        d_ei = tube.material.youngs_modulus * d_second
        d_gj = tube.material.shear_modulus * 2 * d_second
        ei, gj = tube.bending_stiffness, tube.torsional_stiffness
        out = np.zeros((layout.n_unknowns, n))
        for j in range(n - 1):
            for i in (j, j + 1):
                bend = layout.bending_rows.start + j
                twist = layout.torsion_rows.start + j
                out[bend, i] += q * self.h[j] / 2 * moment[i] / ei[i] ** 2 * d_ei[i]
                out[twist, i] += q * DEG_PER_RAD * self.h[j] / 2 * torque[i] / gj[i] ** 2 * d_gj[i]
        return out

    def _spar_functions(self, record, tube, moment, torque, ev, terms, nv, nx) -> None:
        layout, q, n = self.layout, self.q, self.wing.n_stations
        ei, gj = self._stiffness(tube)
        moment_x = self._back_substitute(ev.jacobian1[layout.bending_rows], ei, 1.0)
        torque_x = self._back_substitute(ev.jacobian1[layout.torsion_rows], gj, DEG_PER_RAD)
        moment_v = np.zeros((n, nv))
        torque_v = np.zeros((n, nv))
        twist_cols = layout.twist
        moment_v[:, : self.n_twist] = moment_x[:, twist_cols] / self.cos_sweep @ self.basis
        torque_v[:, : self.n_twist] = torque_x[:, twist_cols] / self.cos_sweep @ self.basis
        self._explicit_loads(moment_v, torque_v, terms, tube)
        radius = tube.outer_diameter / 2
        second, polar = tube.second_moment, tube.polar_moment
        allowable = tube.material.yield_stress / self.options.safety_factor
        bend = q * moment * radius / second / allowable
        shear = q * torque * radius / polar / allowable
        # (von Mises / allowable)^2 - 1 <= 0: smooth where the stress vanishes (the tip).
        usage = bend**2 + 3 * shear**2 - 1
        bend_m, shear_t = q * radius / second / allowable, q * radius / polar / allowable
        usage_x = (
            2 * bend[:, None] * bend_m[:, None] * moment_x
            + 6 * shear[:, None] * shear_t[:, None] * torque_x
        )
        usage_v = (
            2 * bend[:, None] * bend_m[:, None] * moment_v
            + 6 * shear[:, None] * shear_t[:, None] * torque_v
        )
        if self.n_wall:
            inner = tube.outer_diameter - 2 * tube.wall_thickness
            d_second = math.pi / 64 * 8 * inner**3  # dI/dt [m^3]
            # d(bend)/dt = -bend / I dI/dt, likewise the shear with J = 2 I.
            usage_v[:, self.walls] += np.diag(
                -2 * bend**2 * d_second / second - 6 * shear**2 * d_second / second
            )
        record("von_mises", usage[:-1], usage_x[:-1], usage_v[:-1])
        area_v = np.zeros(nv)
        if self.n_wall:
            inner = tube.outer_diameter - 2 * tube.wall_thickness
            d_area = math.pi * inner  # dA/dt [m]
            weights = np.zeros(n)
            weights[:-1] += self.h / 2
            weights[1:] += self.h / 2
            area_v[self.walls] = 2 * tube.material.density * weights * d_area
        record("spar_mass", tube.mass(self.arc), np.zeros(nx), area_v)


def _loaded(
    evaluate: Callable[[np.ndarray], Evaluation],
    residual: Callable[[np.ndarray], tuple[np.ndarray, np.ndarray]],
    load: Callable[[np.ndarray], tuple[np.ndarray, np.ndarray | None]],
) -> tuple[
    Callable[[np.ndarray], Evaluation], Callable[[np.ndarray], tuple[np.ndarray, np.ndarray]]
]:
    """The model's evaluations with `load(x)` added to r1: (n_unknowns,) per unit q, and its
    derivative in x (n_unknowns, n_unknowns) added to J1, None where it is constant in x
    (`solver.statics.system.CoupledSystem._loaded`)."""

    def loaded_evaluate(x: np.ndarray) -> Evaluation:
        ev = evaluate(x)
        rows, rows_x = load(x)
        if rows_x is None:
            return dataclasses.replace(ev, r1=ev.r1 + rows)
        return dataclasses.replace(ev, r1=ev.r1 + rows, jacobian1=ev.jacobian1 + rows_x)

    def loaded_residual(x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        r0, r1 = residual(x)
        return r0, r1 + load(x)[0]

    return loaded_evaluate, loaded_residual
