"""The dynamic question: vibration modes and flutter over airspeeds (`FlutterInput`)."""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

from solver import fields
from solver.dynamics.flutter import FlutterOptions, flutter
from solver.fields import parameter
from solver.inputs.flight import FLIGHT_RULE, FlightCondition, VelocityRange
from solver.inputs.options import SolverOptions, check_lag
from solver.inputs.wing import Wing, require_mass
from solver.operations.common import airspeeds_of, check_airspeeds, check_meshed
from solver.results.flutter import FlutterResult
from solver.results.quantities import Progress

__all__ = ["FlutterInput"]

_VIBRATION = "vibration and flutter need it"


@dataclass(frozen=True, eq=False)
class FlutterInput:
    """The wing's vibration modes and its flutter: damping and frequency of every mode at each
    airspeed (the V-g and V-f diagrams), linearised about the static equilibrium of `flight`
    at each airspeed, or about the unloaded jig (`flutter.about`)."""

    wing: Wing = parameter("", "the wing, with its mass", form="nested", given=Wing)
    flight: FlightCondition = parameter(
        "",
        f"the flight condition at every airspeed: {FLIGHT_RULE}; its density is the air's in "
        "the unsteady loads, its alpha or lift the equilibrium linearised about (at an alpha "
        "a load_factor weighs the wing's mass as a dead load at every airspeed: a wind "
        "tunnel's gravity)",
        form="nested",
        given=FlightCondition,
        without=FlightCondition.AIRSPEEDS,
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
        check_meshed(self.wing, self.options)
        check_lag(self.wing.in_plane_bending_stiffness, self.options, "")
        require_mass(self.wing, _VIBRATION)
        check_airspeeds(self.velocities)

    @property
    def airspeeds(self) -> tuple[float, ...]:
        """[m/s] the airspeeds, in request order."""
        return airspeeds_of(self.velocities)

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

    @property
    def loaded(self) -> bool:
        """Linearised about the static equilibrium at each airspeed (not the jig)."""
        return (self.flutter or FlutterOptions()).about == "equilibrium"

    def run(self, progress: Progress | None = None) -> FlutterResult:
        """The answer; `progress(done, total)` as each airspeed is analysed."""
        settings = self.flutter or FlutterOptions()
        loaded = self.loaded
        return flutter(
            self.wing,
            None,
            self.airspeeds,
            self.flight.density,
            alpha=self.flight.alpha if loaded else None,
            lift=self.flight.required_lift if loaded else None,
            load_factor=self.flight.load_factor if loaded else None,
            options=self.modelled,
            flutter_options=settings,
            progress=progress,
        )
