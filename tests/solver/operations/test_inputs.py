"""solver.operations: one input type per operation, holding everything its answer depends on.

- `run()` answers what the plain function answers for the same arguments (solve,
  airspeed_sweep, optimize), options and guess included.
- `key` is the input's canonical identity: equal inputs built apart have equal keys, a change
  of any value changes it, and a sweep's airspeeds given as a list or as a range are one sweep.
- What cannot be asked is refused where the input is built, naming the field: a solve without
  an airspeed, a starting deformation for a trimmed flight, sizing a spar the wing has not.

Every answer here is compared with the plain function's to 1e-12 relative: the same computation
twice (the solver promises the same bits, tests/solver/test_solve.py; the margin only spares a
round-off-level difference from warm starts, while a dropped option or guess changes the answer
at 1e-3 or more)."""

from __future__ import annotations

import functools
from typing import Any

import numpy as np
import pytest

import solver
from solver.controls.antisymmetric import without_aileron_deflections
from tests import study

SAME = 1e-12  # relative, see the module docstring
K2 = solver.SolverOptions(chordwise_panels=2)  # not the default: a dropped option shows


def _close(ours: Any, theirs: Any) -> bool:
    ours, theirs = np.atleast_1d(ours), np.atleast_1d(theirs)
    return bool(np.max(np.abs(ours - theirs)) <= SAME * max(np.max(np.abs(theirs)), 1e-300))


@functools.cache
def _small_wing() -> solver.Wing:
    """The study's wing on 12 stations: a solve takes milliseconds once its model is built."""
    return study.study_wing(n=12)


# ------------------------------------------------------------------------------- run()


def test_a_solve_input_answers_what_solve_answers_with_its_options() -> None:
    wing, flight = _small_wing(), study.flight(10.0)
    ran = solver.SolveInput(wing, flight, options=K2).run()
    plain = solver.solve(wing, flight, options=K2)
    assert _close(ran.state, plain.state)
    assert ran.options.chordwise_panels == 2
    default = solver.solve(wing, flight)
    assert not np.isclose(ran.totals.lift, default.totals.lift, rtol=1e-4)  # options matter


def test_a_solve_input_answers_what_solve_answers_from_its_guess() -> None:
    """A guess 70 deg nose-down on a wing of GJ = 1 N m^2 past its divergence (the bistable wing
    of tests/study.py on 10 stations) reaches another equilibrium than the jig branch's,
    flagged `other`: only a guess passed on leads there."""
    y = np.linspace(0, 5, 10)
    wing = solver.Wing.create(y, 1.438 * (1 - 0.877 * y / 5), 0.4, 1.232e6, 1.0)
    velocity = solver.FlightCondition.velocity_for(0.519, 1.0)
    flight = solver.FlightCondition(velocity, 5.0, 1.0)
    guess = solver.InitialGuess(heave=(0.0,) * 10, twist=tuple(np.linspace(0, -70, 10)))
    ran = solver.SolveInput(wing, flight, initial_guess=guess).run()
    plain = solver.solve(wing, flight, guess)
    assert ran.stability.branch == plain.stability.branch == "other"
    assert ran.totals.tip_twist < -10  # nose-down
    assert _close(ran.state, plain.state)


@pytest.mark.parametrize(
    "velocities",
    [(6.0, 12.0, 18.0), solver.VelocityRange(start=6.0, stop=18.0, count=3)],
    ids=["list", "range"],
)
def test_a_sweep_input_answers_what_airspeed_sweep_answers(velocities: Any) -> None:
    wing = _small_wing()
    flight = solver.FlightCondition(None, 5.0, study.DENSITY)
    ran = solver.SweepInput(wing, flight, velocities, options=K2).run()
    plain = solver.airspeed_sweep(wing, [6.0, 12.0, 18.0], flight, K2)
    assert [p.velocity for p in ran.points] == [6.0, 12.0, 18.0]
    for ours, theirs in zip(ran.points, plain.points, strict=True):
        assert ours.status == theirs.status == "equilibrium"
        assert ours.equilibrium is not None and theirs.equilibrium is not None
        assert _close(ours.equilibrium.state, theirs.equilibrium.state)


