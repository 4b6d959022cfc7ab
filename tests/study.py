"""The design study's wing (shared/seed, chapter 14) and the other wings the tests share, defined
once: as solver inputs and as request bodies."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import numpy as np

import solver

ROOT = Path(__file__).resolve().parents[1]
REFERENCE = ROOT.parent / "shared" / "reference" / "ref_seed.json"

# AeroSandbox's sea-level ISA density, used by the study and its reference data [kg/m^3].
DENSITY = 1.2249991558876672
ALPHA = 5.0  # [deg] the study's angle of attack
FOLD_VELOCITY = 21.4397  # [m/s] where the study wing's branch from the jig ends, at 5 deg
SPAN = 10.0  # [m] the study wing's span

# The study's printed sweep (section 14.6): V [m/s] -> (CL on the deformed area, tip twist [deg]),
# printed to 3 and 2 decimals.
SWEEP = {
    10: (0.522, 1.71),
    6: (0.470, 0.55),
    12: (0.565, 2.67),
    15: (0.666, 4.93),
    18: (0.847, 8.89),
    20: (1.070, 13.65),
}


def study_arrays(
    n: int = 30, stiffness_scale: float = 1.0, elastic_axis: float = 0.4
) -> dict[str, Any]:
    """y = linspace(0, 5, n), c = sqrt(linspace(2, 0.02, n)), x_ea 0.4, EI 2e4 c^3, GJ 1e3 c^3
    (the study's wing has n = 30)."""
    chord = np.sqrt(np.linspace(2, 0.02, n))
    return {
        "y": np.linspace(0, 5, n),
        "chord": chord,
        "elastic_axis": elastic_axis,
        "bending_stiffness": 2e4 * chord**3 * stiffness_scale,
        "torsional_stiffness": 1e3 * chord**3 * stiffness_scale,
    }


def study_wing(n: int = 30, stiffness_scale: float = 1.0, elastic_axis: float = 0.4) -> solver.Wing:
    return solver.Wing.create(**study_arrays(n, stiffness_scale, elastic_axis))


def wing_json(n: int = 30, stiffness_scale: float = 1.0) -> dict[str, Any]:
    """The study's wing as a request body's `wing` member."""
    return {
        key: value.tolist() if isinstance(value, np.ndarray) else value
        for key, value in study_arrays(n, stiffness_scale).items()
    }


def flight(
    velocity: float, alpha: float = ALPHA, density: float = DENSITY
) -> solver.FlightCondition:
    return solver.FlightCondition(velocity=velocity, alpha=alpha, density=density)


def solve_request(velocity: float, alpha: float = ALPHA, **extra: Any) -> dict[str, Any]:
    return {
        "wing": wing_json(),
        "flight": {"velocity": velocity, "alpha": alpha, "density": DENSITY},
    } | extra


def rect_public() -> solver.Wing:
    """shared/reference/case_rect_public.json (fold at 15.66 m/s at 4 deg)."""
    return solver.Wing.create(np.linspace(0, 4, 24), np.full(24, 0.8), 0.35, 5000.0, 400.0)


def tapered_forward_ea() -> solver.Wing:
    """N = 17, linear taper, elastic axis ahead of the quarter chord, EI ~ c^2, GJ ~ c."""
    chord = 1.0 - 0.6 * np.linspace(0, 1, 17)
    return solver.Wing.create(np.linspace(0, 6, 17), chord, 0.15, 2.5e4 * chord**2, 1.5e3 * chord)


def bistable_wing() -> solver.Wing:
    """Found by fuzzing (simplified): uniform stations, linear taper, GJ = 1 N m^2. Past its
    linear divergence (0.311 Pa) the branch from the jig reaches +70 deg of tip twist at
    q = 0.519 Pa; a nose-down equilibrium (-70 deg, negative lift) is statically stable too."""
    y = np.linspace(0, 5, 27)
    return solver.Wing.create(y, 1.438 * (1 - 0.877 * y / 5), 0.4, 1.232e6, 1.0)


def bistable_wing_json() -> dict[str, Any]:
    wing = bistable_wing()
    return {
        "y": wing.y.tolist(),
        "chord": wing.chord.tolist(),
        "elastic_axis": 0.4,
        "bending_stiffness": 1.232e6,
        "torsional_stiffness": 1.0,
    }


def reference() -> dict[float, Any]:
    """AeroSandbox's equilibria of the study's wing (shared/reference), by velocity."""
    data = json.loads(REFERENCE.read_text())
    return {float(e["velocity"]): e for e in data["equilibria"]}


def relative_difference(ours: Any, theirs: Any) -> float:
    """max |ours - theirs| / max |theirs|."""
    ours, theirs = np.atleast_1d(ours), np.atleast_1d(theirs)
    return float(np.max(np.abs(ours - theirs)) / np.max(np.abs(theirs)))
