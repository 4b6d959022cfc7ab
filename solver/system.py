"""One wing at one angle of attack, as modelled: the compiled model bound to the wing's parameters.

Everything above this module speaks of a `CoupledSystem`: evaluate r0, r1, J0, J1 at a state,
the residual alone, the panel loads, and the scaled coordinates its continuation uses.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from solver.cache import cached, model_for
from solver.compiled import CompiledModel
from solver.continuation import branch_scales
from solver.evaluation import AlphaTerms, Evaluation
from solver.geometry import chordwise_nodes
from solver.inputs import SolverOptions, Wing
from solver.layout import Aerodynamics, Layout

__all__ = ["CoupledSystem"]


@dataclass(frozen=True, eq=False)
class CoupledSystem:
    """The residual r(x; q) = r0(x) + q r1(x) of `wing` at `alpha` [deg], with `chordwise`
    panels per strip, the torque about the heaved elastic axis if `deformed_axis`, and the
    lattice's or strip theory's `aerodynamics` (`solver.layout`)."""

    wing: Wing
    alpha: float
    chordwise: int = 1
    deformed_axis: bool = False
    aerodynamics: Aerodynamics = "lattice"

    @classmethod
    def of(cls, wing: Wing, alpha: float, options: SolverOptions) -> CoupledSystem:
        return cls(
            wing,
            alpha,
            options.chordwise_panels,
            options.torque_axis == "deformed",
            options.aerodynamics,
        )

    def at_alpha(self, alpha: float) -> CoupledSystem:
        """The same wing and model at `alpha` [deg], sharing what does not depend on it (the
        model and every other parameter: a trimmed solve changes alpha at every iteration)."""
        other = CoupledSystem(
            self.wing, alpha, self.chordwise, self.deformed_axis, self.aerodynamics
        )
        parameters = self.parameters.copy()
        parameters[self.layout.alpha_index] = alpha
        other.__dict__["parameters"] = parameters
        other.__dict__["layout"] = self.layout
        if "model" in self.__dict__:
            other.__dict__["model"] = self.__dict__["model"]
        return other

    @cached_property
    def layout(self) -> Layout:
        return Layout(self.wing.n_stations, self.chordwise, self.aerodynamics)

    @cached_property
    def model(self) -> CompiledModel:
        # Looked up once per system (a system lives for one request): the model swaps compiled
        # code in by itself, and `model_for` picks up a library another process compiled.
        return model_for(self.layout)

    @cached_property
    def parameters(self) -> np.ndarray:
        """(n_parameters,) the model's parameter vector, read-only. Kept in the solver's cache:
        a request builds a new system, and assembling the vector costs ~0.05 ms at N = 30."""
        return cached(("parameters", *self.key), self._assemble_parameters, _nbytes)

    def _assemble_parameters(self) -> np.ndarray:
        camber = self.wing.camber_at(chordwise_nodes(self.chordwise))
        parameters = self.layout.parameters(
            self.wing.arrays(), camber, self.alpha, self.wing.sweep, self.deformed_axis
        )
        parameters.setflags(write=False)
        return parameters

    @property
    def key(self) -> tuple[bytes, float, int, bool, str]:
        """The canonical identity of the wing at this alpha, as modelled (-0.0 and 0.0 alike)."""
        return (
            self.wing.key,
            self.alpha + 0.0,
            self.chordwise,
            self.deformed_axis,
            self.aerodynamics,
        )

    @property
    def model_key(self) -> tuple[bytes, int, bool, str]:
        """The identity of the wing as modelled, whatever the alpha (what its rest state keys)."""
        return (self.wing.key, self.chordwise, self.deformed_axis, self.aerodynamics)

    def evaluate(self, x: np.ndarray) -> Evaluation:
        return self.model.evaluate(x, self.parameters)

    def evaluate_with_alpha(self, x: np.ndarray) -> tuple[Evaluation, AlphaTerms]:
        return self.model.evaluate_with_alpha(x, self.parameters)

    def residual(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        return self.model.residual(x, self.parameters)

    def residual_with_lift(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray, float]:
        """(r0, r1) and the lift of both halves per unit q [m^2] at x."""
        return self.model.residual_with_lift(x, self.parameters)

    def panel_loads(self, x: np.ndarray) -> list[np.ndarray]:
        """[force (3, M) per unit q, torque (1, M) per unit q, center (3, M), quarter_chord
        (3, N)]."""
        return self.model.panel_loads(x, self.parameters)

    def scale(self, q_scale: float) -> np.ndarray:
        """(n + 1,) scaled coordinates of states and q, with q measured in q_scale [Pa]."""
        return branch_scales(self.layout, self.wing.semispan, self.wing.mean_chord, q_scale)


def _nbytes(array: np.ndarray) -> int:
    return array.nbytes
