"""The wings the gust tests share: a rigid high-aspect-ratio rectangle (the two-dimensional,
rigid limit of Pratt's analysis) and the study's wing with a light mass."""

from __future__ import annotations

import math

import numpy as np

import solver
from tests.study import DENSITY, study_arrays

RHO = 1.225  # [kg/m^3] sea level, so that EAS = TAS
LIGHT_MASS = {"mass_per_length": 1.0, "center_of_gravity": 0.42, "inertia_per_length": 0.02}


def rectangle(
    semispan: float = 20.0,
    chord: float = 1.0,
    stiffness: float = 1e12,
    stations: int = 9,
    sweep: float = 0.0,
    elastic_axis: float = 0.25,
) -> solver.Wing:
    """A rectangular wing, stiff by default (1e12 N m^2: rigid for every load here)."""
    return solver.Wing.create(
        np.linspace(0.0, semispan, stations),
        chord,
        elastic_axis,
        stiffness,
        stiffness,
        sweep=sweep,
        mass={"mass_per_length": 1.0, "center_of_gravity": 0.3, "inertia_per_length": 0.01},
    )


def weight_for_mass_ratio(mu: float, wing: solver.Wing, lift_slope: float = 2 * math.pi) -> float:
    """[N] the weight whose gust mass ratio 2 (W/S) / (rho c a g) is `mu` at sea level."""
    loading = mu * RHO * wing.mean_chord * lift_slope * 9.80665 / 2
    return loading * wing.planform_area


def study() -> solver.Wing:
    return solver.Wing.create(**study_arrays(), mass=LIGHT_MASS)


STUDY_FLIGHT = solver.FlightCondition(12.0, density=DENSITY, weight=300.0)
STRIP = solver.SolverOptions(aerodynamics="strip")
