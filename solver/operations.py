"""What the solver can be asked, one input type per operation: each holds everything its answer
depends on, declared once (`solver.fields`), and `run()` answers it.

These are the web service's request bodies too (`app.schemas` derives them), and what its
workers run, so a request changes form once, into one of these, between the route and the
answer. Each one's `key` is its canonical identity (equal inputs, equal keys; no options and
the default options are equal), which the service's result cache keys by.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from dataclasses import dataclass
from functools import cached_property
from typing import Literal

from solver import fields
from solver.controls.effectiveness import control_sweep
from solver.controls.roll import roll
from solver.dynamics.flutter import FlutterOptions, flutter
from solver.errors import InvalidInput
from solver.fields import parameter
from solver.inputs.control_surfaces import check_resolution
from solver.inputs.design import DesignProblem
from solver.inputs.flight import FLIGHT_RULE, FlightCondition, VelocityRange
from solver.inputs.options import InitialGuess, SolverOptions
from solver.inputs.wing import Wing
from solver.model.geometry import chordwise_nodes
from solver.optimization.optimize import optimize
from solver.results.controls import ControlSweep, RollResponse
from solver.results.design import OptimalDesign
from solver.results.equilibrium import Equilibrium
from solver.results.flutter import FlutterResult
from solver.results.quantities import Progress
from solver.results.sweep import AirspeedSweep
from solver.statics.airspeed_sweep import airspeed_sweep
from solver.statics.solve import solve

__all__ = [
    "OPERATIONS",
    "ControlsInput",
    "FlutterInput",
    "OptimizeInput",
    "RollInput",
    "SolveInput",
    "SweepInput",
]


def _identity(operation: object, **in_force: object) -> bytes:
    """What an operation input's answers are cached by (`fields.digest`): its fields, those
    given as None by the values in force (`in_force`): no options and the default options
    are one question, answered once."""
    values = {f.name: getattr(operation, f.name) for f in dataclasses.fields(operation)}  # type: ignore[arg-type]
    return fields.digest((type(operation).__name__, values | in_force))


def _check_meshed(wing: Wing, options: SolverOptions | None) -> None:
    """Every control surface carried by the chordwise panels of `options`, refused before the
    work starts (naming `wing.control_surfaces[i].hinge`)."""
    if wing.control_surfaces:
        k = (options or SolverOptions()).chordwise_panels
        with fields.prefixed("wing"):
            check_resolution(wing.control_surfaces, chordwise_nodes(k))


def _check_airspeeds(velocities: tuple[float, ...] | VelocityRange) -> None:
    """Each listed airspeed within a flight condition's, at least one."""
    if isinstance(velocities, VelocityRange):
        return
    spec = fields.spec_of(FlightCondition, "velocity")
    for index, velocity in enumerate(velocities):
        fields.number(f"velocities[{index}]", velocity, spec)
    if not velocities:
        raise InvalidInput("velocities", "needs at least one airspeed")


def _airspeeds(velocities: tuple[float, ...] | VelocityRange) -> tuple[float, ...]:
    """[m/s] the airspeeds a list or a range gives, in order."""
    if isinstance(velocities, VelocityRange):
        return velocities.velocities()
    return tuple(float(v) for v in velocities)


@dataclass(frozen=True, eq=False)
class SolveInput:
    """One wing at one flight condition."""

    wing: Wing = parameter("", "the wing", form="nested", given=Wing)
    flight: FlightCondition = parameter(
        "", f"the flight condition: {FLIGHT_RULE}", form="nested", given=FlightCondition
    )
    initial_guess: InitialGuess | None = parameter(
        "",
        "optional starting deformation for Newton",
        form="nested",
        given=InitialGuess,
        default=None,
    )
    options: SolverOptions | None = parameter(
        "", "optional solver options", form="nested", given=SolverOptions, default=None
    )

    def __post_init__(self) -> None:
        _check_meshed(self.wing, self.options)
        if self.flight.velocity is None:
            raise InvalidInput("flight.velocity", "is required: the airspeed to solve at")
        if self.initial_guess is not None and self.flight.trimmed:
            raise InvalidInput(
                "initial_guess",
                "a starting deformation is for flight at a given alpha; a trimmed solve starts "
                "from the rigid jig trimmed to the same lift",
            )
        if self.initial_guess is not None:
            with fields.prefixed("initial_guess"):
                self.initial_guess.state(self.wing.n_stations, self.modelled.chordwise_panels)

    @property
    def modelled(self) -> SolverOptions:
        """The options in force (the defaults where none are given)."""
        return self.options or SolverOptions()

    @cached_property
    def key(self) -> bytes:
        return _identity(self, options=self.modelled)

    def run(self, progress: Progress | None = None) -> Equilibrium:
        """The answer (`progress` is for the operations that have parts: none here)."""
        return solve(self.wing, self.flight, self.initial_guess, self.modelled)