def test_an_optimize_input_answers_what_optimize_answers() -> None:
    wing = _small_wing()
    problem = solver.DesignProblem(
        solver.DesignCondition(12.0, lift=100.0),
        solver.Design(solver.TwistDesign(control_points=4)),
        objective="trefftz_drag",
    )
    ran = solver.OptimizeInput(wing, problem).run()
    plain = solver.optimize(wing, problem)
    assert _close(ran.jig_twist, plain.jig_twist)
    assert ran.objective == "trefftz_drag"
    assert ran.equilibrium.totals.lift == pytest.approx(100.0, rel=1e-8)


SURFACES = (
    {"name": "flap", "start": 0.0, "end": 0.45, "hinge": 0.75, "deflection": 4.0},
    {"name": "aileron", "start": 0.55, "end": 0.95, "hinge": 0.75, "deflection": 3.0,
     "kind": "aileron"},
)  # fmt: skip
K3 = solver.SolverOptions(chordwise_panels=3)  # the aftmost hinge 3 panels carry: 0.75


@functools.cache
def _surfaced_wing() -> solver.Wing:
    return solver.Wing.create(**study.study_arrays(12), control_surfaces=SURFACES)


@pytest.mark.parametrize(
    ("flight", "free_roll"),
    [(study.flight(12.0), False), (solver.FlightCondition(12.0, lift=200.0), True)],
    ids=["at-alpha", "trimmed-free-roll"],
)
def test_a_roll_input_answers_what_roll_answers(
    flight: solver.FlightCondition, free_roll: bool
) -> None:
    ran = solver.RollInput(_surfaced_wing(), flight, free_roll=free_roll, options=K3).run()
    if flight.alpha is None:  # trimmed: about the equilibrium that carries the lift
        flight = solver.solve(_surfaced_wing(), flight, options=K3).flight
    plain = solver.roll(_surfaced_wing(), flight, K3, roll_rate=None if free_roll else 0.0)
    assert _close(ran.rolling_moment, plain.rolling_moment) or abs(plain.rolling_moment) < 1e-9
    assert _close(ran.roll_rate, plain.roll_rate)
    assert _close(ran.right.twist, plain.right.twist)


def test_a_controls_input_answers_what_control_sweep_answers() -> None:
    velocities = (8.0, 14.0, 19.0)
    flight = solver.FlightCondition(None, alpha=2.0, density=study.DENSITY)
    ran = solver.ControlsInput(_surfaced_wing(), flight, velocities, options=K3).run()
    plain = solver.control_sweep(_surfaced_wing(), velocities, 2.0, study.DENSITY, K3)
    for ours, theirs in zip(ran.points, plain.points, strict=True):
        assert [c.derivative for c in ours.controls] == pytest.approx(
            [c.derivative for c in theirs.controls], rel=SAME
        )
    for ours, theirs in zip(ran.reversals, plain.reversals, strict=True):
        assert (ours.name, ours.first) == (theirs.name, theirs.first)
        assert ours.reversal.velocity == pytest.approx(theirs.reversal.velocity, rel=SAME)


def test_a_trimmed_control_sweep_is_at_each_airspeeds_trimmed_alpha() -> None:
    """Trimmed, each airspeed's effectiveness is the one at the alpha that carries the lift."""
    lift = 200.0
    flight = solver.FlightCondition(None, lift=lift, density=study.DENSITY)
    ran = solver.ControlsInput(_surfaced_wing(), flight, (10.0, 16.0), options=K3).run()
    for point in ran.points:
        trimmed = solver.solve(
            without_aileron_deflections(_surfaced_wing()),
            solver.FlightCondition(point.velocity, lift=lift, density=study.DENSITY),
            options=K3,
        )
        assert trimmed.totals.lift == pytest.approx(lift, rel=1e-8)
        at_alpha = solver.control_effectiveness(_surfaced_wing(), trimmed.flight, K3)
        assert [c.derivative for c in point.controls] == pytest.approx(
            [c.derivative for c in at_alpha], rel=1e-9
        )


