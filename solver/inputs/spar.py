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

from solver import fields
from solver.errors import InvalidInput
from solver.fields import parameter

__all__ = ["Material", "SparDesign", "SparStresses", "ThicknessFraction", "TubeSpar"]


@dataclass(frozen=True)
class Material:
    """An isotropic spar material (e.g. carbon-fibre tube: E 70 GPa, G 27 GPa, 1600 kg/m^3,
    yield 600 MPa; aluminium 7075: 71.7 GPa, 26.9 GPa, 2810 kg/m^3, 503 MPa)."""

    youngs_modulus: float = parameter(
        "Pa", "Young's modulus E", ge=1e6, le=1e13, why="foam to diamond", example=70e9
    )
    shear_modulus: float = parameter(
        "Pa", "shear modulus G", ge=1e6, le=1e13, why="foam to diamond", example=27e9
    )
    density: float = parameter(
        "kg/m^3", "density", ge=1.0, le=25000.0, why="foam to osmium", example=1600.0
    )
    yield_stress: float = parameter(
        "Pa",
        "von Mises stress at which it yields",
        ge=1e3,
        le=1e11,
        why="foam to the strongest fibres",
        example=600e6,
    )

    def __post_init__(self) -> None:
        for name, spec in fields.specs(Material).items():
            fields.number(name, getattr(self, name), spec)


@dataclass(frozen=True)
class ThicknessFraction:
    """The outer diameter as a fraction of each section's airfoil thickness (known for NACA
    4-digit sections: the last two digits, percent of the chord)."""

    fraction_of_thickness: float = parameter(
        "-",
        "outer diameter over the airfoil's thickness",
        ge=0.01,
        le=1.0,
        why="the tube fits inside the section",
        example=0.8,
    )

    def __post_init__(self) -> None:
        with fields.prefixed("outer_diameter"):
            spec = fields.spec_of(ThicknessFraction, "fraction_of_thickness")
            fields.number("fraction_of_thickness", self.fraction_of_thickness, spec)

    @property
    def fraction(self) -> float:
        return self.fraction_of_thickness


@dataclass(frozen=True)
class SparDesign:
    """A circular tube spar as given, per station: EI = E pi/64 (D^4 - d^4), GJ = G pi/32
    (D^4 - d^4) with d = D - 2t (thick-walled); stresses at the outer fibre and the spar's mass
    are reported. `solver.Wing.create` resolves it into the wing's `TubeSpar`."""

    outer_diameter: object = parameter(
        "m",
        "outer diameter D: one number for every station, N values, or {fraction_of_thickness} "
        "of a NACA 4-digit section's thickness",
        ge=1e-4,
        le=10.0,
        why="a model's carbon rod to a bridge girder",
        form="diameter",
        given=ThicknessFraction,
        example=0.04,
    )
    wall_thickness: object = parameter(
        "m",
        "wall thickness t, at most D / 2 (a solid rod)",
        ge=1e-5,
        le=5.0,
        why="10 micrometres to a solid 10 m rod",
        per_station=True,
        example=0.001,
    )
    material: Material = parameter("", "the spar's material", form="nested", given=Material)

    def __post_init__(self) -> None:
        if not isinstance(self.material, Material):
            raise InvalidInput("material", "must be a solver.Material")


@dataclass(frozen=True, eq=False)
class TubeSpar:
    """The spar of a wing: outer_diameter, wall_thickness: (N,) [m] per station; material."""

    outer_diameter: np.ndarray
    wall_thickness: np.ndarray
    material: Material

    def __post_init__(self) -> None:
        # Read-only copies: a wing and its digest never change under it (`fields.digested_once`).
        for name in ("outer_diameter", "wall_thickness"):
            array = np.array(getattr(self, name), dtype=float)
            array.setflags(write=False)
            object.__setattr__(self, name, array)
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

    def stresses(
        self,
        bending_moment: np.ndarray,
        torque: np.ndarray,
        lag_bending_moment: np.ndarray | None = None,
        in_plane_bending_stiffness: np.ndarray | None = None,
    ) -> SparStresses:
        """The outer fibre's stresses under the section's `bending_moment` and `torque` (N,)
        [N m], and with lag bending its in-plane moment `lag_bending_moment` (N,) [N m] of a
        section whose in-plane stiffness is `in_plane_bending_stiffness` (N,) [N m^2]: the
        section bends in its plane as one, so the tube carries EI_tube / EI_lag of that
        moment (its own in-plane curvature's), and on a round tube the two bending stresses
        add as a vector at the outer fibre."""
        radius = self.outer_diameter / 2
        bending = bending_moment * radius / self.second_moment
        shear = torque * radius / self.polar_moment
        across = np.zeros_like(bending)
        if lag_bending_moment is not None and in_plane_bending_stiffness is not None:
            share = self.bending_stiffness / np.asarray(in_plane_bending_stiffness, dtype=float)
            across = share * lag_bending_moment * radius / self.second_moment
        return SparStresses(bending, shear, np.sqrt(bending**2 + across**2 + 3 * shear**2))


@dataclass(frozen=True)
class SparStresses:
    """(N,) [Pa] at each station's outer fibre: bending, M (D/2) / I (positive where the moment
    bends the tip up: the lower fibre in tension, the upper in compression by as much);
    torsional shear, T (D/2) / J (the sign of the torque); von Mises, sqrt(bending^2 +
    3 shear^2), with lag bending sqrt(bending^2 + in-plane bending^2 + 3 shear^2)."""

    bending: np.ndarray
    shear: np.ndarray
    von_mises: np.ndarray
