"""Design: the jig twist (and the spar's wall) of the wing that flies, by IPOPT on exact gradients.

The study's closing sketch: make the jig twist a design variable, require the lift, minimise the
drag of the deformed wing. Solved here in the reduced (nested) space: the design vector v holds
the jig-twist variables d (k control points, or every station) and, when the spar is sized, the
wall thickness t (N); each design's equilibrium x(v) comes from Newton (warm-started from the
previous design's, in IPOPT's deterministic order), and every function's gradient from one
forward sensitivity at the equilibrium,

    dx/dv = -J^{-1} dr/dv,    dF/dv = F_x dx/dv + F_v,

with J the coupled Jacobian the solver already has. Design derivatives come for free from the
model's structure: the jig twist enters the lattice only through the streamwise twist
phi cos(sweep) - u' sin(sweep) + jig, so dr/d(jig) is the aerodynamic part of dr/dphi over
cos(sweep); EI and GJ enter only the beam's trapezoid rows, differentiated by hand. IPOPT runs
with a limited-memory Hessian.

Why nested: the simultaneous form (the equilibrium equations as IPOPT constraints, as the study
and the AeroSandbox reference solve it) needs the Hessian of the lattice's residual; CasADi takes
100-160 s to build it for N = 30 (measured), where one reduced gradient costs one evaluation.

Well-posed by construction: the vortex lattice's near-field drag over free station twists runs
away (a zigzag between stations costs nothing). Control points (a cubic spline with zero slope
at the root) are the default; with every station free, the total twist's slope at the root is
held at zero (tw[0] = tw[1], as the reference) and a smoothness penalty
w sum (tw[i+1] - 2 tw[i] + tw[i-1])^2 [N, w in N/deg^2] is offered. The far-field (Trefftz
plane) drag of the planar wake, which such zigzags cannot lower, is reported and offered as the
objective.
"""

from __future__ import annotations

import dataclasses
import math
import time
from dataclasses import dataclass
from typing import Any, Literal

import casadi as ca
import numpy as np
import scipy.interpolate
import scipy.linalg

from solver.errors import (
    ConvergenceError,
    InfeasibleDesign,
    InvalidInput,
    SolverError,
    numerical_failures_as,
)
from solver.geometry import DEG
from solver.inputs import ISA_SEA_LEVEL_DENSITY, FlightCondition, SolverOptions, Wing, _is_number
from solver.newton import newton
from solver.residual import DEG_PER_RAD
from solver.results import (
    ConstraintValue,
    Equilibrium,
    OptimalDesign,
    OptimizerInfo,
    RigidOptimum,
)
from solver.solve import solve
from solver.spar import SparDesign, TubeSpar
from solver.system import CoupledSystem

__all__ = ["DesignProblem", "optimize", "trefftz_drag"]

_ACTIVE = 1e-6  # relative distance to a limit at which a constraint counts as active
_NEWTON_ITERATIONS = 20