@dataclass(frozen=True, eq=False)
class SweepInput:
    """One wing over several airspeeds; every point is the equilibrium on the branch from the
    jig shape at that airspeed, whatever the order."""

    wing: Wing = parameter("", "the wing", form="nested", given=Wing)
    flight: FlightCondition = parameter(
        "",
        f"the flight condition at every airspeed: {FLIGHT_RULE}",
        form="nested",
        given=FlightCondition,
        without=("velocity",),
    )
    velocities: tuple[float, ...] | VelocityRange = parameter(
        "m/s",
        "airspeeds, each from 0.01 to 1000, answered in this order: a list (1 to "
        "FLEXWING_MAX_SWEEP_POINTS values, default 50) or {start, stop, count}",
        form="velocities",
        given=VelocityRange,
        example=[6.0, 10.0, 12.0, 15.0, 18.0, 20.0],
    )
    options: SolverOptions | None = parameter(
        "", "optional solver options", form="nested", given=SolverOptions, default=None
    )

    def __post_init__(self) -> None:
        _check_meshed(self.wing, self.options)
        _check_airspeeds(self.velocities)

    @property
    def airspeeds(self) -> tuple[float, ...]:
        """[m/s] the airspeeds, in request order."""
        return _airspeeds(self.velocities)

    @property
    def modelled(self) -> SolverOptions:
        return self.options or SolverOptions()

    @cached_property
    def key(self) -> bytes:
        """The same airspeeds given as a list or as a range are one sweep."""
        return fields.digest((self.wing, self.flight, self.airspeeds, self.modelled))

    def run(self, progress: Progress | None = None) -> AirspeedSweep:
        """The answer; `progress(done, total)` as each airspeed is answered."""
        return airspeed_sweep(self.wing, self.airspeeds, self.flight, self.modelled, progress)


@dataclass(frozen=True, eq=False)
class OptimizeInput:
    """A design problem: the jig twist (and spar wall) of the wing that flies."""

    wing: Wing = parameter("", "the wing", form="nested", given=Wing)
    problem: DesignProblem = parameter(
        "", "the design problem", form="nested", given=DesignProblem, flatten=True
    )
    options: SolverOptions | None = parameter(
        "", "optional solver options", form="nested", given=SolverOptions, default=None
    )

    def __post_init__(self) -> None:
        _check_meshed(self.wing, self.options)
        if self.problem.size_spar and self.wing.spar is None:
            raise InvalidInput("design.wall_thickness", "the wing has no spar to size")

    @property
    def modelled(self) -> SolverOptions:
        return self.options or SolverOptions()

    @cached_property
    def key(self) -> bytes:
        return _identity(self, options=self.modelled)

    def run(self, progress: Progress | None = None) -> OptimalDesign:
        """The answer (`progress` is for the operations that have parts: none here)."""
        return optimize(self.wing, self.problem, self.modelled)