@pytest.mark.parametrize(
    ("build", "field"),
    [
        (
            lambda: solver.RollInput(study.study_wing(12), study.flight(12.0)),
            "wing.control_surfaces",
        ),
        (
            lambda: solver.RollInput(_surfaced_wing(), study.flight(12.0)),
            "wing.control_surfaces[0].hinge",
        ),
        (
            lambda: solver.RollInput(
                _surfaced_wing(), study.flight(12.0), roll_rate=0.1, free_roll=True, options=K3
            ),
            "roll_rate",
        ),
        (
            lambda: solver.RollInput(
                _surfaced_wing(), solver.FlightCondition(None, alpha=5.0), options=K3
            ),
            "flight.velocity",
        ),
        (
            lambda: solver.ControlsInput(
                study.study_wing(12), solver.FlightCondition(None, 5.0), (10.0,)
            ),
            "wing.control_surfaces",
        ),
        (
            lambda: solver.SolveInput(_surfaced_wing(), study.flight(12.0)),
            "wing.control_surfaces[0].hinge",
        ),
    ],
    ids=[
        "roll-without-surfaces",
        "hinge-the-default-mesh-cannot-carry",
        "a-free-roll-with-a-rate",
        "roll-without-airspeed",
        "controls-without-surfaces",
        "a-solve-whose-flap-the-mesh-cannot-carry",
    ],
)
def test_what_cannot_be_asked_of_the_controls_is_refused_naming_the_field(
    build: Any, field: str
) -> None:
    with pytest.raises(solver.InvalidInput) as refused:
        build()
    assert refused.value.field == field


def test_the_registry_names_each_input_type() -> None:
    assert {
        "solve": solver.SolveInput,
        "sweep": solver.SweepInput,
        "optimize": solver.OptimizeInput,
        "flutter": solver.FlutterInput,
        "roll": solver.RollInput,
        "controls": solver.ControlsInput,
        "loads": solver.LoadsInput,
        "gust": solver.GustInput,
    } == solver.OPERATIONS


# --------------------------------------------------------------------------------- key


def _solve_input(velocity: float = 10.0, alpha: float = 5.0, **options: Any) -> solver.SolveInput:
    """Built afresh each time: new arrays, new objects, the same values."""
    wing = solver.Wing.create(**study.study_arrays())
    flight = solver.FlightCondition(velocity, alpha, study.DENSITY)
    return solver.SolveInput(wing, flight, options=solver.SolverOptions(**options))


def test_equal_inputs_built_apart_have_equal_keys() -> None:
    first, second = _solve_input(), _solve_input()
    assert first.wing is not second.wing
    assert first.key == second.key
    assert len(first.key) == 16  # a 128-bit digest


def test_a_signed_zero_is_the_same_input() -> None:
    assert _solve_input(alpha=0.0).key == _solve_input(alpha=-0.0).key


CHANGES = {
    "velocity": lambda: _solve_input(velocity=10.000000001),
    "alpha": lambda: _solve_input(alpha=4.0),
    "an option": lambda: _solve_input(chordwise_panels=2),
    "a stiffness": lambda: solver.SolveInput(
        study.study_wing(stiffness_scale=1.0 + 1e-12), study.flight(10.0)
    ),
    "a guess": lambda: solver.SolveInput(
        study.study_wing(),
        study.flight(10.0),
        initial_guess=solver.InitialGuess(heave=(0.0,) * 30, twist=(0.0,) * 30),
    ),
}


@pytest.mark.parametrize("change", list(CHANGES.values()), ids=list(CHANGES))
def test_any_change_of_a_value_is_another_input(change: Any) -> None:
    assert change().key != _solve_input().key


def test_no_options_are_modelled_as_the_default_options() -> None:
    wing, flight = study.study_wing(), study.flight(10.0)
    given = solver.SolveInput(wing, flight, options=solver.SolverOptions())
    none = solver.SolveInput(wing, flight)
    assert none.modelled == given.modelled == solver.SolverOptions()


@functools.cache
def _massive_wing() -> solver.Wing:
    return solver.Wing.create(
        **study.study_arrays(12), mass=solver.MassModel.create(12, 0.75, 0.5, 0.1)
    )


def test_no_flutter_options_and_the_default_ones_are_one_question() -> None:
    build = DEFAULTS_GIVEN["flutter"]
    assert build().key == build(flutter=solver.FlutterOptions()).key
    assert build().key != build(flutter=solver.FlutterOptions(about="jig")).key


def _design() -> solver.DesignProblem:
    return solver.DesignProblem(
        solver.DesignCondition(12.0, lift=100.0), solver.Design(solver.TwistDesign(4))
    )