@dataclass(frozen=True)
class DesignProblem:
    """What to design, for what flight, under which constraints.

    lift: [N] lift of both halves to carry (> 0), at `velocity` [m/s], `density` [kg/m^3] and
        `alpha` [deg] (the jig's angle of attack, fixed: the twist does the trimming).
    control_points: k >= 2 jig-twist values at evenly spaced fractions of the semispan,
        interpolated by a cubic spline with zero slope at the root; None: every station's jig
        twist is a variable (then the total twist's root slope is held at zero).
    objective: "induced_drag" (near field, as AeroSandbox), "trefftz_drag" (far field) or
        "spar_mass" (needs `size_spar`).
    smoothness_weight: [N/deg^2] w of the penalty on the total twist's second differences.
    twist_bounds: [deg] (lower, upper) on the jig twist at every station.
    size_spar: the spar's wall thickness is a variable at every station (the wing needs a spar);
        wall_thickness_bounds [m] (lower, upper), the upper one also capped at D / 2.
    max_tip_heave: [m] |tip heave| limit, or None.
    max_stability_margin: [-] largest q / local divergence pressure accepted at the optimum.
    """

    lift: float
    velocity: float
    density: float = ISA_SEA_LEVEL_DENSITY
    alpha: float = 0.0
    control_points: int | None = 6
    objective: Literal["induced_drag", "trefftz_drag", "spar_mass"] = "induced_drag"
    smoothness_weight: float = 0.0
    twist_bounds: tuple[float, float] = (-15.0, 15.0)
    size_spar: bool = False
    wall_thickness_bounds: tuple[float, float] = (1e-4, 0.05)
    max_tip_heave: float | None = None
    max_stability_margin: float = 0.95

    def __post_init__(self) -> None:
        FlightCondition(self.velocity, self.alpha, self.density)  # the same checks
        for name in ("lift", "smoothness_weight", "max_stability_margin"):
            if not (_is_number(getattr(self, name)) and math.isfinite(getattr(self, name))):
                raise InvalidInput(name, "must be a finite number")
        if self.lift <= 0:
            raise InvalidInput("lift", "must be positive")
        if self.smoothness_weight < 0:
            raise InvalidInput("smoothness_weight", "must not be negative")
        if not 0 < self.max_stability_margin < 1:
            raise InvalidInput("max_stability_margin", "must lie between 0 and 1")
        k = self.control_points
        if k is not None and not (isinstance(k, int) and 2 <= k <= 50):
            raise InvalidInput("control_points", "must be an integer from 2 to 50, or null")
        if self.objective not in ("induced_drag", "trefftz_drag", "spar_mass"):
            raise InvalidInput("objective", "must be induced_drag, trefftz_drag or spar_mass")
        if self.objective == "spar_mass" and not self.size_spar:
            raise InvalidInput("objective", "spar_mass needs the spar sized (size_spar)")
        for name in ("twist_bounds", "wall_thickness_bounds"):
            lower, upper = getattr(self, name)
            if not (math.isfinite(lower) and math.isfinite(upper) and lower < upper):
                raise InvalidInput(name, "must be finite with lower < upper")
        if self.wall_thickness_bounds[0] <= 0:
            raise InvalidInput("wall_thickness_bounds", "the lower bound must be positive")
        heave = self.max_tip_heave
        if heave is not None and not (_is_number(heave) and 0 < heave < math.inf):
            raise InvalidInput("max_tip_heave", "must be a positive number, or null")

    @property
    def dynamic_pressure(self) -> float:
        return 0.5 * self.density * self.velocity**2


# ----------------------------------------------------------------------------- far-field drag


def trefftz_matrix(y: np.ndarray) -> np.ndarray:
    """(N-1, N-1) [-] A with D_T / q = G^T A G for strip circulations G (N-1,) [m] per unit
    airspeed (both halves): the Trefftz-plane drag of the planar wake, its trailing vortices at
    the stations' y (z = 0), the downwash taken at the strips' middles."""
    middle, width = (y[1:] + y[:-1]) / 2, np.diff(y)
    n = y.size
    shed = np.zeros((n, n - 1))  # trailing strengths at the stations: inboard minus outboard
    shed[np.arange(1, n), np.arange(n - 1)] = 1.0
    shed[np.arange(1, n - 1), np.arange(1, n - 1)] = -1.0
    with np.errstate(divide="ignore"):
        kernel = (1 / (middle[:, None] - y[None, :]) - 1 / (middle[:, None] + y[None, :])) / (
            2 * math.pi
        )
    kernel[:, 0] = 0.0  # the root's trailing vortex and its mirror image cancel
    return -2 * np.diag(width) @ kernel @ shed