@dataclass(frozen=True, eq=False)
class FlutterInput:
    """The wing's vibration modes and its flutter: damping and frequency of every mode at each
    airspeed (the V-g and V-f diagrams), linearised about the static equilibrium of `flight`
    at each airspeed, or about the unloaded jig (`flutter.about`)."""

    wing: Wing = parameter("", "the wing, with its mass", form="nested", given=Wing)
    flight: FlightCondition = parameter(
        "",
        f"the flight condition at every airspeed: {FLIGHT_RULE}; its density is the air's in "
        "the unsteady loads, its alpha or lift the equilibrium linearised about",
        form="nested",
        given=FlightCondition,
        without=("velocity",),
    )
    velocities: tuple[float, ...] | VelocityRange = parameter(
        "m/s",
        "airspeeds, each from 0.01 to 1000, answered in this order: a list (1 to "
        "FLEXWING_MAX_SWEEP_POINTS values, default 50) or {start, stop, count}; the flutter and "
        "divergence speeds are located between them",
        form="velocities",
        given=VelocityRange,
        example=[20.0, 60.0, 100.0, 140.0, 180.0],
    )
    options: SolverOptions | None = parameter(
        "", "optional solver options", form="nested", given=SolverOptions, default=None
    )
    flutter: FlutterOptions | None = parameter(
        "",
        "optional flutter options (the state linearised about, the basis, the lag)",
        form="nested",
        given=FlutterOptions,
        default=None,
    )

    def __post_init__(self) -> None:
        _check_meshed(self.wing, self.options)
        if self.wing.mass is None:
            raise InvalidInput(
                "wing.mass",
                "is required for vibration and flutter: mass per unit length, centre of "
                "gravity and inertia per station",
            )
        _check_airspeeds(self.velocities)

    @property
    def airspeeds(self) -> tuple[float, ...]:
        """[m/s] the airspeeds, in request order."""
        return _airspeeds(self.velocities)

    @property
    def modelled(self) -> SolverOptions:
        return self.options or SolverOptions()

    @cached_property
    def key(self) -> bytes:
        return fields.digest(
            (
                self.wing,
                self.flight,
                self.airspeeds,
                self.modelled,
                self.flutter or FlutterOptions(),
            )
        )

    def run(self, progress: Progress | None = None) -> FlutterResult:
        """The answer; `progress(done, total)` as each airspeed is analysed."""
        settings = self.flutter or FlutterOptions()
        loaded = settings.about == "equilibrium"
        return flutter(
            self.wing,
            None,
            self.airspeeds,
            self.flight.density,
            alpha=self.flight.alpha if loaded else None,
            lift=self.flight.required_lift if loaded else None,
            options=self.modelled,
            flutter_options=settings,
            progress=progress,
        )


def _needs_control_surfaces(wing: Wing, what: str) -> None:
    if not wing.control_surfaces:
        raise InvalidInput("wing.control_surfaces", f"needs at least one surface: {what}")


