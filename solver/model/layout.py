"""Index arithmetic of one mesh: where each unknown, equation and parameter sits.

N structural stations, k chordwise panels per strip, M = (N - 1) k panels on the right half.

Unknowns x (3N + M), in this order:
    u (N) [m]          heave at stations
    du (N) [-]         slope du/ds along the elastic axis
    phi (N) [deg]      twist about the elastic axis
    g (M) [m]          circulation per unit airspeed of each right-half panel, Gamma / V
Equations (3N + M), in this order:
    root clamps (3), heave kinematics (N - 1), bending (N - 1), torsion (N - 1),
    flow tangency (M)
Parameters p, in this order:
    y, chord, elastic_axis, EI, GJ, jig_twist (N each), camber (N (k + 1), station-major:
    camber / chord at each station's chordwise nodes), alpha [deg], sweep [deg],
    deformed_axis (0: torque about the undeformed elastic axis, 1: about the heaved one).

The aerodynamics (`Layout.aerodynamics`) changes what the tangency rows say, never where
anything sits: "lattice" (the horseshoe lattice, every panel seeing every horseshoe) or "strip"
(strip theory: each strip a two-dimensional airfoil, `solver.model.residual`).

The flow model's parameters (control surfaces and roll, `solver.model.residual`'s flow functions)
follow these, in this order:
    image (+1 the mirror, symmetric flow; -1 the rotation about x, antisymmetric flow),
    image_jacobian (the weight of the image's own derivatives: equal to image for the exact
    Jacobian; `solver.model.vlm`), roll_rate [rad/m] (p / V, a steady roll rate about x per unit
    airspeed), control (N (k + 1), station-major: the direction d(camber)/d(deflection)
    [1/rad] of the control derivatives), direction (3N + M: a direction in the unknowns along
    which the panel loads' derivatives are returned, a roll answer's linearised loads).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from typing import Literal

import numpy as np

__all__ = ["AERODYNAMICS", "Aerodynamics", "Layout"]

Aerodynamics = Literal["lattice", "strip"]
AERODYNAMICS: tuple[Aerodynamics, ...] = ("lattice", "strip")


@dataclass(frozen=True)
class Layout:
    """The mesh of N structural stations and its (N - 1) k panels, and the aerodynamics on it."""

    n: int
    chordwise: int = 1
    aerodynamics: Aerodynamics = "lattice"

    @property
    def n_panels(self) -> int:
        """M: panels of the right half-wing."""
        return (self.n - 1) * self.chordwise

    @property
    def n_strips(self) -> int:
        return self.n - 1

    @property
    def n_unknowns(self) -> int:
        return 3 * self.n + self.n_panels

    @property
    def n_parameters(self) -> int:
        return 6 * self.n + self.n * (self.chordwise + 1) + 3

    # Unknowns
    @property
    def heave(self) -> slice:
        return slice(0, self.n)

    @property
    def slope(self) -> slice:
        return slice(self.n, 2 * self.n)

    @property
    def twist(self) -> slice:
        """The twist about the elastic axis, phi [deg]."""
        return slice(2 * self.n, 3 * self.n)

    @property
    def circulation(self) -> slice:
        return slice(3 * self.n, 3 * self.n + self.n_panels)

    @property
    def structure(self) -> slice:
        """Unknowns of the beam: heave, slope and twist."""
        return slice(0, 3 * self.n)

    # Equations
    @property
    def bending_rows(self) -> slice:
        return slice(3 + self.n_strips, 3 + 2 * self.n_strips)

    @property
    def torsion_rows(self) -> slice:
        return slice(3 + 2 * self.n_strips, 3 + 3 * self.n_strips)

    @property
    def structure_rows(self) -> slice:
        """Equations of the beam: clamps, kinematics, bending, torsion."""
        return slice(0, 3 * self.n)

    @property
    def tangency_rows(self) -> slice:
        return slice(3 * self.n, 3 * self.n + self.n_panels)

    @cached_property
    def load_rows(self) -> np.ndarray:
        """Equations in which the aerodynamic loads appear (J1's only non-zero rows); read-only,
        built once per layout (every stability verdict reads it)."""
        # The torsion rows follow the bending rows.
        load_rows = np.arange(self.bending_rows.start, self.torsion_rows.stop)
        load_rows.setflags(write=False)
        return load_rows

    # Parameters
    def parameters(
        self,
        arrays: tuple[np.ndarray, ...],
        camber: np.ndarray,
        alpha_deg: float,
        sweep_deg: float,
        deformed_axis: bool,
    ) -> np.ndarray:
        """(n_parameters,) from the wing's six station arrays (y, chord, elastic_axis, EI, GJ,
        jig_twist), its camber at the chordwise nodes (N, k + 1), alpha and sweep [deg]."""
        return np.concatenate(
            [*arrays, np.ravel(camber), [alpha_deg, sweep_deg, 1.0 if deformed_axis else 0.0]]
        )

    @property
    def alpha_index(self) -> int:
        """Where alpha [deg] sits in the parameter vector."""
        return self.n_parameters - 3

    def split(self, p):  # type: ignore[no-untyped-def]
        """The parameter vector's parts (symbolic or numeric): y, chord, elastic_axis, EI, GJ,
        jig (N each), camber (N, k + 1), alpha, sweep, deformed_axis."""
        n, k1 = self.n, self.chordwise + 1
        parts = [p[i * n : (i + 1) * n] for i in range(6)]
        start = 6 * n
        camber = p[start : start + n * k1]
        end = start + n * k1
        return (*parts, camber, p[end], p[end + 1], p[end + 2])

    # The flow model's parameters, after these
    @property
    def n_flow_parameters(self) -> int:
        """How many parameters the flow model adds (module docstring)."""
        return 3 + self.n * (self.chordwise + 1) + self.n_unknowns

    def flow_parameters(
        self,
        image: float = 1.0,
        image_jacobian: float = 1.0,
        roll_rate: float = 0.0,
        control: np.ndarray | None = None,
        direction: np.ndarray | None = None,
    ) -> np.ndarray:
        """(n_flow_parameters,) the flow model's part of its parameter vector: control (N,
        k + 1) [1/rad] and direction (n,), default zero."""
        if control is None:
            control = np.zeros(self.n * (self.chordwise + 1))
        if direction is None:
            direction = np.zeros(self.n_unknowns)
        return np.concatenate(
            [[image, image_jacobian, roll_rate], np.ravel(control), np.ravel(direction)]
        )

    def split_flow(self, p):  # type: ignore[no-untyped-def]
        """The flow model's parameter vector's flow parts (symbolic or numeric): image,
        image_jacobian, roll_rate [rad/m], control (N (k + 1)) [1/rad], direction (n)."""
        start = self.n_parameters
        control = self.control_slice
        return p[start], p[start + 1], p[start + 2], p[control], p[self.direction_slice]

    @property
    def roll_rate_index(self) -> int:
        """Where p / V [rad/m] sits in the flow model's parameter vector."""
        return self.n_parameters + 2

    @property
    def control_slice(self) -> slice:
        """Where the control direction sits in the flow model's parameter vector."""
        start = self.n_parameters + 3
        return slice(start, start + self.n * (self.chordwise + 1))

    @property
    def direction_slice(self) -> slice:
        """Where the direction in the unknowns sits in the flow model's parameter vector."""
        end = self.n_parameters + self.n_flow_parameters
        return slice(end - self.n_unknowns, end)

    @property
    def camber_slice(self) -> slice:
        """Where the camber sits in the parameter vector (either model's)."""
        return slice(6 * self.n, 6 * self.n + self.n * (self.chordwise + 1))
