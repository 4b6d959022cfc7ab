"""One wing at one angle of attack: the compiled model bound to the wing's parameters.

Everything above this module speaks of a `CoupledSystem`: evaluate r0, r1, J0, J1 at a state,
the residual alone, the panel loads, and the scaled coordinates its continuation uses.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from solver.cache import model_for
from solver.compiled import CompiledModel
from solver.continuation import branch_scales
from solver.evaluation import Evaluation
from solver.inputs import Wing
from solver.layout import Layout

__all__ = ["CoupledSystem"]


@dataclass(frozen=True, eq=False)
class CoupledSystem:
    """The residual r(x; q) = r0(x) + q r1(x) of `wing` at `alpha` [deg]."""

    wing: Wing
    alpha: float

    @cached_property
    def layout(self) -> Layout:
        return Layout(self.wing.n_stations)

    @property
    def model(self) -> CompiledModel:
        # Looked up on every use: the cache may have swapped in compiled code, or evicted it.
        return model_for(self.layout)

    @cached_property
    def parameters(self) -> np.ndarray:
        """(n_parameters,) the model's parameter vector."""
        return self.layout.parameters(self.wing.arrays(), self.alpha)

    @property
    def key(self) -> tuple[str, float]:
        """The canonical identity of the wing at this alpha (-0.0 and 0.0 alike)."""
        return (self.wing.key, self.alpha + 0.0)

    def evaluate(self, x: np.ndarray) -> Evaluation:
        return self.model.evaluate(x, self.parameters)

    def residual(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        return self.model.residual(x, self.parameters)

    def panel_loads(self, x: np.ndarray) -> list[np.ndarray]:
        """[force (3, M) per unit q, torque (1, M) per unit q, vortex_center (3, M),
        vortex_vertex (3, N)]."""
        return self.model.panel_loads(x, self.parameters)

    def scale(self, q_scale: float) -> np.ndarray:
        """(n + 1,) scaled coordinates of states and q, with q measured in q_scale [Pa]."""
        return branch_scales(self.layout, self.wing.semispan, self.wing.mean_chord, q_scale)