@dataclass(frozen=True, eq=False)
class RollInput:
    """The wing's antisymmetric response to its ailerons (and a steady roll rate) at one flight
    condition: both halves, the rolling moment, the hinge moments, or the free-roll rate."""

    wing: Wing = parameter("", "the wing, with its ailerons", form="nested", given=Wing)
    flight: FlightCondition = parameter(
        "",
        f"the flight condition: {FLIGHT_RULE}; trimmed, the ailerons act about the trimmed "
        "symmetric equilibrium (the wing with its ailerons neutral carrying the lift)",
        form="nested",
        given=FlightCondition,
    )
    roll_rate: float = parameter(
        "rad/s",
        "steady roll rate p about the x axis through the root chord, positive raising the "
        "right wing (the helix angle p y / V adds antisymmetric incidence)",
        ge=-20.0,
        le=20.0,
        why="about 1,150 deg/s: past any aircraft's",
        default=0.0,
    )
    free_roll: bool = parameter(
        "",
        "solve for the roll rate at which the rolling moment vanishes (the free roll, pb/2V) "
        "instead of giving roll_rate",
        form="flag",
        default=False,
    )
    method: Literal["auto", "antisymmetric", "linearised"] = parameter(
        "",
        "auto: the exact antisymmetric equilibrium where it applies (alpha 0, sections "
        "symmetric in z, no jig twist, no flap deflected), else linearised about the symmetric "
        "equilibrium; antisymmetric (refused where it does not apply); linearised",
        form="choice",
        choices=("auto", "antisymmetric", "linearised"),
        default="auto",
    )
    options: SolverOptions | None = parameter(
        "", "optional solver options", form="nested", given=SolverOptions, default=None
    )

    def __post_init__(self) -> None:
        _check_meshed(self.wing, self.options)
        if self.flight.velocity is None:
            raise InvalidInput("flight.velocity", "is required: the airspeed to roll at")
        _needs_control_surfaces(self.wing, "the roll response is the ailerons'")
        if not any(not surface.symmetric for surface in self.wing.control_surfaces) and (
            self.roll_rate == 0.0 and not self.free_roll
        ):
            raise InvalidInput(
                "wing.control_surfaces",
                "has no aileron and the roll rate is 0: nothing rolls the wing",
            )
        if self.free_roll and self.roll_rate != 0.0:
            raise InvalidInput(
                "roll_rate", "is solved for in a free roll: give roll_rate or free_roll, not both"
            )

    @property
    def modelled(self) -> SolverOptions:
        return self.options or SolverOptions()

    @cached_property
    def key(self) -> bytes:
        return _identity(self, options=self.modelled)

    def run(self, progress: Progress | None = None) -> RollResponse:
        """The answer (`progress` is for the operations that have parts: none here)."""
        try:
            return roll(
                self.wing,
                self.flight,
                self.modelled,
                roll_rate=None if self.free_roll else self.roll_rate,
                method=self.method,
            )
        except InvalidInput as error:
            if self.free_roll and error.field == "roll_rate":  # the rate it solves for
                raise InvalidInput("free_roll", error.reason) from None
            raise


@dataclass(frozen=True, eq=False)
class ControlsInput:
    """Control effectiveness and reversal: every control surface's rigid and elastic control
    derivative, their ratio and its hinge moment at each airspeed, each surface's reversal
    speed (an eigenvalue of the exact Jacobians, cross-checked by the sweep's zero crossing)
    and which comes first, reversal or divergence."""

    wing: Wing = parameter("", "the wing, with its control surfaces", form="nested", given=Wing)
    flight: FlightCondition = parameter(
        "",
        f"the flight condition at every airspeed: {FLIGHT_RULE}; trimmed, each airspeed at "
        "the alpha at which the wing (ailerons neutral) carries the lift",
        form="nested",
        given=FlightCondition,
        without=("velocity",),
    )
    velocities: tuple[float, ...] | VelocityRange = parameter(
        "m/s",
        "airspeeds, each from 0.01 to 1000, answered in this order: a list (1 to "
        "FLEXWING_MAX_SWEEP_POINTS values, default 50) or {start, stop, count}",
        form="velocities",
        given=VelocityRange,
        example=[6.0, 10.0, 14.0, 18.0, 20.0],
    )
    options: SolverOptions | None = parameter(
        "", "optional solver options", form="nested", given=SolverOptions, default=None
    )

    def __post_init__(self) -> None:
        _check_meshed(self.wing, self.options)
        _needs_control_surfaces(self.wing, "effectiveness is a control surface's")
        _check_airspeeds(self.velocities)

    @property
    def airspeeds(self) -> tuple[float, ...]:
        """[m/s] the airspeeds, in request order."""
        return _airspeeds(self.velocities)

    @property
    def modelled(self) -> SolverOptions:
        return self.options or SolverOptions()

    @cached_property
    def key(self) -> bytes:
        return fields.digest((self.wing, self.flight, self.airspeeds, self.modelled))

    def run(self, progress: Progress | None = None) -> ControlSweep:
        """The answer; `progress(done, total)` as each airspeed is answered."""
        return control_sweep(
            self.wing,
            self.airspeeds,
            self.flight.alpha,
            self.flight.density,
            self.modelled,
            lift=self.flight.required_lift,
            progress=progress,
        )


# Operation name -> its input type; `run()` answers each.
OPERATIONS: dict[str, Callable[..., object]] = {
    "solve": SolveInput,
    "sweep": SweepInput,
    "optimize": OptimizeInput,
    "flutter": FlutterInput,
    "roll": RollInput,
    "controls": ControlsInput,
}
