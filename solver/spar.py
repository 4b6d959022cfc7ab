"""A circular tube spar: the structure behind EI and GJ, and the stresses the loads put in it.

Per station, a thick-walled tube of outer diameter D and wall thickness t (inner diameter
d = D - 2t), in an isotropic material of Young's modulus E and shear modulus G:

    A = pi/4 (D^2 - d^2)        [m^2]   cross-section
    I = pi/64 (D^4 - d^4)       [m^4]   second moment of area (bending)
    J = 2 I = pi/32 (D^4 - d^4) [m^4]   polar moment (torsion of a circular tube)
    EI = E I,  GJ = G J         [N m^2]

(AeroSandbox's `TubeSparBendingStructure` with its mid-wall diameter D - t, OpenAeroStruct's
`SectionPropertiesTube` with radius D / 2: the same formulas.) At the outer fibre, where both
peak, a bending moment M and a torque T give

    bending stress sigma = M (D/2) / I,  torsional shear tau = T (D/2) / J,
    von Mises stress = sqrt(sigma^2 + 3 tau^2)     [Pa]

as OpenAeroStruct's `VonMisesTube` (the transverse shear's stress, zero at the outer fibre's
extreme, is left out there as here). The spar's mass is rho A integrated along the elastic axis.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from solver.errors import InvalidInput

__all__ = ["Material", "SparDesign", "SparStresses", "ThicknessFraction", "TubeSpar"]


def _positive_number(field: str, value: object) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float | np.floating | np.integer):
        raise InvalidInput(field, "must be a number")
    number = float(value)
    if not (math.isfinite(number) and number > 0):
        raise InvalidInput(field, "must be a positive, finite number")
    return number


@dataclass(frozen=True)
class Material:
    """An isotropic spar material.

    youngs_modulus: E [Pa]; shear_modulus: G [Pa]; density: [kg/m^3]; yield_stress: [Pa], the
    von Mises stress at which it yields. All positive.
    """

    youngs_modulus: float
    shear_modulus: float
    density: float
    yield_stress: float

    def __post_init__(self) -> None:
        for name in ("youngs_modulus", "shear_modulus", "density", "yield_stress"):
            _positive_number(f"material.{name}", getattr(self, name))


@dataclass(frozen=True)
class ThicknessFraction:
    """An outer diameter given as `fraction` (0 to 1] of each section's airfoil thickness
    (known for NACA 4-digit sections: the last two digits, percent of the chord)."""

    fraction: float

    def __post_init__(self) -> None:
        value = _positive_number("outer_diameter.fraction_of_thickness", self.fraction)
        if value > 1:
            raise InvalidInput(
                "outer_diameter.fraction_of_thickness", "must not exceed 1: the tube fits inside"
            )


@dataclass(frozen=True)
class SparDesign:
    """A spar as given: `outer_diameter` one number [m] for every station, N numbers, or a
    `ThicknessFraction`; `wall_thickness` one number or N [m]; `material`.
    `solver.Wing.create` resolves it into the wing's `TubeSpar`."""

    outer_diameter: object
    wall_thickness: object
    material: Material


@dataclass(frozen=True, eq=False)
class TubeSpar:
    """The spar of a wing: outer_diameter, wall_thickness: (N,) [m] per station; material."""

    outer_diameter: np.ndarray
    wall_thickness: np.ndarray
    material: Material

    def __post_init__(self) -> None:
        outer, wall = self.outer_diameter, self.wall_thickness
        if outer.shape != wall.shape or outer.ndim != 1:
            raise InvalidInput(
                "spar", "outer_diameter and wall_thickness need one value per station"
            )
        if not (np.all(np.isfinite(outer)) and np.all(outer > 0)):
            raise InvalidInput("spar.outer_diameter", "must be positive at every station")
        if not (np.all(np.isfinite(wall)) and np.all(wall > 0)):
            raise InvalidInput("spar.wall_thickness", "must be positive at every station")
        if np.any(2 * wall > outer):
            raise InvalidInput(
                "spar.wall_thickness", "must not exceed half the outer diameter (a solid rod)"
            )

    @property
    def inner_diameter(self) -> np.ndarray:
        """(N,) [m] d = D - 2 t."""
        return self.outer_diameter - 2 * self.wall_thickness

    @property
    def area(self) -> np.ndarray:
        """(N,) [m^2] cross-section of the wall."""
        return math.pi / 4 * (self.outer_diameter**2 - self.inner_diameter**2)

    @property
    def second_moment(self) -> np.ndarray:
        """(N,) [m^4] I."""
        return math.pi / 64 * (self.outer_diameter**4 - self.inner_diameter**4)

    @property
    def polar_moment(self) -> np.ndarray:
        """(N,) [m^4] J = 2 I."""
        return 2 * self.second_moment

    @property
    def bending_stiffness(self) -> np.ndarray:
        """(N,) [N m^2] EI."""
        return self.material.youngs_modulus * self.second_moment

    @property
    def torsional_stiffness(self) -> np.ndarray:
        """(N,) [N m^2] GJ."""
        return self.material.shear_modulus * self.polar_moment

    def mass(self, arc: np.ndarray) -> float:
        """[kg] of both halves: rho A integrated (trapezoids) over `arc` (N,) [m], the stations'
        distance from the root along the elastic axis."""
        area = self.area
        return float(2 * self.material.density * np.sum((area[1:] + area[:-1]) / 2 * np.diff(arc)))

    def stresses(self, bending_moment: np.ndarray, torque: np.ndarray) -> SparStresses:
        """The outer fibre's stresses under `bending_moment` and `torque` (N,) [N m]."""
        radius = self.outer_diameter / 2
        bending = bending_moment * radius / self.second_moment
        shear = torque * radius / self.polar_moment
        return SparStresses(bending, shear, np.sqrt(bending**2 + 3 * shear**2))

    @property
    def key(self) -> bytes:
        m = self.material
        numbers = [m.youngs_modulus, m.shear_modulus, m.density, m.yield_stress]
        return b"".join(
            np.ascontiguousarray(a + 0.0, dtype=np.float64).tobytes()
            for a in (self.outer_diameter, self.wall_thickness, np.array(numbers))
        )


@dataclass(frozen=True)
class SparStresses:
    """(N,) [Pa] at each station's outer fibre: bending, M (D/2) / I (positive where the moment
    bends the tip up: the lower fibre in tension, the upper in compression by as much);
    torsional shear, T (D/2) / J (the sign of the torque); von Mises, sqrt(bending^2 +
    3 shear^2)."""

    bending: np.ndarray
    shear: np.ndarray
    von_mises: np.ndarray
