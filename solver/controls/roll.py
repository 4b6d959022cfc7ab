"""The antisymmetric response: ailerons, a steady roll rate and the free-roll rate.

An aileron deflects the right wing's trailing edge down and the left's up; a roll rate p about x
adds (p / V) (0, z, -y) to the air the wing sees. Both are antisymmetric: they change the right
and left wings oppositely. Two ways to compute the response (`RollResponse.method`):

- "antisymmetric", exact: a wing whose sections are symmetric in z (no camber at the chordwise
  nodes, no jig twist, no flap deflected) at alpha 0 has an exactly antisymmetric equilibrium:
  the left wing is the right one turned 180 deg about x. The model with its image rotated
  (`solver.model.flow_vlm`, image -1) solves for it as a plain equilibrium of the right half,
  followed in q from the rigid wing as `solver.solve` does, nonlinear in the deflections and the
  response.
- "linearised", anywhere else: the symmetric equilibrium at the flight condition (flaps
  included, `solver.solve`) and the antisymmetric disturbance of the ailerons (their camber
  -(x - hinge) delta, linear in delta [rad]) and the roll rate linearised about it, with the
  exact antisymmetric block of the full-span Jacobian there (image +1, its own derivatives
  turned): J_a dx = -(r_delta + r_p p / V). Both wings are the symmetric equilibrium plus and
  minus dx. Exact to first order in the deflections and the roll rate; where both apply (alpha
  0, symmetric sections) the two differ by the response's third-order terms (measured in
  tests/solver/test_roll.py).

The rolling moment is about the x axis through the root chord (geometry axes: x aft, y right,
z up), positive raising the right wing; the roll rate likewise. The free-roll rate is the p at
which the rolling moment vanishes: a bordered system in (x, p / V) (exact method) or a 2 x 2
elimination (linearised). p b / (2 V) is its helix angle.
"""

from __future__ import annotations

import dataclasses
import math
import time
from collections.abc import Callable
from typing import Literal

import numpy as np

from solver.controls.antisymmetric import (
    aileron_direction,
    antisymmetric_system,
    is_antisymmetric,
    without_aileron_deflections,
)
from solver.controls.hinge_moments import hinge_pairs
from solver.controls.superposition import roll_response, scaled_panels, scaled_stations
from solver.errors import ConvergenceError, InvalidInput, NoEquilibrium, numerical_failures_as
from solver.inputs.flight import FlightCondition, OperatingPoint
from solver.inputs.options import SolverOptions
from solver.inputs.wing import Wing
from solver.model.exact_beam import exact_internal_loads
from solver.model.geometry import DEG
from solver.model.lag_beam import lag_internal_loads
from solver.numerics.evaluation import Evaluation
from solver.numerics.newton import newton
from solver.numerics.path import PathSettings, follow
from solver.numerics.stability import beam_response, divergence_pressure
from solver.results.controls import RollResponse, RollStability
from solver.results.equilibrium import Panels, SolveInfo, Stations
from solver.statics.branch import pressure_scale
from solver.statics.jig import at_rest, jig
from solver.statics.loads import (
    PanelLoads,
    RigidLoads,
    equilibrium_loads,
    flow_panel_loads,
    outboard_sum,
    panel_loads,
)
from solver.statics.solve import solve
from solver.statics.system import CoupledSystem, Flow

__all__ = ["operating_point", "roll"]

Method = Literal["auto", "antisymmetric", "linearised"]


# ------------------------------------------------------------------------------ the answer


def operating_point(wing: Wing, flight: FlightCondition, options: SolverOptions) -> OperatingPoint:
    """The point a condition gives: its alpha, or for a trimmed one the alpha at which the wing,
    its ailerons neutral, carries the lift at this airspeed (an aileron's antisymmetric lift
    sums to zero, so the ailerons do not change the trim to first order). Raises as `solve`
    does for a trim past divergence."""
    if flight.alpha is not None:
        return flight.at_alpha(flight.alpha)
    return solve(without_aileron_deflections(wing), flight, options=options).flight


