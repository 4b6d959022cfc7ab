"""Control effectiveness and reversal: how much of a control's effect survives the twist it
causes (the third static aeroelastic question, after the load redistribution and divergence).

A trailing-edge surface's lift acts aft of the elastic axis and twists the wing nose-down; the
twist takes back part of the surface's lift, more as q rises, until at the reversal pressure
q_R the surface's effect vanishes and beyond it reverses. For each surface:

- the control derivative of its measure m, the lift of both halves for a flap, the rolling
  moment about x for an aileron (`solver.roll`'s axis and sign), per degree at the flight's q:
  elastic, dm/d(delta) = q (m_c + m_x . dx/d(delta)) with (J0 + q J1) dx/d(delta) =
  -(c0 + q c1), exact (the compiled model's control columns, `solver.model.residual`); rigid, the
  same with the structure held (only the circulations answer); their ratio, the
  effectiveness. The flap's Jacobians are the symmetric model's at the symmetric equilibrium;
  the aileron's the antisymmetric block of the full-span Jacobian there (`solver.model.vlm`).
- the reversal pressure, the smallest positive q at which the elastic derivative vanishes: a
  generalised eigenvalue problem on the bordered Jacobian
  (`solver.numerics.stability.reversal_pressure`), at the unloaded jig (`reversal`, the classical
  linear problem, alpha 0: Nastran's) and at this equilibrium (`local_reversal`);
- the linear divergence of the problem the surface acts in (symmetric for a flap,
  antisymmetric for an aileron), and which comes first;
- its hinge moment at the equilibrium.

A sweep (`control_sweep`) reports the effectiveness against airspeed and cross-checks each
reversal by the zero crossing of its elastic derivative between the sweep's speeds.
"""

from __future__ import annotations

import itertools
import math
import time
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Literal

import numpy as np

from solver.controls.antisymmetric import without_aileron_deflections
from solver.controls.hinge_moments import hinge_moments
from solver.controls.roll import operating_point
from solver.errors import (
    ConvergenceError,
    InvalidInput,
    NoEquilibrium,
    SolverError,
    numerical_failures_as,
)
from solver.inputs.flight import (
    FlightCondition,
    OperatingPoint,
    check_over_airspeeds,
    dynamic_pressure,
)
from solver.inputs.options import SolverOptions
from solver.inputs.wing import Wing, require_control_surfaces
from solver.model.geometry import DEG
from solver.numerics.evaluation import AlphaTerms, ControlTerms, Evaluation
from solver.numerics.stability import beam_response, divergence_pressure, reversal_pressure
from solver.results.controls import (
    ControlEffectiveness,
    ControlSweep,
    ControlSweepPoint,
    Reversal,
    ReversalSummary,
)
from solver.results.quantities import Progress
from solver.results.sweep import AirspeedSweepInfo, LinearDivergence, PointFailure
from solver.statics.jig import at_rest
from solver.statics.loads import flow_panel_loads
from solver.statics.solve import solve
from solver.statics.system import CoupledSystem, Flow

_EFFECTIVENESS = "effectiveness is a control surface's"

__all__ = [
    "antisymmetric_divergence",
    "control_effectiveness",
    "control_sweep",
    "linear_reversal",
]


def _flow(wing: Wing, index: int) -> Flow:
    """The model a surface's derivatives come from: the symmetric one along a flap, the
    antisymmetric block (image's own derivatives turned) along an aileron."""
    count = len(wing.control_surfaces)
    if wing.control_surfaces[index].symmetric:
        return Flow.along(index, count)
    return Flow.along(index, count, image_jacobian=-1.0)


