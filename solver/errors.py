"""Typed failures of the solver. Every way a solve can fail without a bug ends in one of these."""

from __future__ import annotations

__all__ = ["SolverError", "ConvergenceError", "NoEquilibrium"]


class SolverError(Exception):
    """Base class: the solver could not produce an equilibrium."""


class ConvergenceError(SolverError):
    """Newton's method stopped without meeting the residual tolerance.

    Attributes:
        velocity: [m/s] airspeed of the attempted solve.
        iterations: Newton iterations taken.
        residual_norm: max-norm of the final residual (mixed units, see `solver.model`).
        reason: what stopped it (iteration limit, singular Jacobian, non-finite residual...).
    """

    def __init__(self, velocity: float, iterations: int, residual_norm: float, reason: str):
        self.velocity = velocity
        self.iterations = iterations
        self.residual_norm = residual_norm
        self.reason = reason
        super().__init__(
            f"no converged equilibrium at V = {velocity:g} m/s: {reason} "
            f"after {iterations} Newton iterations (residual {residual_norm:.3g})"
        )


class NoEquilibrium(SolverError):
    """No static equilibrium exists on the branch from the jig shape at this airspeed.

    Attributes:
        velocity: [m/s] requested airspeed.
        fold_velocity: [m/s] where the equilibrium branch from the jig shape ends (its fold), or
            None if it could not be located.
    """

    def __init__(self, velocity: float, fold_velocity: float | None, detail: str = "") -> None:
        self.velocity = velocity
        self.fold_velocity = fold_velocity
        where = (
            f"beyond the fold of the equilibrium branch at {fold_velocity:.4g} m/s"
            if fold_velocity is not None
            else "the equilibrium branch from the jig shape does not reach it"
        )
        message = f"no static aeroelastic equilibrium at V = {velocity:g} m/s: {where}"
        super().__init__(message + (f" ({detail})" if detail else ""))
