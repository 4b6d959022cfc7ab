"""Torsional divergence: three estimates that check each other (issue 3).

- linear: the classical eigenvalue at the unloaded jig (`solver.stability`).
- fit: the design study's estimate, 1/A against q over a sweep's stable points, extrapolated.
- fold: where the equilibrium branch from the jig shape ends (pseudo-arclength continuation).

CONTRACT (used by app/): the dataclasses below and `find_fold`, `divergence_summary`.
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["LinearDivergence", "FitDivergence", "Fold", "DivergenceSummary"]


@dataclass(frozen=True)
class LinearDivergence:
    """Classical linear divergence at the unloaded jig; None values with a reason if none."""

    dynamic_pressure: float | None  # [Pa]
    velocity: float | None  # [m/s] at the sweep's density
    reason: str | None = None


@dataclass(frozen=True)
class FitDivergence:
    """The study's fit 1/A = intercept + slope q over stable sweep points."""

    slope: float | None  # [1/Pa]
    intercept: float | None  # [-]
    dynamic_pressure: float | None  # [Pa] where 1/A -> 0
    velocity: float | None  # [m/s]
    reason: str | None = None


@dataclass(frozen=True)
class Fold:
    """The fold of the equilibrium branch from the jig shape (its last equilibrium)."""

    velocity: float | None  # [m/s]
    dynamic_pressure: float | None  # [Pa]
    tip_twist: float | None  # [deg] at the fold
    lift: float | None  # [N] at the fold
    searched_to_velocity: float  # [m/s] how far the branch was followed
    reason: str | None = None


@dataclass(frozen=True)
class DivergenceSummary:
    linear: LinearDivergence
    fit: FitDivergence
    fold: Fold
