"""Static aeroelastic equilibrium of one wing at one flight condition."""

from __future__ import annotations

import functools
import math
import time
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from solver.compiled import CompiledModel, Evaluation, model_for
from solver.errors import ConvergenceError, NoEquilibrium
from solver.newton import newton
from solver.stability import divergence_pressure
from solver.wing import FlightCondition, Wing

if TYPE_CHECKING:
    from solver.divergence import Fold

__all__ = ["Equilibrium", "SolverOptions", "Stability", "solve", "linear_divergence_pressure"]


@dataclass(frozen=True)
class SolverOptions:
    """Newton settings.

    tolerance: max-norm of the residual at convergence (units in `solver.model`).
    max_iterations: Newton iterations of one attempt before giving up. A failed attempt below
        the fold is retried once from the branch from the jig, so a solve runs at most twice
        this many; `Equilibrium.iterations` counts them all.
    find_fold: also locate the fold of the branch from the jig shape (`Equilibrium.fold`).
    """

    tolerance: float = 1e-10
    max_iterations: int = 30
    find_fold: bool = False


@dataclass(frozen=True)
class Stability:
    """Static stability of an equilibrium and the wing's linear divergence.

    stable: the equilibrium is statically stable, lambda(x*) > q.
    margin: q / lambda(x*) [-]; 0 when no positive real lambda exists (never divergent).
    local_divergence_pressure: lambda(x*) [Pa], None when it does not exist.
    divergence_dynamic_pressure: classical linear divergence q_div at the unloaded jig shape
        (alpha = 0) [Pa], None for a wing that never diverges.
    divergence_velocity: sqrt(2 q_div / rho) at the flight's density [m/s], or None.
    """

    stable: bool
    margin: float
    local_divergence_pressure: float | None
    divergence_dynamic_pressure: float | None
    divergence_velocity: float | None


@dataclass(frozen=True, eq=False)
class Equilibrium:
    """A converged equilibrium. Arrays over stations are (N,), over right-half panels (N-1,).

    Stations: y [m], heave [m], slope [-], twist [deg], shear [N], bending_moment [N m],
    torque [N m] (internal loads carried by the structure at each station).
    Panels (root to tip): panel_y [m] deformed load location, panel_lift [N] vertical force,
    panel_lift_per_span [N/m] (per jig strip width), panel_torque [N m] about the elastic axis.
    Totals (both halves): lift, induced_drag [N]; CL, CDi on the jig planform area
    `reference_area` [m^2]; `deformed_area` [m^2] is AeroSandbox's planform area of the deformed
    wing (its CL uses it); rigid_lift [N] of the jig shape at the same condition.
    """

    wing: Wing
    flight: FlightCondition
    state: np.ndarray
    heave: np.ndarray
    slope: np.ndarray
    twist: np.ndarray
    shear: np.ndarray
    bending_moment: np.ndarray
    torque: np.ndarray
    panel_y: np.ndarray
    panel_lift: np.ndarray
    panel_lift_per_span: np.ndarray
    panel_torque: np.ndarray
    lift: float
    induced_drag: float
    CL: float
    CDi: float
    reference_area: float
    deformed_area: float
    rigid_lift: float
    stability: Stability
    iterations: int
    residual_norm: float
    warm_start: bool
    seconds: float
    evaluation: Evaluation  # r0, r1, J0, J1 at `state`: warm starts and continuation reuse it
    fold: Fold | None = None  # with `SolverOptions.find_fold`, or when solve had to consult it

    @property
    def y(self) -> np.ndarray:
        return self.wing.y

    @property
    def dynamic_pressure(self) -> float:
        return self.flight.dynamic_pressure

    @property
    def lift_amplification(self) -> float:
        """L / L_rigid [-]."""
        return self.lift / self.rigid_lift if self.rigid_lift != 0 else math.nan

    @property
    def tip_heave(self) -> float:
        return float(self.heave[-1])

    @property
    def tip_twist(self) -> float:
        return float(self.twist[-1])

    @property
    def root_bending_moment(self) -> float:
        return float(self.bending_moment[0])

    @property
    def root_torque(self) -> float:
        return float(self.torque[0])


