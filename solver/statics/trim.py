"""Trimmed flight: the angle of attack at which the flexible wing carries a given lift.

Trimmed, alpha is one more unknown and the lift one more equation of the same Newton system,
z = (x, alpha):

    r(x, alpha; q) = r0(x, alpha) + q r1(x, alpha) = 0,    (l(x, alpha) - W / q*) / S = 0,

with l the lift of both halves per unit q [m^2], W the lift to carry [N] at the dynamic pressure
q* [Pa], and S the jig's planform area (the extra row is an error in lift coefficient). Its
Jacobian is exact: the compiled model gives dr/dalpha, dl/dx and dl/dalpha with J0 and J1.

The lift row does not depend on q, so the bordered system is affine in q like the untrimmed one,
and the answer is found the same way, by following the branch in q from the rigid jig
(`solver.numerics.path`):

1. the rigid jig's trim: the alpha at which the undeformed wing's lift per unit q is W / q*
   (its state is known in closed form at every alpha, `solver.statics.jig.AtRest`; a scalar secant
   iteration on the lift, started from the linear lattice's exact answer);
2. natural-parameter path following in q from (rigid state, rigid alpha) at q = 0 to q*, the
   lift coefficient held at W / (q* S) all the way: at q* the lift is W.

Every step is a deterministic function of the request, so a trimmed answer is as history-free as
any other. The stability verdict is the wing's at its trimmed alpha (the structure does not know
about trim). At a fixed lift the trimmed equilibrium goes on past the wing's divergence pressure
(the nose-up twist is trimmed out by a falling alpha), but it is statically unstable there at
fixed alpha: such points are answered `NoEquilibrium`, and the speed at which the trimmed wing
loses stability is its trimmed divergence limit (`trimmed_divergence_limit`).
"""

from __future__ import annotations

import dataclasses
import math
import time
from collections.abc import Sequence
from typing import Literal

import numpy as np

from solver import fields
from solver.errors import (
    ConvergenceError,
    InvalidInput,
    NoEquilibrium,
    SolverError,
    numerical_failures_as,
)
from solver.inputs.flight import FlightCondition, OperatingPoint
from solver.inputs.options import SolverOptions
from solver.inputs.wing import Wing
from solver.model.geometry import DEG
from solver.numerics.cache import cached
from solver.numerics.evaluation import Evaluation
from solver.numerics.path import PathResult, PathSettings, follow
from solver.results.equilibrium import Equilibrium, Fold
from solver.results.quantities import Progress
from solver.results.sweep import AirspeedPoint, AirspeedSweep, AirspeedSweepInfo, DivergenceSummary
from solver.statics.branch import pressure_scale
from solver.statics.divergence import fit_divergence, linear_divergence
from solver.statics.jig import AtRest, at_rest, linear_pressure
from solver.statics.loads import rigid_loads
from solver.statics.system import CoupledSystem
from solver.statics.validity import onsets
from solver.statics.verdict import judge, stability_of

__all__ = [
    "MAX_TRIM_ALPHA",
    "rigid_trim_alpha",
    "trim",
    "trimmed_airspeed_sweep",
    "trimmed_divergence_limit",
]

MAX_TRIM_ALPHA = 30.0  # [deg] the API's alpha limit: beyond it the attached-flow lattice is moot
_SECANT_ITERATIONS = 30
_ALPHA_TOLERANCE = 1e-12  # [deg]
_LIMIT_ITERATIONS = 40
_LIMIT_TOLERANCE = 1e-9  # relative, on the dynamic pressure of the trimmed divergence limit


# ----------------------------------------------------------------------------- the rigid trim


def _rigid_lift(base: CoupledSystem, rest: AtRest, alpha: float) -> float:
    """[m^2] the rigid jig's lift of both halves per unit q at `alpha` [deg]."""
    return base.at_alpha(alpha).residual_with_lift(rest.rigid_state(alpha))[2]


