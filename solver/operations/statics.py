"""The static questions: one wing at one flight condition (`SolveInput`), and over airspeeds
(`SweepInput`)."""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

from solver import fields
from solver.errors import InvalidInput
from solver.fields import parameter
from solver.inputs.flight import FLIGHT_RULE, FlightCondition, VelocityRange, check_over_airspeeds
from solver.inputs.options import InitialGuess, SolverOptions, check_lag
from solver.inputs.wing import Wing
from solver.operations.common import airspeeds_of, check_airspeeds, check_meshed, identity
from solver.results.equilibrium import Equilibrium
from solver.results.quantities import Progress
from solver.results.sweep import AirspeedSweep
from solver.statics.airspeed_sweep import airspeed_sweep
from solver.statics.solve import solve

__all__ = ["SolveInput", "SweepInput"]


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
        check_meshed(self.wing, self.options)
        check_lag(self.wing.in_plane_bending_stiffness, self.options, "")
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
        return identity(self, options=self.modelled)

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
        without=FlightCondition.AIRSPEEDS,
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
        check_meshed(self.wing, self.options)
        check_lag(self.wing.in_plane_bending_stiffness, self.options, "")
        check_airspeeds(self.velocities)
        check_over_airspeeds(self.flight.alpha, self.flight.load_factor, self.wing.mass is not None)

    @property
    def airspeeds(self) -> tuple[float, ...]:
        """[m/s] the airspeeds, in request order."""
        return airspeeds_of(self.velocities)

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