# Each operation's input with no options, and with those it then runs with, written out.
DEFAULTS_GIVEN = {
    "solve": lambda **o: solver.SolveInput(_small_wing(), study.flight(10.0), **o),
    "sweep": lambda **o: solver.SweepInput(
        _small_wing(), solver.FlightCondition(None, alpha=5.0), (8.0, 10.0), **o
    ),
    "optimize": lambda **o: solver.OptimizeInput(_small_wing(), _design(), **o),
    "flutter": lambda **o: solver.FlutterInput(
        _massive_wing(), solver.FlightCondition(None, alpha=2.0), (20.0, 40.0), **o
    ),
}  # roll and controls: a control surface needs more chordwise panels than the default's one


@pytest.mark.parametrize("build", list(DEFAULTS_GIVEN.values()), ids=list(DEFAULTS_GIVEN))
def test_no_options_and_the_default_options_are_one_question(build: Any) -> None:
    """Answered alike (`modelled`), so cached alike: a client that sends `options: {}` and one
    that sends none share one answer."""
    none, given = build(), build(options=solver.SolverOptions())
    assert none.key == given.key
    assert build(options=K2).key != none.key  # an option that is not the default still counts


def _sweep(velocities: Any, **flight: Any) -> solver.SweepInput:
    condition = solver.FlightCondition(None, **({"alpha": 5.0} | flight))
    return solver.SweepInput(study.study_wing(), condition, velocities)


SAME_SWEEPS = {
    "list and range": ([6.0, 8.0, 10.0], solver.VelocityRange(start=6.0, stop=10.0, count=3)),
    "tuple and list": ((6.0, 8.0, 10.0), [6.0, 8.0, 10.0]),
    "integers and floats": ([6, 8, 10], [6.0, 8.0, 10.0]),
    "one point": ([7.5], solver.VelocityRange(start=7.5, stop=99.0, count=1)),
}


@pytest.mark.parametrize(("one", "other"), list(SAME_SWEEPS.values()), ids=list(SAME_SWEEPS))
def test_the_same_airspeeds_however_given_are_one_sweep(one: Any, other: Any) -> None:
    first, second = _sweep(one), _sweep(other)
    assert first.airspeeds == second.airspeeds
    assert first.key == second.key


@pytest.mark.parametrize(
    ("one", "other"),
    [
        ([6.0, 8.0, 10.0], [10.0, 8.0, 6.0]),
        ([6.0, 8.0, 10.0], solver.VelocityRange(start=6.0, stop=10.0, count=4)),
    ],
    ids=["another-order", "another-count"],
)
def test_other_airspeeds_are_another_sweep(one: Any, other: Any) -> None:
    """Answered in request order: the order is part of the question."""
    assert _sweep(one).key != _sweep(other).key


# ----------------------------------------------------------------------------- refusals


def _trimmed_with_guess() -> object:
    flight = solver.FlightCondition(10.0, weight=300.0, density=study.DENSITY)
    guess = solver.InitialGuess(heave=(0.0,) * 30, twist=(0.0,) * 30)
    return solver.SolveInput(study.study_wing(), flight, initial_guess=guess)


def _sizing_without_a_spar() -> object:
    problem = solver.DesignProblem(
        solver.DesignCondition(12.0, lift=300.0),
        solver.Design(wall_thickness=solver.WallDesign()),
    )
    return solver.OptimizeInput(study.study_wing(), problem)


REFUSED = {
    "a solve without velocity": (
        lambda: solver.SolveInput(study.study_wing(), solver.FlightCondition(None, 5.0)),
        "flight.velocity",
    ),
    "a guess with a trimmed flight": (_trimmed_with_guess, "initial_guess"),
    "a guess of another mesh": (
        lambda: solver.SolveInput(
            study.study_wing(),
            study.flight(10.0),
            initial_guess=solver.InitialGuess(heave=(0.0,) * 29, twist=(0.0,) * 30),
        ),
        "initial_guess.heave",
    ),
    "sizing without a spar": (_sizing_without_a_spar, "design.wall_thickness"),
    "a sweep without airspeeds": (lambda: _sweep(()), "velocities"),
    "a sweep past mach 3": (lambda: _sweep([10.0, 1001.0]), "velocities[1]"),
}


@pytest.mark.parametrize(("build", "field"), list(REFUSED.values()), ids=list(REFUSED))
def test_what_cannot_be_asked_is_refused_naming_the_field(build: Any, field: str) -> None:
    with pytest.raises(solver.InvalidInput) as raised:
        build()
    assert raised.value.field == field
    assert raised.value.reason
