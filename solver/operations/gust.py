"""The gust question: the flexible wing's loads in the discrete 1-cos gusts and the continuous
turbulence of CS-25.341 (`GustInput`)."""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

from solver import fields
from solver.errors import InvalidInput
from solver.fields import parameter
from solver.gusts.analysis import gust_analysis
from solver.inputs.flight import FlightCondition
from solver.inputs.gust import GustSettings
from solver.inputs.options import SolverOptions, check_lag
from solver.inputs.wing import Wing, require_mass
from solver.operations.common import check_meshed
from solver.results.gusts import GustResult
from solver.results.quantities import Progress

__all__ = ["GustInput"]


@dataclass(frozen=True, eq=False)
class GustInput:
    """Gust loads: the aircraft's plunge and the wing's modes with Wagner's and Kuessner's
    lags (with the unsteady lattice: its transfer functions in the frequency domain), about
    the 1 g trim of `flight`, in the 1-cos gusts of every gradient (the tuned ones) and in
    continuous turbulence."""

    wing: Wing = parameter("", "the wing, with its mass", form="nested", given=Wing)
    flight: FlightCondition = parameter(
        "",
        "the flight: airspeed, density and the aircraft's weight (trimmed to it, with its load "
        "factor, default 1)",
        form="nested",
        given=FlightCondition,
    )
    gust: GustSettings | None = parameter(
        "",
        "optional gust settings (altitude, V_C or V_D, F_g, gradients, modes, clamped, turbulence)",
        form="nested",
        given=GustSettings,
        default=None,
    )
    options: SolverOptions | None = parameter(
        "", "optional solver options", form="nested", given=SolverOptions, default=None
    )

    def __post_init__(self) -> None:
        check_meshed(self.wing, self.options)
        check_lag(self.wing.in_plane_bending_stiffness, self.options, "gust loads (/gust)")
        require_mass(self.wing, "gust loads need it")
        if self.flight.weight is None:
            raise InvalidInput("flight.weight", "a gust analysis needs the aircraft's weight")

    @property
    def modelled(self) -> SolverOptions:
        return self.options or SolverOptions()

    @cached_property
    def key(self) -> bytes:
        return fields.digest((self.wing, self.flight, self.gust or GustSettings(), self.modelled))

    def run(self, progress: Progress | None = None) -> GustResult:
        """The answer."""
        return gust_analysis(self.wing, self.flight, self.gust, self.modelled)