def _rigid_trim(base: CoupledSystem, lift_per_q: float, velocity: float) -> float:
    """[deg] the alpha at which the rigid jig's lift per unit q is `lift_per_q` [m^2].

    With the lift linear in the circulation, l(alpha) = l_cos cos(alpha) + l_sin sin(alpha)
    exactly; secant iterations then remove what the induced velocities add (a few percent).
    `velocity` [m/s] only names the request in errors.
    """
    rest = at_rest(base)
    l_cos = float(rest.lift_gradient @ rest.cos_state)
    l_sin = float(rest.lift_gradient @ rest.sin_state)
    amplitude, phase = math.hypot(l_cos, l_sin), math.atan2(l_sin, l_cos)
    if not abs(lift_per_q) < amplitude:
        raise NoEquilibrium(
            velocity, None, where="the rigid wing cannot carry this lift at any angle of attack"
        )
    a0 = math.degrees(math.remainder(phase - math.acos(lift_per_q / amplitude), 2 * math.pi))
    f0 = _rigid_lift(base, rest, a0) - lift_per_q
    slope = (l_sin * math.cos(a0 * DEG) - l_cos * math.sin(a0 * DEG)) * DEG  # [m^2/deg]
    a1 = a0 - f0 / slope
    for _ in range(_SECANT_ITERATIONS):
        if abs(a1 - a0) <= _ALPHA_TOLERANCE or not abs(a1) < 90.0:
            break
        f1 = _rigid_lift(base, rest, a1) - lift_per_q
        if f1 == f0:
            break
        a0, a1, f0 = a1, a1 - f1 * (a1 - a0) / (f1 - f0), f1
    if not abs(a1) < MAX_TRIM_ALPHA:
        raise NoEquilibrium(
            velocity,
            None,
            where=f"the rigid wing needs alpha = {a1:.4g} deg for this lift, beyond "
            f"+-{MAX_TRIM_ALPHA:g} deg: fly faster or carry less",
        )
    if not abs(a1 - a0) <= 1e-9:
        raise ConvergenceError(velocity, _SECANT_ITERATIONS, math.nan, "the rigid trim diverged")
    return a1


def rigid_trim_alpha(
    wing: Wing, condition: FlightCondition, options: SolverOptions | None = None
) -> float:
    """[deg] the angle of attack at which the rigid jig carries a trimmed `condition`'s lift."""
    base = CoupledSystem.of(wing, 0.0, options or SolverOptions())
    velocity, lift = _airspeed_and_lift(condition)
    with numerical_failures_as(velocity):
        return _rigid_trim(base, lift / condition.dynamic_pressure, velocity)


def _airspeed_and_lift(condition: FlightCondition) -> tuple[float, float]:
    """([m/s], [N]) of a trimmed condition at an airspeed."""
    lift = condition.required_lift
    if condition.velocity is None or lift is None:
        raise InvalidInput("", "a trimmed condition at an airspeed (velocity, and lift or weight)")
    return condition.velocity, lift


# ------------------------------------------------------------------------ the trimmed system


