"""What a flutter analysis is linearised about at each airspeed: the unloaded jig at rest, or
the static equilibrium there (`solver.statics.airspeed_sweep`, `solver.statics.solve`) at an
angle of attack or trimmed to a lift, its tangent aerodynamic stiffness included (the loaded
wing's flutter); and the equations of motion about it (`solver.dynamics.reduced`).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Literal

import numpy as np

from solver.dynamics.reduced import Equations
from solver.errors import SolverError
from solver.inputs.flight import FlightCondition, dynamic_pressure
from solver.inputs.options import SolverOptions
from solver.inputs.wing import Wing
from solver.numerics.evaluation import Evaluation
from solver.results.equilibrium import Equilibrium
from solver.results.flutter import DivergenceOnset
from solver.statics.airspeed_sweep import airspeed_sweep
from solver.statics.jig import at_rest
from solver.statics.solve import solve
from solver.statics.system import CoupledSystem

__all__ = ["Build", "States"]

# The equations of motion on the flutter basis about a state: its system, its exact Jacobians
# and the state x itself (n_unknowns,).
Build = Callable[[CoupledSystem, Evaluation, np.ndarray], Equations]


class States:
    """The state to linearise about at each airspeed: the jig, or the equilibrium there."""

    def __init__(
        self,
        wing: Wing,
        density: float,
        alpha: float | None,
        lift: float | None,
        options: SolverOptions,
        load_factor: float | None = None,
    ) -> None:
        self.wing, self.density, self.options = wing, density, options
        self.alpha, self.lift, self.load_factor = alpha, lift, load_factor
        self.about: Literal["jig", "alpha", "trim"] = (
            "jig" if alpha is None and lift is None else "alpha" if lift is None else "trim"
        )
        self.rest = CoupledSystem.of(wing, 0.0, options)
        self.equilibria: dict[float, Equilibrium | SolverError] = {}
        self.divergence: DivergenceOnset | None = None
        self.rest_equations: Equations | None = None

    def prepare(self, speeds: np.ndarray, largest: float) -> None:
        """Solve the equilibria at every tracking speed (loaded states only), and find where
        the loaded wing diverges."""
        if self.about == "jig":
            return
        positive = [float(v) for v in speeds if v > 0]
        if self.about == "alpha" and self.load_factor is not None:
            # The weight at a given alpha (a wind tunnel's gravity, a dead tip load) does not
            # grow with the dynamic pressure, which the sweep's continuation follows: each
            # airspeed's equilibrium is solved on its own (past a fold there is none: an error
            # at those speeds, and the p-k roots' zero-frequency root shows the divergence).
            for velocity in positive:
                self._solve(velocity)
            return
        result = airspeed_sweep(self.wing, positive, self._flight(None), self.options)
        for point in result.points:
            self.equilibria[point.velocity] = point.equilibrium or point.error  # type: ignore[assignment]
        fold = result.divergence.fold
        if fold.velocity is not None and fold.dynamic_pressure is not None:
            self.divergence = DivergenceOnset(
                fold.velocity, fold.dynamic_pressure, fold.velocity <= largest, fold.kind
            )

    def evaluation(self, velocity: float) -> tuple[CoupledSystem, Evaluation]:
        """The system and the exact Jacobians to linearise about at `velocity` [m/s]."""
        if self.about == "jig" or velocity == 0:
            return self.rest, at_rest(self.rest).evaluation
        equilibrium = self.equilibria.get(velocity)
        if equilibrium is None:
            equilibrium = self._solve(velocity)
        if isinstance(equilibrium, SolverError):
            raise equilibrium
        # The wing's weight as the equilibrium carries it: under the geometrically exact beam a
        # dead load about the deformed stations, whose derivative (J1) is its geometric stiffness.
        flight = self._flight(velocity)
        system = CoupledSystem.of(self.wing, equilibrium.totals.alpha, self.options).with_inertia(
            flight.inertial_load_factor, dynamic_pressure(self.density, velocity)
        )
        return system, system.evaluate(equilibrium.state)

    def state(self, velocity: float) -> np.ndarray:
        """(n_unknowns,) the state x linearised about at `velocity` [m/s]: zero about the jig,
        else the equilibrium's (`evaluation` solves it first)."""
        equilibrium = None if self.about == "jig" else self.equilibria.get(velocity)
        if velocity == 0 or not isinstance(equilibrium, Equilibrium):
            return np.zeros(self.rest.layout.n_unknowns)
        return np.asarray(equilibrium.state, dtype=float)

    def equations(self, velocity: float, build: Build) -> Equations:
        """The equations on the basis about the state at `velocity` (about the jig: one state
        for every airspeed, built once)."""
        if self.about == "jig" or velocity == 0:
            if self.rest_equations is None:
                self.rest_equations = build(*self.evaluation(0.0), self.state(0.0))
            return self.rest_equations
        system, evaluation = self.evaluation(velocity)
        return build(system, evaluation, self.state(velocity))

    def _flight(self, velocity: float | None) -> FlightCondition:
        """The flight the loaded wing flies at `velocity` [m/s] (None: at each of a sweep's)."""
        if self.about == "alpha":
            return FlightCondition(
                velocity, self.alpha or 0.0, self.density, load_factor=self.load_factor
            )
        return FlightCondition(
            velocity, density=self.density, lift=self.lift or 0.0, load_factor=self.load_factor
        )

    def _solve(self, velocity: float) -> Equilibrium | SolverError:
        try:
            flight = self._flight(velocity)
            answer: Equilibrium | SolverError = solve(self.wing, flight, options=self.options)
        except SolverError as error:
            answer = error
        self.equilibria[velocity] = answer
        return answer
