"""The wing's mass: what its vibration and flutter need beyond the static model.

Per station, like the stiffnesses, and per unit length along the elastic axis (EA):

    mass_per_length      m      [kg/m]
    center_of_gravity    x_cg   [-]     fraction of the chord from the leading edge
    inertia_per_length   I_cg   [kg m]  the section's mass moment of inertia about its own
                                        centre of gravity, about an axis parallel to the EA

The inertia is stated about the centre of gravity because that is the section's own property:
moving the spar (the EA) leaves it unchanged, and the model adds the parallel-axis term itself,
exactly as for a concentrated mass. Published beam data are often about the EA; subtract
m d^2, d the centre of gravity's distance from the EA. The Goland wing's 8.64 kg m is about its
EA (Goland 1945, as tabulated by Eastep and by Bisplinghoff, Ashley and Halfman: a radius of
gyration of 25 % chord about the centre of gravity, which lies 10 % chord behind the EA):
8.64 - 35.71 (0.1 c)^2 = 7.45 kg m about the centre of gravity, r = 0.2497 c.

Concentrated masses (a tip store, an engine, a balance weight) sit at a station: mass [kg],
mass moment of inertia about their own centre of gravity [kg m^2] (about an axis parallel to the
EA), and the distance of that centre of gravity aft of the EA [m].

With a tube spar (`solver.inputs.spar.TubeSpar`) the distributed mass given here is everything but
the spar (the non-structural mass); the spar's own mass, density times its wall's area, is added on
the EA (a circular tube's centroid is its shear centre), with its polar inertia density times
pi/32 (D^4 - d^4).

On a swept wing the centre of gravity's offset from the EA is taken normal to the axis in the
wing plane, (x_cg - x_ea) c cos(sweep) for streamwise chords c.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from solver.errors import InvalidInput
from solver.fields import number, parameter, spec_of, specs, stations
from solver.inputs.spar import TubeSpar

__all__ = ["ConcentratedMass", "MassModel", "SectionInertia", "section_inertia"]


@dataclass(frozen=True)
class ConcentratedMass:
    """A mass attached at one station (a store, an engine, a balance weight)."""

    station: int = parameter(
        "-",
        "index of the station it is attached at (0 is the clamped root, where it never moves)",
        ge=0,
        why="an index into the stations",
        form="integer",
        example=29,
    )
    mass: float = parameter(
        "kg", "its mass", gt=0, why="a concentrated mass of no mass is no mass", example=50.0
    )
    inertia: float = parameter(
        "kg m^2",
        "its mass moment of inertia about its own centre of gravity, about an axis parallel to "
        "the elastic axis",
        ge=0,
        why="a moment of inertia is a sum of mass times squared distance",
        example=5.0,
    )
    offset: float = parameter(
        "m",
        "distance of its centre of gravity aft of the elastic axis (ahead of it: negative)",
        example=0.2,
    )

    @classmethod
    def create(
        cls, station: object, mass: object, inertia: object, offset: object, path: str = ""
    ) -> ConcentratedMass:
        """Validated: every field a finite number within its limits, `station` a whole number."""
        index = number(f"{path}station", station, spec_of(cls, "station"))
        if index != int(index):
            raise InvalidInput(f"{path}station", "must be a whole number (a station's index)")
        return cls(
            int(index),
            number(f"{path}mass", mass, spec_of(cls, "mass")),
            number(f"{path}inertia", inertia, spec_of(cls, "inertia")),
            number(f"{path}offset", offset, spec_of(cls, "offset")),
        )


@dataclass(frozen=True, eq=False)
class MassModel:
    """The wing's distributed mass per station, and its concentrated masses (module docstring).

    Arrays are (N,), one value per station, per unit length along the elastic axis."""

    mass_per_length: np.ndarray = parameter(
        "kg/m",
        "mass per unit length along the elastic axis (with a spar: everything but the spar, "
        "whose own mass is added)",
        ge=0,
        why="a negative mass has no meaning",
        per_station=True,
        example=35.71,
    )
    center_of_gravity: np.ndarray = parameter(
        "-",
        "the section's centre of gravity, as a fraction of the chord from the leading edge",
        ge=0,
        le=1,
        why="a section's centre of gravity lies within it; a mass beyond its chord is a "
        "concentrated mass",
        per_station=True,
        example=0.43,
    )
    inertia_per_length: np.ndarray = parameter(
        "kg m",
        "the section's mass moment of inertia per unit length about its own centre of "
        "gravity, about an axis parallel to the elastic axis (about the elastic axis: subtract "
        "mass_per_length times the squared distance between the two)",
        ge=0,
        why="a moment of inertia is a sum of mass times squared distance",
        per_station=True,
        example=7.45,
    )
    concentrated: tuple[ConcentratedMass, ...] = parameter(
        "",
        "concentrated masses (a tip store, an engine, a balance weight), each at a station",
        form="items",
        given=ConcentratedMass,
        default=(),
    )

    @classmethod
    def create(
        cls,
        n_stations: int,
        mass_per_length: object,
        center_of_gravity: object,
        inertia_per_length: object,
        concentrated: Sequence[ConcentratedMass] = (),
        path: str = "mass.",
    ) -> MassModel:
        """Validated for a wing of `n_stations` stations: each array one number for every
        station or N numbers, within its limits; `concentrated` at stations of the wing."""
        arrays = {
            name: stations(f"{path}{name}", value, n_stations, spec_of(cls, name))
            for name, value in (
                ("mass_per_length", mass_per_length),
                ("center_of_gravity", center_of_gravity),
                ("inertia_per_length", inertia_per_length),
            )
        }
        masses = tuple(concentrated or ())
        for i, item in enumerate(masses):
            where = f"{path}concentrated[{i}]"
            if not isinstance(item, ConcentratedMass):
                raise InvalidInput(where, "must be a solver.ConcentratedMass")
            if item.station >= n_stations:
                raise InvalidInput(
                    f"{where}.station", f"must be below {n_stations}, the number of stations"
                )
        return cls(**arrays, concentrated=masses)

    @classmethod
    def resolved(cls, given: MassModel | Mapping[str, Any], n_stations: int) -> MassModel:
        """The mass model of a wing of `n_stations`, from its fields as given (a mapping: a
        request's, built here once) or a `MassModel` (kept when `create` made it for these
        stations, else checked and normalised as one)."""
        if isinstance(given, Mapping):
            unknown = set(given) - set(specs(cls))
            if unknown:
                raise InvalidInput(f"mass.{sorted(unknown)[0]}", "is not a mass input")
            return cls.create(n_stations, **given)
        if not isinstance(given, MassModel):
            raise InvalidInput("mass", "must be a solver.MassModel")
        if given._made_for(n_stations):
            return given
        return cls.create(
            n_stations,
            given.mass_per_length,
            given.center_of_gravity,
            given.inertia_per_length,
            given.concentrated,
        )

    def _made_for(self, n_stations: int) -> bool:
        """`create` made it for `n_stations` (its arrays normalised: read-only, N values)."""
        arrays = (self.mass_per_length, self.center_of_gravity, self.inertia_per_length)
        return all(
            isinstance(a, np.ndarray) and a.shape == (n_stations,) and not a.flags.writeable
            for a in arrays
        )


@dataclass(frozen=True)
class SectionInertia:
    """The sections' inertia about the elastic axis, per station, spar included.

    mass: (N,) [kg/m]; static_moment: (N,) [kg] mass times the centre of gravity's distance
    aft of the elastic axis; inertia: (N,) [kg m] mass moment of inertia about the elastic
    axis; all per unit length along it.
    """

    mass: np.ndarray
    static_moment: np.ndarray
    inertia: np.ndarray


def section_inertia(
    mass: MassModel,
    chord: np.ndarray,
    elastic_axis: np.ndarray,
    sweep_deg: float = 0.0,
    spar: TubeSpar | None = None,
) -> SectionInertia:
    """The sections' inertia about the elastic axis (`SectionInertia`) of a wing of streamwise
    `chord` (N,) [m], `elastic_axis` (N,) [-] fraction of chord, `sweep_deg` [deg], with its
    `spar` or None. Raises `InvalidInput` where a section would have no mass or no inertia
    about its centre of gravity (its motion would need no force: no finite frequency)."""
    offset = (mass.center_of_gravity - elastic_axis) * chord * math.cos(math.radians(sweep_deg))
    total = mass.mass_per_length.astype(float)
    static_moment = total * offset
    inertia = mass.inertia_per_length + total * offset**2
    if spar is not None:
        density = spar.material.density
        total = total + density * spar.area
        inertia = inertia + density * spar.polar_moment  # the tube turns about its own axis
    if not np.all(total > 0):
        raise InvalidInput(
            "mass.mass_per_length", "must be positive at every station (with the spar's own)"
        )
    # m I_ea - S^2 = m I_cg: positive when the section has inertia about its centre of gravity.
    if not np.all(total * inertia - static_moment**2 > 0):
        raise InvalidInput(
            "mass.inertia_per_length",
            "must be positive at every station (with the spar's own): a section without "
            "inertia about its centre of gravity turns without torque",
        )
    return SectionInertia(total, static_moment, inertia)