@dataclass(frozen=True)
class _Linear:
    """One surface's linear problem at one state: the Jacobians, its control columns and the
    measure's row (per unit q, per radian)."""

    evaluation: Evaluation
    control0: np.ndarray
    control1: np.ndarray
    measure_x: np.ndarray
    measure_control: float

    @classmethod
    def at(cls, system: CoupledSystem, x: np.ndarray, aileron: bool) -> _Linear:
        evaluation, alpha_terms, terms = system.evaluate_with_controls(x)
        row, corner = _measure(alpha_terms, terms, aileron)
        return cls(evaluation, terms.r0, terms.r1, row, corner)

    def derivative(self, q: float) -> float:
        """[m^2/rad or m^3/rad] the elastic derivative per unit q at q."""
        column = self.control0 + q * self.control1
        response = np.linalg.solve(self.evaluation.jacobian(q), -column)
        return self.measure_control + float(self.measure_x @ response)

    def rigid_derivative(self, layout) -> float:  # type: ignore[no-untyped-def]
        """The same with the structure held: only the circulations answer the control."""
        rows, free = layout.tangency_rows, layout.circulation
        tangency = self.evaluation.jacobian0[rows, free]
        response = np.linalg.solve(tangency, -self.control0[rows])
        return self.measure_control + float(self.measure_x[free] @ response)

    def reversal(self, layout, beam: np.ndarray) -> float | None:  # type: ignore[no-untyped-def]
        return reversal_pressure(
            self.evaluation,
            layout,
            self.control0,
            self.control1,
            self.measure_x,
            self.measure_control,
            beam,
        )


def _measure(
    alpha_terms: AlphaTerms, terms: ControlTerms, aileron: bool
) -> tuple[np.ndarray, float]:
    """The measure's gradient in x and its derivative along the control, per unit q."""
    if aileron:
        return terms.roll_x, terms.roll_control
    return alpha_terms.lift_x, terms.lift


def _reversal(q: float | None, density: float, none: str) -> Reversal:
    if q is None:
        return Reversal(None, None, none)
    return Reversal(q, FlightCondition.velocity_for(q, density))


def _first(
    reversal: float | None, divergence: float | None
) -> Literal["reversal", "divergence", "neither"]:
    if reversal is None and divergence is None:
        return "neither"
    if divergence is None or (reversal is not None and reversal < divergence):
        return "reversal"
    return "divergence"


_NO_REVERSAL = (
    "no positive real reversal eigenvalue: the surface's elastic derivative keeps its sign "
    "(its aerodynamic moment never overcomes the structure)"
)


def _rest_system(wing: Wing, index: int, options: SolverOptions) -> CoupledSystem:
    return CoupledSystem.of(wing, 0.0, options, _flow(wing, index))


def _at_rest_linear(wing: Wing, index: int, options: SolverOptions) -> tuple[_Linear, np.ndarray]:
    """The surface's linear problem at the unloaded jig (alpha 0, no circulation) and the
    beam's response there."""
    system = _rest_system(wing, index, options)
    x = np.zeros(system.layout.n_unknowns)
    linear = _Linear.at(system, x, not wing.control_surfaces[index].symmetric)
    return linear, beam_response(linear.evaluation, system.layout)


def linear_reversal(
    wing: Wing, surface: int | str, density: float, options: SolverOptions | None = None
) -> Reversal:
    """The classical linear reversal of `surface` (its index or name): the smallest positive q
    at which its elastic derivative vanishes, linearised at the unloaded jig (alpha 0, no
    circulation), and its speed at `density` [kg/m^3]."""
    options = options or SolverOptions()
    base = without_aileron_deflections(wing)
    index = _index(wing, surface)
    with numerical_failures_as(0.0):
        linear, beam = _at_rest_linear(base, index, options)
        return _reversal(
            linear.reversal(_rest_system(base, index, options).layout, beam), density, _NO_REVERSAL
        )


