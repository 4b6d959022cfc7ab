"""Flutter: damping and frequency of every mode against airspeed, by the p-k method.

The equations of motion of small oscillations w e^{st} about a state of the static model are
(`solver.dynamics.modes`, `solver.dynamics.unsteady`)

    (s^2 M + K - f(s)) w = 0,

f(s) the aerodynamic loads: quasi-steady and non-circulatory terms polynomial in s, the
circulation's lag C(k) a function of the reduced frequency k = omega b / V of harmonic motion
only. The p-k method (Hassig, J. Aircraft 8(11), 1971; Rodden and Johnson, MSC Nastran
Aeroelastic Analysis User's Guide, section 2.6) finds, for each mode and airspeed, the root s
for which the lag is evaluated at its own frequency: with C(k) fixed the equations are a
quadratic eigenvalue problem, solved exactly; k is updated from the root, to a fixed point.
Its damping -Re(s) / |s| is exact where it matters, at zero (the flutter boundary, where the
motion is harmonic), and an approximation (with C of the root's frequency) elsewhere.

Degrees of freedom: the lowest natural modes (`FlutterOptions.modes`, six by default; the
Goland wing's flutter speed moves by 5e-7 with every mode) and, when the wing can diverge, the
part of the unloaded wing's static divergence shape outside them, condensed statically (it
follows the modes as the stiffness says, `_condense`). With it the equations keep the full
model's static divergence exactly: at s = 0 they are K w = q Q w, and its solution at the
divergence pressure lies in the basis. One root is followed per mode, from its frequency in
still air (V = 0) up the airspeeds, in steps no larger than a fortieth of the largest one, each
step's p-k started from the roots extrapolated from the last three.

- Flutter: the first airspeed at which an oscillating root's damping crosses from positive to
  negative, located between the sweep's speeds by the Illinois secant method on Re(s).
- Divergence: the real roots of the zero-frequency equations (C = 1: a non-oscillating motion)
  are computed at each airspeed too (`FlutterPoint.divergence_rate`); the largest crosses zero
  where the wing diverges. About the jig that is the static linear divergence under the same
  aerodynamics (the number reported); about a loaded equilibrium the static model's fold (at
  an angle of attack) or trimmed stability limit (at a lift).

About the jig the state is the unloaded wing at rest; "about an equilibrium" (`alpha` or `lift`)
the state at each airspeed is the static equilibrium there (`solver.sweep`, `solver.trim`), its
tangent aerodynamic stiffness included: the loaded wing's flutter.
"""

from __future__ import annotations

import math
import time
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Literal

import numpy as np

from solver.dynamics.modes import Structure, mode_shape, structure
from solver.dynamics.unsteady import UnsteadyAerodynamics, theodorsen, unsteady_aerodynamics
from solver.errors import ConvergenceError, InvalidInput, SolverError, numerical_failures_as
from solver.fields import integer, is_number, number, parameter, specs
from solver.inputs.flight import FlightCondition
from solver.inputs.mass import MassModel
from solver.inputs.options import SolverOptions
from solver.inputs.wing import Wing
from solver.numerics.evaluation import Evaluation
from solver.results.equilibrium import Equilibrium
from solver.results.flutter import (
    DivergenceOnset,
    FlutterInfo,
    FlutterOnset,
    FlutterPoint,
    FlutterResult,
    NoFlutter,
)
from solver.results.quantities import Progress
from solver.statics.airspeed_sweep import airspeed_sweep
from solver.statics.jig import at_rest, linear_pressure
from solver.statics.solve import solve
from solver.statics.system import CoupledSystem

__all__ = ["FlutterOptions", "flutter"]

# The lowest natural modes in the basis by default: the Goland wing's flutter speed moves by
# 5e-7 from six to all 22 of an N = 12 mesh (tests/solver/test_flutter.py).
_DEFAULT_MODES = 6
# The tracking steps: at most this fraction of the largest airspeed each.
_STEPS = 40
# A root is oscillating when its frequency exceeds this fraction of its modulus.
_OSCILLATING = 1e-6
# The flutter speed is located to this relative tolerance.
_SPEED_TOLERANCE = 1e-10
_SECANT_ITERATIONS = 60
# A divergence shape inside the natural modes' span to this fraction needs no basis vector.
_INSIDE_SPAN = 1e-9


