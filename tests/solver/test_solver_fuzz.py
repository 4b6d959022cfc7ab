"""Solver fuzzing: random but valid wings, speeds below and beyond divergence.

Every generated case must end in one of the solver's documented outcomes:

- an `Equilibrium`: every reported number finite, the residual within the tolerance, the root
  clamped, statically stable and on the branch from the jig, the stability flag consistent with
  the margin (stable exactly when q is below the local divergence pressure);
- a `NoEquilibrium` naming a fold below the requested speed (or no fold: the branch's
  equilibrium is unstable there);
- a `ConvergenceError` (the branch could not be followed to the requested speed).

Anything else escaping the solver (ValueError, IndexError, ...) is a defect, and so is a call
that does not return within `HANG_SECONDS` (a generous guard against true hangs, not a timing
requirement: solves here take milliseconds to a few seconds).

Wings and flights come from tests/strategies.py: N = 3..40 stations, semispan 0.3..30 m, taper
0.1..1, elastic axis at 5..70 % chord, EI and GJ over six decades each with a decade of scatter
between stations, alpha -15..15 deg, and airspeeds 0.05 to 2.5 times the linear divergence speed
(1..500 m/s for wings that never diverge).

Models are built without C compilation (CasADi's virtual machine, FLEXWING_COMPILE=0): forty
mesh sizes would otherwise start forty background gcc runs in this process.

Profiles: HYPOTHESIS_PROFILE=ci (default, bounded, derandomized) or nightly (tests/conftest.py);
the long run with figures is benchmarks/solver_fuzz_benchmark.py.
"""

from __future__ import annotations

import contextlib
import math
import signal
from collections.abc import Callable, Iterator
from typing import TypeVar

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import solver
from solver import (
    ConvergenceError,
    Equilibrium,
    FlightCondition,
    NoEquilibrium,
    SolverError,
    SolverOptions,
)
from tests.conftest import fuzz_examples
from tests.strategies import alphas, densities, ratios, speed_for, wings
from tests.study import study_wing

# Run with the live-server tests, after the fast loop: hundreds of random wings on the VM.
pytestmark = pytest.mark.server

HANG_SECONDS = 120.0
OPTIONS = SolverOptions()
# Reported arrays over stations and panels, and scalars, that must be finite.
STATION_FIELDS = ("heave", "slope", "twist", "shear", "bending_moment", "torque")
PANEL_FIELDS = ("y", "lift", "lift_per_span", "torque")
TOTAL_FIELDS = (
    "lift",
    "induced_drag",
    "CL",
    "CDi",
    "reference_area",
    "deformed_area",
    "rigid_lift",
)

T = TypeVar("T")


@pytest.fixture(scope="module", autouse=True)
def _virtual_machine_only() -> Iterator[None]:
    with pytest.MonkeyPatch.context() as patch:
        patch.setenv("FLEXWING_COMPILE", "0")
        yield


# ------------------------------------------------------------------------------- contract


class Hang(Exception):
    """A solver call ran past HANG_SECONDS."""


@contextlib.contextmanager
def hang_guard(seconds: float = HANG_SECONDS) -> Iterator[None]:
    """Interrupt the (main-thread) call inside after `seconds` of wall-clock time."""

    def on_alarm(signum: int, frame: object) -> None:
        raise Hang(f"no outcome within {seconds:g} s")

    previous = signal.signal(signal.SIGALRM, on_alarm)
    signal.setitimer(signal.ITIMER_REAL, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0.0)
        signal.signal(signal.SIGALRM, previous)


def outcome(call: Callable[[], T]) -> T | SolverError:
    """The call's result or its typed solver error; any other exception is a defect."""
    try:
        with hang_guard():
            return call()
    except SolverError as error:
        return error
    except Hang:
        raise
    except Exception as error:
        raise AssertionError(
            f"untyped {type(error).__name__} escaped the solver: {error}"
        ) from error


def check_equilibrium(eq: Equilibrium, flight: FlightCondition) -> None:
    n = eq.wing.n_stations
    for name in STATION_FIELDS:
        values = getattr(eq.stations, name)
        assert values.shape == (n,), name
        assert np.all(np.isfinite(values)), f"{name} has non-finite values: {values}"
    for name in PANEL_FIELDS:
        values = getattr(eq.panels, name)
        assert values.shape == (n - 1,), name
        assert np.all(np.isfinite(values)), f"{name} has non-finite values: {values}"
    for name in TOTAL_FIELDS:
        assert math.isfinite(getattr(eq.totals, name)), f"{name} = {getattr(eq.totals, name)}"
    amplification = eq.totals.lift_amplification
    assert amplification is None or math.isfinite(amplification)
    assert math.isfinite(eq.solver.residual_norm)
    assert eq.flight == flight.at_alpha(eq.flight.alpha) and eq.flight.alpha == flight.alpha
    assert eq.solver.residual_norm <= OPTIONS.tolerance
    # The root clamps are residual rows: they hold to the tolerance.
    s = eq.stations
    assert abs(s.heave[0]) <= OPTIONS.tolerance
    assert abs(s.slope[0]) <= OPTIONS.tolerance
    assert abs(s.twist[0]) <= OPTIONS.tolerance
    # Every answer without an initial guess is the jig branch's, and stable.
    assert eq.stability.branch == "jig" and eq.stability.stable
    check_stability(eq)


