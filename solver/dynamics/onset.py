"""Where a flutter analysis's roots cross: the flutter onset (an oscillating root's damping
from positive to negative), located between the sweep's airspeeds by the Illinois secant method
on Re(s); the unloaded wing's linear divergence; and, without flutter, the least damped mode.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from solver.dynamics.linearisation import Build, States
from solver.dynamics.pk import Tracking, oscillating, track
from solver.dynamics.reduced import Basis
from solver.inputs.flight import FlightCondition, dynamic_pressure
from solver.results.flutter import DivergenceOnset, FlutterOnset, FlutterPoint, NoFlutter

__all__ = ["Tracked", "flutter_onset", "linear_onset", "no_flutter"]

# The flutter speed is located to this relative tolerance.
_SPEED_TOLERANCE = 1e-10
_SECANT_ITERATIONS = 60
# A root grows when Re(s) exceeds this share of |s|: below it a root is neutral to round-off (a
# mode no air damps, as an in-plane bending mode about the unloaded wing: Re(s) ~2e-16 |s|, its
# sign the arithmetic's), so it never "crosses"; a real flutter's growth past its crossing is
# orders of magnitude above it (the p-k roots converge to 1e-10 of |s| by default).
_NEUTRAL = 1e-9
# A growing root counts as flutter only below this reduced frequency k = omega b / V (b: half
# the mean chord). Wings flutter at k of 0.05 to 1; past 5 the wake's wavelength 2 pi b / k is
# shorter than the chord, and the roots there are the mesh's highest modes, whose shapes turn
# sign from one strip to the next: no strip's or panel's loads describe them (about a bent wing
# with lag they grow by 1e-9 to 1e-4 of critical, docs/accuracy.md). They stay in the V-g.
_MAX_REDUCED_FREQUENCY = 5.0


@dataclass
class Tracked:
    """The roots along the grid: per grid speed, the roots (r,) or None past the equilibria,
    and why not."""

    grid: np.ndarray
    roots: list[np.ndarray | None]
    reasons: list[str | None]
    iterations: int
    divergence_rates: list[float | None]


def flutter_onset(
    tracked: Tracked,
    basis: Basis,
    states: States,
    build: Build,
    density: float,
    tracking: Tracking,
    semichord: float,
) -> tuple[FlutterOnset | None, int]:
    """The first crossing of an oscillating root to growth below the reduced frequency
    `_MAX_REDUCED_FREQUENCY` (`semichord` [m] its b), located by the secant method, and the
    solves it took."""
    scale = float(basis.vacuum.min())
    # From the first airspeed on: in still air every root is undamped, Re(s) = 0 to round-off.
    for i in range(2, len(tracked.grid)):
        before, after = tracked.roots[i - 1], tracked.roots[i]
        if before is None or after is None:
            continue  # no equilibrium at one of them: nothing to bracket
        resolved = np.abs(after.imag) * semichord <= _MAX_REDUCED_FREQUENCY * tracked.grid[i]
        crossing = (
            (before.real <= _NEUTRAL * np.abs(before))
            & (after.real > _NEUTRAL * np.abs(after))
            & oscillating(after)
            & resolved
        )
        if not np.any(crossing):
            continue
        modes = np.flatnonzero(crossing)
        low, high = float(tracked.grid[i - 1]), float(tracked.grid[i])
        located = [
            _locate(int(mode), low, high, before, after, states, build, density, tracking, scale)
            for mode in modes
        ]
        velocity, root, mode, _ = min(located, key=lambda item: item[0])
        q = dynamic_pressure(density, velocity)
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
    states: States,
    build: Build,
    density: float,
    tracking: Tracking,
    scale: float,
) -> tuple[float, complex, int, int]:
    """(speed, root, mode, iterations) where `mode`'s root crosses Re(s) = 0 in [low, high]:
    the Illinois variant of the secant method (bracketing, superlinear), following that root
    alone."""
    f_low, f_high = float(before[mode].real), float(after[mode].real)
    s_low, s_high = before[mode : mode + 1], after[mode : mode + 1]
    if f_low >= 0:  # neutral at `low` to round-off (`_NEUTRAL`): it starts to grow there
        return low, complex(before[mode]), mode, 0
    iterations = 0
    velocity, root = high, after[mode]
    side = 0
    for _ in range(_SECANT_ITERATIONS):
        velocity = (low * f_high - high * f_low) / (f_high - f_low)
        weight = (velocity - low) / (high - low)
        guesses = s_low + (s_high - s_low) * weight
        equations = states.equations(velocity, build)
        roots, spent = track(equations, guesses, velocity, density, tracking, scale)
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


def linear_onset(basis: Basis, density: float, largest: float) -> DivergenceOnset | None:
    """The unloaded wing's linear divergence (None: it cannot diverge)."""
    q = basis.divergence_pressure
    if q is None:
        return None
    velocity = FlightCondition.velocity_for(q, density)
    return DivergenceOnset(velocity, q, velocity <= largest, "linear")


def no_flutter(points: list[FlutterPoint], speeds: np.ndarray) -> NoFlutter:
    """What was searched, and the least damped oscillating root over it."""
    least, where, which = math.inf, float(speeds.min()), 0
    highest = float(speeds.min())
    for point in points:
        if point.damping is None or point.frequency is None:
            continue
        highest = max(highest, point.velocity)
        oscillates = point.frequency > 0
        if np.any(oscillates):
            damping = np.where(oscillates, point.damping, np.inf)
            mode = int(np.argmin(damping))
            if damping[mode] < least:
                least, where, which = float(damping[mode]), point.velocity, mode
    return NoFlutter(float(speeds.min()), highest, least, where, which)
