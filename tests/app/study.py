"""The design study's wing and the numbers the study prints (shared/seed, chapter 14)."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
REFERENCE = ROOT.parent / "shared" / "reference" / "ref_seed.json"

# AeroSandbox's sea-level density, used by the study and its reference data [kg/m^3].
DENSITY = 1.2249991558876672


def wing(stiffness_scale: float = 1.0, n: int = 30) -> dict[str, Any]:
    """y = linspace(0, 5, n), c = sqrt(linspace(2, 0.02, n)), x_ea 0.4, EI 2e4 c^3, GJ 1e3 c^3
    (the study's wing has n = 30; more stations make a slower solve for the fault tests)."""
    y = np.linspace(0, 5, n)
    chord = np.sqrt(np.linspace(2, 0.02, n))
    return {
        "y": y.tolist(),
        "chord": chord.tolist(),
        "elastic_axis": 0.4,
        "bending_stiffness": (2e4 * chord**3 * stiffness_scale).tolist(),
        "torsional_stiffness": (1e3 * chord**3 * stiffness_scale).tolist(),
    }


def solve_request(velocity: float, alpha: float = 5.0, **extra: Any) -> dict[str, Any]:
    return {
        "wing": wing(),
        "flight": {"velocity": velocity, "alpha": alpha, "density": DENSITY},
    } | extra


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


def reference() -> dict[str, Any]:
    """AeroSandbox's equilibria of the study's wing (shared/reference), by velocity."""
    data = json.loads(REFERENCE.read_text())
    return {float(e["velocity"]): e for e in data["equilibria"]}
