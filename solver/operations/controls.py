"""The control surfaces' questions: the roll response (`RollInput`), and control
effectiveness and reversal over airspeeds (`ControlsInput`)."""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from typing import Literal

from solver import fields
from solver.controls.effectiveness import control_sweep
from solver.controls.roll import roll
from solver.errors import InvalidInput
from solver.fields import parameter
from solver.inputs.flight import FLIGHT_RULE, FlightCondition, VelocityRange, check_over_airspeeds
from solver.inputs.options import SolverOptions, check_lag, require_flow_model
from solver.inputs.wing import Wing, require_control_surfaces
from solver.operations.common import airspeeds_of, check_airspeeds, check_meshed, identity
from solver.results.controls import ControlSweep, RollResponse
from solver.results.quantities import Progress

__all__ = ["ControlsInput", "RollInput"]


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
        check_meshed(self.wing, self.options)
        check_lag(self.wing.in_plane_bending_stiffness, self.options, "")
        if self.flight.velocity is None:
            raise InvalidInput("flight.velocity", "is required: the airspeed to roll at")
        require_control_surfaces(self.wing, "the roll response is the ailerons'")
        require_flow_model(self.modelled.aerodynamics)
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
        return identity(self, options=self.modelled)

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
        without=FlightCondition.AIRSPEEDS,
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
        check_meshed(self.wing, self.options)
        check_lag(self.wing.in_plane_bending_stiffness, self.options, "")
        require_control_surfaces(self.wing, "effectiveness is a control surface's")
        require_flow_model(self.modelled.aerodynamics)
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
            load_factor=self.flight.load_factor,
            progress=progress,
        )
