"""The wings and cases the sizing-loads tests fly: the design study's wing (N = 16, a light mass
under the load factor), with a tube spar for the margins, with ailerons for rolling pull-outs."""

from __future__ import annotations

import numpy as np

import solver
from tests.study import DENSITY, study_arrays

N = 16
MASS = {"mass_per_length": 1.0, "center_of_gravity": 0.42, "inertia_per_length": 0.02}
AILERON = {"name": "aileron", "start": 0.55, "end": 0.95, "hinge": 0.75, "kind": "aileron"}
CARBON = solver.Material(youngs_modulus=70e9, shear_modulus=27e9, density=1600.0, yield_stress=6e8)


def wing(**extra: object) -> solver.Wing:
    """The study's wing on N stations with a light mass (its own weight relieves the lift)."""
    arrays = study_arrays(N)
    return solver.Wing.create(**arrays, mass=MASS, **extra)  # type: ignore[arg-type]


def spar_wing() -> solver.Wing:
    """The study's planform carried by a carbon tube 0.8 of a NACA 0012's depth, 2 mm wall."""
    arrays = study_arrays(N)
    spar = solver.SparDesign(solver.ThicknessFraction(0.8), 0.002, CARBON)
    return solver.Wing.create(
        arrays["y"], arrays["chord"], 0.4, airfoil="naca0012", spar=spar, mass=MASS
    )


def case(
    name: str, velocity: float, load_factor: float, weight: float = 300.0
) -> solver.FlightCase:
    flight = solver.FlightCondition(
        velocity, density=DENSITY, weight=weight, load_factor=load_factor
    )
    return solver.FlightCase(name=name, flight=flight)


CASES = (
    case("cruise", 14.0, 1.0),
    case("pull-up", 12.0, 2.5),
    case("push-over", 16.0, -0.5),
    case("fast pull-up", 18.0, 2.0),
)


def extremes(per_case: list[np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
    """Per station, the largest and smallest of the cases' values (N,)."""
    table = np.vstack(per_case)
    return table.max(axis=0), table.min(axis=0)
