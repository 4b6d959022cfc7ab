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
    deformed_axis (0: torque about the undeformed elastic axis, 1: about the heaved one),
    then the image half's flow (`solver.vlm`): image (+1 the mirror, symmetric flow; -1 the
    rotation about x, antisymmetric flow), image_jacobian (the weight of the image's own
    derivatives: equal to image for the exact Jacobian), roll_rate [rad/m] (p / V, a steady
    roll rate about x per unit airspeed), control (N (k + 1), station-major): the
    direction d(camber)/d(deflection) [1/rad] of the control derivatives, and direction (3N +
    M): a direction in the unknowns along which the panel loads' derivative is returned (the
    linearised loads of a roll answer, `solver.roll`).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

__all__ = ["Layout"]


@dataclass(frozen=True)
class Layout:
    """The mesh of N structural stations and its (N - 1) k panels."""

    n: int
    chordwise: int = 1

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
        return 6 * self.n + 2 * self.n * (self.chordwise + 1) + 6 + self.n_unknowns

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
        image: float = 1.0,
        image_jacobian: float = 1.0,
        roll_rate: float = 0.0,
        control: np.ndarray | None = None,
        direction: np.ndarray | None = None,
    ) -> np.ndarray:
        """(n_parameters,) from the wing's six station arrays (y, chord, elastic_axis, EI, GJ,
        jig_twist), its camber at the chordwise nodes (N, k + 1), alpha and sweep [deg], and the
        image's flow (module docstring; control (N, k + 1) [1/rad] and direction (n,), default
        zero)."""
        if control is None:
            control = np.zeros(self.n * (self.chordwise + 1))
        if direction is None:
            direction = np.zeros(self.n_unknowns)
        return np.concatenate(
            [
                *arrays,
                np.ravel(camber),
                [alpha_deg, sweep_deg, 1.0 if deformed_axis else 0.0],
                [image, image_jacobian, roll_rate],
                np.ravel(control),
                np.ravel(direction),
            ]
        )

    @property
    def alpha_index(self) -> int:
        """Where alpha [deg] sits in the parameter vector."""
        return 6 * self.n + self.n * (self.chordwise + 1)

    def split(self, p):  # type: ignore[no-untyped-def]
        """The parameter vector's parts (symbolic or numeric): y, chord, elastic_axis, EI, GJ,
        jig (N each), camber (N, k + 1), alpha, sweep, deformed_axis."""
        n, k1 = self.n, self.chordwise + 1
        parts = [p[i * n : (i + 1) * n] for i in range(6)]
        start = 6 * n
        camber = p[start : start + n * k1]
        end = start + n * k1
        return (*parts, camber, p[end], p[end + 1], p[end + 2])

    def split_flow(self, p):  # type: ignore[no-untyped-def]
        """The image's flow in the parameter vector (symbolic or numeric): image,
        image_jacobian, roll_rate [rad/m], control (N (k + 1)) [1/rad]."""
        start = self.alpha_index + 3
        end = start + 3 + self.n * (self.chordwise + 1)
        return p[start], p[start + 1], p[start + 2], p[start + 3 : end]

    @property
    def direction_slice(self) -> slice:
        """Where the direction in the unknowns (`parameters`) sits in the parameter vector."""
        return slice(self.n_parameters - self.n_unknowns, self.n_parameters)

    @property
    def roll_rate_index(self) -> int:
        """Where the roll rate p / V [rad/m] sits in the parameter vector."""
        return self.alpha_index + 5