@dataclass(frozen=True)
class FlutterOptions:
    """How the flutter solution is made, and about which state."""

    about: Literal["equilibrium", "jig"] = parameter(
        "",
        "the state the equations of motion are linearised about: equilibrium (the static "
        "equilibrium of the flight condition at each airspeed: its tangent stiffness, "
        "aerodynamic stiffness included) or jig (the unloaded wing, the classical analysis)",
        form="choice",
        choices=("equilibrium", "jig"),
        default="equilibrium",
    )
    modes: int | None = parameter(
        "-",
        "natural modes in the solution's basis, the lowest (the divergence shape's remainder "
        "comes on top, condensed); null: six, or all of a mesh with fewer",
        ge=1,
        le=100,
        why="at least one mode; at most the mesh's 2 (N - 1)",
        form="integer",
        default=None,
    )
    unsteady: Literal["theodorsen", "quasi_steady"] = parameter(
        "",
        "the circulation's lag: theodorsen (C(k)) or quasi_steady (C = 1, no wake lag)",
        form="choice",
        choices=("theodorsen", "quasi_steady"),
        default="theodorsen",
    )
    tolerance: float = parameter(
        "-",
        "relative change of a root at which its p-k iteration has converged",
        ge=1e-14,
        le=1e-3,
        why="a looser fixed point moves the flutter speed by as much",
        default=1e-10,
    )
    max_iterations: int = parameter(
        "-",
        "p-k iterations of one root at one airspeed before it is given up",
        ge=1,
        le=1000,
        why="the fixed point needs at least one",
        form="integer",
        default=100,
    )

    def __post_init__(self) -> None:
        for name, spec in specs(FlutterOptions).items():
            value = getattr(self, name)
            if value is None:
                continue
            if spec.form == "integer":
                integer(name, value, spec)
            elif spec.form == "number":
                number(name, value, spec)
            elif value not in spec.choices:
                raise InvalidInput(name, "must be one of " + ", ".join(spec.choices))


@dataclass(frozen=True)
class _Basis:
    """The reduced degrees of freedom: w = right c, equations projected on left; the last
    column, with `condensed`, the divergence shape's remainder (statically condensed)."""

    right: np.ndarray  # (n, r)
    left: np.ndarray  # (n, r)
    vacuum: np.ndarray  # (modes,) [rad/s] the natural modes' frequencies in vacuum
    divergence_pressure: float | None  # [Pa] of the unloaded wing
    condensed: bool  # the last column is the divergence shape's remainder