def trefftz_drag(equilibrium: Equilibrium) -> float:
    """[N] the far-field induced drag of an equilibrium (planar wake, `trefftz_matrix`)."""
    system = CoupledSystem.of(equilibrium.wing, equilibrium.flight.alpha, equilibrium.options)
    strips = _strip_sum(system) @ equilibrium.state[system.layout.circulation]
    return float(equilibrium.dynamic_pressure * strips @ trefftz_matrix(system.wing.y) @ strips)


def _strip_sum(system: CoupledSystem) -> np.ndarray:
    """(N-1, M) panels to strips."""
    return np.kron(np.eye(system.layout.n_strips), np.ones((1, system.chordwise)))


# -------------------------------------------------------------------------- the design space


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
class _Point:
    """One design's equilibrium and every function the optimiser sees, with gradients."""

    x: np.ndarray
    values: dict[str, np.ndarray]  # name -> (m,) values
    gradients: dict[str, np.ndarray]  # name -> (m, nv)


class _DesignSpace:
    """The reduced functions of one problem: v -> equilibrium -> objective and constraints."""

    def __init__(
        self, wing: Wing, problem: DesignProblem, options: SolverOptions, rigid: bool
    ) -> None:
        self.wing, self.problem, self.options, self.rigid = wing, problem, options, rigid
        self.system = CoupledSystem.of(wing, problem.alpha, options)
        self.layout = self.system.layout
        self.q = problem.dynamic_pressure
        self.basis = _twist_basis(wing, problem.control_points)
        self.n_twist = self.basis.shape[1]
        n = wing.n_stations
        self.n_wall = n if problem.size_spar else 0
        self.cos_sweep = math.cos(wing.sweep * DEG)
        self.sin_sweep = math.sin(wing.sweep * DEG)
        self.arc = wing.y / self.cos_sweep
        self.h = np.diff(self.arc)
        self.spar = wing.spar
        self.strips = _strip_sum(self.system)
        self.trefftz = trefftz_matrix(wing.y)
        self.x = np.zeros(self.layout.n_unknowns)
        self.evaluations = 0
        self._cache: dict[bytes, _Point] = {}

    # --- the wing a design vector describes

    @property
    def n_design(self) -> int:
        return self.n_twist + self.n_wall

    def split(self, v: np.ndarray) -> tuple[np.ndarray, np.ndarray | None]:
        """(jig twist (N,) [deg], wall thickness (N,) [m] or None)."""
        jig = self.basis @ v[: self.n_twist]
        return jig, (v[self.n_twist :] if self.n_wall else None)

    def tube(self, wall: np.ndarray | None) -> TubeSpar | None:
        if self.spar is None:
            return None
        if wall is None:
            return self.spar
        return TubeSpar(self.spar.outer_diameter, wall, self.spar.material)

    def parameters(self, jig: np.ndarray, tube: TubeSpar | None) -> np.ndarray:
        n, p = self.wing.n_stations, self.system.parameters.copy()
        p[5 * n : 6 * n] = jig
        if self.n_wall and tube is not None:
            p[3 * n : 4 * n] = tube.bending_stiffness
            p[4 * n : 5 * n] = tube.torsional_stiffness
        return p

    def design_wing(self, v: np.ndarray) -> Wing:
        jig, wall = self.split(v)
        w = self.wing
        airfoil = list(w.camber)
        if w.spar is not None:
            tube = self.tube(wall)
            assert tube is not None
            spar = SparDesign(tube.outer_diameter, tube.wall_thickness, tube.material)
            return Wing.create(
                w.y,
                w.chord,
                w.elastic_axis,
                sweep=w.sweep,
                jig_twist=jig,
                airfoil=airfoil,
                spar=spar,
                cl_max=w.cl_max,
            )
        return Wing.create(
            w.y,
            w.chord,
            w.elastic_axis,
            w.bending_stiffness,
            w.torsional_stiffness,
            sweep=w.sweep,
            jig_twist=jig,
            airfoil=airfoil,
            cl_max=w.cl_max,
        )

    # --- the equilibrium of a design

    def _equilibrium(self, p: np.ndarray) -> np.ndarray:
        model, q, layout = self.system.model, self.q, self.layout
        if self.rigid:
            # Undeformed: the tangency rows alone, linear in the circulation at z = 0.
            x = np.zeros(layout.n_unknowns)
            ev = model.evaluate(x, p)
            rows, cols = layout.tangency_rows, layout.circulation
            x[cols] = -np.linalg.solve(ev.jacobian0[rows, cols], ev.r0[rows])
            return x
        result = newton(
            lambda x: model.evaluate(x, p),
            lambda x: model.residual(x, p),
            self.x,
            q,
            self.options.tolerance,
            _NEWTON_ITERATIONS,
        )
        if not result.converged:
            raise ConvergenceError(
                self.problem.velocity, result.iterations, result.residual_norm, result.reason
            )
        return result.x

    def at(self, v: np.ndarray) -> _Point:
        key = v.tobytes()
        point = self._cache.get(key)
        if point is None:
            point = self._evaluate(v)
            self._cache = {key: point}  # IPOPT asks for values, then gradients, of one point
        return point

    def _evaluate(self, v: np.ndarray) -> _Point:
        jig, wall = self.split(v)
        tube = self.tube(wall)
        p = self.parameters(jig, tube)
        x = self._equilibrium(p)
        self.evaluations += 1
        if not self.rigid:
            self.x = x
        ev, terms = self.system.model.evaluate_with_alpha(x, p)
        return self._functions(v, x, ev, terms, tube)

    def _functions(self, v, x, ev, terms, tube) -> _Point:
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
            r_v[:, self.n_twist :] = self._stiffness_rows(moment, torque, tube)
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
        record("lift", q * terms.lift, q * terms.lift_x, q * lift_v)
        drag_v = np.zeros(nv)
        drag_v[: self.n_twist] = terms.drag_x[twist_cols] / self.cos_sweep @ self.basis
        record("induced_drag", q * terms.drag, q * terms.drag_x, q * drag_v)
        strips = self.strips @ x[layout.circulation]
        trefftz_x = np.zeros(nx)
        trefftz_x[layout.circulation] = q * (self.trefftz + self.trefftz.T) @ strips @ self.strips
        record("trefftz_drag", q * strips @ self.trefftz @ strips, trefftz_x, np.zeros(nv))
        # Total streamwise twist (elastic + jig) [deg] and its smoothness penalty [N].
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
            self._spar_functions(record, tube, moment, torque, ev, nv, nx)
        return _Point(x, values, gradients)

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

    def _spar_functions(self, record, tube, moment, torque, ev, nv, nx) -> None:
        layout, q, n = self.layout, self.q, self.wing.n_stations
        ei, gj = self._stiffness(tube)
        moment_x = self._back_substitute(ev.jacobian1[layout.bending_rows], ei, 1.0)
        torque_x = self._back_substitute(ev.jacobian1[layout.torsion_rows], gj, DEG_PER_RAD)
        moment_v = np.zeros((n, nv))
        torque_v = np.zeros((n, nv))
        twist_cols = layout.twist
        moment_v[:, : self.n_twist] = moment_x[:, twist_cols] / self.cos_sweep @ self.basis
        torque_v[:, : self.n_twist] = torque_x[:, twist_cols] / self.cos_sweep @ self.basis
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
            usage_v[:, self.n_twist :] += np.diag(
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
            area_v[self.n_twist :] = 2 * tube.material.density * weights * d_area
        record("spar_mass", tube.mass(self.arc), np.zeros(nx), area_v)


# ------------------------------------------------------------------------------------ IPOPT


class _Functions(ca.Callback):
    """v -> (objective, constraints) for IPOPT, from a `_DesignSpace`."""

    def __init__(self, space: _DesignSpace, constraints: _Constraints) -> None:
        ca.Callback.__init__(self)
        self.space, self.constraints = space, constraints
        self.jacobian_callback: _Jacobian | None = None
        self.construct("flexwing_design", {})

    def get_n_in(self) -> int:
        return 1

    def get_n_out(self) -> int:
        return 2

    def get_sparsity_in(self, i: int) -> ca.Sparsity:
        return ca.Sparsity.dense(self.space.n_design, 1)

    def get_sparsity_out(self, i: int) -> ca.Sparsity:
        return ca.Sparsity.dense(1, 1) if i == 0 else ca.Sparsity.dense(self.constraints.size, 1)

    def eval(self, arg: Any) -> list[Any]:  # type: ignore[override]
        point = self.constraints.point(np.array(arg[0]).ravel())
        if point is None:
            return [ca.DM(math.nan), ca.DM.nan(self.constraints.size, 1)]
        return [ca.DM(self.constraints.objective(point)), ca.DM(self.constraints.values(point))]

    def has_jacobian(self) -> bool:
        return True

    def get_jacobian(self, name: str, inames: Any, onames: Any, opts: Any) -> ca.Function:
        self.jacobian_callback = _Jacobian(name, self.space, self.constraints, opts)
        return self.jacobian_callback


class _Jacobian(ca.Callback):
    def __init__(
        self, name: str, space: _DesignSpace, constraints: _Constraints, opts: Any
    ) -> None:
        ca.Callback.__init__(self)
        self.space, self.constraints = space, constraints
        self.construct(name, opts)

    def get_n_in(self) -> int:
        return 3

    def get_n_out(self) -> int:
        return 2

    def get_sparsity_in(self, i: int) -> ca.Sparsity:
        sizes = (self.space.n_design, 1, self.constraints.size)
        return ca.Sparsity.dense(sizes[i], 1)

    def get_sparsity_out(self, i: int) -> ca.Sparsity:
        rows = 1 if i == 0 else self.constraints.size
        return ca.Sparsity.dense(rows, self.space.n_design)

    def eval(self, arg: Any) -> list[Any]:  # type: ignore[override]
        point = self.constraints.point(np.array(arg[0]).ravel())
        nv = self.space.n_design
        if point is None:
            return [ca.DM.nan(1, nv), ca.DM.nan(self.constraints.size, nv)]
        return [
            ca.DM(self.constraints.objective_gradient(point)[None, :]),
            ca.DM(self.constraints.jacobian(point)),
        ]


class _Constraints:
    """Which functions are IPOPT's objective and constraints, scaled, with their bounds."""

    def __init__(self, space: _DesignSpace, problem: DesignProblem) -> None:
        self.space, self.problem = space, problem
        n = space.wing.n_stations
        weight = problem.lift
        # name -> (scale, lower, upper) in the function's own units
        self.entries: list[tuple[str, float, np.ndarray, np.ndarray]] = [
            ("lift", weight, np.array([weight]), np.array([weight]))
        ]
        if problem.control_points is None:
            self.entries.append(("root_twist_slope", 1.0, np.zeros(1), np.zeros(1)))
        lower, upper = problem.twist_bounds
        self.entries.append(("jig_twist", 1.0, np.full(n, lower), np.full(n, upper)))
        if problem.max_tip_heave is not None and not space.rigid:
            limit = problem.max_tip_heave
            self.entries.append(("tip_heave", limit, np.array([-limit]), np.array([limit])))
        if space.spar is not None:
            self.entries.append(("von_mises", 1.0, np.full(n - 1, -np.inf), np.zeros(n - 1)))
        self.size = sum(lo.size for _, _, lo, _ in self.entries)
        self.failure: SolverError | None = None
        # IPOPT's variables: twist in degrees, walls in millimetres (both of order one).
        self.variable_scale = np.ones(space.n_design)
        self.variable_scale[space.n_twist :] = 1e-3

    def point(self, scaled: np.ndarray) -> _Point | None:
        try:
            with numerical_failures_as(self.problem.velocity):
                return self.space.at(scaled * self.variable_scale)
        except SolverError as error:  # IPOPT shortens its step on NaN
            self.failure = error
            return None

    def objective(self, point: _Point) -> float:
        name = self.problem.objective
        return float(point.values[name][0] + point.values["penalty"][0])

    def objective_gradient(self, point: _Point) -> np.ndarray:
        name = self.problem.objective
        return (point.gradients[name][0] + point.gradients["penalty"][0]) * self.variable_scale

    def values(self, point: _Point) -> np.ndarray:
        return np.concatenate([point.values[name] / scale for name, scale, _, _ in self.entries])

    def jacobian(self, point: _Point) -> np.ndarray:
        rows = [point.gradients[name] / scale for name, scale, _, _ in self.entries]
        return np.vstack(rows) * self.variable_scale

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        return (
            np.concatenate([lo / scale for _, scale, lo, _ in self.entries]),
            np.concatenate([hi / scale for _, scale, _, hi in self.entries]),
        )


def _run_ipopt(
    space: _DesignSpace, problem: DesignProblem, start: np.ndarray, tolerance: float
) -> tuple[np.ndarray, OptimizerInfo, _Constraints]:
    started = time.perf_counter()
    constraints = _Constraints(space, problem)
    functions = _Functions(space, constraints)
    v = ca.MX.sym("v", space.n_design)
    objective, g = functions(v)
    nlp = {"x": v, "f": objective, "g": g}
    options: dict[str, Any] = {
        "ipopt.hessian_approximation": "limited-memory",
        # Twist alone is nearly quadratic: a history as long as the design vector (up to 20)
        # takes 46 iterations on 30 stations where IPOPT's 6 takes 66. With the spar's walls
        # the long history overshoots into designs without equilibrium: IPOPT's 6 there.
        "ipopt.limited_memory_max_history": 6 if space.n_wall else min(20, space.n_design),
        "ipopt.tol": tolerance,
        "ipopt.constr_viol_tol": tolerance,
        "ipopt.max_iter": 500,
        # Stop three iterations after the error is below 1e-8 (default: fifteen below 1e-6):
        # the optimum then holds to ~1e-9 in drag and ~1e-7 deg in twist.
        "ipopt.acceptable_tol": 1e-8,
        "ipopt.acceptable_iter": 3,
        "ipopt.print_level": 0,
        "ipopt.sb": "yes",
        "print_time": False,
        "show_eval_warnings": False,  # a design without equilibrium: a NaN IPOPT steps back from
    }
    ipopt = ca.nlpsol("flexwing_design", "ipopt", nlp, options)  # type: ignore[arg-type]
    lower_v = np.full(space.n_design, -np.inf)
    upper_v = np.full(space.n_design, np.inf)
    if space.n_wall:
        tube = space.spar
        assert tube is not None
        low, high = problem.wall_thickness_bounds
        radius = tube.outer_diameter / 2
        if np.any(radius < low):
            thin = int(np.argmin(radius))
            raise InfeasibleDesign(
                "wall_thickness",
                f"the thinnest wall allowed, {low:g} m, is thicker than the tube's radius at "
                f"station {thin} ({radius[thin]:.3g} m): no tube has such a wall",
            )
        lower_v[space.n_twist :] = low
        upper_v[space.n_twist :] = np.minimum(high, radius)
    lbg, ubg = constraints.bounds()
    scale = constraints.variable_scale
    result = ipopt(x0=start / scale, lbx=lower_v / scale, ubx=upper_v / scale, lbg=lbg, ubg=ubg)
    stats = ipopt.stats()
    info = OptimizerInfo(
        iterations=int(stats.get("iter_count", 0)),
        evaluations=space.evaluations,
        status=str(stats.get("return_status", "unknown")),
        seconds=time.perf_counter() - started,
    )
    return np.array(result["x"]).ravel() * scale, info, constraints


# ----------------------------------------------------------------------------------- answers


def optimize(
    wing: Wing, problem: DesignProblem, options: SolverOptions | None = None
) -> OptimalDesign:
    """The jig twist (and spar wall) that minimises `problem.objective` while the flexible wing
    carries `problem.lift`, with the equilibrium of the optimal wing as `solve` answers it and
    the rigid wing's optimum beside it. Raises `InfeasibleDesign` naming the constraint that
    could not be met, `InvalidInput` for a problem the wing cannot pose (sizing without a spar).
    """
    options = options or SolverOptions()
    if problem.size_spar and wing.spar is None:
        raise InvalidInput("size_spar", "the wing has no spar to size")
    tolerance = 1e-10
    rigid, rigid_twist = None, None
    if problem.objective != "spar_mass":
        rigid, rigid_twist = _rigid_optimum(wing, problem, options, tolerance)
    space = _DesignSpace(wing, problem, options, rigid=False)
    start = np.zeros(space.n_design)
    if rigid_twist is not None:
        start[: space.n_twist] = rigid_twist  # the flying shape the flexible wing aims at
    if space.n_wall:
        assert wing.spar is not None
        start[space.n_twist :] = wing.spar.wall_thickness
    v, info, constraints = _run_ipopt(space, problem, start, tolerance)
    if not info.status.startswith("Solve_Succeeded") and "Acceptable" not in info.status:
        raise _infeasible(space, constraints, v, info)
    optimal_wing = space.design_wing(v)
    flight = FlightCondition(problem.velocity, problem.alpha, problem.density)
    equilibrium = solve(optimal_wing, flight, options=options)
    point = space.at(v)
    values = _constraint_values(space, constraints, point, equilibrium)
    for value in values:
        if (
            value.name == "stability_margin"
            and value.upper is not None
            and value.value > value.upper
        ):
            raise InfeasibleDesign(
                "stability_margin",
                f"the optimum's q / local divergence pressure is {value.value:.4g}, above the "
                f"allowed {value.upper:.4g}",
            )
    jig, wall = space.split(v)
    lift = equilibrium.totals.lift
    near, far = equilibrium.totals.induced_drag, trefftz_drag(equilibrium)
    objective = {
        "induced_drag": near,
        "trefftz_drag": far,
        "spar_mass": equilibrium.totals.spar_mass or 0.0,
    }[problem.objective] + float(point.values["penalty"][0])
    return OptimalDesign(
        wing=optimal_wing,
        jig_twist=jig,
        control_points=None if problem.control_points is None else v[: space.n_twist].copy(),
        wall_thickness=None if wall is None else wall.copy(),
        objective=problem.objective,
        objective_value=objective,
        induced_drag=near,
        trefftz_drag=far,
        span_efficiency=_efficiency(lift, problem, wing, near),
        trefftz_span_efficiency=_efficiency(lift, problem, wing, far),
        spar_mass=equilibrium.totals.spar_mass,
        constraints=values,
        equilibrium=equilibrium,
        rigid=rigid,
        optimizer=info,
    )


def _efficiency(lift: float, problem: DesignProblem, wing: Wing, drag: float) -> float:
    """e = L^2 / (q pi b^2 D)."""
    span = 2 * wing.semispan
    return lift**2 / (problem.dynamic_pressure * math.pi * span**2 * drag)


def _rigid_optimum(
    wing: Wing, problem: DesignProblem, options: SolverOptions, tolerance: float
) -> tuple[RigidOptimum, np.ndarray]:
    """The rigid wing's optimum, and its twist variables (where the flexible search starts)."""
    rigid_problem = dataclasses.replace(problem, size_spar=False, max_tip_heave=None)
    space = _DesignSpace(wing, rigid_problem, options, rigid=True)
    v, info, constraints = _run_ipopt(space, rigid_problem, np.zeros(space.n_design), tolerance)
    if not info.status.startswith("Solve_Succeeded") and "Acceptable" not in info.status:
        raise _infeasible(space, constraints, v, info)
    point = space.at(v)
    lift = float(point.values["lift"][0])
    near = float(point.values["induced_drag"][0])
    far = float(point.values["trefftz_drag"][0])
    optimum = RigidOptimum(
        jig_twist=space.split(v)[0],
        induced_drag=near,
        trefftz_drag=far,
        span_efficiency=_efficiency(lift, problem, wing, near),
        trefftz_span_efficiency=_efficiency(lift, problem, wing, far),
        optimizer=info,
    )
    return optimum, v[: space.n_twist]


def _infeasible(
    space: _DesignSpace, constraints: _Constraints, v: np.ndarray, info: OptimizerInfo
) -> InfeasibleDesign:
    """Name the constraint the optimiser could not meet (the most violated at its last point).

    v: (n_design,) the last design in physical units (twist [deg], walls [m])."""
    point = constraints.point(v / constraints.variable_scale)
    if point is None:
        return InfeasibleDesign(
            "lift", f"no equilibrium near the last design: {constraints.failure}"
        )
    worst, excess = "optimizer", 0.0
    for name, scale, lower, upper in constraints.entries:
        value = point.values[name] / scale
        violation = float(np.max(np.maximum(lower / scale - value, value - upper / scale)))
        if violation > excess:
            worst, excess = name, violation
    return InfeasibleDesign(
        worst,
        f"IPOPT stopped with {info.status} after {info.iterations} iterations"
        + (f"; violated by {excess:.3g} of its scale" if worst != "optimizer" else ""),
        violation=excess if worst != "optimizer" else None,
    )


def _station_of(name: str, index: int, y: np.ndarray) -> float | None:
    """[m] where a constraint binds: its station, the tip for the tip heave, None for totals."""
    if name == "tip_heave":
        return float(y[-1])
    if name in ("jig_twist", "von_mises"):
        return float(y[index])
    return None


def _constraint_values(
    space: _DesignSpace, constraints: _Constraints, point: _Point, equilibrium: Equilibrium
) -> list[ConstraintValue]:
    units = {
        "lift": "N",
        "root_twist_slope": "deg",
        "jig_twist": "deg",
        "tip_heave": "m",
        "von_mises": "Pa",
    }
    out = []
    y = space.wing.y
    for name, scale, lower, upper in constraints.entries:
        values = point.values[name]
        # The station closest to a limit.
        gaps = np.minimum(values - lower, upper - values)
        worst = int(np.argmin(gaps))
        active = bool(gaps[worst] <= _ACTIVE * scale) if np.isfinite(gaps[worst]) else False
        value, low, high = float(values[worst]), lower[worst], upper[worst]
        if name == "von_mises":
            tube = equilibrium.wing.spar
            assert tube is not None
            allowable = tube.material.yield_stress / space.options.safety_factor
            stresses = equilibrium.stations.von_mises_stress
            assert stresses is not None
            worst = int(np.argmax(stresses))
            value, low, high = float(stresses[worst]), -np.inf, allowable
            active = bool(high - value <= _ACTIVE * allowable)
        out.append(
            ConstraintValue(
                name=name,  # type: ignore[arg-type]
                value=value,
                lower=None if not np.isfinite(low) else float(low),
                upper=None if not np.isfinite(high) else float(high),
                unit=units[name],
                active=active,
                y=_station_of(name, worst, y),
            )
        )
    margin = equilibrium.stability.margin
    limit = space.problem.max_stability_margin
    out.append(
        ConstraintValue(
            name="stability_margin",
            value=margin,
            lower=None,
            upper=limit,
            unit="-",
            active=bool(limit - margin <= _ACTIVE),
        )
    )
    return out