class _Trimmed:
    """The bordered system in z = (x, alpha) of one wing holding the lift per unit q
    `lift_per_q` [m^2]: affine in q, like the system it borders."""

    def __init__(self, base: CoupledSystem, lift_per_q: float) -> None:
        self.base, self.lift_per_q = base, lift_per_q
        self.area = base.wing.planform_area  # [m^2] the lift row is an error in CL

    def evaluate(self, z: np.ndarray) -> Evaluation:
        """The bordered r0, r1, J0, J1 at z (one evaluation of the compiled model)."""
        x, alpha = z[:-1], float(z[-1])
        ev, terms = self.base.at_alpha(alpha).evaluate_with_alpha(x)
        n = x.size
        j0, j1 = np.zeros((n + 1, n + 1)), np.zeros((n + 1, n + 1))
        j0[:n, :n], j0[:n, n] = ev.jacobian0, terms.r0
        j0[n, :n], j0[n, n] = terms.lift_x / self.area, terms.lift_alpha / self.area
        j1[:n, :n], j1[:n, n] = ev.jacobian1, terms.r1
        r0 = np.append(ev.r0, (terms.lift - self.lift_per_q) / self.area)
        return Evaluation(r0, np.append(ev.r1, 0.0), j0, j1)

    def residual(self, z: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        x, alpha = z[:-1], float(z[-1])
        r0, r1, lift = self.base.at_alpha(alpha).residual_with_lift(x)
        return np.append(r0, (lift - self.lift_per_q) / self.area), np.append(r1, 0.0)

    def scale(self) -> np.ndarray:
        """(n + 2,) scaled coordinates of (x, alpha [deg], q [Pa]): a radian of alpha weighs
        as a radian of twist at every station."""
        base = self.base.scale(pressure_scale(self.base))
        return np.concatenate([base[:-1], [math.degrees(1.0)], base[-1:]])


@dataclasses.dataclass(frozen=True)
class _TrimmedPoint:
    """A converged trimmed state, before its verdict."""

    system: CoupledSystem  # at the trimmed alpha
    flight: OperatingPoint
    x: np.ndarray
    evaluation: Evaluation  # of the untrimmed system at x (Jacobians at x or one step away)
    alpha_column: np.ndarray  # (n,) dr/dalpha at q
    lift_x: np.ndarray  # (n,) [m^2] the lift per unit q's gradient in x
    lift_alpha: float  # [m^2/deg]
    rigid_alpha: float
    rigid_slope: float  # [m^2/deg] the rigid jig's dl/dalpha at its trim
    rigid_state: np.ndarray
    path: PathResult

    def local_divergence_pressure(self) -> float | None:
        return stability_of(self.system, self.flight, self.evaluation).local_divergence_pressure


def _split(point: np.ndarray, evaluation: Evaluation, q: float) -> tuple[Evaluation, np.ndarray]:
    n = point.size - 1
    untrimmed = Evaluation(
        evaluation.r0[:n],
        evaluation.r1[:n],
        evaluation.jacobian0[:n, :n],
        evaluation.jacobian1[:n, :n],
    )
    return untrimmed, evaluation.jacobian0[:n, n] + q * evaluation.jacobian1[:n, n]


def _trimmed_point(wing: Wing, condition: FlightCondition, options: SolverOptions) -> _TrimmedPoint:
    """Follow the trimmed branch from the rigid trim at q = 0 to the condition's q."""
    q = condition.dynamic_pressure
    velocity, lift = _airspeed_and_lift(condition)
    base = CoupledSystem.of(wing, 0.0, options).with_inertia(condition.inertial_load_factor, q)
    lift_per_q = lift / q
    rigid_alpha = _rigid_trim(base, lift_per_q, velocity)
    trimmed = _Trimmed(base, lift_per_q)
    rigid_state = at_rest(base).rigid_state(rigid_alpha)
    start = np.append(rigid_state, rigid_alpha)
    start_evaluation = trimmed.evaluate(start)
    path = follow(
        trimmed.evaluate,
        trimmed.residual,
        start,
        0.0,
        start_evaluation,
        q,
        trimmed.scale(),
        options.tolerance,
        PathSettings(max_corrector_iterations=min(options.max_iterations, 8)),
    )
    if not path.reached:
        if path.reason.startswith("path stalled"):
            raise NoEquilibrium(
                velocity,
                FlightCondition.velocity_for(path.dynamic_pressure, condition.density),
                path.reason,
                where="the trimmed branch from the rigid jig turns back before this airspeed",
            )
        raise ConvergenceError(
            velocity, path.iterations, path.residual_norm, f"trimming: {path.reason}"
        )
    alpha = float(path.x[-1])
    if not abs(alpha) < MAX_TRIM_ALPHA:
        raise NoEquilibrium(
            velocity,
            None,
            where=f"the flexible wing needs alpha = {alpha:.4g} deg for this lift, beyond "
            f"+-{MAX_TRIM_ALPHA:g} deg",
        )
    evaluation, alpha_column = _split(path.x, path.evaluation, q)
    # The rigid jig's lift slope at its trim: through its closed-form state and the wind axes.
    start_terms = start_evaluation.jacobian0[-1] * trimmed.area
    rest = at_rest(base)
    rate = (
        -math.sin(rigid_alpha * DEG) * rest.cos_state + math.cos(rigid_alpha * DEG) * rest.sin_state
    ) * DEG
    rigid_slope = float(start_terms[-1] + start_terms[:-1] @ rate)
    lift_row = path.evaluation.jacobian0[-1] * trimmed.area
    return _TrimmedPoint(
        system=base.at_alpha(alpha),
        flight=condition.at_alpha(alpha),
        x=path.x[:-1],
        evaluation=evaluation,
        alpha_column=alpha_column,
        lift_x=lift_row[:-1],
        lift_alpha=float(lift_row[-1]),
        rigid_alpha=rigid_alpha,
        rigid_slope=rigid_slope,
        rigid_state=rigid_state,
        path=path,
    )


# ------------------------------------------------------------------------------ the answers


def trim(
    wing: Wing, condition: FlightCondition, options: SolverOptions | None = None
) -> Equilibrium:
    """The equilibrium that carries a trimmed `condition`'s lift [N] at its airspeed and
    density: alpha is solved for (`totals.alpha`), and the rigid jig's trim for the same lift
    reported beside it
    (`totals.rigid_alpha`, `panels.rigid_lift_per_span`, `totals.rigid_root_bending_moment`).

    Raises `NoEquilibrium` where the trimmed wing is statically unstable (past its trimmed
    divergence limit), where the lift needs |alpha| >= 30 deg, or where the trimmed branch from
    the rigid jig turns back; `ConvergenceError` where no answer could be reached. With
    `options.find_fold`, `fold` holds the trimmed divergence limit.
    """
    started = time.perf_counter()
    options = options or SolverOptions()
    velocity, lift = _airspeed_and_lift(condition)
    with numerical_failures_as(velocity):
        try:
            point = _trimmed_point(wing, condition, options)
            equilibrium = _answer(point, condition, options, started)
        except NoEquilibrium as error:
            raise _past_the_limit(wing, condition, options) or error from None
        if options.find_fold:
            limit = trimmed_divergence_limit(
                wing, lift, condition.density, options, load_factor=condition.load_factor
            )
            equilibrium = dataclasses.replace(equilibrium, fold=limit)
    return equilibrium


def _answer(
    point: _TrimmedPoint, condition: FlightCondition, options: SolverOptions, started: float
) -> Equilibrium:
    q = condition.dynamic_pressure
    stability = stability_of(point.system, point.flight, point.evaluation)
    if not stability.stable:
        raise NoEquilibrium(
            _airspeed_and_lift(condition)[0],
            None,
            f"its divergence pressure at the trimmed alpha {point.flight.alpha:.4g} deg is "
            f"{stability.local_divergence_pressure:.6g} Pa, below q = {q:.6g} Pa",
            where="the wing trimmed to this lift is statically unstable (past its trimmed "
            "divergence limit)",
        )
    equilibrium = judge(
        point.system,
        point.flight,
        options,
        point.x,
        point.evaluation,
        iterations=point.path.iterations,
        residual_norm=point.path.residual_norm,
        warm_start=False,
        started=started,
        rigid=rigid_loads(point.system.at_alpha(point.rigid_alpha), point.rigid_state),
        stability=stability,
    )
    # dl/dalpha of the flexible wing at fixed q: the state answers alpha through J dx = -dr.
    response = np.linalg.solve(point.evaluation.jacobian(q), -point.alpha_column)
    flexible_slope = point.lift_alpha + float(point.lift_x @ response)
    totals = dataclasses.replace(
        equilibrium.totals,
        rigid_alpha=point.rigid_alpha,
        lift_effectiveness=flexible_slope / point.rigid_slope,
    )
    return dataclasses.replace(equilibrium, totals=totals)


class _PastTheAirspeeds(Exception):
    """The trimmed divergence limit's search reached an airspeed [m/s] no flight condition
    takes."""

    def __init__(self, velocity: float) -> None:
        super().__init__(velocity)
        self.velocity = velocity


def _trimmed(
    velocity: float, lift: float, density: float, load_factor: float | None
) -> FlightCondition:
    """Trimmed to `lift` [N] at `velocity` [m/s], the wing's mass carrying `load_factor` g
    (None: 1 g)."""
    return FlightCondition(velocity, density=density, lift=lift, load_factor=load_factor)


def _past_the_limit(
    wing: Wing, condition: FlightCondition, options: SolverOptions
) -> NoEquilibrium | None:
    """The answer for a trimmed condition beyond the wing's trimmed divergence limit, or None
    when it lies below the limit (or the wing has none)."""
    velocity, lift = _airspeed_and_lift(condition)
    limit = trimmed_divergence_limit(
        wing, lift, condition.density, options, load_factor=condition.load_factor
    )
    return _beyond(limit, velocity)


def _beyond(limit: Fold, velocity: float) -> NoEquilibrium | None:
    """`NoEquilibrium` at `velocity` [m/s] if it lies past the trimmed divergence limit."""
    if limit.velocity is None or not velocity > limit.velocity:
        return None
    return NoEquilibrium(
        velocity,
        limit.velocity,
        where=f"past the trimmed divergence limit at {limit.velocity:.6g} m/s: the wing trimmed "
        "to this lift is statically unstable at fixed alpha beyond it",
    )


def trimmed_divergence_limit(
    wing: Wing,
    lift: float,
    density: float,
    options: SolverOptions | None = None,
    *,
    load_factor: float | None = None,
) -> Fold:
    """Where the wing trimmed to `lift` [N] at `density` [kg/m^3] loses static stability: the
    dynamic pressure at which its trimmed equilibrium's own divergence pressure equals q.

    Reported as a `Fold` of kind "trimmed_stability_limit": past it the trimmed equilibrium
    exists but is statically unstable at fixed alpha (at a fixed lift the twist hardly changes
    with q, so neither does the trimmed wing's divergence pressure: q passes it once). Found by
    secant iterations on q_local(q) - q from the linear divergence pressure, each point a
    trimmed solve; a deterministic function of its arguments, kept in the solver's cache, so a
    trimmed sweep or solve asked of the same wing again finds it at once. With `wing.mass`, the
    wing's own mass weighs `load_factor` g (None: 1 g) at every trimmed point.
    """
    options = options or SolverOptions()
    inertia = None if wing.mass is None else (1.0 if load_factor is None else load_factor + 0.0)
    key = ("trimmed_limit", wing.key, lift + 0.0, density + 0.0, _modelled(options), inertia)
    return cached(
        key, lambda: _trimmed_divergence_limit(wing, lift, density, options, load_factor), _size
    )


def _modelled(options: SolverOptions) -> tuple[object, ...]:
    """What of the options can change the limit (validity limits only change findings)."""
    return (
        options.chordwise_panels,
        options.torque_axis,
        options.aerodynamics,
        options.tolerance,
        options.max_iterations,
    )


def _size(fold: Fold) -> int:
    return 512  # [bytes] a handful of floats and a reason


def _trimmed_divergence_limit(
    wing: Wing, lift: float, density: float, options: SolverOptions, load_factor: float | None
) -> Fold:
    base = CoupledSystem.of(wing, 0.0, options)
    kind: Literal["trimmed_stability_limit"] = "trimmed_stability_limit"
    try:
        with numerical_failures_as(0.0):
            q_linear = linear_pressure(base)
    except ConvergenceError as error:
        reason = f"the linear divergence could not be computed: {error.reason}"
        return Fold(None, None, None, None, 0.0, reason, kind=kind)
    if q_linear is None:
        return Fold(None, None, None, None, 0.0, "the wing cannot diverge", kind=kind)
    evaluations = 0
    fastest = fields.spec_of(FlightCondition, "velocity").limits.le
    assert fastest is not None

    def gap(q: float) -> tuple[float, _TrimmedPoint]:
        nonlocal evaluations
        velocity = FlightCondition.velocity_for(q, density)
        if velocity > fastest:
            raise _PastTheAirspeeds(velocity)
        with numerical_failures_as(velocity):
            point = _trimmed_point(wing, _trimmed(velocity, lift, density, load_factor), options)
            local = point.local_divergence_pressure()
        evaluations += point.path.iterations
        return (math.inf if local is None else local) - q, point

    try:
        q0, q1 = 0.9 * q_linear, q_linear
        g0, _ = gap(q0)
        g1, point = gap(q1)
        for _ in range(_LIMIT_ITERATIONS):
            if abs(q1 - q0) <= _LIMIT_TOLERANCE * q1 or g1 == g0 or not math.isfinite(g1):
                break
            q_next = q1 - g1 * (q1 - q0) / (g1 - g0)
            if not (math.isfinite(q_next) and q_next > 0):
                return Fold(
                    None,
                    None,
                    None,
                    None,
                    FlightCondition.velocity_for(q1, density),
                    f"the secant left the positive dynamic pressures (next q = {q_next:.3g} Pa)",
                    kind=kind,
                )
            q0, q1, g0 = q1, q_next, g1
            g1, point = gap(q1)
    except SolverError as error:
        return Fold(
            None,
            None,
            None,
            None,
            0.0,
            f"the trimmed branch could not be traced: {error}",
            kind=kind,
        )
    except _PastTheAirspeeds as past:
        reason = (
            f"the limit lies past {fastest:g} m/s, the fastest airspeed the model takes (its "
            f"search reached {past.velocity:.4g} m/s)"
        )
        return Fold(None, None, None, None, fastest, reason, kind=kind)
    velocity = FlightCondition.velocity_for(q1, density)
    if not (math.isfinite(g1) and abs(q1 - q0) <= 1e-6 * q1):
        return Fold(None, None, None, None, velocity, "the secant did not settle", kind=kind)
    totals = judge(
        point.system,
        point.flight,
        options,
        point.x,
        point.evaluation,
        iterations=0,
        residual_norm=0.0,
        warm_start=False,
        started=time.perf_counter(),
        rigid=rigid_loads(point.system.at_alpha(point.rigid_alpha), point.rigid_state),
    ).totals
    return Fold(
        velocity=velocity,
        dynamic_pressure=q1,
        tip_twist=totals.tip_twist,
        lift=lift,
        searched_to_velocity=velocity,
        tip_heave=totals.tip_heave,
        evaluations=evaluations,
        kind=kind,
    )


def trimmed_airspeed_sweep(
    wing: Wing,
    velocities: Sequence[float],
    lift: float,
    density: float,
    options: SolverOptions | None = None,
    progress: Progress | None = None,
    *,
    load_factor: float | None = None,
) -> AirspeedSweep:
    """The wing trimmed to `lift` [N] at each airspeed [m/s], answered in the given order.

    Each point is `trim` at its speed (history-free). The trimmed divergence limit is found
    first: a speed beyond it is answered with `NoEquilibrium` without a solve, as `trim`
    answers it (a trimmed path past the limit can take hundreds of steps to give up). The
    divergence summary says what divergence means at a fixed lift: `linear` as for any sweep;
    `fit` the study's 1/A fit with A the lift effectiveness (for a single torsion mode
    1/A = 1 - q/q_div exactly); `fold` the trimmed divergence limit (kind
    "trimmed_stability_limit"), where each point's `stability.margin` reaches 1.
    """
    started = time.perf_counter()
    options = options or SolverOptions()
    limit = trimmed_divergence_limit(wing, lift, density, options, load_factor=load_factor)
    points: list[AirspeedPoint] = []
    for velocity in velocities:
        if progress is not None and points:
            progress(len(points), len(velocities))
        beyond = _beyond(limit, velocity)
        if beyond is not None:
            points.append(AirspeedPoint.failed(velocity, beyond))
            continue
        try:
            condition = _trimmed(velocity, lift, density, load_factor)
            with numerical_failures_as(velocity):
                try:
                    point = _trimmed_point(wing, condition, options)
                    equilibrium = _answer(point, condition, options, time.perf_counter())
                except NoEquilibrium as error:
                    raise _past_the_limit(wing, condition, options) or error from None
        except SolverError as error:
            points.append(AirspeedPoint.failed(velocity, error))
            continue
        points.append(AirspeedPoint(None, velocity, "equilibrium", equilibrium, None))
    if progress is not None:
        progress(len(points), len(velocities))
    stable = [p.equilibrium for p in points if p.equilibrium is not None]
    divergence = DivergenceSummary(
        linear=linear_divergence(wing, density, options),
        fit=fit_divergence(stable, "lift_effectiveness"),
        fold=limit,
    )
    return AirspeedSweep(
        points,
        divergence,
        AirspeedSweepInfo(time.perf_counter() - started),
        validity=onsets(points),
    )