@dataclass(frozen=True)
class _Reduced:
    """The equations on the basis at one state (`solver.dynamics.unsteady.UnsteadyAerodynamics`),
    the circulatory terms grouped by the strips' semichords (one lag per group):

        (s^2 mass + s damping(C) + stiffness(C)) c = 0,
        stiffness(C) = stiffness - q (geometric + sum_g C_g lagged_deformation_g),
        damping(C) = -(q / V) sum_g C_g lagged_motion_g - density V apparent_damping,
        mass = mass - density apparent_mass.
    """

    stiffness: np.ndarray  # (r, r)
    mass: np.ndarray  # (r, r)
    geometric: np.ndarray  # (r, r)
    lagged_deformation: np.ndarray  # (groups, r, r)
    lagged_motion: np.ndarray  # (groups, r, r)
    apparent_mass: np.ndarray  # (r, r)
    apparent_damping: np.ndarray  # (r, r)
    semichord: np.ndarray  # (groups,) [m]
    condensed: bool  # the last degree of freedom is condensed statically (`_condense`)

    @classmethod
    def of(cls, beam: Structure, basis: _Basis, aero: UnsteadyAerodynamics) -> _Reduced:
        left, right = basis.left.T, basis.right
        loads = left @ aero.circulation_loads  # (r, M)
        deformation, motion = aero.deformation @ right, aero.motion @ right
        semichord, group = np.unique(aero.semichord, return_inverse=True)
        members = [np.flatnonzero(group == g) for g in range(semichord.size)]
        return cls(
            stiffness=left @ beam.stiffness @ right,
            mass=left @ beam.mass @ right,
            geometric=left @ aero.geometric @ right,
            lagged_deformation=np.array([loads[:, p] @ deformation[p] for p in members]),
            lagged_motion=np.array([loads[:, p] @ motion[p] for p in members]),
            apparent_mass=left @ aero.apparent_mass @ right,
            apparent_damping=left @ aero.apparent_damping @ right,
            semichord=semichord,
            condensed=basis.condensed,
        )

    def divergence_rate(self, velocity: float, density: float) -> float | None:
        """[1/s] the largest real root of the equations at zero reduced frequency (C = 1, the
        p-k root of a non-oscillating motion), or None when they have no real root; positive
        beyond divergence. At s = 0 the equations are the static model's, K w = q Q w."""
        if velocity == 0:
            return None
        q = 0.5 * density * velocity * velocity
        # No lag: real coefficients, a real eigenvalue problem (half the work of a complex one).
        stiffness = self.stiffness - q * (self.geometric + self.lagged_deformation.sum(axis=0).real)
        damping = -(q / velocity) * self.lagged_motion.sum(axis=0).real
        damping = damping - density * velocity * self.apparent_damping
        mass = self.mass - density * self.apparent_mass
        matrices = (mass[None], damping[None], stiffness[None])
        if self.condensed:
            matrices = _condense(*matrices)
        roots = np.linalg.eigvals(_companion(*matrices))[0]
        real = roots[np.abs(roots.imag) <= _OSCILLATING * np.abs(roots)].real
        return float(real.max()) if real.size else None

    def blend(self, other: _Reduced, weight: float) -> _Reduced:
        """The equations (1 - weight) self + weight other (the same basis and strips)."""
        names = [n for n in self.__dataclass_fields__ if n not in ("semichord", "condensed")]
        mixed = {
            name: (1 - weight) * getattr(self, name) + weight * getattr(other, name)
            for name in names
        }
        return _Reduced(**mixed, semichord=self.semichord, condensed=self.condensed)

    def roots(
        self, frequency: np.ndarray, velocity: float, density: float, lagged: bool
    ) -> np.ndarray:
        """(t, 2r) the roots s [1/s] of the equations with the lag of each of the t
        `frequency` [rad/s] (C = 1 without `lagged`, or in still air)."""
        r, t = self.stiffness.shape[0], frequency.shape[0]
        q = 0.5 * density * velocity * velocity
        if velocity > 0 and lagged:
            lag = theodorsen(frequency[:, None] * self.semichord[None, :] / velocity)
        else:
            lag = np.ones((t, self.semichord.shape[0]), dtype=complex)
        circulatory = np.tensordot(lag, self.lagged_deformation, axes=1)  # (t, r, r)
        stiffness = self.stiffness - q * (self.geometric + circulatory)
        damping = np.broadcast_to(-density * velocity * self.apparent_damping, (t, r, r))
        if velocity > 0:
            damping = damping - (q / velocity) * np.tensordot(lag, self.lagged_motion, axes=1)
        mass = np.broadcast_to(self.mass - density * self.apparent_mass, (t, r, r))
        if self.condensed:
            mass, damping, stiffness = _condense(mass, damping, stiffness)
        return np.linalg.eigvals(_companion(mass, damping, stiffness))


