"""Public names that were renamed, kept for a release as deprecated aliases (docs/changelog.md):
each use warns with a `DeprecationWarning` naming its replacement, and answers as it does."""

from __future__ import annotations

import warnings
from collections.abc import Sequence
from typing import Any

from solver.inputs.flight import ISA_SEA_LEVEL_DENSITY, FlightCondition
from solver.inputs.options import SolverOptions
from solver.inputs.wing import Wing
from solver.results.sweep import AirspeedPoint, AirspeedSweep, AirspeedSweepInfo
from solver.statics.airspeed_sweep import airspeed_sweep

__all__ = ["RENAMED", "renamed"]


def sweep(
    wing: Wing,
    velocities: Sequence[float],
    alpha: float,
    density: float,
    options: SolverOptions | None = None,
) -> AirspeedSweep:
    """`airspeed_sweep` at a fixed angle of attack [deg] and density [kg/m^3] (round 1's form)."""
    return airspeed_sweep(
        wing, velocities, FlightCondition(None, alpha=alpha, density=density), options
    )


def trim_sweep(
    wing: Wing,
    velocities: Sequence[float],
    lift: float,
    density: float,
    options: SolverOptions | None = None,
) -> AirspeedSweep:
    """`airspeed_sweep` trimmed to a lift [N] at a density [kg/m^3] (round 1's form)."""
    return airspeed_sweep(
        wing, velocities, FlightCondition(None, lift=lift, density=density), options
    )


def TrimCondition(
    velocity: float, lift: float, density: float = ISA_SEA_LEVEL_DENSITY
) -> FlightCondition:
    """A trimmed `FlightCondition`: `lift` [N] at `velocity` [m/s] (round 1's form)."""
    return FlightCondition(velocity=velocity, lift=lift, density=density)


# Old name -> (what it is now, the name to use).
RENAMED: dict[str, tuple[Any, str]] = {
    "sweep": (sweep, "airspeed_sweep(wing, velocities, FlightCondition(None, alpha, density))"),
    "trim_sweep": (
        trim_sweep,
        "airspeed_sweep(wing, velocities, FlightCondition(None, lift=lift, density=density))",
    ),
    "TrimCondition": (TrimCondition, "FlightCondition(velocity, lift=lift, density=density)"),
    "SweepResult": (AirspeedSweep, "AirspeedSweep"),
    "SweepPoint": (AirspeedPoint, "AirspeedPoint"),
    "SweepInfo": (AirspeedSweepInfo, "AirspeedSweepInfo"),
}


def renamed(name: str) -> Any:
    """The deprecated alias `name`, with its warning; AttributeError for any other name."""
    if name not in RENAMED:
        raise AttributeError(f"module 'solver' has no attribute {name!r}")
    alias, replacement = RENAMED[name]
    warnings.warn(
        f"solver.{name} is deprecated and will be removed in the next release: use "
        f"solver.{replacement}",
        DeprecationWarning,
        stacklevel=3,
    )
    return alias
