"""What the unsteady lattice's transfer functions return (`solver.dynamics.aerodynamic_forces`):
the aerodynamic loads of harmonic motion of each mode and of a gust, at reduced frequencies,
each field with its unit (`quantity`).

Harmonic motion is Re(x e^{i omega t}); the reduced frequency k = omega b / V with b the
reference semichord; complex arrays are in-phase (real) and quadrature (imaginary) parts.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from solver.results.flutter import ModeShape
from solver.results.quantities import quantity

__all__ = ["GeneralisedAerodynamicForces"]


@dataclass(frozen=True, eq=False)
class GeneralisedAerodynamicForces:
    """The unsteady lattice's loads of harmonic motion of the modes and of a vertical gust, per
    unit dynamic pressure, at each reduced frequency (K of them), on r modes of n = 2 (N - 1)
    degrees of freedom: the modal equations of forced motion are

        c'' + diag(frequency^2) c = q (modal c + modal_gust w_g / V),

    c the modes' coordinates [m] (each mode's shape scaled as `modes`: its largest leading or
    trailing edge displacement 1 m), w_g e^{i omega (t - x / V)} the gust's vertical velocity,
    meeting each point x [m] aft of the root's elastic axis x / V later."""

    reduced_frequency: np.ndarray = quantity("-", "(K,) k = omega b / V of each answer")
    reference_semichord: float = quantity("m", "b of the reduced frequencies: half the mean chord")
    modes: list[ModeShape] = quantity("", "the r modes, lowest frequency first")
    modal: np.ndarray = quantity(
        "m/kg",
        "(K, r, r) complex: mode i's generalised aerodynamic force per unit dynamic pressure and "
        "unit coordinate of mode j in harmonic motion (Nastran's Q_hh over the modal mass)",
    )
    modal_gust: np.ndarray = quantity(
        "m^2/kg",
        "(K, r) complex: mode i's generalised aerodynamic force per unit dynamic pressure and "
        "unit gust angle w_g / V (each panel at its own delay)",
    )
    loads: np.ndarray = quantity(
        "m^2 | m^3",
        "(K, n, r) complex: the strips' equivalent loads per unit dynamic pressure and unit "
        "coordinate of each mode: rows 0 to N - 2 the vertical forces at the strips' midpoints "
        "on the elastic axis [N / Pa / m], rows N - 1 on the torques about it [N m / Pa / m] "
        "(`solver.dynamics.modes.Structure`)",
    )
    gust_loads: np.ndarray = quantity(
        "m^2 | m^3",
        "(K, n) complex: the same per unit dynamic pressure and unit gust angle",
    )
