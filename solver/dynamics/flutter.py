"""Flutter: damping and frequency of every mode against airspeed, by the p-k method.

The equations of motion of small oscillations w e^{st} about a state of the static model are
(`solver.dynamics.modes`, `solver.dynamics.reduced`)

    (s^2 M + K - f(s)) w = 0,

f(s) the aerodynamic loads of the model `options.aerodynamics` names:

- "strip": Theodorsen's strip theory (`solver.dynamics.unsteady`), each strip's circulation
  lagged by C(k) of its own reduced frequency k = omega b / V;
- "lattice": the lattice's steady 3D circulation, lagged strip by strip likewise (quasi-3D);
- "unsteady_lattice": the unsteady vortex lattice (`solver.dynamics.lattice_loads`): the wake
  shed and convected, the loads of the same panels as the statics', tabulated at
  `FlutterOptions.reduced_frequencies` reduced frequencies up to
  `FlutterOptions.max_reduced_frequency` and interpolated (as Nastran's MKAERO1).

The p-k method (Hassig, J. Aircraft 8(11), 1971; `solver.dynamics.pk`) finds, for each mode and
airspeed, the root s for which the loads are evaluated at its own frequency.

Degrees of freedom: the lowest natural modes (`FlutterOptions.modes`, six by default; the
Goland wing's flutter speed moves by 5e-7 with every mode) and, when the wing can diverge, the
part of the unloaded wing's static divergence shape outside them, condensed statically (it
follows the modes as the stiffness says, `solver.dynamics.reduced.condense`). With it the
equations keep the full model's static divergence exactly: at s = 0 they are K w = q Q w, and
its solution at the divergence pressure lies in the basis. One root is followed per mode, from
its frequency in still air (V = 0) up the airspeeds, in steps no larger than a fortieth of the
largest one, each step's p-k started from the roots extrapolated from the last three.

- Flutter: the first airspeed at which an oscillating root's damping crosses from positive to
  negative, located between the sweep's speeds by the Illinois secant method on Re(s)
  (`solver.dynamics.onset`).
- Divergence: the real roots of the zero-frequency equations (no lag: a non-oscillating motion)
  are computed at each airspeed too (`FlutterPoint.divergence_rate`); the largest crosses zero
  where the wing diverges. About the jig that is the static linear divergence under the same
  aerodynamics (the number reported); about a loaded equilibrium the static model's fold (at
  an angle of attack) or trimmed stability limit (at a lift).

About the jig the state is the unloaded wing at rest; "about an equilibrium" (`alpha` or `lift`)
the state at each airspeed is the static equilibrium there (`solver.dynamics.linearisation`),
its tangent aerodynamic stiffness included: the loaded wing's flutter.
"""

from __future__ import annotations

import math
import time
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Literal

import numpy as np

from solver.dynamics.lattice_loads import lattice_loads
from solver.dynamics.linearisation import Build, States
from solver.dynamics.modes import Structure, mode_shape, structure
from solver.dynamics.onset import Tracked, flutter_onset, linear_onset, no_flutter
from solver.dynamics.pk import Follower, Tracking, damping, oscillating
from solver.dynamics.reduced import (
    Basis,
    LatticeEquations,
    TheodorsenEquations,
    reduced_frequency_nodes,
)
from solver.dynamics.unsteady import unsteady_aerodynamics
from solver.errors import InvalidInput, SolverError, numerical_failures_as
from solver.fields import integer, is_number, number, parameter, specs
from solver.inputs.flight import dynamic_pressure
from solver.inputs.mass import MassModel
from solver.inputs.options import SolverOptions, check_lag
from solver.inputs.wing import Wing
from solver.model.lag_beam import bent_station_load_rows, bent_strip_load_rows
from solver.numerics.evaluation import Evaluation
from solver.results.flutter import FlutterInfo, FlutterPoint, FlutterResult
from solver.results.quantities import Progress
from solver.statics.jig import at_rest, linear_pressure
from solver.statics.system import CoupledSystem
from solver.unsteady_lattice.panels import panels
from solver.unsteady_lattice.wake import shed_wake

__all__ = ["FlutterOptions", "flutter"]