def check_stability(eq: Equilibrium) -> None:
    s = eq.stability
    q = eq.dynamic_pressure
    assert math.isfinite(s.margin) and s.margin >= 0
    if s.local_divergence_pressure is None:
        assert s.stable and s.margin == 0
    else:
        assert math.isfinite(s.local_divergence_pressure) and s.local_divergence_pressure > 0
        assert s.stable == (s.local_divergence_pressure > q)
        assert s.margin == pytest.approx(q / s.local_divergence_pressure, rel=1e-12)
        # The flag and the margin agree (away from the round-off band at margin = 1).
        if abs(s.margin - 1) > 1e-12:
            assert s.stable == (s.margin < 1)
    if s.divergence_dynamic_pressure is None:
        assert s.divergence_velocity is None
    else:
        assert math.isfinite(s.divergence_dynamic_pressure) and s.divergence_dynamic_pressure > 0
        assert s.divergence_velocity is not None and math.isfinite(s.divergence_velocity)


def check_error(error: SolverError, velocity: float) -> None:
    assert isinstance(error, NoEquilibrium | ConvergenceError), type(error)
    assert error.velocity == velocity
    if isinstance(error, NoEquilibrium):
        fold = error.fold_velocity
        # Beyond the fold: below the requested speed, or equal to it within round-off (a
        # request exactly at a bifurcation, alpha = 0 and V = the linear divergence speed).
        assert fold is None or (math.isfinite(fold) and 0 < fold <= velocity * (1 + 1e-12)), fold
    else:
        assert error.reason


def check(result: Equilibrium | SolverError, flight: FlightCondition) -> None:
    if isinstance(result, Equilibrium):
        check_equilibrium(result, flight)
    else:
        check_error(result, flight.velocity)


# --------------------------------------------------------------------------------- tests


@settings(max_examples=fuzz_examples(100))
@given(case=wings(), alpha=alphas, ratio=ratios, density=densities)
def test_a_cold_solve_ends_in_a_documented_outcome(case, alpha, ratio, density):
    flight = FlightCondition(speed_for(case.wing, ratio, density), alpha, density)
    check(outcome(lambda: solver.solve(case.wing, flight, options=OPTIONS)), flight)


@settings(max_examples=fuzz_examples(40))
@given(case=wings(), alpha=alphas, ratio=ratios, hint_ratio=ratios)
def test_a_hint_never_changes_the_answer(case, alpha, ratio, hint_ratio):
    """`solve(..., hint=)` from another answer of the same wing gives the cold solve's answer:
    the same outcome, and the same equilibrium. Two roots within the residual tolerance differ
    by the tolerance times the problem's condition number: up to ~2e-6 relative for the softest
    wings generated (EI = 10 N m^2 over 10 m), so "the same" is 1e-4 relative here, with 1e-6
    deg / 1e-9 m floors for near-rigid wings. Only a cold ConvergenceError (the path could not be
    followed that far) may become an answer from a closer start."""
    density = solver.ISA_SEA_LEVEL_DENSITY
    flight = FlightCondition(speed_for(case.wing, ratio, density), alpha, density)
    hint = outcome(
        lambda: solver.solve(
            case.wing, flight.at_velocity(speed_for(case.wing, hint_ratio, density))
        )
    )
    if not isinstance(hint, Equilibrium):
        return
    cold = outcome(lambda: solver.solve(case.wing, flight, options=OPTIONS))
    hinted = outcome(lambda: solver.solve(case.wing, flight, options=OPTIONS, hint=hint))
    check(hinted, flight)
    if isinstance(cold, ConvergenceError):
        return
    assert type(hinted) is type(cold), (cold, hinted)
    if isinstance(cold, Equilibrium):
        np.testing.assert_allclose(hinted.stations.twist, cold.stations.twist, rtol=1e-4, atol=1e-6)
        np.testing.assert_allclose(hinted.stations.heave, cold.stations.heave, rtol=1e-4, atol=1e-9)
    if isinstance(cold, NoEquilibrium):
        assert hinted.fold_velocity == cold.fold_velocity


