"""Index arithmetic of one mesh: where each unknown, equation and parameter sits.

Unknowns x (4N - 1), in this order:
    u (N) [m]        heave at stations
    du (N) [-]       slope u' at stations
    theta (N) [deg]  twist at stations
    g (N - 1) [m]    circulation per unit airspeed of each right-half panel, Gamma / V
Equations (4N - 1), in this order:
    root clamps (3), heave kinematics (N - 1), bending (N - 1), torsion (N - 1),
    flow tangency (N - 1)
Parameters p (5N + 1): y, chord, elastic_axis, EI, GJ (N each), alpha [deg].
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["Layout"]


@dataclass(frozen=True)
class Layout:
    """The mesh of N structural stations and its N - 1 panels."""

    n: int

    @property
    def n_panels(self) -> int:
        return self.n - 1

    @property
    def n_unknowns(self) -> int:
        return 4 * self.n - 1

    @property
    def n_parameters(self) -> int:
        return 5 * self.n + 1

    # Unknowns
    @property
    def heave(self) -> slice:
        return slice(0, self.n)

    @property
    def slope(self) -> slice:
        return slice(self.n, 2 * self.n)

    @property
    def twist(self) -> slice:
        return slice(2 * self.n, 3 * self.n)

    @property
    def circulation(self) -> slice:
        return slice(3 * self.n, 4 * self.n - 1)

    # Equations
    @property
    def bending_rows(self) -> slice:
        return slice(3 + self.n_panels, 3 + 2 * self.n_panels)

    @property
    def torsion_rows(self) -> slice:
        return slice(3 + 2 * self.n_panels, 3 + 3 * self.n_panels)

    @property
    def tangency_rows(self) -> slice:
        return slice(3 + 3 * self.n_panels, 3 + 4 * self.n_panels)

    @property
    def load_rows(self) -> np.ndarray:
        """Equations in which the aerodynamic loads appear (J1's only non-zero rows)."""
        rows = np.arange(self.n_unknowns)
        return np.r_[rows[self.bending_rows], rows[self.torsion_rows]]

    def parameters(self, arrays: tuple[np.ndarray, ...], alpha_deg: float) -> np.ndarray:
        """(5N + 1,) the parameter vector from the wing's station arrays and alpha [deg]."""
        return np.concatenate([*arrays, [alpha_deg]])