def antisymmetric_divergence(
    wing: Wing, density: float, options: SolverOptions | None = None
) -> LinearDivergence:
    """The linear antisymmetric divergence of the unloaded jig: the smallest positive q at which
    the antisymmetric block of the full-span Jacobian is singular (the wing twisting up on one
    side and down on the other)."""
    options = options or SolverOptions()
    system = CoupledSystem.of(
        without_aileron_deflections(wing), 0.0, options, Flow(image_jacobian=-1.0)
    )
    try:
        with numerical_failures_as(0.0):
            evaluation = system.evaluate(np.zeros(system.layout.n_unknowns))
            q = divergence_pressure(evaluation, system.layout)
    except ConvergenceError as error:
        return LinearDivergence(None, None, f"it could not be computed: {error.reason}")
    if q is None:
        return LinearDivergence(None, None, "no positive real antisymmetric divergence eigenvalue")
    return LinearDivergence(q, FlightCondition.velocity_for(q, density))


def _index(wing: Wing, surface: int | str) -> int:
    names = [s.name for s in wing.control_surfaces]
    if isinstance(surface, str):
        if surface not in names:
            raise InvalidInput("surface", f"{surface!r} is not one of the wing's surfaces {names}")
        return names.index(surface)
    if not (isinstance(surface, int) and 0 <= surface < len(names)):
        raise InvalidInput("surface", f"must be a surface's name or an index below {len(names)}")
    return surface


@dataclass(frozen=True)
class _Classical:
    """Per surface, what does not depend on the flight condition: its linear problem at the
    unloaded jig (`rest`), the linear reversal and the linear divergence of its problem."""

    rest: _Linear
    reversal: float | None
    divergence: float | None


def _classical(wing: Wing, options: SolverOptions) -> tuple[list[_Classical], float | None]:
    """Each surface's `_Classical`, and the linear antisymmetric divergence pressure [Pa] (None
    without ailerons: from an aileron's own evaluation at rest, which has the antisymmetric
    Jacobians)."""
    symmetric = CoupledSystem.of(wing, 0.0, options)
    rest = at_rest(symmetric)
    symmetric_divergence = divergence_pressure(rest.evaluation, symmetric.layout, rest.beam)
    layout = symmetric.layout
    linears = [_at_rest_linear(wing, index, options) for index in range(len(wing.control_surfaces))]
    antisymmetric = next(
        (
            divergence_pressure(linear.evaluation, layout, beam)
            for (linear, beam), surface in zip(linears, wing.control_surfaces, strict=True)
            if not surface.symmetric
        ),
        None,
    )
    out = []
    for (linear, beam), surface in zip(linears, wing.control_surfaces, strict=True):
        divergence = symmetric_divergence if surface.symmetric else antisymmetric
        out.append(_Classical(linear, linear.reversal(layout, beam), divergence))
    return out, antisymmetric


def _effectiveness(
    wing: Wing,
    index: int,
    flight: OperatingPoint,
    options: SolverOptions,
    state: np.ndarray,
    rigid_state: np.ndarray,
    classical: _Classical,
    hinge: float,
) -> ControlEffectiveness:
    surface = wing.control_surfaces[index]
    aileron = not surface.symmetric
    system = CoupledSystem.of(wing, flight.alpha, options, _flow(wing, index))
    layout, q = system.layout, flight.dynamic_pressure
    linear = _Linear.at(system, state, aileron)
    elastic = q * linear.derivative(q) * DEG
    # The rigid wing at rest is the unloaded jig (alpha 0 on a flat wing): its problem is the
    # classical one's, already evaluated.
    at_rest_already = flight.alpha == 0.0 and not np.any(rigid_state)
    rigid_linear = classical.rest if at_rest_already else _Linear.at(system, rigid_state, aileron)
    rigid = q * rigid_linear.rigid_derivative(layout) * DEG
    local = linear.reversal(layout, beam_response(linear.evaluation, layout))
    reference = q * wing.planform_area * (2 * wing.semispan if aileron else 1.0)
    ratio = elastic / rigid if rigid != 0.0 and math.isfinite(rigid) else None
    return ControlEffectiveness(
        name=surface.name,
        kind=surface.kind,
        measure="rolling_moment" if aileron else "lift",
        unit="N m/deg" if aileron else "N/deg",
        derivative=elastic,
        rigid_derivative=rigid,
        effectiveness=ratio,
        coefficient_derivative=elastic / reference,
        hinge_moment=hinge,
        reversal=_reversal(classical.reversal, flight.density, _NO_REVERSAL),
        local_reversal=_reversal(local, flight.density, _NO_REVERSAL),
        divergence_pressure=classical.divergence,
        first=_first(classical.reversal, classical.divergence),
    )


