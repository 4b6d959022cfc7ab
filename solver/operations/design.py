"""The design question: the jig twist (and spar walls) of the wing that flies
(`OptimizeInput`)."""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

from solver.errors import InvalidInput
from solver.fields import parameter
from solver.inputs.design import DesignProblem
from solver.inputs.options import SolverOptions, check_lag
from solver.inputs.wing import Wing
from solver.operations.common import check_meshed, identity
from solver.optimization.optimize import optimize
from solver.results.design import OptimalDesign
from solver.results.quantities import Progress

__all__ = ["OptimizeInput"]


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
        check_meshed(self.wing, self.options)
        check_lag(self.wing.in_plane_bending_stiffness, self.options, "the optimiser (/optimize)")
        if self.problem.size_spar and self.wing.spar is None:
            raise InvalidInput("design.wall_thickness", "the wing has no spar to size")

    @property
    def modelled(self) -> SolverOptions:
        return self.options or SolverOptions()

    @cached_property
    def key(self) -> bytes:
        return identity(self, options=self.modelled)

    def run(self, progress: Progress | None = None) -> OptimalDesign:
        """The answer (`progress` is for the operations that have parts: none here)."""
        return optimize(self.wing, self.problem, self.modelled)
