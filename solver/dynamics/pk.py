"""The p-k method: each mode's root at each airspeed, with the aerodynamic loads of its own
frequency (Hassig, J. Aircraft 8(11), 1971; Rodden and Johnson, MSC Nastran Aeroelastic
Analysis User's Guide, section 2.6).

With the loads of one frequency omega fixed, the equations of motion (`solver.dynamics.reduced`)
are a quadratic eigenvalue problem, solved exactly; a root s(omega) is the p-k root when
Im s(omega) = omega, a fixed point found by the secant method (`track`). Its damping
-Re(s) / |s| is exact where it matters, at zero (the flutter boundary, where the motion is
harmonic), and an approximation (with the loads of the root's frequency) elsewhere. A
`Follower` carries one root per mode up the airspeeds (continuation in V, p-k at each).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from solver.dynamics.reduced import OSCILLATING, Equations
from solver.errors import ConvergenceError

__all__ = [
    "Follower",
    "Tracking",
    "closest",
    "damping",
    "extrapolate",
    "oscillating",
    "still_air",
    "track",
]

# A restart from another follower's roots blends the equations in this many steps, a step
# halved (down to 1/_FINEST of the way) where two roots would otherwise fall on one, and
# doubled back after.
_BLEND_STEPS = 4
_FINEST = 1024
# The secant's slope d(Im s - omega)/d omega must fall below minus this to be used.
_FLAT = 0.01


@dataclass(frozen=True)
class Tracking:
    """How a root's fixed point is found: `lagged` (the loads of the root's frequency; else of
    zero frequency, one solve), to the relative `tolerance` in at most `max_iterations`."""

    lagged: bool
    tolerance: float
    max_iterations: int


def closest(candidates: np.ndarray, guesses: np.ndarray) -> np.ndarray:
    """(t,) for each row of candidates (t, 2r) the one closest to its guess in the upper
    half-plane. With the lag C(k) of a positive frequency the equations' coefficients are
    complex: only the upper roots belong to it (their conjugates would need the conjugate lag);
    a real root is real to round-off, and taken as real."""
    modulus = np.abs(candidates)
    upper = candidates.imag >= -OSCILLATING * modulus
    distance = np.where(upper, np.abs(candidates - guesses[:, None]), np.inf)
    chosen = candidates[np.arange(candidates.shape[0]), np.argmin(distance, axis=1)]
    return np.where(chosen.imag < 0, chosen.real + 0j, chosen)


def track(
    equations: Equations,
    guesses: np.ndarray,
    velocity: float,
    density: float,
    tracking: Tracking,
    scale: float,
) -> tuple[np.ndarray, int]:
    """The p-k roots (t,) at `velocity` from `guesses`, and the solves spent; raises
    `ConvergenceError` when a root's fixed point is not reached. `scale` [rad/s]: the
    frequency below which a root's change is measured absolutely.

    The fixed point is in the lag's frequency omega: a root s(omega) of the equations with
    the loads of omega is the p-k root when Im s(omega) = omega. It is found by the secant
    method on Im s(omega) - omega (a plain fixed-point iteration converges linearly, ~12 solves
    a root on the Goland wing; the secant ~4), each solve the exact quadratic eigenvalue
    problem."""
    lagged = tracking.lagged
    roots = guesses.copy()
    frequency = np.maximum(guesses.imag, 0.0)
    active = np.arange(roots.shape[0])
    previous: tuple[np.ndarray, np.ndarray] | None = None
    solves = 0
    for _ in range(tracking.max_iterations):
        candidates = equations.roots(frequency[active], velocity, density, lagged)
        found = closest(candidates, roots[active])
        solves += active.size
        roots[active] = found
        if not lagged:
            return roots, solves  # no lag: the first solve is the root
        mismatch = found.imag - frequency[active]
        done = np.abs(mismatch) <= tracking.tolerance * np.maximum(np.abs(found), scale)
        step = mismatch.copy()
        if previous is not None:
            last_frequency, last_mismatch = previous
            slope = (mismatch - last_mismatch) / (frequency[active] - last_frequency)
            # d mismatch / d omega is -1 where the loads change slowly with the frequency, near
            # 0 for a heavily damped root of low frequency (a plain fixed-point step crawls
            # there, ~0.9 of the mismatch left per step): the secant wherever it falls.
            usable = np.isfinite(slope) & (slope < -_FLAT)
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


def still_air(equations: Equations, density: float) -> np.ndarray:
    """(modes,) the roots at V = 0 (in still air, apparent mass only), one per natural mode:
    the i-th lowest frequency to the i-th mode."""
    roots = equations.roots(np.zeros(1), 0.0, density, False)[0]
    upper = roots[roots.imag > 0]
    return upper[np.argsort(upper.imag)]


class Follower:
    """One set of roots followed up the airspeeds (continuation in V, p-k at each)."""

    def __init__(self, rest: Equations, density: float, tracking: Tracking, scale: float):
        self.density, self.tracking, self.scale = density, tracking, scale
        self.history: list[tuple[float, np.ndarray]] = [(0.0, still_air(rest, density))]
        self.equations = rest
        self.solves = 0

    def step(
        self, equations: Equations, velocity: float, start: Follower | None = None
    ) -> np.ndarray:
        """The roots at `velocity` of `equations`: from this follower's last roots, or, when it
        has none (a restart), from `start`'s at this speed through blended equations."""
        if velocity == 0:
            return self.history[0][1]
        if self.history:
            guesses = extrapolate(self.history, velocity)
            roots = self._track(equations, guesses, velocity)
        else:
            assert start is not None and start.history
            base = start.history[-1]
            roots = self._blend(start.equations, equations, base[1], velocity)
        self.history.append((velocity, roots))
        del self.history[:-3]
        self.equations = equations
        return roots

    def _blend(
        self, before: Equations, after: Equations, roots: np.ndarray, velocity: float
    ) -> np.ndarray:
        """The roots of `after` at `velocity`, followed from `roots`, those of `before`, through
        the equations blended between them. A load can split a pair of near roots fast (the
        bent wing's torsion and lag) and move roots of other modes across each other: each
        root starts on the line through its last two, and a step on which two roots would
        become one is halved."""
        done, step = 0.0, 1.0 / _BLEND_STEPS
        rate = np.zeros_like(roots)  # d roots / d blend
        while done < 1.0:
            share = min(1.0, done + step)
            blended = before.blend(after, share)  # type: ignore[arg-type]
            found = self._track(blended, roots + rate * (share - done), velocity)
            if _merged(found, roots, self.scale) and step > 1.0 / _FINEST:
                step /= 2
                continue
            rate, roots, done = (found - roots) / (share - done), found, share
            step = min(2 * step, 1.0 / _BLEND_STEPS)
        return roots

    def _track(self, equations: Equations, guesses: np.ndarray, velocity: float) -> np.ndarray:
        roots, spent = track(equations, guesses, velocity, self.density, self.tracking, self.scale)
        self.solves += spent
        return roots


def _merged(found: np.ndarray, before: np.ndarray, scale: float) -> bool:
    """Whether two of the roots `found` are one (to 1e-6 of their size, or of `scale` [rad/s]
    below it) that were two `before`."""
    size = np.maximum(np.abs(found), scale)[:, None]
    same = np.abs(found[:, None] - found[None, :]) <= 1e-6 * size
    were = np.abs(before[:, None] - before[None, :]) <= 1e-6 * size
    return bool(np.any(same & ~were & ~np.eye(found.shape[0], dtype=bool)))


def extrapolate(history: list[tuple[float, np.ndarray]], velocity: float) -> np.ndarray:
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


def damping(roots: np.ndarray) -> np.ndarray:
    """The damping ratios -Re(s) / |s| of `roots` (0 for a zero root)."""
    modulus = np.abs(roots)
    return np.where(modulus > 0, -roots.real / np.where(modulus > 0, modulus, 1.0), 0.0)


def oscillating(roots: np.ndarray) -> np.ndarray:
    """Which of `roots` oscillate (a frequency beyond round-off of the modulus)."""
    return roots.imag > OSCILLATING * np.abs(roots)
