"""Hypothesis strategies for random but valid wings and flight conditions (issue 5 fuzzing).

Wings: N stations (uniform, cosine or random spacing), semispan 0.3..30 m, root chord 0.1..3 m
with taper ratio 0.1..1, elastic axis at 5..70 % chord (one value or per station), EI and GJ
levels over six decades each, times chord^k (k = 0..3), scattered by up to a decade either way
from station to station. Flight: alpha -15..15 deg, density 0.4..1.3 kg/m^3, airspeed drawn
relative to the wing's linear divergence speed (`speed_for`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from hypothesis import strategies as st

import solver
from solver import FlightCondition, Wing

# The inputs' own limits (solver.fields): a generated wing and airspeed are valid input.
STIFFNESS = (1e-3, 1e12)  # [N m^2]
AIRSPEED = (0.01, 1000.0)  # [m/s]

__all__ = ["WingCase", "alphas", "densities", "ratios", "speed_for", "wings"]


@dataclass(frozen=True)
class WingCase:
    """A generated wing and the numbers it was made from (shown when a case fails)."""

    wing: Wing
    recipe: dict[str, object]

    def json(self) -> dict[str, Any]:
        """The wing as a request body's `wing` member."""
        return {
            "y": self.wing.y.tolist(),
            "chord": self.wing.chord.tolist(),
            "elastic_axis": self.wing.elastic_axis.tolist(),
            "bending_stiffness": self.wing.bending_stiffness.tolist(),
            "torsional_stiffness": self.wing.torsional_stiffness.tolist(),
        }

    def __repr__(self) -> str:
        shown = ", ".join(f"{k}={v!r}" for k, v in self.json().items())
        return f"Wing.create({shown})  # {self.recipe}"


def _stations(draw: st.DrawFn, n: int, semispan: float) -> np.ndarray:
    spacing = draw(st.sampled_from(["uniform", "cosine", "random"]))
    if spacing == "uniform":
        unit = np.linspace(0.0, 1.0, n)
    elif spacing == "cosine":  # clustered at the tip
        unit = np.sin(np.linspace(0.0, np.pi / 2, n))
    else:
        gaps = np.array(draw(st.lists(st.floats(0.2, 1.0), min_size=n - 1, max_size=n - 1)))
        unit = np.concatenate([[0.0], np.cumsum(gaps) / gaps.sum()])
        unit[-1] = 1.0
    return unit * semispan


def _stiffness(
    draw: st.DrawFn, n: int, decades: tuple[float, float], chord: np.ndarray
) -> tuple[np.ndarray, dict[str, float]]:
    """A level over `decades` (log10), times chord^k, scattered per station within a decade."""
    level = 10.0 ** draw(st.floats(*decades))
    power = draw(st.sampled_from([0, 1, 2, 3]))
    scatter = np.array(draw(st.lists(st.floats(-1.0, 1.0), min_size=n, max_size=n)))
    stiffness = np.clip(level * chord**power * 10.0**scatter, *STIFFNESS)
    return stiffness, {"level": level, "chord_power": power}


@st.composite
def wings(draw: st.DrawFn, min_stations: int = 3, max_stations: int = 40) -> WingCase:
    n = draw(st.integers(min_stations, max_stations))
    semispan = 10.0 ** draw(st.floats(-0.5, 1.5))
    y = _stations(draw, n, semispan)
    root_chord = 10.0 ** draw(st.floats(-1.0, 0.5))
    taper = draw(st.floats(0.1, 1.0))
    chord = root_chord * (1.0 - (1.0 - taper) * y / semispan)
    if draw(st.booleans()):
        elastic_axis: float | np.ndarray = draw(st.floats(0.05, 0.7))
    else:
        elastic_axis = np.array(draw(st.lists(st.floats(0.05, 0.7), min_size=n, max_size=n)))
    ei, ei_recipe = _stiffness(draw, n, (1.0, 7.0), chord)
    gj, gj_recipe = _stiffness(draw, n, (0.0, 6.0), chord)
    recipe: dict[str, object] = {"n": n, "semispan": semispan, "root_chord": root_chord}
    recipe |= {"taper": taper, "EI": ei_recipe, "GJ": gj_recipe}
    return WingCase(Wing.create(y, chord, elastic_axis, ei, gj), recipe)


def speed_for(wing: Wing, ratio: float, density: float) -> float:
    """`ratio` times the linear divergence speed or, for a wing that never diverges, a speed
    spread log-uniformly over 1..500 m/s by the same ratio (`ratios` spans 0.05..2.5); within
    the airspeeds an input may have."""
    q_div = solver.linear_divergence_pressure(wing)
    if q_div is None:
        return float(10.0 ** (2.7 * ratio / 2.5))
    return float(np.clip(ratio * FlightCondition.velocity_for(q_div, density), *AIRSPEED))


alphas = st.floats(-15.0, 15.0)
densities = st.floats(0.4, 1.3)
ratios = st.floats(0.05, 2.5)
