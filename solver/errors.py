"""Typed failures. Bad inputs raise `InvalidInput`; every way a valid solve can end without an
equilibrium raises a `SolverError`."""

from __future__ import annotations

import contextlib
from collections.abc import Iterator

import numpy as np

__all__ = [
    "ConvergenceError",
    "DynamicInstability",
    "InfeasibleDesign",
    "InvalidInput",
    "NoEquilibrium",
    "OptimizerNotConverged",
    "SolverError",
    "numerical_failures_as",
]


class InvalidInput(ValueError):
    """An input that cannot describe a physical wing or flight condition.

    `field` names the offending input (e.g. ``"chord"``), `reason` says what is wrong with it.
    """

    def __init__(self, field: str, reason: str) -> None:
        super().__init__(f"{field}: {reason}" if field else reason)
        self.field = field
        self.reason = reason

    def __reduce__(self) -> tuple[type, tuple[str, str]]:
        return type(self), (self.field, self.reason)


class SolverError(Exception):
    """Base class: the solver could not produce an equilibrium."""


class ConvergenceError(SolverError):
    """Newton's method, or the path to the requested condition, stopped short of an equilibrium.

    Attributes:
        velocity: [m/s] airspeed of the attempted solve.
        iterations: Newton iterations taken.
        residual_norm: max-norm of the final residual (mixed units, see `solver.model.residual`).
        reason: what stopped it (iteration limit, singular Jacobian, a stalled branch...).
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

    def __reduce__(self) -> tuple[type, tuple[float, int, float, str]]:
        return type(self), (self.velocity, self.iterations, self.residual_norm, self.reason)


class NoEquilibrium(SolverError):
    """No statically stable equilibrium exists on the branch from the jig shape at this airspeed.

    Attributes:
        velocity: [m/s] requested airspeed.
        fold_velocity: [m/s] where the equilibrium branch from the jig shape ends (its fold), or
            None if it has none below the requested speed (e.g. the branch continues but is
            statically unstable there).
        detail: why, beyond the fold speed.
        where: what is missing, when not the jig branch's stable equilibrium (trimmed flight).
    """

    def __init__(
        self,
        velocity: float,
        fold_velocity: float | None,
        detail: str = "",
        where: str | None = None,
    ) -> None:
        self.velocity = velocity
        self.fold_velocity = fold_velocity
        self.detail = detail
        self.where = where
        if where is None:
            where = (
                f"beyond the fold of the equilibrium branch at {fold_velocity:.6g} m/s"
                if fold_velocity is not None
                else "the equilibrium branch from the jig shape has no stable equilibrium there"
            )
        message = f"no static aeroelastic equilibrium at V = {velocity:g} m/s: {where}"
        super().__init__(message + (f" ({detail})" if detail else ""))

    def __reduce__(self) -> tuple[type, tuple[float, float | None, str, str | None]]:
        return type(self), (self.velocity, self.fold_velocity, self.detail, self.where)


class FoldedWing(NoEquilibrium):
    """The geometrically exact beam's equilibrium turns the wing back on itself: a station's
    bending rotation reaches 90 deg (the axis vertical, then pointing back toward the root),
    where the model's streamwise sections cannot be placed (`solver.model.exact_beam`).

    Attributes (besides `NoEquilibrium`'s): station: the first such station's index; y: [m] its
    jig position; rotation: [deg] its bending rotation there.
    """

    def __init__(self, velocity: float, station: int, y: float, rotation: float) -> None:
        self.station, self.y, self.rotation = station, y, rotation
        where = (
            f"the wing folds back on itself at station {station} (y = {y:.4g} m): its bending "
            f"rotation {rotation:.4g} deg reaches 90 deg, past which streamwise sections "
            "cannot be placed"
        )
        super().__init__(velocity, None, where=where)

    def __reduce__(self) -> tuple[type, tuple[float, int, float, float]]:  # type: ignore[override]
        return type(self), (self.velocity, self.station, self.y, self.rotation)


class InfeasibleDesign(SolverError):
    """A design problem without an acceptable optimum.

    Attributes:
        constraint: which constraint could not be met ("lift", "von_mises", "tip_heave",
            "stability_margin", "jig_twist", ...) or "optimizer" when IPOPT failed otherwise.
        detail: what was found.
        violation: [-] how far the last design the optimizer reached breaks `constraint`, in
            units of the constraint's scale (its limit, or 1 for dimensionless ones); None when
            no design was judged (no equilibrium there, or the problem cannot be posed).
        case: the load case in which `constraint` could not be met ("flight": the design
            flight, else a load case's name), for a problem with load cases; None for a
            single-point problem, or a constraint of no case (the jig twist's bounds).
    """

    def __init__(
        self,
        constraint: str,
        detail: str,
        violation: float | None = None,
        case: str | None = None,
    ) -> None:
        self.constraint = constraint
        self.detail = detail
        self.violation = violation
        self.case = case
        where = "" if case is None else f" in case {case!r}"
        super().__init__(f"no feasible optimum: {constraint}{where}: {detail}")

    def __reduce__(self) -> tuple[type, tuple[str, str, float | None, str | None]]:
        return type(self), (self.constraint, self.detail, self.violation, self.case)


class OptimizerNotConverged(ConvergenceError):
    """The optimizer stopped before its optimality test held, at a design it could not judge
    (its iteration limit): not a proof that no design is feasible (`InfeasibleDesign`).

    Attributes as `ConvergenceError`'s: velocity: [m/s] the design flight's airspeed;
    iterations: the optimizer's iterations; residual_norm: [-] the largest violation of a
    constraint at the last design, in units of its scale; reason: what stopped it.
    """

    def __init__(self, velocity: float, iterations: int, residual_norm: float, reason: str):
        self.velocity = velocity
        self.iterations = iterations
        self.residual_norm = residual_norm
        self.reason = reason
        SolverError.__init__(
            self,
            f"the design optimizer did not converge: {reason} after {iterations} iterations "
            f"(largest constraint violation {residual_norm:.3g} of its scale)",
        )


class DynamicInstability(SolverError):
    """The linear aeroelastic system has a growing motion at this airspeed (past flutter or
    divergence): a gust has no bounded response.

    Attributes:
        velocity: [m/s] airspeed analysed.
        growth_rate: [1/s] the largest real part of the system's roots (positive).
        frequency: [rad/s] that root's frequency (0: divergence, else flutter).
    """

    def __init__(self, velocity: float, growth_rate: float, frequency: float) -> None:
        self.velocity = velocity
        self.growth_rate = growth_rate
        self.frequency = frequency
        kind = "divergence" if frequency == 0 else f"flutter at {frequency:.4g} rad/s"
        super().__init__(
            f"the wing is dynamically unstable at V = {velocity:g} m/s ({kind}, growing at "
            f"{growth_rate:.3g} 1/s): no bounded gust response"
        )

    def __reduce__(self) -> tuple[type, tuple[float, float, float]]:
        return type(self), (self.velocity, self.growth_rate, self.frequency)


@contextlib.contextmanager
def numerical_failures_as(velocity: float) -> Iterator[None]:
    """Linear algebra that breaks down on a degenerate wing (a singular rigid-wing system, an
    eigenvalue solve that does not converge, loads that are not finite) ends the work with a
    typed ConvergenceError at `velocity` [m/s]: the wing is valid input, the numbers could not
    be computed."""
    try:
        yield
    except (np.linalg.LinAlgError, FloatingPointError, ZeroDivisionError) as error:
        raise ConvergenceError(
            velocity, 0, float("nan"), f"the linear algebra broke down ({error})"
        ) from error