def roll(
    wing: Wing,
    flight: FlightCondition | OperatingPoint,
    options: SolverOptions | None = None,
    *,
    roll_rate: float | None = 0.0,
    method: Method = "auto",
) -> RollResponse:
    """The wing's antisymmetric response to its ailerons at `flight`.

    flight: at a given alpha, or trimmed (`operating_point`: the trimmed symmetric equilibrium,
        the response linearised about it).
    roll_rate: [rad/s] a steady roll rate p about x (positive raising the right wing), or None
        for the free-roll rate at which the rolling moment vanishes.
    method: "auto" (exact where the response is exactly antisymmetric, else linearised),
        "antisymmetric" (refused where it does not apply) or "linearised".
    Raises `NoEquilibrium` past the antisymmetric (or, linearised, the symmetric) divergence,
    `ConvergenceError` where no answer could be reached, `InvalidInput` for a method that does
    not apply or a free roll of a wing that cannot roll freely (no roll damping).
    """
    started = time.perf_counter()
    options = options or SolverOptions()
    if not isinstance(flight, OperatingPoint):
        flight = operating_point(wing, flight, options)
    if roll_rate is not None and not (
        isinstance(roll_rate, int | float) and math.isfinite(roll_rate)
    ):
        raise InvalidInput("roll_rate", "must be a finite number or null (free roll)")
    exact = is_antisymmetric(wing, flight.alpha, options.chordwise_panels)
    if method == "antisymmetric" and not exact:
        raise InvalidInput(
            "method",
            "the exactly antisymmetric response needs alpha 0, no dihedral and sections "
            "symmetric in z (no camber at the chordwise nodes, no jig twist, no flap deflected); "
            "use 'linearised'",
        )
    if method not in ("auto", "antisymmetric", "linearised"):
        raise InvalidInput("method", "must be 'auto', 'antisymmetric' or 'linearised'")
    with numerical_failures_as(flight.velocity):
        if exact and method != "linearised":
            return _exact(wing, flight, options, roll_rate, started)
        return _linearised(wing, flight, options, roll_rate, started)


# -------------------------------------------------------------------- the exact response