def _at_flight(
    wing: Wing, flight: OperatingPoint, options: SolverOptions, classical: list[_Classical]
) -> list[ControlEffectiveness]:
    equilibrium = solve(wing, flight, options=options)
    symmetric = CoupledSystem.of(wing, flight.alpha, options)
    rigid_state = at_rest(symmetric).rigid_state(flight.alpha)
    loads = flow_panel_loads(symmetric, equilibrium.state, flight.dynamic_pressure)
    hinges = hinge_moments(wing, loads, options.chordwise_panels)
    return [
        _effectiveness(
            wing,
            index,
            flight,
            options,
            equilibrium.state,
            rigid_state,
            classical[index],
            float(hinges[index]),
        )
        for index in range(len(wing.control_surfaces))
    ]


def control_effectiveness(
    wing: Wing, flight: FlightCondition | OperatingPoint, options: SolverOptions | None = None
) -> list[ControlEffectiveness]:
    """Every control surface's rigid and elastic derivative, effectiveness, reversal and hinge
    moment at `flight`, linearised at the symmetric equilibrium there (flaps at their
    deflections, ailerons neutral: their derivative is the linear theory's at zero).

    Raises `NoEquilibrium` or `ConvergenceError` as `solve` does, `InvalidInput` for a wing
    without control surfaces."""
    options = options or SolverOptions()
    require_control_surfaces(wing, _EFFECTIVENESS)
    point = flight if isinstance(flight, OperatingPoint) else operating_point(wing, flight, options)
    base = without_aileron_deflections(wing)
    with numerical_failures_as(point.velocity):
        return _at_flight(base, point, options, _classical(base, options)[0])


def control_sweep(
    wing: Wing,
    velocities: Sequence[float],
    alpha: float | None,
    density: float,
    options: SolverOptions | None = None,
    *,
    lift: float | None = None,
    progress: Progress | None = None,
    load_factor: float | None = None,
) -> ControlSweep:
    """`control_effectiveness` at each airspeed [m/s], in the given order, with each surface's
    reversal two ways (the linear eigenvalue, and where the sweep's elastic derivative changes
    sign) and which comes first, reversal or the divergence of its problem.

    alpha: [deg] the jig's angle of attack at every airspeed, or None with `lift` [N]: trimmed,
        each airspeed at the alpha at which the wing (ailerons neutral) carries it.
    progress: called as `progress(done, total)` as each airspeed is answered.
    load_factor: the load factor the wing's own mass carries (`solver.FlightCondition`: trimmed,
        None is 1; at a given alpha, None is no inertial load, and a load factor is refused:
        it loads one flight condition, not a sweep)."""
    started = time.perf_counter()
    options = options or SolverOptions()
    require_control_surfaces(wing, _EFFECTIVENESS)
    check_over_airspeeds(alpha, load_factor, wing.mass is not None)
    base = without_aileron_deflections(wing)
    with numerical_failures_as(0.0):
        classical, antisymmetric = _classical(base, options)
    points: list[ControlSweepPoint] = []
    for velocity in velocities:
        if progress is not None and points:
            progress(len(points), len(velocities))
        try:
            with numerical_failures_as(velocity):
                flight = _point(base, velocity, alpha, lift, density, options, load_factor)
                controls = _at_flight(base, flight, options, classical)
        except SolverError as error:
            status: Literal["no_equilibrium", "not_converged"] = (
                "not_converged" if isinstance(error, ConvergenceError) else "no_equilibrium"
            )
            fold = error.fold_velocity if isinstance(error, NoEquilibrium) else None
            points.append(ControlSweepPoint(velocity, status, [], PointFailure(str(error), fold)))
            continue
        points.append(ControlSweepPoint(velocity, "equilibrium", controls, None))
    if progress is not None:
        progress(len(points), len(velocities))
    summaries = [
        _summary(base, index, classical[index], points, density)
        for index in range(len(base.control_surfaces))
    ]
    return ControlSweep(
        points=points,
        reversals=summaries,
        symmetric_divergence=_linear_divergence(base, density, options),
        antisymmetric_divergence=(
            antisymmetric_divergence(base, density, options)
            if antisymmetric is None
            else LinearDivergence(
                antisymmetric, FlightCondition.velocity_for(antisymmetric, density)
            )
        ),
        solver=AirspeedSweepInfo(time.perf_counter() - started),
    )