def _condense(
    mass: np.ndarray, damping: np.ndarray, stiffness: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(t, r - 1, r - 1) each: the equations with their last degree of freedom condensed
    statically (Guyan): it follows the others as the stiffness says, c_last = T c, and its
    equation is combined with theirs likewise. The condensed stiffness is the Schur
    complement, singular exactly when the whole is: the static divergence is kept; the last
    shape's own dynamics (a high-frequency remainder) are not, and it is no mode of its own."""
    k_last = stiffness[:, -1, -1]
    right = -stiffness[:, -1, :-1] / k_last[:, None]  # (t, r - 1)
    left = -stiffness[:, :-1, -1] / k_last[:, None]

    def apply(x: np.ndarray) -> np.ndarray:
        return (
            x[:, :-1, :-1]
            + x[:, :-1, -1:] * right[:, None, :]
            + left[:, :, None] * x[:, -1:, :-1]
            + x[:, -1:, -1:] * left[:, :, None] * right[:, None, :]
        )

    return apply(mass), apply(damping), apply(stiffness)


def _companion(mass: np.ndarray, damping: np.ndarray, stiffness: np.ndarray) -> np.ndarray:
    """(t, 2r, 2r): the first-order form of (s^2 mass + s damping + stiffness) c = 0."""
    t, r = stiffness.shape[0], stiffness.shape[1]
    inverse = np.linalg.inv(mass)
    companion = np.zeros((t, 2 * r, 2 * r), dtype=np.result_type(stiffness, damping, mass))
    companion[:, :r, r:] = np.eye(r)
    companion[:, r:, :r] = -inverse @ stiffness
    companion[:, r:, r:] = -inverse @ damping
    return companion


def _closest(candidates: np.ndarray, guesses: np.ndarray) -> np.ndarray:
    """(t,) for each row of candidates (t, 2r) the one closest to its guess in the upper
    half-plane. With the lag C(k) of a positive frequency the equations' coefficients are
    complex: only the upper roots belong to it (their conjugates would need the conjugate lag);
    a real root is real to round-off, and taken as real."""
    modulus = np.abs(candidates)
    upper = candidates.imag >= -_OSCILLATING * modulus
    distance = np.where(upper, np.abs(candidates - guesses[:, None]), np.inf)
    chosen = candidates[np.arange(candidates.shape[0]), np.argmin(distance, axis=1)]
    return np.where(chosen.imag < 0, chosen.real + 0j, chosen)


def _track(
    reduced: _Reduced,
    guesses: np.ndarray,
    velocity: float,
    density: float,
    options: FlutterOptions,
    scale: float,
) -> tuple[np.ndarray, int]:
    """The p-k roots (t,) at `velocity` from `guesses`, and the solves spent; raises
    `ConvergenceError` when a root's fixed point is not reached.

    The fixed point is in the lag's frequency omega: a root s(omega) of the equations with
    C(omega b / V) is the p-k root when Im s(omega) = omega. It is found by the secant method
    on Im s(omega) - omega (a plain fixed-point iteration converges linearly, ~12 solves a root
    on the Goland wing; the secant ~4), each solve the exact quadratic eigenvalue problem."""
    lagged = options.unsteady == "theodorsen"
    roots = guesses.copy()
    frequency = np.maximum(guesses.imag, 0.0)
    active = np.arange(roots.shape[0])
    previous: tuple[np.ndarray, np.ndarray] | None = None
    solves = 0
    for _ in range(options.max_iterations):
        found = _closest(reduced.roots(frequency[active], velocity, density, lagged), roots[active])
        solves += active.size
        roots[active] = found
        if not lagged:
            return roots, solves  # no lag: the first solve is the root
        mismatch = found.imag - frequency[active]
        done = np.abs(mismatch) <= options.tolerance * np.maximum(np.abs(found), scale)
        step = mismatch.copy()
        if previous is not None:
            last_frequency, last_mismatch = previous
            slope = (mismatch - last_mismatch) / (frequency[active] - last_frequency)
            usable = np.isfinite(slope) & (slope < -0.1)  # d mismatch / d omega ~ -1
            step = np.where(usable, -mismatch / np.where(usable, slope, 1.0), mismatch)
        keep = ~done
        previous = (frequency[active][keep], mismatch[keep])
        active = active[keep]
        frequency[active] = np.maximum(frequency[active] + step[keep], 0.0)
        if active.size == 0:
            return roots, solves
    raise ConvergenceError(
        velocity, solves, math.nan, "the p-k iteration of a mode's root did not converge"
    )


def _basis(beam: Structure, aero: UnsteadyAerodynamics, q_div: float | None, count: int) -> _Basis:
    """The lowest `count` modes and, with a divergence pressure, the divergence shape's part
    outside them (`solver.dynamics.modes.Structure.modes`: left.T M right = I)."""
    omega2, right, left = beam.modes
    right, left = right[:, :count], left[:, :count]
    vacuum = np.sqrt(omega2[:count])
    if q_div is None:
        return _Basis(right, left, vacuum, None, False)
    operator = beam.stiffness - q_div * aero.stiffness()
    u, _, vt = np.linalg.svd(operator)
    shape, left_shape = vt[-1], u[:, -1]
    remainder = shape - right @ (left.T @ beam.mass @ shape)
    if np.linalg.norm(remainder) <= _INSIDE_SPAN * np.linalg.norm(shape):
        return _Basis(right, left, vacuum, q_div, False)
    left_remainder = left_shape - left @ (right.T @ beam.mass.T @ left_shape)
    generalised = left_remainder @ beam.stiffness @ remainder
    return _Basis(
        np.column_stack([right, remainder]),
        np.column_stack([left, left_remainder / generalised]),
        vacuum,
        q_div,
        True,
    )


def _grid(velocities: np.ndarray) -> np.ndarray:
    """Ascending tracking speeds from 0: the requested ones and enough between them."""
    largest = float(velocities.max())
    step = largest / _STEPS
    points = [0.0]
    for velocity in np.unique(velocities):
        gap = velocity - points[-1]
        count = max(1, math.ceil(gap / step - 1e-9))
        points.extend(points[-1] + gap * np.arange(1, count + 1) / count)
        points[-1] = float(velocity)
    return np.array(points)


def _still_air(reduced: _Reduced, density: float) -> np.ndarray:
    """(modes,) the roots at V = 0 (in still air, apparent mass only), one per natural mode:
    the i-th lowest frequency to the i-th mode."""
    roots = reduced.roots(np.zeros(1), 0.0, density, False)[0]
    upper = roots[roots.imag > 0]
    return upper[np.argsort(upper.imag)]


def _check(
    wing: Wing, velocities: Sequence[float], density: float, alpha: object, lift: object
) -> np.ndarray:
    speeds = np.asarray(velocities, dtype=float) if len(velocities) else np.zeros(0)
    if speeds.ndim != 1 or speeds.size == 0:
        raise InvalidInput("velocities", "must be a list of at least one airspeed")
    if not np.all(np.isfinite(speeds)) or not np.all(speeds > 0):
        raise InvalidInput("velocities", "must be positive, finite airspeeds")
    if not (is_number(density) and math.isfinite(density) and density > 0):
        raise InvalidInput("density", "must be a positive, finite number")
    if alpha is not None and lift is not None:
        raise InvalidInput("alpha", "give an alpha or a lift to linearise about, not both")
    return speeds


class _States:
    """The state to linearise about at each airspeed: the jig, or the equilibrium there."""

    def __init__(
        self,
        wing: Wing,
        density: float,
        alpha: float | None,
        lift: float | None,
        options: SolverOptions,
    ) -> None:
        self.wing, self.density, self.options = wing, density, options
        self.alpha, self.lift = alpha, lift
        self.about: Literal["jig", "alpha", "trim"] = (
            "jig" if alpha is None and lift is None else "alpha" if lift is None else "trim"
        )
        self.rest = CoupledSystem.of(wing, 0.0, options)
        self.equilibria: dict[float, Equilibrium | SolverError] = {}
        self.divergence: DivergenceOnset | None = None
        self.rest_equations: _Reduced | None = None

    def prepare(self, speeds: np.ndarray, largest: float) -> None:
        """Solve the equilibria at every tracking speed (loaded states only), and find where
        the loaded wing diverges."""
        if self.about == "jig":
            return
        positive = [float(v) for v in speeds if v > 0]
        result = airspeed_sweep(self.wing, positive, self._flight(None), self.options)
        for point in result.points:
            self.equilibria[point.velocity] = point.equilibrium or point.error  # type: ignore[assignment]
        fold = result.divergence.fold
        if fold.velocity is not None and fold.dynamic_pressure is not None:
            self.divergence = DivergenceOnset(
                fold.velocity, fold.dynamic_pressure, fold.velocity <= largest, fold.kind
            )

    def evaluation(self, velocity: float) -> tuple[CoupledSystem, Evaluation]:
        """The system and the exact Jacobians to linearise about at `velocity` [m/s]."""
        if self.about == "jig" or velocity == 0:
            return self.rest, at_rest(self.rest).evaluation
        equilibrium = self.equilibria.get(velocity)
        if equilibrium is None:
            equilibrium = self._solve(velocity)
        if isinstance(equilibrium, SolverError):
            raise equilibrium
        system = CoupledSystem.of(self.wing, equilibrium.totals.alpha, self.options)
        return system, system.evaluate(equilibrium.state)

    def _flight(self, velocity: float | None) -> FlightCondition:
        """The flight the loaded wing flies at `velocity` [m/s] (None: at each of a sweep's)."""
        if self.about == "alpha":
            return FlightCondition(velocity, self.alpha or 0.0, self.density)
        return FlightCondition(velocity, density=self.density, lift=self.lift or 0.0)

    def _solve(self, velocity: float) -> Equilibrium | SolverError:
        try:
            flight = self._flight(velocity)
            answer: Equilibrium | SolverError = solve(self.wing, flight, options=self.options)
        except SolverError as error:
            answer = error
        self.equilibria[velocity] = answer
        return answer


def flutter(
    wing: Wing,
    mass: MassModel | None,
    velocities: Sequence[float],
    density: float,
    *,
    alpha: float | None = None,
    lift: float | None = None,
    options: SolverOptions | None = None,
    flutter_options: FlutterOptions | None = None,
    progress: Progress | None = None,
) -> FlutterResult:
    """Damping and frequency of every mode of `wing` with `mass` at each airspeed [m/s] (the
    V-g and V-f diagrams) at `density` [kg/m^3], the flutter and divergence speeds.

    Linearised about the unloaded jig, or, given `alpha` [deg] or `lift` [N], about the static
    equilibrium at each airspeed at that angle of attack or trimmed to that lift. `options`
    chooses the aerodynamics ("strip": Theodorsen's strip theory; "lattice", the default: the
    lattice's steady circulation with Theodorsen's lag), `flutter_options` the basis and the
    lag. `progress(done, total)` is called after each requested airspeed.

    Raises `InvalidInput` without a mass model or for invalid inputs; `ConvergenceError` when a
    root cannot be followed. Airspeeds beyond a loaded wing's fold have no roots
    (status "no_equilibrium")."""
    started = time.perf_counter()
    options = options or SolverOptions()
    settings = flutter_options or FlutterOptions()
    speeds = _check(wing, velocities, density, alpha, lift)
    beam = structure(wing, mass)
    count = min(_DEFAULT_MODES, beam.n_dof) if settings.modes is None else settings.modes
    if count > beam.n_dof:
        raise InvalidInput("flutter.modes", f"must be at most {beam.n_dof} on this mesh")
    states = _States(wing, density, alpha, lift, options)
    with numerical_failures_as(float(speeds[0])):
        layout = states.rest.layout
        rest_aero = unsteady_aerodynamics(beam, layout, at_rest(states.rest).evaluation)
        q_div = linear_pressure(states.rest)
        basis = _basis(beam, rest_aero, q_div, count)
        grid = _grid(speeds)
        states.prepare(grid, float(speeds.max()))
        tracked = _follow(beam, basis, states, grid, speeds, density, settings, progress)
    return _result(wing, beam, basis, states, speeds, tracked, density, options, settings, started)


@dataclass
class _Tracked:
    """The roots along the grid: per grid speed, the roots (r,) or None past the equilibria,
    and why not."""

    grid: np.ndarray
    roots: list[np.ndarray | None]
    reasons: list[str | None]
    iterations: int
    divergence_rates: list[float | None]


def _follow(
    beam: Structure,
    basis: _Basis,
    states: _States,
    grid: np.ndarray,
    speeds: np.ndarray,
    density: float,
    settings: FlutterOptions,
    progress: Progress | None,
) -> _Tracked:
    """Every root from still air up the grid. About a loaded equilibrium the unloaded wing's
    roots are followed alongside: where the loaded roots start (after speeds without an
    equilibrium: a lift too large to carry slowly, a fold) they start from the unloaded ones,
    the equations blended from unloaded to loaded in `_BLEND_STEPS` steps."""
    requested = set(speeds.tolist())
    total, done = len(requested), 0
    roots: list[np.ndarray | None] = []
    reasons: list[str | None] = []
    scale = float(basis.vacuum.min())
    rates: list[float | None] = []
    rest = _reduced_at(beam, basis, states, 0.0)
    follow = _Follower(rest, density, settings, scale)
    unloaded = _Follower(rest, density, settings, scale)
    for velocity in (float(v) for v in grid):
        reason, rate = None, None
        try:
            if states.about == "jig":
                current: np.ndarray | None = follow.step(rest, velocity)
                rate = rest.divergence_rate(velocity, density)
            else:
                unloaded.step(rest, velocity)
                loaded = _reduced_at(beam, basis, states, velocity)
                current = follow.step(loaded, velocity, start=unloaded)
                rate = loaded.divergence_rate(velocity, density)
        except SolverError as error:
            current, reason = None, str(error)
            follow.history.clear()
        roots.append(current)
        reasons.append(reason)
        rates.append(rate)
        if velocity in requested:
            done += 1
            if progress is not None:
                progress(done, total)
    return _Tracked(grid, roots, reasons, follow.solves + unloaded.solves, rates)


_BLEND_STEPS = 4


class _Follower:
    """One set of roots followed up the airspeeds (continuation in V, p-k at each)."""

    def __init__(self, rest: _Reduced, density: float, settings: FlutterOptions, scale: float):
        self.density, self.settings, self.scale = density, settings, scale
        self.history: list[tuple[float, np.ndarray]] = [(0.0, _still_air(rest, density))]
        self.equations = rest
        self.solves = 0

    def step(
        self, reduced: _Reduced, velocity: float, start: _Follower | None = None
    ) -> np.ndarray:
        """The roots at `velocity` of `reduced`: from this follower's last roots, or, when it
        has none (a restart), from `start`'s at this speed through blended equations."""
        if velocity == 0:
            return self.history[0][1]
        if self.history:
            guesses = _extrapolate(self.history, velocity)
            roots = self._track(reduced, guesses, velocity)
        else:
            assert start is not None and start.history
            base = start.history[-1]
            roots, equations = base[1], start.equations
            for step in range(1, _BLEND_STEPS + 1):
                roots = self._track(equations.blend(reduced, step / _BLEND_STEPS), roots, velocity)
        self.history.append((velocity, roots))
        del self.history[:-3]
        self.equations = reduced
        return roots

    def _track(self, reduced: _Reduced, guesses: np.ndarray, velocity: float) -> np.ndarray:
        roots, spent = _track(reduced, guesses, velocity, self.density, self.settings, self.scale)
        self.solves += spent
        return roots


def _reduced_at(beam: Structure, basis: _Basis, states: _States, velocity: float) -> _Reduced:
    """The equations on the basis about the state at `velocity` (about the jig: one state for
    every airspeed, built once)."""
    if states.about == "jig" or velocity == 0:
        if states.rest_equations is None:
            system, evaluation = states.evaluation(0.0)
            aero = unsteady_aerodynamics(beam, system.layout, evaluation)
            states.rest_equations = _Reduced.of(beam, basis, aero)
        return states.rest_equations
    system, evaluation = states.evaluation(velocity)
    return _Reduced.of(beam, basis, unsteady_aerodynamics(beam, system.layout, evaluation))


def _extrapolate(history: list[tuple[float, np.ndarray]], velocity: float) -> np.ndarray:
    """The roots' start at `velocity`: the parabola (or line) through the last three (two)
    speeds' roots, extrapolated; a start below the real axis is taken as real."""
    if len(history) < 2:
        return history[-1][1].copy()
    speeds = [v for v, _ in history[-3:]]
    roots = [s for _, s in history[-3:]]
    guess = np.zeros_like(roots[-1])
    for i, (v_i, s_i) in enumerate(zip(speeds, roots, strict=True)):
        weight = 1.0
        for j, v_j in enumerate(speeds):
            if j != i:
                weight *= (velocity - v_j) / (v_i - v_j)
        guess = guess + weight * s_i
    return np.where(guess.imag < 0, guess.real + 0j, guess)


def _damping(roots: np.ndarray) -> np.ndarray:
    modulus = np.abs(roots)
    return np.where(modulus > 0, -roots.real / np.where(modulus > 0, modulus, 1.0), 0.0)


def _oscillating(roots: np.ndarray) -> np.ndarray:
    return roots.imag > _OSCILLATING * np.abs(roots)


def _onset(
    tracked: _Tracked,
    beam: Structure,
    basis: _Basis,
    states: _States,
    density: float,
    settings: FlutterOptions,
    semichord: float,
) -> tuple[FlutterOnset | None, int]:
    """The first crossing of an oscillating root to growth, located by the secant method."""
    scale = float(basis.vacuum.min())
    # From the first airspeed on: in still air every root is undamped, Re(s) = 0 to round-off.
    for i in range(2, len(tracked.grid)):
        before, after = tracked.roots[i - 1], tracked.roots[i]
        if before is None or after is None:
            continue  # no equilibrium at one of them: nothing to bracket
        crossing = (before.real <= 0) & (after.real > 0) & _oscillating(after)
        if not np.any(crossing):
            continue
        modes = np.flatnonzero(crossing)
        low, high = float(tracked.grid[i - 1]), float(tracked.grid[i])
        located = [
            _locate(
                int(mode), low, high, before, after, beam, basis, states, density, settings, scale
            )
            for mode in modes
        ]
        velocity, root, mode, _ = min(located, key=lambda item: item[0])
        q = 0.5 * density * velocity * velocity
        frequency = float(root.imag)
        onset = FlutterOnset(velocity, q, frequency, frequency * semichord / velocity, int(mode))
        return onset, sum(item[3] for item in located)
    return None, 0


def _locate(
    mode: int,
    low: float,
    high: float,
    before: np.ndarray,
    after: np.ndarray,
    beam: Structure,
    basis: _Basis,
    states: _States,
    density: float,
    settings: FlutterOptions,
    scale: float,
) -> tuple[float, complex, int, int]:
    """(speed, root, mode, iterations) where `mode`'s root crosses Re(s) = 0 in [low, high]:
    the Illinois variant of the secant method (bracketing, superlinear), following that root
    alone."""
    f_low, f_high = float(before[mode].real), float(after[mode].real)
    s_low, s_high = before[mode : mode + 1], after[mode : mode + 1]
    iterations = 0
    velocity, root = high, after[mode]
    side = 0
    for _ in range(_SECANT_ITERATIONS):
        velocity = (low * f_high - high * f_low) / (f_high - f_low)
        weight = (velocity - low) / (high - low)
        guesses = s_low + (s_high - s_low) * weight
        reduced = _reduced_at(beam, basis, states, velocity)
        roots, spent = _track(reduced, guesses, velocity, density, settings, scale)
        iterations += spent
        root = roots[0]
        value = float(root.real)
        converged = abs(value) <= _SPEED_TOLERANCE * abs(root)
        if converged or abs(high - low) <= _SPEED_TOLERANCE * high:
            break
        if value > 0:
            high, f_high, s_high = velocity, value, roots
            if side == 1:
                f_low /= 2
            side = 1
        else:
            low, f_low, s_low = velocity, value, roots
            if side == -1:
                f_high /= 2
            side = -1
    return velocity, complex(root), mode, iterations


def _result(
    wing: Wing,
    beam: Structure,
    basis: _Basis,
    states: _States,
    speeds: np.ndarray,
    tracked: _Tracked,
    density: float,
    options: SolverOptions,
    settings: FlutterOptions,
    started: float,
) -> FlutterResult:
    semichord = wing.mean_chord / 2
    at = {float(v): i for i, v in enumerate(tracked.grid)}
    points: list[FlutterPoint] = []
    table: list[np.ndarray] = []
    for velocity in speeds:
        i = at[float(velocity)]
        roots = tracked.roots[i]
        q = 0.5 * density * float(velocity) ** 2
        if roots is None:
            points.append(
                FlutterPoint(
                    float(velocity),
                    q,
                    "no_equilibrium",
                    None,
                    None,
                    None,
                    reason=tracked.reasons[i],
                )
            )
            table.append(np.full(basis.vacuum.shape, np.nan + 0j))
            continue
        frequency = np.where(_oscillating(roots), roots.imag, 0.0)
        points.append(
            FlutterPoint(
                float(velocity),
                q,
                "solved",
                frequency,
                _damping(roots),
                frequency * semichord / float(velocity),
                divergence_rate=tracked.divergence_rates[i],
            )
        )
        table.append(roots)
    onset, spent = _onset(tracked, beam, basis, states, density, settings, semichord)
    if states.about == "jig":
        states.divergence = _linear_onset(basis, density, float(speeds.max()))
    modes = [
        mode_shape(beam, basis.right[:, i], float(basis.vacuum[i]))
        for i in range(basis.vacuum.size)
    ]
    solved = any(point.status == "solved" for point in points)
    no_flutter = None if onset is not None or not solved else _no_flutter(points, speeds)
    status: Literal["flutter", "no_flutter_in_range", "no_equilibrium"] = (
        "flutter" if onset is not None else "no_flutter_in_range" if solved else "no_equilibrium"
    )
    return FlutterResult(
        status=status,
        flutter=onset,
        no_flutter=no_flutter,
        divergence=states.divergence,
        modes=modes,
        static_correction=basis.condensed,
        points=points,
        y=wing.y,
        about=states.about,
        aerodynamics=options.aerodynamics,
        unsteady=settings.unsteady,
        reference_semichord=semichord,
        solver=FlutterInfo(tracked.iterations + spent, time.perf_counter() - started),
        roots=np.array(table),
    )


def _linear_onset(basis: _Basis, density: float, largest: float) -> DivergenceOnset | None:
    q = basis.divergence_pressure
    if q is None:
        return None
    velocity = FlightCondition.velocity_for(q, density)
    return DivergenceOnset(velocity, q, velocity <= largest, "linear")


def _no_flutter(points: list[FlutterPoint], speeds: np.ndarray) -> NoFlutter:
    least, where, which = math.inf, float(speeds.min()), 0
    highest = float(speeds.min())
    for point in points:
        if point.damping is None or point.frequency is None:
            continue
        highest = max(highest, point.velocity)
        oscillating = point.frequency > 0
        if np.any(oscillating):
            damping = np.where(oscillating, point.damping, np.inf)
            mode = int(np.argmin(damping))
            if damping[mode] < least:
                least, where, which = float(damping[mode]), point.velocity, mode
    return NoFlutter(float(speeds.min()), highest, least, where, which)
