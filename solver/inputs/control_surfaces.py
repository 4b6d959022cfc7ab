"""Control surfaces: flaps and ailerons, as the deflected camber line aft of a hinge.

A surface is a plain, sealed flap: the part of each section aft of the hinge line (a fraction of
the chord) turned trailing edge down by its deflection. The lattice sees a section only through
the camber at its chordwise nodes, so a surface is modelled as the change it makes there:

    d(camber / chord)(x) = -(x - hinge) tan(deflection)   for x > hinge, else 0,

the flap's chord line turned about the hinge and sampled at fixed x / chord, so that the flap's
panels meet the flow exactly at the deflection. A flap deflects alike on both wings (the
symmetric problem: every existing operation sees it through `Wing.camber_at`); an aileron
deflects the other way on the left wing, trailing edge up there for a positive deflection (the
antisymmetric problem, `solver.roll`).

Two discretisation rules, both exact for the geometry the lattice can represent:

- Chordwise: the camber is sampled at the nodes x_j. A hinge on a node is a sharp hinge line;
  a hinge between nodes x_a < hinge < x_b tilts the panel between them by the fraction
  (x_b - hinge) / (x_b - x_a) of the deflection (the sampled line is linear in the hinge
  position in between). A surface needs at least one whole panel aft of its hinge: a hinge aft
  of the last interior node x_{k-1} is refused, and so is any surface at k = 1 (a single panel
  cannot carry a camber line: the deflection would only turn its chord).
- Spanwise: the camber lives at the stations and the lattice blends it linearly across each
  strip. Station i carries the deflection times the fraction of its tributary span (from the
  midpoint of the strip inboard to that of the strip outboard; from the root, to the tip) that
  the surface covers. The blended deflection then has the surface's exact deflected area,
  integral of deflection dy = deflection (end - start), on any mesh, and moves continuously as
  an edge crosses a station; an edge on a station gives that station half the deflection.

Everything here is geometry: no CasADi, no solves.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, fields
from typing import Literal

import numpy as np

from solver.errors import InvalidInput
from solver.fields import number, parameter, spec_of

__all__ = [
    "MAX_DEFLECTION",
    "ControlSurface",
    "antisymmetric_camber",
    "camber_rate",
    "validate_surfaces",
    "hinge_nodes",
    "station_weights",
    "strip_weights",
    "symmetric_camber",
]

MAX_DEFLECTION = 25.0  # [deg] see ControlSurface.deflection
_MAX_NAME = 64
# [-] of the chord: a hinge this close to a node is on it (cosine nodes carry round-off: the
# k = 3 node at 0.75 is 0.7499999999999999).
_ON_NODE = 1e-12


@dataclass(frozen=True)
class ControlSurface:
    """One control surface of the right wing (the left wing's is its image).

    Attributes:
        name: how answers refer to it (unique on the wing).
        start, end: [-] of the semispan (`extent_unit` "fraction", default) or [m] from the root
            ("m"): its spanwise extent, 0 <= start < end <= the semispan.
        extent_unit: "fraction" or "m".
        hinge: [-] hinge line as a fraction of the chord from the leading edge, 0 < hinge < 1.
        deflection: [deg] trailing edge down positive, |deflection| <= 25.
        kind: "flap" (both wings alike: symmetric) or "aileron" (the left wing's the other way,
            trailing edge up there for a positive deflection: antisymmetric).
    """

    name: str = parameter(
        "",
        "how answers refer to the surface; unique on the wing",
        le=_MAX_NAME,
        why="a name, not a text",
        form="text",
        example="aileron",
    )
    start: float = parameter(
        "-",
        "inboard edge, as a fraction of the semispan or in metres from the root (extent_unit)",
        ge=0.0,
        why="it must lie on the wing",
    )
    end: float = parameter(
        "-",
        "outboard edge, as a fraction of the semispan or in metres from the root (extent_unit)",
        gt=0.0,
        why="it must lie on the wing, outboard of start",
    )
    extent_unit: Literal["fraction", "m"] = parameter(
        "",
        "what start and end are: fractions of the semispan, or metres from the root",
        form="choice",
        choices=("fraction", "m"),
        default="fraction",
    )
    hinge: float = parameter(
        "-",
        "hinge line, as a fraction of the chord from the leading edge",
        gt=0.0,
        lt=1.0,
        why="a hinge at the leading edge turns the whole section (that is twist, not a "
        "control surface); one at the trailing edge leaves the surface no chord",
        default=0.75,
    )
    deflection: float = parameter(
        "deg",
        "deflection, trailing edge down positive (an aileron's left-wing surface deflects the "
        "other way)",
        ge=-MAX_DEFLECTION,
        le=MAX_DEFLECTION,
        why="a plain flap's lift stops growing linearly past about 10 to 15 deg and the flow "
        "separates from it well before 25 deg, where the lattice's lift keeps growing linearly "
        "(empirical flap-effectiveness corrections, e.g. USAF DATCOM 6.1.1.1); the sampled "
        "camber line tan(deflection) also departs 7 % from the angle there",
        default=0.0,
    )
    kind: Literal["flap", "aileron"] = parameter(
        "",
        "flap: both wings deflect alike (symmetric); aileron: the left wing's deflects the "
        "other way (antisymmetric; trailing edge up on the left for a positive deflection)",
        form="choice",
        choices=("flap", "aileron"),
        default="flap",
    )

    def __post_init__(self) -> None:
        if not isinstance(self.name, str) or not self.name.strip():
            raise InvalidInput("name", "must be a non-empty string")
        if len(self.name) > _MAX_NAME:
            raise InvalidInput("name", f"must be at most {_MAX_NAME} characters")
        if self.extent_unit not in ("fraction", "m"):
            raise InvalidInput("extent_unit", "must be 'fraction' or 'm'")
        if self.kind not in ("flap", "aileron"):
            raise InvalidInput("kind", "must be 'flap' or 'aileron'")
        for name in ("start", "end", "hinge", "deflection"):
            value = number(name, getattr(self, name), spec_of(ControlSurface, name))
            object.__setattr__(self, name, value)
        if self.extent_unit == "fraction" and self.end > 1.0:
            raise InvalidInput("end", "must be at most 1 (a fraction of the semispan)")
        if not self.start < self.end:
            raise InvalidInput("end", "must lie outboard of start")

    @classmethod
    def create(cls, spec: ControlSurface | Mapping[str, object]) -> ControlSurface:
        """A surface from itself or from a mapping of its fields (as a request gives it)."""
        if isinstance(spec, ControlSurface):
            return spec
        if not isinstance(spec, Mapping):
            raise InvalidInput("", "must be a control surface (an object of its fields)")
        known = {f.name for f in fields(cls)}
        unknown = sorted(set(spec) - known)
        if unknown:
            raise InvalidInput(unknown[0], "is not a field of a control surface")
        if "name" not in spec or "start" not in spec or "end" not in spec:
            missing = next(k for k in ("name", "start", "end") if k not in spec)
            raise InvalidInput(missing, "is required")
        return cls(**spec)  # type: ignore[arg-type]

    @property
    def symmetric(self) -> bool:
        """A flap: both wings deflect alike."""
        return self.kind == "flap"

    def extent(self, semispan: float) -> tuple[float, float]:
        """[m] (start, end) from the root."""
        scale = semispan if self.extent_unit == "fraction" else 1.0
        return self.start * scale, self.end * scale

    @property
    def key(self) -> bytes:
        numbers = np.array([self.start, self.end, self.hinge, self.deflection]) + 0.0
        return f"{self.name}\0{self.extent_unit}\0{self.kind}\0".encode() + numbers.tobytes()


def validate_surfaces(specs: object, y: np.ndarray) -> tuple[ControlSurface, ...]:
    """The wing's surfaces, validated against its stations y (N,) [m]: each on the wing, names
    unique, no two overlapping. Errors name `control_surfaces[i].field`."""
    if specs is None:
        return ()
    if not isinstance(specs, Sequence) or isinstance(specs, str | bytes):
        raise InvalidInput("control_surfaces", "must be a list of control surfaces")
    surfaces = []
    for i, spec in enumerate(specs):
        try:
            surfaces.append(ControlSurface.create(spec))  # type: ignore[arg-type]
        except InvalidInput as error:
            path = f"control_surfaces[{i}]" + (f".{error.field}" if error.field else "")
            raise InvalidInput(path, error.reason) from None
    semispan = float(y[-1])
    for i, surface in enumerate(surfaces):
        _, end = surface.extent(semispan)
        if end > semispan * (1 + 1e-12):
            raise InvalidInput(
                f"control_surfaces[{i}].end",
                f"lies at {end:g} m, beyond the tip ({semispan:g} m): a surface must lie on the "
                "wing",
            )
        for j, other in enumerate(surfaces[:i]):
            if other.name == surface.name:
                raise InvalidInput(
                    f"control_surfaces[{i}].name", f"repeats control_surfaces[{j}]'s name"
                )
            if _overlap(surface.extent(semispan), other.extent(semispan)):
                raise InvalidInput(
                    f"control_surfaces[{i}].start",
                    f"overlaps control_surfaces[{j}] ({other.name!r}): one part of a wing "
                    "carries one surface",
                )
    return tuple(surfaces)


def _overlap(a: tuple[float, float], b: tuple[float, float]) -> bool:
    """Open intervals that share more than an edge (to round-off of the semispan)."""
    shared = min(a[1], b[1]) - max(a[0], b[0])
    return shared > 1e-12 * max(abs(a[1]), abs(b[1]), 1.0)


def station_weights(surface: ControlSurface, y: np.ndarray) -> np.ndarray:
    """(N,) [-] the fraction of each station's tributary span that `surface` covers: the share
    of its deflection the station carries (module docstring)."""
    start, end = surface.extent(float(y[-1]))
    middles = (y[1:] + y[:-1]) / 2
    lower = np.concatenate([[y[0]], middles])
    upper = np.concatenate([middles, [y[-1]]])
    covered = np.clip(np.minimum(upper, end) - np.maximum(lower, start), 0.0, None)
    return covered / (upper - lower)


def strip_weights(surface: ControlSurface, y: np.ndarray) -> np.ndarray:
    """(N-1,) [-] the fraction of each strip's span that `surface` covers."""
    start, end = surface.extent(float(y[-1]))
    covered = np.clip(np.minimum(y[1:], end) - np.maximum(y[:-1], start), 0.0, None)
    return covered / np.diff(y)


def hinge_nodes(x: np.ndarray) -> float:
    """[-] the aftmost hinge the chordwise nodes x (k + 1,) can carry: the last interior node
    (no hinge at all for k = 1)."""
    return float(x[-2]) if x.size > 2 else 0.0


def check_resolution(surfaces: Sequence[ControlSurface], x: np.ndarray) -> None:
    """Refuses (InvalidInput naming `control_surfaces[i].hinge`) a surface whose hinge the
    chordwise nodes x (k + 1,) [-] leave no whole panel aft of: its camber line would vanish."""
    for index, surface in enumerate(surfaces):
        _check_resolution(surface, index, x)


def _check_resolution(surface: ControlSurface, index: int, x: np.ndarray) -> None:
    aftmost = hinge_nodes(x)
    if surface.hinge > aftmost + _ON_NODE:
        k = x.size - 1
        needed = _panels_for(surface.hinge)
        fix = (
            f"use chordwise_panels >= {needed}"
            if needed is not None
            else "move the hinge forward (no lattice of up to 8 panels resolves it)"
        )
        raise InvalidInput(
            f"control_surfaces[{index}].hinge",
            f"at {surface.hinge:g} of the chord leaves no whole chordwise panel aft of it with "
            f"{k} panel{'s' if k > 1 else ''} per strip (the last interior node is at "
            f"{aftmost:.4g}): the lattice could not carry its camber line; {fix}",
        )


def _panels_for(hinge: float) -> int | None:
    """The fewest cosine-spaced chordwise panels (<= 8) whose last interior node is aft of or
    at `hinge`."""
    for k in range(2, 9):
        if 0.5 - 0.5 * math.cos(math.pi * (k - 1) / k) + _ON_NODE >= hinge:
            return k
    return None


def _shape(surface: ControlSurface, x: np.ndarray) -> np.ndarray:
    """(k + 1,) [-] d(camber / chord) per unit tan(deflection) at the nodes x."""
    return -np.clip(x - surface.hinge, 0.0, None)


def _camber(
    surfaces: Sequence[ControlSurface], y: np.ndarray, x: np.ndarray, symmetric: bool
) -> np.ndarray:
    change = np.zeros((y.shape[0], x.shape[0]))
    for i, surface in enumerate(surfaces):
        if surface.symmetric != symmetric:
            continue
        _check_resolution(surface, i, x)
        tangent = math.tan(math.radians(surface.deflection))
        change += np.outer(station_weights(surface, y), tangent * _shape(surface, x))
    return change


def symmetric_camber(
    surfaces: Sequence[ControlSurface], y: np.ndarray, x: np.ndarray
) -> np.ndarray:
    """(N, len(x)) [-] what the flaps add to camber / chord at the nodes x of every station
    (the right wing's, and the left wing's alike). Refuses a flap the nodes cannot carry."""
    return _camber(surfaces, y, x, symmetric=True)


def antisymmetric_camber(
    surfaces: Sequence[ControlSurface], y: np.ndarray, x: np.ndarray
) -> np.ndarray:
    """(N, len(x)) [-] what the ailerons add to the right wing's camber / chord at the nodes x
    (the left wing's is its negative). Refuses an aileron the nodes cannot carry."""
    return _camber(surfaces, y, x, symmetric=False)


def camber_rate(
    surfaces: Sequence[ControlSurface], index: int, y: np.ndarray, x: np.ndarray
) -> np.ndarray:
    """(N, len(x)) [1/rad] d(camber / chord)/d(deflection) of surface `index` at its current
    deflection, at the nodes x of the right wing's stations."""
    surface = surfaces[index]
    _check_resolution(surface, index, x)
    secant = 1.0 / math.cos(math.radians(surface.deflection)) ** 2  # d tan / d angle
    return np.outer(station_weights(surface, y), secant * _shape(surface, x))