@settings(max_examples=fuzz_examples(20))
@given(
    case=wings(max_stations=30),
    alpha=alphas,
    speeds=st.lists(ratios, min_size=1, max_size=6),
)
def test_a_sweep_answers_every_speed_in_order(case, alpha, speeds):
    density = solver.ISA_SEA_LEVEL_DENSITY
    velocities = [speed_for(case.wing, ratio, density) for ratio in speeds]
    result = outcome(
        lambda: solver.airspeed_sweep(
            case.wing, velocities, solver.FlightCondition(None, alpha, density), OPTIONS
        )
    )
    assert not isinstance(result, SolverError), f"sweep raised {result!r}"
    assert [point.velocity for point in result.points] == velocities
    for point in result.points:
        flight = FlightCondition(point.velocity, alpha, density)
        assert (point.equilibrium is None) != (point.error is None)
        check(point.equilibrium if point.equilibrium is not None else point.error, flight)
    divergence = result.divergence
    for value in (
        divergence.linear.dynamic_pressure,
        divergence.linear.velocity,
        divergence.fold.velocity,
        divergence.fold.dynamic_pressure,
    ):
        assert value is None or (math.isfinite(value) and value > 0), divergence
    # The fit may extrapolate to a negative q (documented, with a reason), never to NaN.
    fit = divergence.fit
    assert fit.dynamic_pressure is None or math.isfinite(fit.dynamic_pressure), fit
    assert math.isfinite(divergence.fold.searched_to_velocity)


# ------------------------------------------------------------------ cases found by fuzzing
# Each is kept where its outcome is robust to a 1e-12 relative change of its inputs; the ones on
# hints and on stability moved to tests/solver/test_solve.py and test_stability.py.


@pytest.mark.parametrize("velocity", [5.0, 30.0, 300.0], ids=["5mps", "30mps", "300mps"])
def test_a_soft_wing_that_never_diverges_linearly_gets_a_typed_answer(velocity):
    """Found by fuzzing before commit 8c26d18: the fold search of this wing (elastic axis ahead
    of the quarter chord, so no linear divergence, GJ = 0.1 N m^2) stepped to negative q and
    `solve` raised ValueError('math domain error') at 30 m/s. Its branch folds at 3.75 m/s."""
    wing = solver.Wing.create([0.0, 5.0, 10.0], [0.25] * 3, 0.2, 20.0, 0.1)
    flight = FlightCondition(velocity=velocity, alpha=1.0)
    result = outcome(lambda: solver.solve(wing, flight))
    check(result, flight)
    assert isinstance(result, NoEquilibrium)
    assert result.fold_velocity == pytest.approx(3.753, abs=1e-3)


def _never_diverging_in_practice() -> solver.Wing:
    """Found by fuzzing: N = 7, linear taper, elastic axis scattered about the quarter chord;
    its divergence pressure is round-off (1.5e18 Pa, 1.76e9 m/s at 1 kg/m^3, before round-off
    was filtered)."""
    y = np.linspace(0, 1, 7)
    chord = 1.7782794100389228 * (1 - 0.875 * y)
    elastic_axis = [0.25, 0.25, 0.125, 0.125, 0.25, 0.125, 0.5]
    return solver.Wing.create(y, chord, elastic_axis, 10.0, 1.0)


def test_the_fastest_airspeed_gets_a_typed_answer_and_leaves_the_wing_solvable():
    """Found by fuzzing before commit 43ab74b: at 1.76e9 m/s the branch's 'fold' was traced at
    q = -2.8e6 Pa, solve() raised ValueError('math domain error'), and the cached branch made
    every later solve of this wing and alpha raise it too (500 through the API). Such a speed
    is refused as input now; the fastest accepted gets a documented answer, and after it the
    wing solves as before."""
    wing = _never_diverging_in_practice()
    with pytest.raises(solver.InvalidInput):
        FlightCondition(velocity=1.7584768587e9, alpha=1.0, density=1.0)
    fastest = FlightCondition(velocity=1000.0, alpha=1.0, density=1.0)
    check(outcome(lambda: solver.solve(wing, fastest)), fastest)
    usual = FlightCondition(velocity=6.0, alpha=1.0, density=1.0)
    result = outcome(lambda: solver.solve(wing, usual))
    check(result, usual)
    assert isinstance(result, Equilibrium) and result.stability.stable


@pytest.mark.parametrize("alpha", [1e-12, 1e-300], ids=["1e-12_deg", "1e-300_deg"])
def test_a_cold_solve_past_divergence_at_a_tiny_alpha_is_no_equilibrium(alpha):
    """Found by fuzzing before commit 43ab74b: at alpha = 1e-12 deg a cold solve past the
    linear divergence speed returned the unloaded jig flagged unstable, where alpha = 0 and
    alpha = 1e-6 got NoEquilibrium."""
    flight = FlightCondition(velocity=25.0, alpha=alpha, density=1.225)
    result = outcome(lambda: solver.solve(study_wing(), flight))
    check(result, flight)
    assert isinstance(result, NoEquilibrium)