def _point(
    wing: Wing,
    velocity: float,
    alpha: float | None,
    lift: float | None,
    density: float,
    options: SolverOptions,
    load_factor: float | None,
) -> OperatingPoint:
    """The airspeed's point: at `alpha`, or trimmed to `lift` (`wing` has its ailerons
    neutral), the wing's mass carrying `load_factor` (`FlightCondition`)."""
    if alpha is not None:
        return OperatingPoint(velocity, alpha, density, load_factor)
    trimmed = FlightCondition(velocity, density=density, lift=lift, load_factor=load_factor)
    return solve(wing, trimmed, options=options).flight


def _linear_divergence(wing: Wing, density: float, options: SolverOptions) -> LinearDivergence:
    system = CoupledSystem.of(wing, 0.0, options)
    rest = at_rest(system)
    q = divergence_pressure(rest.evaluation, system.layout, rest.beam)
    if q is None:
        return LinearDivergence(None, None, "no positive real divergence eigenvalue")
    return LinearDivergence(q, FlightCondition.velocity_for(q, density))


def _summary(
    wing: Wing,
    index: int,
    classical: _Classical,
    points: Sequence[ControlSweepPoint],
    density: float,
) -> ReversalSummary:
    surface = wing.control_surfaces[index]
    return ReversalSummary(
        name=surface.name,
        kind=surface.kind,
        reversal=_reversal(classical.reversal, density, _NO_REVERSAL),
        crossing=_crossing(index, points, density, classical.divergence),
        divergence_pressure=classical.divergence,
        first=_first(classical.reversal, classical.divergence),
    )


def _crossing(
    index: int,
    points: Sequence[ControlSweepPoint],
    density: float,
    divergence: float | None,
) -> Reversal:
    """Where the sweep's effectiveness changes sign, in q: interpolated linearly in q after the
    divergence pole is taken out, E (1 - q / q_D), which is exactly linear for one torsion mode
    (the typical section's (1 - q/q_R) / (1 - q/q_D)); the first change of sign in q."""
    samples = sorted(
        (dynamic_pressure(density, p.velocity), p.controls[index].effectiveness)
        for p in points
        if p.controls and p.controls[index].effectiveness is not None
    )
    pole = (lambda q: 1.0 - q / divergence) if divergence else (lambda q: 1.0)
    for (q0, e0), (q1, e1) in itertools.pairwise(samples):
        f0, f1 = e0 * pole(q0), e1 * pole(q1)  # type: ignore[operator]
        if f0 == 0.0:
            return _reversal(q0, density, "")
        if f0 * f1 < 0:
            q = q0 + (q1 - q0) * f0 / (f0 - f1)
            return _reversal(q, density, "")
    return Reversal(
        None,
        None,
        "the sweep's effectiveness does not change sign between its airspeeds"
        if len(samples) > 1
        else "the sweep has fewer than two equilibria",
    )