class _FreeRoll:
    """The antisymmetric system bordered by the roll rate z = (x, p / V) and the rolling
    moment's row: affine in q like the system it borders (the row does not scale with q)."""

    def __init__(self, system: CoupledSystem) -> None:
        self.system = system
        wing = system.wing
        self.scale_row = wing.planform_area * 2 * wing.semispan  # [m^3]: the row is a Cl

    def at(self, rate: float) -> CoupledSystem:
        return self.system.with_flow(dataclasses.replace(self.system.flow, roll_rate=rate))

    def evaluate(self, z: np.ndarray) -> Evaluation:
        x, rate = z[:-1], float(z[-1])
        ev, _, terms = self.at(rate).evaluate_with_controls(x)
        n = x.size
        j0, j1 = np.zeros((n + 1, n + 1)), np.zeros((n + 1, n + 1))
        j0[:n, :n], j0[:n, n] = ev.jacobian0, terms.rate_r0
        j0[n, :n], j0[n, n] = terms.roll_x / self.scale_row, terms.roll_rate / self.scale_row
        j1[:n, :n], j1[:n, n] = ev.jacobian1, terms.rate_r1
        r0 = np.append(ev.r0, terms.roll / self.scale_row)
        return Evaluation(r0, np.append(ev.r1, 0.0), j0, j1)

    def residual(self, z: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        r0, r1, moment = self.at(float(z[-1])).residual_with_roll(z[:-1])
        return np.append(r0, moment / self.scale_row), np.append(r1, 0.0)

    def scale(self) -> np.ndarray:
        """(n + 2,) scaled coordinates of (x, p / V, q): a radian of helix angle p b / 2V
        weighs as a radian of twist."""
        base = self.system.scale(pressure_scale(self.system))
        return np.concatenate([base[:-1], [1.0 / self.system.wing.semispan], base[-1:]])


def _rigid_antisymmetric_state(system: CoupledSystem) -> tuple[np.ndarray, Evaluation]:
    """The rigid wing's antisymmetric state: no deformation, the circulation of its tangency,
    which at fixed geometry is linear in the circulation (exact in one solve)."""
    zero = np.zeros(system.layout.n_unknowns)
    at_zero = system.evaluate(zero)
    state = np.linalg.solve(at_zero.jacobian0, -at_zero.r0)
    return state, system.evaluate(state)


def _follow(
    evaluate: Callable[[np.ndarray], Evaluation],
    residual: Callable[[np.ndarray], tuple[np.ndarray, np.ndarray]],
    start: np.ndarray,
    start_evaluation: Evaluation,
    flight: OperatingPoint,
    scale: np.ndarray,
    options: SolverOptions,
) -> tuple[np.ndarray, Evaluation, int, float]:
    path = follow(
        evaluate,
        residual,
        start,
        0.0,
        start_evaluation,
        flight.dynamic_pressure,
        scale,
        options.tolerance,
        PathSettings(max_corrector_iterations=min(options.max_iterations, 8)),
    )
    if not path.reached:
        if path.reason.startswith("path stalled"):
            raise NoEquilibrium(
                flight.velocity,
                FlightCondition.velocity_for(path.dynamic_pressure, flight.density),
                path.reason,
                where="the antisymmetric response turns back before this airspeed "
                "(antisymmetric divergence)",
            )
        raise ConvergenceError(
            flight.velocity, path.iterations, path.residual_norm, f"rolling: {path.reason}"
        )
    return path.x, path.evaluation, path.iterations, path.residual_norm


def _exact(
    wing: Wing,
    flight: OperatingPoint,
    options: SolverOptions,
    roll_rate: float | None,
    started: float,
) -> RollResponse:
    rate = 0.0 if roll_rate is None else roll_rate / flight.velocity
    system = antisymmetric_system(wing, options, rate)
    q = flight.dynamic_pressure
    rigid_state, rigid_evaluation = _rigid_antisymmetric_state(system)
    if roll_rate is None:
        bordered = _FreeRoll(system)
        rigid_state, rate = _rigid_free_roll(bordered, rigid_state, options, flight.velocity)
        system = bordered.at(rate)
        start = np.append(rigid_state, rate)
        z, z_evaluation, iterations, norm = _follow(
            bordered.evaluate,
            bordered.residual,
            start,
            bordered.evaluate(start),
            flight,
            bordered.scale(),
            options,
        )
        x, rate = z[:-1], float(z[-1])
        system = bordered.at(rate)
        evaluation = _unbordered(z_evaluation)
    else:
        x, evaluation, iterations, norm = _follow(
            system.evaluate,
            system.residual,
            rigid_state,
            rigid_evaluation,
            flight,
            system.scale(pressure_scale(system)),
            options,
        )
    stability = _stability(system, evaluation, flight)
    if not stability.stable:
        raise NoEquilibrium(
            flight.velocity,
            None,
            f"its antisymmetric divergence pressure here is "
            f"{stability.antisymmetric_divergence_pressure:.6g} Pa, below q = {q:.6g} Pa",
            where="the antisymmetric response is statically unstable (past antisymmetric "
            "divergence)",
        )
    rigid_state, _ = _rigid_antisymmetric_state(system)  # at the answer's roll rate
    rigid = _rigid_loads_per_q(system, rigid_state)
    stations, panels, _ = equilibrium_loads(
        system, x, q, rigid, unloaded=True, safety_factor=options.safety_factor
    )
    loads = panel_loads(system, x, q)
    zero_stations = scaled_stations(stations, 0.0)
    zero_panels = scaled_panels(panels, 0.0)
    moment = q * system.residual_with_roll(x)[2]
    rigid_moment = q * system.residual_with_roll(rigid_state)[2]
    return roll_response(
        wing,
        flight,
        options,
        method="antisymmetric",
        antisymmetric_state=x,
        symmetric=None,
        rate=rate,
        free=roll_rate is None,
        moment=moment,
        rigid_moment=rigid_moment,
        lift=0.0,
        symmetric_parts=(zero_stations, zero_panels),
        antisymmetric_parts=(stations, panels),
        hinge=hinge_pairs(wing, loads, None),
        stability=stability,
        info=SolveInfo(iterations, norm, False, time.perf_counter() - started),
    )


def _rigid_free_roll(
    bordered: _FreeRoll, state: np.ndarray, options: SolverOptions, velocity: float
) -> tuple[np.ndarray, float]:
    """The rigid wing's free-roll state at q = 0: Newton on the bordered system from the
    rigid state at p = 0 and the linear estimate of p (the row is quadratic in the
    circulation and the rate)."""
    start = np.append(state, 0.0)
    ev = bordered.evaluate(start)
    n = state.size
    # Structure held: only the circulations and the rate move at q = 0.
    free = np.r_[np.arange(bordered.system.layout.circulation.start, n), n]
    step = np.zeros(n + 1)
    step[free] = np.linalg.solve(ev.jacobian0[np.ix_(free, free)], -ev.r0[free])
    result = newton(
        bordered.evaluate,
        bordered.residual,
        start + step,
        0.0,
        options.tolerance,
        options.max_iterations,
    )
    if not result.converged:
        raise ConvergenceError(
            velocity, result.iterations, result.residual_norm, "the rigid free roll did not settle"
        )
    return result.x[:-1], float(result.x[-1])


def _unbordered(evaluation: Evaluation) -> Evaluation:
    n = evaluation.r0.size - 1
    return Evaluation(
        evaluation.r0[:n],
        evaluation.r1[:n],
        evaluation.jacobian0[:n, :n],
        evaluation.jacobian1[:n, :n],
    )


def _stability(
    system: CoupledSystem, evaluation: Evaluation, flight: OperatingPoint
) -> RollStability:
    beam = beam_response(evaluation, system.layout)
    local = divergence_pressure(evaluation, system.layout, beam)
    q = flight.dynamic_pressure
    return RollStability(
        stable=local is None or local > q,
        margin=0.0 if local is None else q / local,
        antisymmetric_divergence_pressure=local,
        antisymmetric_divergence_velocity=(
            None if local is None else FlightCondition.velocity_for(local, flight.density)
        ),
    )


def _rigid_loads_per_q(system: CoupledSystem, state: np.ndarray) -> RigidLoads:
    per_q = panel_loads(system, state, 1.0)
    strips = per_q.per_strip(per_q.force[2], system.chordwise)
    return RigidLoads(0.0, strips, 0.0)


# -------------------------------------------------------------------- the linearised response


def _linearised(
    wing: Wing,
    flight: OperatingPoint,
    options: SolverOptions,
    roll_rate: float | None,
    started: float,
) -> RollResponse:
    base_wing = without_aileron_deflections(wing)
    symmetric = solve(base_wing, flight, options=options)
    q = flight.dynamic_pressure
    flow = Flow(image=1.0, image_jacobian=-1.0, control=aileron_direction(wing))
    system = CoupledSystem.of(base_wing, flight.alpha, options, flow)
    x_s = symmetric.state
    evaluation, _, terms = system.evaluate_with_controls(x_s)
    jacobian = evaluation.jacobian(q)
    forcing = terms.r0 + q * terms.r1
    rate_column = terms.rate_r0 + q * terms.rate_r1
    response = np.linalg.solve(jacobian, -np.column_stack([forcing, rate_column]))
    # The rolling moment per unit q, linear in the deflections (1) and p / V.
    per_deflection = terms.roll_control + float(terms.roll_x @ response[:, 0])
    per_rate = terms.roll_rate + float(terms.roll_x @ response[:, 1])
    if roll_rate is None:
        if per_rate == 0.0 or not math.isfinite(per_rate):
            raise InvalidInput("roll_rate", "the wing has no roll damping: it cannot roll freely")
        rate = -per_deflection / per_rate
    else:
        rate = roll_rate / flight.velocity
    dx = response[:, 0] + rate * response[:, 1]
    moment = q * (per_deflection + rate * per_rate)
    rigid_moment, rigid_dx, rigid_state = _rigid_linearised(system, flight.alpha, q, rate)
    stability = _stability(system, evaluation, flight)
    rigid = jig(CoupledSystem.of(base_wing, flight.alpha, options)).rigid
    antisymmetric_loads = _linear_loads(system, x_s, dx, rate, q)
    rigid_antisymmetric = _linear_loads(system, rigid_state, rigid_dx, rate, 1.0)
    antisymmetric = _antisymmetric_parts(
        system, x_s, dx, antisymmetric_loads, rigid_antisymmetric, q, symmetric.panels
    )
    symmetric_loads = flow_panel_loads(system, x_s, q)  # with the leading edges
    return roll_response(
        wing,
        flight,
        options,
        method="linearised",
        antisymmetric_state=dx,
        symmetric=symmetric,
        rate=rate,
        free=roll_rate is None,
        moment=moment,
        rigid_moment=rigid_moment,
        lift=symmetric.totals.lift,
        symmetric_parts=(
            symmetric.stations,
            dataclasses.replace(
                symmetric.panels, rigid_lift_per_span=q * rigid.strip_lift / np.diff(wing.y)
            ),
        ),
        antisymmetric_parts=antisymmetric,
        hinge=hinge_pairs(wing, symmetric_loads, antisymmetric_loads),
        stability=stability,
        info=SolveInfo(
            symmetric.solver.iterations,
            symmetric.solver.residual_norm,
            False,
            time.perf_counter() - started,
        ),
    )


def _rigid_linearised(
    system: CoupledSystem, alpha: float, q: float, rate: float
) -> tuple[float, np.ndarray, np.ndarray]:
    """The rigid wing's rolling moment [N m] at the same deflections and rate, its
    antisymmetric circulation (n,) and the rigid symmetric state (n,) it is linearised at:
    the structure held, only the circulations answer."""
    layout = system.layout
    rigid_state = at_rest(system.with_flow(Flow())).rigid_state(alpha)
    evaluation, _, terms = system.evaluate_with_controls(rigid_state)
    free = layout.circulation
    tangency = evaluation.jacobian0[layout.tangency_rows, free]
    forcing = terms.r0[layout.tangency_rows] + rate * terms.rate_r0[layout.tangency_rows]
    dx = np.zeros(layout.n_unknowns)
    dx[free] = np.linalg.solve(tangency, -forcing)
    per_q = terms.roll_control + rate * terms.roll_rate + float(terms.roll_x @ dx)
    return q * per_q, dx, rigid_state


def _linear_loads(
    system: CoupledSystem, x: np.ndarray, dx: np.ndarray, rate: float, q: float
) -> PanelLoads:
    """The right half's panel loads' and geometry's change [N, N m, m] for the antisymmetric
    disturbance dx at the symmetric state x (the left half moving by -dx, the ailerons' camber
    +c on the right and -c on the left, the roll rate p / V = `rate`): the compiled model's own
    derivatives with the image's turned (`solver.model.flow_vlm`), exact; one evaluation."""
    layout = system.layout
    parameters = system.parameters.copy()
    parameters[layout.slot("direction")] = dx
    _, _, terms = system.model.evaluate_with_controls(x, parameters)
    loads = terms.loads_along + terms.loads_control + rate * terms.loads_rate
    return PanelLoads(
        q * loads[:3],
        q * loads[4],
        terms.center_along + terms.center_control,
        terms.quarter_chord_along,
        terms.leading_edge_along,
    )


def _antisymmetric_parts(
    system: CoupledSystem,
    x: np.ndarray,
    dx: np.ndarray,
    change: PanelLoads,
    rigid_change: PanelLoads,
    q: float,
    panels: Panels,
) -> tuple[Stations, Panels]:
    """The antisymmetric disturbance's stations and strips: deformation dx and the loads'
    change (linear in dx), per strip and summed outboard as `solver.statics.loads` does."""
    wing, layout, k = system.wing, system.layout, system.chordwise
    base = panel_loads(system.with_flow(Flow()), x, q)
    sweep = wing.sweep * DEG
    slope, phi = dx[layout.slope], dx[layout.twist]
    statics = (_exact_statics if layout.exact else _linear_statics)(system, x, dx, base, change)
    stations = Stations(
        y=wing.y,
        heave=dx[layout.heave].copy(),
        twist=phi * math.cos(sweep) - np.degrees(slope) * math.sin(sweep),
        axis_twist=phi.copy(),
        shear=outboard_sum(base.per_strip(change.force[2], k)),
        **statics,
    )
    strip, dfz, widths = base.per_strip, change.force[2], np.diff(wing.y)
    lift = strip(dfz, k)
    strips = Panels(
        y=panels.y,
        lift=lift,
        lift_per_span=lift / widths,
        torque=strip(change.torque, k),
        rigid_lift_per_span=q * strip(rigid_change.force[2], k) / widths,
    )
    return stations, strips


def _linear_statics(
    system: CoupledSystem, x: np.ndarray, dx: np.ndarray, base: PanelLoads, change: PanelLoads
) -> dict[str, np.ndarray]:
    """Under the linear beam, the disturbance's slope, bending moment and torque [N m]: the
    change of the linear statics (`solver.statics.loads`: vertical forces at their arms along
    the elastic axis, the torque about it, about the heaved axis with `deformed_axis`) along
    the loads' change and dx."""
    wing, layout, k = system.wing, system.layout, system.chordwise
    sweep = wing.sweep * DEG
    e_s = np.array([math.sin(sweep), math.cos(sweep), 0.0])
    dfz = change.force[2]
    arm, darm = e_s @ base.center, e_s @ change.center
    strip = base.per_strip
    shear = outboard_sum(strip(dfz, k))
    arc = wing.y / math.cos(sweep)
    bending = outboard_sum(strip(dfz * arm + base.force[2] * darm, k)) - arc * shear
    torque = outboard_sum(strip(change.torque, k))
    if system.deformed_axis:
        axis = base.force[0] * math.cos(sweep) - base.force[1] * math.sin(sweep)
        daxis = change.force[0] * math.cos(sweep) - change.force[1] * math.sin(sweep)
        heave, u0 = dx[layout.heave], x[layout.heave]
        torque = torque - heave * outboard_sum(strip(axis, k)) - u0 * outboard_sum(strip(daxis, k))
    return {"slope": dx[layout.slope].copy(), "bending_moment": bending, "torque": torque}


# The complex step of `_exact_statics` [-]: its imaginary part carries the derivative, and
# nothing is subtracted, so any step far below the real parts gives it to round-off.
_COMPLEX_STEP = 1e-30


def _exact_statics(
    system: CoupledSystem, x: np.ndarray, dx: np.ndarray, base: PanelLoads, change: PanelLoads
) -> dict[str, np.ndarray]:
    """Under the geometrically exact beam, the disturbance's slope (the exact beam reports
    sin(beta): cos(beta) dbeta), bending moment and torque [N m] (and with lag its lag
    displacement [m], rotation [deg] and lag bending moment [N m]): the derivative of the
    statics about the deformed stations that the symmetric answer reports
    (`solver.model.exact_beam.exact_internal_loads`, with lag
    `solver.model.lag_beam.lag_internal_loads`) along the loads' change and the rotations'
    (dx), by a complex step (the statics are analytic in the forces, their points and the
    rotations: exact to round-off)."""
    layout, h, k = system.layout, _COMPLEX_STEP, system.chordwise
    force = base.force + 1j * h * change.force
    center = base.center + 1j * h * change.center
    beta = x[layout.slope] + 1j * h * dx[layout.slope]
    slope = np.cos(x[layout.slope]) * dx[layout.slope]
    if not layout.lag:
        flap, torque = exact_internal_loads(system.wing, force, center, beta, k)  # type: ignore[arg-type]
        return {"slope": slope, "bending_moment": flap.imag / h, "torque": torque.imag / h}
    psi = x[layout.lag_rotation] + 1j * h * dx[layout.lag_rotation]
    flap, torque, lag_moment = lag_internal_loads(system.wing, force, center, (beta, psi), k)  # type: ignore[arg-type]
    return {
        "slope": slope,
        "bending_moment": flap.imag / h,
        "torque": torque.imag / h,
        "lag": dx[layout.lag_displacement].copy(),
        "lag_rotation": np.degrees(dx[layout.lag_rotation]),
        "lag_bending_moment": lag_moment.imag / h,
    }