def _outboard_sum(panel_values: np.ndarray) -> np.ndarray:
    """(N-1,) per panel -> (N,) per station: sum over panels outboard of each station."""
    return np.append(np.cumsum(panel_values[::-1])[::-1], 0.0)


@dataclass(frozen=True)
class _Loads:
    force: np.ndarray  # (3, N-1) [N]
    torque: np.ndarray  # (N-1,) [N m]
    center: np.ndarray  # (3, N-1) [m]
    vertex: np.ndarray  # (3, N) [m]

    def lift_and_drag(self, alpha_deg: float) -> tuple[float, float]:
        """Both halves: mirrored panels carry the same Fx and Fz."""
        alpha = math.radians(alpha_deg)
        fx, fz = 2 * self.force[0].sum(), 2 * self.force[2].sum()
        return (
            float(fz * math.cos(alpha) - fx * math.sin(alpha)),
            float(fx * math.cos(alpha) + fz * math.sin(alpha)),
        )


def _loads(model: CompiledModel, x: np.ndarray, p: np.ndarray, q: float) -> _Loads:
    force, torque, center, vertex = model.panel_loads(x, p)
    return _Loads(q * force, q * torque.ravel(), center, vertex)


def _parameter_key(wing: Wing) -> bytes:
    return wing.parameters(0.0).tobytes()


@functools.lru_cache(maxsize=256)
def _linear_divergence_cached(key: bytes) -> float | None:
    p = np.frombuffer(key, dtype=float).copy()
    n = (p.size - 1) // 5
    model = model_for(n)
    jig = np.zeros(model.layout.n_unknowns)  # at alpha = 0 the jig carries no circulation
    return divergence_pressure(model.evaluate(jig, p), model.layout)


def linear_divergence_pressure(wing: Wing) -> float | None:
    """Classical linear divergence dynamic pressure [Pa] at the unloaded jig, or None."""
    return _linear_divergence_cached(_parameter_key(wing))


@dataclass(frozen=True)
class _Jig:
    """The undeformed wing at one alpha, shared by every airspeed (loads scale with q)."""

    evaluation: Evaluation  # at u = u' = theta = 0 with zero circulation
    rigid_state: np.ndarray  # (4N-1,) jig geometry with the rigid wing's circulations
    rigid_lift_per_q: float  # [m^2] rigid lift / q