# The lowest natural modes in the basis by default: the Goland wing's flutter speed moves by
# 5e-7 from six to all 22 of an N = 12 mesh (tests/solver/test_flutter.py).
_DEFAULT_MODES = 6
# About a loaded equilibrium with lag: the bent wing's torsion and lag couple into modes that
# need the jig's second lag mode (the HALE wing's tenth, 202 rad/s; bent by 8 % of its span its
# flutter speed is 27.03 m/s on six modes, 31.06 on eight, 25.95 on ten, 25.93 on twelve, 25.91
# on eighteen; bent by 11 %, none found on six). Not enough where the lag modes lie far above
# the others: the Pazy wing's twelve hold one lag mode, and its hump flutter needs 36 of its 45
# modes (its outer part swings fore and aft as it twists: docs/accuracy.md, Lag bending).
_DEFAULT_MODES_BENT_LAG = 12
# The tracking steps: at most this fraction of the largest airspeed each.
_STEPS = 40
# A divergence shape inside the natural modes' span to this fraction needs no basis vector.
_INSIDE_SPAN = 1e-9
# What `FlutterResult.aerodynamic_model` calls each `options.aerodynamics`.
_MODELS: dict[str, Literal["strip_theory", "quasi_3d_lattice", "unsteady_lattice"]] = {
    "strip": "strip_theory",
    "lattice": "quasi_3d_lattice",
    "unsteady_lattice": "unsteady_lattice",
}


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
        "comes on top, condensed); null: six (twelve about a loaded equilibrium of a wing "
        "with lag bending), or all of a mesh with fewer. A wing bent far with lag swings its "
        "outer part fore and aft as it twists, which takes its higher in-plane modes: the Pazy "
        "wing's hump needs 36 of its 45",
        ge=1,
        le=100,
        why="at least one mode; at most the mesh's 2 (N - 1), 3 (N - 1) with lag",
        form="integer",
        default=None,
    )
    unsteady: Literal["theodorsen", "quasi_steady"] = parameter(
        "",
        "the circulation's lag: theodorsen (C(k); with the unsteady lattice, its own wake's "
        "lag) or quasi_steady (C = 1, no wake lag: the loads of zero frequency)",
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
    max_reduced_frequency: float = parameter(
        "-",
        "unsteady lattice only: the largest reduced frequency k = omega b / V (b: half the "
        "mean chord) at which its aerodynamic matrices are computed; between 0 and it they are "
        "interpolated, beyond it towards their infinite-frequency limit (default 2: flutter "
        "of wings sits at k of 0.05 to 1)",
        gt=0.0,
        le=10.0,
        why="a flutter analysis's reduced frequencies; past 10 a lattice of at most 8 "
        "chordwise panels resolves no wave on the chord",
        default=2.0,
    )
    reduced_frequencies: int = parameter(
        "-",
        "unsteady lattice only: how many reduced frequencies from 0 to max_reduced_frequency "
        "its aerodynamic matrices are computed at (each one solve of the lattice), closer "
        "together at low k",
        ge=4,
        le=40,
        why="a cubic interpolation needs four; forty resolve any wing's loads",
        form="integer",
        default=12,
    )
    structural_damping: float = parameter(
        "-",
        "the structure's own damping, each natural mode's ratio zeta to critical (viscous "
        "modal damping 2 zeta omega m on the basis's modes, Nastran's TABDMP1 CRIT; the V-g "
        "method's g is 2 zeta); 0: none, as the published flutter cases take it. A mode that "
        "nothing else damps (in-plane bending: the model has no profile drag) needs some",
        ge=0.0,
        le=0.2,
        why="built-up and composite wings measure 0.5 to 5 % of critical; none 20 %",
        default=0.0,
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
    load_factor: float | None = None,
) -> FlutterResult:
    """Damping and frequency of every mode of `wing` with `mass` at each airspeed [m/s] (the
    V-g and V-f diagrams) at `density` [kg/m^3], the flutter and divergence speeds.

    Linearised about the unloaded jig, or, given `alpha` [deg] or `lift` [N], about the static
    equilibrium at each airspeed at that angle of attack or trimmed to that lift. `options`
    chooses the aerodynamics ("strip": Theodorsen's strip theory; "lattice", the default: the
    lattice's steady circulation with Theodorsen's lag; "unsteady_lattice": the unsteady
    vortex lattice), `flutter_options` the basis and the lag. `progress(done, total)` is called
    after each requested airspeed. About a loaded equilibrium the wing's own mass weighs
    `load_factor` g against the lift (`solver.FlightCondition`: trimmed, None is 1 g; at a given
    alpha, None is none, and a load factor a dead weight at every airspeed, each airspeed's
    equilibrium solved on its own: a wind-tunnel model's gravity).

    Raises `InvalidInput` without a mass model or for invalid inputs; `ConvergenceError` when a
    root cannot be followed. Airspeeds beyond a loaded wing's fold have no roots
    (status "no_equilibrium")."""
    started = time.perf_counter()
    options = options or SolverOptions()
    check_lag(wing.in_plane_bending_stiffness, options, "")
    settings = flutter_options or FlutterOptions()
    speeds = _check(wing, velocities, density, alpha, lift)
    beam = structure(wing, mass, in_plane_bending_stiffness=wing.in_plane_bending_stiffness)
    bent_lag = wing.in_plane_bending_stiffness is not None and (alpha, lift) != (None, None)
    default = _DEFAULT_MODES_BENT_LAG if bent_lag else _DEFAULT_MODES
    count = min(default, beam.n_dof) if settings.modes is None else settings.modes
    if count > beam.n_dof:
        raise InvalidInput("flutter.modes", f"must be at most {beam.n_dof} on this mesh")
    states = States(wing, density, alpha, lift, options, load_factor)
    with numerical_failures_as(float(speeds[0])):
        basis, build = _model(beam, states, options, settings, count, mass)
        grid = _grid(speeds)
        states.prepare(grid, float(speeds.max()))
        tracked = _follow(basis, states, build, grid, speeds, density, settings, progress)
        return _result(
            wing, beam, basis, states, build, speeds, tracked, density, options, settings, started
        )


def _model(
    beam: Structure,
    states: States,
    options: SolverOptions,
    settings: FlutterOptions,
    count: int,
    mass: MassModel | None = None,
) -> tuple[Basis, Build]:
    """The basis and how the equations on it are built about a state, for the aerodynamics
    `options` names (module docstring)."""
    rest = at_rest(states.rest).evaluation
    layout = states.rest.layout
    q_div = linear_pressure(states.rest)
    if options.aerodynamics != "unsteady_lattice":
        aerodynamic = unsteady_aerodynamics(beam, layout, rest).stiffness()
        basis = _basis(beam, aerodynamic, q_div, count, settings.structural_damping)

        def theodorsen(
            system: CoupledSystem, evaluation: Evaluation, state: np.ndarray
        ) -> TheodorsenEquations:
            about = _tangent(beam, mass, system, evaluation, state)
            aero = unsteady_aerodynamics(about, system.layout, evaluation)
            return TheodorsenEquations.of(about, basis, aero)

        return basis, theodorsen
    jig = panels(states.wing, layout.chordwise)
    aerodynamic = lattice_loads(beam, layout, rest, jig).stiffness()
    basis = _basis(beam, aerodynamic, q_div, count, settings.structural_damping)
    semichord = states.wing.mean_chord / 2
    nodes = reduced_frequency_nodes(settings.max_reduced_frequency, settings.reduced_frequencies)
    wake = shed_wake(jig, nodes / semichord)

    def lattice(
        system: CoupledSystem, evaluation: Evaluation, state: np.ndarray
    ) -> LatticeEquations:
        about = _tangent(beam, mass, system, evaluation, state)
        loads = lattice_loads(about, system.layout, evaluation, jig)
        return LatticeEquations.of(about, basis, loads, wake, semichord)

    return basis, lattice


def _tangent(
    beam: Structure,
    mass: MassModel | None,
    system: CoupledSystem,
    evaluation: Evaluation,
    state: np.ndarray,
) -> Structure:
    """The structure linearised about `state` (n_unknowns,), whose exact Jacobians
    `evaluation` holds: under the geometrically exact beam its tangent there (J0's structure
    rows: the bent wing's heave kinematics, its stiffness and the states of the degrees of
    freedom; the mass and the rows' loads are the linear beam's, except with lag, where the
    strip loads act on the bent wing, `solver.model.lag_beam.bent_strip_load_rows`, and a lag
    rotation pitches a bent section, `solver.dynamics.modes.structure`), else `beam`, the
    linear beam's, the same about every state."""
    layout = system.layout
    if not layout.exact:
        return beam
    rows = evaluation.jacobian0[layout.structure_rows, layout.structure]
    if not layout.lag:
        return structure(beam.wing, mass, rows=rows)
    beta, phi, psi = state[layout.slope], state[layout.twist], state[layout.lag_rotation]
    return structure(
        beam.wing,
        mass,
        rows=rows,
        in_plane_bending_stiffness=beam.wing.in_plane_bending_stiffness,
        strip_load_rows=bent_strip_load_rows(beam.wing, beta, phi, psi),
        flap_rotation=beta,
        station_load_rows=bent_station_load_rows(beam.wing, beta, phi, psi),
    )


def _basis(
    beam: Structure,
    aerodynamic: np.ndarray,
    q_div: float | None,
    count: int,
    structural_damping: float = 0.0,
) -> Basis:
    """The lowest `count` modes and, with a divergence pressure, the divergence shape's part
    outside them (`solver.dynamics.modes.Structure.modes`: left.T M right = I); `aerodynamic`
    (n, n) the unloaded wing's aerodynamic stiffness per unit q; `structural_damping` zeta [-]
    of every mode."""
    omega2, right, left = beam.modes
    right, left = right[:, :count], left[:, :count]
    vacuum = np.sqrt(omega2[:count])
    zeta = structural_damping
    if q_div is None:
        return Basis(right, left, vacuum, None, False, zeta)
    operator = beam.stiffness - q_div * aerodynamic
    u, _, vt = np.linalg.svd(operator)
    shape, left_shape = vt[-1], u[:, -1]
    remainder = shape - right @ (left.T @ beam.mass @ shape)
    if np.linalg.norm(remainder) <= _INSIDE_SPAN * np.linalg.norm(shape):
        return Basis(right, left, vacuum, q_div, False, zeta)
    left_remainder = left_shape - left @ (right.T @ beam.mass.T @ left_shape)
    generalised = left_remainder @ beam.stiffness @ remainder
    return Basis(
        np.column_stack([right, remainder]),
        np.column_stack([left, left_remainder / generalised]),
        vacuum,
        q_div,
        True,
        zeta,
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


def _tracking(settings: FlutterOptions) -> Tracking:
    return Tracking(settings.unsteady == "theodorsen", settings.tolerance, settings.max_iterations)


def _follow(
    basis: Basis,
    states: States,
    build: Build,
    grid: np.ndarray,
    speeds: np.ndarray,
    density: float,
    settings: FlutterOptions,
    progress: Progress | None,
) -> Tracked:
    """Every root from still air up the grid. About a loaded equilibrium the unloaded wing's
    roots are followed alongside: where the loaded roots start (after speeds without an
    equilibrium: a lift too large to carry slowly, a fold) they start from the unloaded ones,
    the equations blended from unloaded to loaded (`solver.dynamics.pk.Follower`)."""
    requested = set(speeds.tolist())
    total, done = len(requested), 0
    roots: list[np.ndarray | None] = []
    reasons: list[str | None] = []
    scale = float(basis.vacuum.min())
    rates: list[float | None] = []
    tracking = _tracking(settings)
    rest = states.equations(0.0, build)
    follow = Follower(rest, density, tracking, scale)
    unloaded = Follower(rest, density, tracking, scale)
    loaded_started = False
    for velocity in (float(v) for v in grid):
        reason, rate = None, None
        try:
            if states.about == "jig":
                current: np.ndarray | None = follow.step(rest, velocity)
                rate = rest.divergence_rate(velocity, density)
            else:
                unloaded.step(rest, velocity)
                loaded = states.equations(velocity, build)
                if velocity > 0 and not loaded_started:
                    # The loaded roots start from the unloaded ones through blended equations,
                    # not from still air: a load can move a root far at once (a bent wing's
                    # torsion couples with its lag: the HALE wing's, 31 rad/s straight, is 17
                    # bent by 12 % of its span).
                    follow.history.clear()
                    loaded_started = True
                current = follow.step(loaded, velocity, start=unloaded)
                rate = loaded.divergence_rate(velocity, density)
        except SolverError as error:
            current, reason = None, str(error)
            if states.about != "jig":
                follow.history.clear()  # restart from the unloaded wing's roots
        roots.append(current)
        reasons.append(reason)
        rates.append(rate)
        if velocity in requested:
            done += 1
            if progress is not None:
                progress(done, total)
    return Tracked(grid, roots, reasons, follow.solves + unloaded.solves, rates)


def _result(
    wing: Wing,
    beam: Structure,
    basis: Basis,
    states: States,
    build: Build,
    speeds: np.ndarray,
    tracked: Tracked,
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
        q = dynamic_pressure(density, float(velocity))
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
        frequency = np.where(oscillating(roots), roots.imag, 0.0)
        points.append(
            FlutterPoint(
                float(velocity),
                q,
                "solved",
                frequency,
                damping(roots),
                frequency * semichord / float(velocity),
                divergence_rate=tracked.divergence_rates[i],
            )
        )
        table.append(roots)
    tracking = _tracking(settings)
    onset, spent = flutter_onset(tracked, basis, states, build, density, tracking, semichord)
    if states.about == "jig":
        states.divergence = linear_onset(basis, density, float(speeds.max()))
    modes = [
        mode_shape(beam, basis.right[:, i], float(basis.vacuum[i]))
        for i in range(basis.vacuum.size)
    ]
    solved = any(point.status == "solved" for point in points)
    searched = None if onset is not None or not solved else no_flutter(points, speeds)
    status: Literal["flutter", "no_flutter_in_range", "no_equilibrium"] = (
        "flutter" if onset is not None else "no_flutter_in_range" if solved else "no_equilibrium"
    )
    return FlutterResult(
        status=status,
        flutter=onset,
        no_flutter=searched,
        divergence=states.divergence,
        modes=modes,
        static_correction=basis.condensed,
        points=points,
        y=wing.y,
        about=states.about,
        aerodynamics="strip" if options.aerodynamics == "strip" else "lattice",
        aerodynamic_model=_MODELS[options.aerodynamics],
        unsteady=settings.unsteady,
        reference_semichord=semichord,
        solver=FlutterInfo(tracked.iterations + spent, time.perf_counter() - started),
        roots=np.array(table),
    )
