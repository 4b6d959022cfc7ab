"""Load cases: every named point of every V-n diagram of a flight envelope (`solver.sizing.vn`)
as one trimmed flight to solve, named after its point, weight and altitude."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from solver.inputs.atmosphere import STANDARD_GRAVITY, density, true_airspeed
from solver.inputs.envelope import FlightEnvelope
from solver.sizing.vn import Kind, vn_diagrams

__all__ = ["LoadCase", "load_cases"]


@dataclass(frozen=True)
class LoadCase:
    """One trimmed flight to solve: `name` ("A+ at V_A, 2 000 kg, 0 m"), the V-n point it is,
    its equivalent and true airspeeds [m/s], load factor [-], weight [N], geopotential altitude
    [m] and the ISA density there [kg/m^3] (rho V_TAS^2 = rho0 V_EAS^2)."""

    name: str
    point: str
    kind: Kind
    equivalent_airspeed: float
    true_airspeed: float
    load_factor: float
    weight: float
    altitude: float
    density: float


def load_cases(
    envelope: FlightEnvelope,
    *,
    wing_area: float | None = None,
    mean_chord: float | None = None,
    lift_slope: float | None = None,
) -> tuple[LoadCase, ...]:
    """Every point of every V-n diagram of `envelope` as a load case, named "A+ at V_A, 2 000
    kg, 0 m" (mass W/g0, geopotential altitude), weight by weight, altitude by altitude; the
    wing's area [m^2], mean geometric chord [m] and lift slope [1/rad] where the envelope has
    none."""
    masses = _labels([w / STANDARD_GRAVITY for w in envelope.weights], "kg")
    heights = _labels(list(envelope.altitudes), "m")
    cases = []
    for diagram in vn_diagrams(
        envelope, wing_area=wing_area, mean_chord=mean_chord, lift_slope=lift_slope
    ):
        mass = masses[envelope.weights.index(diagram.weight)]
        height = heights[envelope.altitudes.index(diagram.altitude)]
        rho = float(density(diagram.altitude))
        for point in diagram.points:
            cases.append(
                LoadCase(
                    name=f"{point.name} at {point.speed}, {mass}, {height}",
                    point=point.name,
                    kind=point.kind,
                    equivalent_airspeed=point.airspeed,
                    true_airspeed=float(true_airspeed(point.airspeed, diagram.altitude)),
                    load_factor=point.load_factor,
                    weight=diagram.weight,
                    altitude=diagram.altitude,
                    density=rho,
                )
            )
    return tuple(cases)


def _labels(values: Sequence[float], unit: str) -> list[str]:
    """'2 000 kg': each value with as few decimals as tell the values apart."""
    for decimals in range(7):
        texts = [f"{value:,.{decimals}f}".replace(",", " ") + f" {unit}" for value in values]
        if len(set(texts)) == len(texts):
            return texts
    return [f"{value!r} {unit}" for value in values]