# Each entry holds two dense Jacobians (0.2 MB at N = 30, 3.7 MB at N = 120).
@functools.lru_cache(maxsize=16)
def _jig_cached(key: bytes) -> _Jig:
    p = np.frombuffer(key, dtype=float)
    model = model_for((p.size - 1) // 5)
    evaluation = model.evaluate(np.zeros(model.layout.n_unknowns), p)
    # At q = 0 the structure stays undeformed and the residual is linear in the circulation:
    # one step from zero circulation is the exact rigid solution.
    rigid_state = -np.linalg.solve(evaluation.jacobian0, evaluation.r0)
    rigid_state.setflags(write=False)
    lift_per_q, _ = _loads(model, rigid_state, p, 1.0).lift_and_drag(float(p[-1]))
    return _Jig(evaluation, rigid_state, lift_per_q)


def _jig(wing: Wing, alpha_deg: float) -> _Jig:
    return _jig_cached(wing.parameters(alpha_deg).tobytes())


def rigid_solution(wing: Wing, alpha_deg: float) -> np.ndarray:
    """(4N-1,) jig state (u = u' = theta = 0) with the rigid wing's circulations."""
    return _jig(wing, alpha_deg).rigid_state


def _deformed_area(wing: Wing, vertex: np.ndarray) -> float:
    """AeroSandbox's planform area: mean chord times y-z distance of quarter-chord points."""
    span_yz = np.hypot(np.diff(vertex[1]), np.diff(vertex[2]))
    return float(np.sum((wing.chord[1:] + wing.chord[:-1]) * span_yz))


def _stability(
    wing: Wing, flight: FlightCondition, evaluation: Evaluation, model: CompiledModel
) -> Stability:
    q = flight.dynamic_pressure
    local = divergence_pressure(evaluation, model.layout)
    linear = linear_divergence_pressure(wing)
    return Stability(
        stable=local is None or local > q,
        margin=0.0 if local is None else q / local,
        local_divergence_pressure=local,
        divergence_dynamic_pressure=linear,
        divergence_velocity=(
            None if linear is None else FlightCondition.velocity_for(linear, flight.density)
        ),
    )


def equilibrium_from_state(
    wing: Wing,
    flight: FlightCondition,
    x: np.ndarray,
    evaluation: Evaluation,
    *,
    iterations: int,
    residual_norm: float,
    warm_start: bool,
    started: float,
) -> Equilibrium:
    """Post-process a converged state into every reported quantity."""
    model = model_for(wing.n_stations)
    layout = model.layout
    q = flight.dynamic_pressure
    p = wing.parameters(flight.alpha)
    loads = _loads(model, x, p, q)
    lift, drag = loads.lift_and_drag(flight.alpha)
    lift_force = loads.force[2]
    panel_y = loads.center[1]
    shear = _outboard_sum(lift_force)
    bending_moment = _outboard_sum(lift_force * panel_y) - wing.y * shear
    reference_area = wing.planform_area
    return Equilibrium(
        wing=wing,
        flight=flight,
        state=x,
        heave=x[layout.heave].copy(),
        slope=x[layout.slope].copy(),
        twist=x[layout.twist].copy(),
        shear=shear,
        bending_moment=bending_moment,
        torque=_outboard_sum(loads.torque),
        panel_y=panel_y,
        panel_lift=lift_force,
        panel_lift_per_span=lift_force / np.diff(wing.y),
        panel_torque=loads.torque,
        lift=lift,
        induced_drag=drag,
        CL=lift / (q * reference_area),
        CDi=drag / (q * reference_area),
        reference_area=reference_area,
        deformed_area=_deformed_area(wing, loads.vertex),
        rigid_lift=q * _jig(wing, flight.alpha).rigid_lift_per_q,
        stability=_stability(wing, flight, evaluation, model),
        iterations=iterations,
        residual_norm=residual_norm,
        warm_start=warm_start,
        seconds=time.perf_counter() - started,
        evaluation=evaluation,
    )


def _initial_point(
    wing: Wing, flight: FlightCondition, initial_guess: Equilibrium | np.ndarray | None
) -> tuple[np.ndarray, Evaluation | None, bool]:
    """Starting state, its evaluation if already known, and whether it is a warm start."""
    n_unknowns = 4 * wing.n_stations - 1
    if initial_guess is None:
        # From the undeformed, unloaded jig: its cached evaluation makes the first step free.
        return np.zeros(n_unknowns), _jig(wing, flight.alpha).evaluation, False
    if isinstance(initial_guess, Equilibrium):
        same_problem = (
            initial_guess.wing.parameters(initial_guess.flight.alpha).tobytes()
            == wing.parameters(flight.alpha).tobytes()
        )
        # Same wing and alpha: the stored r0, r1, J0, J1 hold at any q, so the first Newton step
        # is the branch-tangent predictor at no evaluation cost.
        return initial_guess.state.copy(), initial_guess.evaluation if same_problem else None, True
    guess = np.asarray(initial_guess, dtype=float)
    if guess.shape != (n_unknowns,) or not np.all(np.isfinite(guess)):
        raise ValueError(f"initial_guess must be a finite state of shape ({n_unknowns},)")
    return guess.copy(), None, True


def _refuse_beyond_known_fold(
    wing: Wing, flight: FlightCondition, initial_guess: Equilibrium | np.ndarray | None
) -> None:
    """NoEquilibrium at once past a fold already traced for this wing and alpha.

    Only for starts on the jig's branch (none, or a stable equilibrium): a start the caller chose
    elsewhere may reach another branch's (unstable) equilibrium, which `solver.recovery` returns
    flagged. Without a cached fold, Newton runs first and the recovery path decides.
    """
    if isinstance(initial_guess, np.ndarray) or (
        isinstance(initial_guess, Equilibrium) and not initial_guess.stability.stable
    ):
        return
    from solver.divergence import known_fold_pressure  # it builds on this module

    fold_pressure = known_fold_pressure(wing, flight.alpha)
    if fold_pressure is not None and flight.dynamic_pressure > fold_pressure:
        raise NoEquilibrium(
            flight.velocity, FlightCondition.velocity_for(fold_pressure, flight.density)
        )


def solve(
    wing: Wing,
    flight: FlightCondition,
    initial_guess: Equilibrium | np.ndarray | None = None,
    options: SolverOptions | None = None,
    *,
    hint: Equilibrium | np.ndarray | None = None,
) -> Equilibrium:
    """The static aeroelastic equilibrium of `wing` at `flight`.

    Starts from the rigid jig solution, or from `initial_guess` (an equilibrium of the same wing,
    e.g. at another airspeed, or a raw state vector). If Newton fails or lands on a statically
    unstable equilibrium, the branch from the jig shape decides (`solver.recovery`): beyond its
    fold, `NoEquilibrium`; below it, Newton again from the branch, then `ConvergenceError`. An
    unstable equilibrium is returned only from a start the caller chose, flagged by
    `stability.stable`.

    `hint` is a start that may only save time, never change the answer (a stored equilibrium of
    this wing, a state interpolated from the branch): if Newton from it does not reach a stable
    equilibrium, the solve proceeds as if no hint had been given.
    """
    started = time.perf_counter()
    options = options or SolverOptions()
    if hint is not None and initial_guess is not None:
        raise ValueError("give an initial_guess or a hint, not both")
    _refuse_beyond_known_fold(wing, flight, initial_guess)
    equilibrium: Equilibrium | None = None
    failure: ConvergenceError | None = None
    spent = 0
    if hint is not None:
        hinted, _, spent = _converge_or_fail(wing, flight, hint, options, started, 0)
        if hinted is not None and hinted.stability.stable:
            equilibrium = hinted
    if equilibrium is None:
        equilibrium, failure, _ = _converge_or_fail(
            wing, flight, initial_guess, options, started, spent
        )
    if equilibrium is not None and equilibrium.stability.stable and not options.find_fold:
        return equilibrium
    from solver.recovery import settle  # imported here: it builds on this module

    return settle(wing, flight, initial_guess, equilibrium, failure, options, started)


def _converge_or_fail(
    wing: Wing,
    flight: FlightCondition,
    start: Equilibrium | np.ndarray | None,
    options: SolverOptions,
    started: float,
    prior_iterations: int,
) -> tuple[Equilibrium | None, ConvergenceError | None, int]:
    """One Newton run from `start` (None: the jig): an equilibrium or the failure, and the
    iterations, which include `prior_iterations` (spent on an earlier attempt)."""
    model = model_for(wing.n_stations)
    p = wing.parameters(flight.alpha)
    x0, evaluation0, warm = _initial_point(wing, flight, start)
    result = newton(
        lambda x: model.evaluate(x, p),
        lambda x: model.residual(x, p),
        x0,
        flight.dynamic_pressure,
        options.tolerance,
        options.max_iterations,
        evaluation0,
    )
    iterations = prior_iterations + result.iterations
    if not result.converged:
        failure = ConvergenceError(flight.velocity, iterations, result.residual_norm, result.reason)
        return None, failure, iterations
    equilibrium = equilibrium_from_state(
        wing,
        flight,
        result.x,
        result.evaluation,
        iterations=iterations,
        residual_norm=result.residual_norm,
        warm_start=warm,
        started=started,
    )
    return equilibrium, None, iterations
