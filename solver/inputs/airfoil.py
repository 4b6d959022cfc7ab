"""Camber lines of airfoil sections: what chordwise panels see of an airfoil.

A camber line gives camber / chord at x / chord from the leading edge (0) to the trailing edge
(1). Two kinds: a NACA 4-digit designation ("naca4412": its analytic mean line, maximum camber m
= 4 % at p = 40 % of the chord; "naca0012" and other symmetric sections have none), or a table of
points, linear between them. With one chordwise panel only x = 0 and 1 matter, where NACA 4-digit
lines, the study's DAE-11 and any symmetric section have no camber: the section is a flat plate.

AeroSandbox builds its camber from generated airfoil coordinates, not the analytic line: its
"naca4412" has camber 0.0030 at the leading edge, which moves lift ~1 % and the root torque by
more. To match it, give its camber at the chordwise nodes as a table (tests/reference).
"""

from __future__ import annotations

import re
from dataclasses import dataclass

import numpy as np

from solver.errors import InvalidInput

__all__ = ["CamberLine", "MAX_CAMBER", "camber_line"]

MAX_CAMBER = 0.2  # [-] of the chord: a thin-airfoil lattice means nothing beyond
_NACA = re.compile(r"^naca(\d)(\d)(\d\d)$")


@dataclass(frozen=True, eq=False)
class CamberLine:
    """camber / chord at x / chord, linear between `x` (0 to 1, increasing) and `camber`; or,
    for a NACA 4-digit line, exact at any x (`naca` holds m, p)."""

    x: np.ndarray
    camber: np.ndarray
    naca: tuple[float, float] | None = None
    thickness: float | None = None  # [-] of the chord, when known (NACA 4-digit)

    def __post_init__(self) -> None:
        # Read-only copies: a wing and its digest never change under it (`fields.digested_once`).
        for name in ("x", "camber"):
            array = np.array(getattr(self, name), dtype=float)
            array.setflags(write=False)
            object.__setattr__(self, name, array)

    def at(self, x: np.ndarray) -> np.ndarray:
        """camber / chord at x / chord [-]."""
        x = np.asarray(x, dtype=float)
        if self.naca is not None:
            m, p = self.naca
            if m == 0 or p == 0:
                return np.zeros_like(x)
            fore = m / p**2 * (2 * p * x - x**2)
            aft = m / (1 - p) ** 2 * ((1 - 2 * p) + 2 * p * x - x**2)
            return np.where(x < p, fore, aft)
        return np.interp(x, self.x, self.camber)

    @property
    def key(self) -> bytes:
        return np.concatenate([self.x, self.camber]).tobytes() + repr(self.naca).encode()


FLAT = CamberLine(np.array([0.0, 1.0]), np.zeros(2))


def camber_line(spec: object, field: str = "airfoil") -> CamberLine:
    """A camber line from None (flat), "nacaXXXX", or {"x": [...], "camber": [...]}."""
    if spec is None:
        return FLAT
    if isinstance(spec, CamberLine):
        return spec
    if isinstance(spec, str):
        match = _NACA.match(spec.strip().lower())
        if match is None:
            raise InvalidInput(field, f"{spec!r} is not a NACA 4-digit designation like 'naca4412'")
        m, p = int(match.group(1)) / 100, int(match.group(2)) / 10
        thickness = int(match.group(3)) / 100
        if (m == 0) != (p == 0):
            raise InvalidInput(field, f"{spec!r}: camber and its position must be both zero or not")
        return CamberLine(np.array([0.0, 1.0]), np.zeros(2), (m, p), thickness or None)
    if isinstance(spec, dict) and set(spec) == {"x", "camber"}:
        try:
            x = np.asarray(spec["x"], dtype=float)
            camber = np.asarray(spec["camber"], dtype=float)
        except (TypeError, ValueError):
            raise InvalidInput(field, "x and camber must be lists of numbers") from None
        if x.ndim != 1 or x.shape != camber.shape or x.size < 2:
            raise InvalidInput(field, "x and camber must be lists of one length, at least 2")
        if not (np.all(np.isfinite(x)) and np.all(np.isfinite(camber))):
            raise InvalidInput(field, "x and camber must be finite numbers")
        if x[0] != 0.0 or x[-1] != 1.0 or not np.all(np.diff(x) > 0):
            raise InvalidInput(field, "x must increase strictly from 0 to 1 (fractions of chord)")
        if np.max(np.abs(camber)) > MAX_CAMBER:
            raise InvalidInput(field, f"camber must lie within +-{MAX_CAMBER:g} of the chord")
        x.setflags(write=False)
        camber.setflags(write=False)
        return CamberLine(x, camber)
    raise InvalidInput(field, "must be null, a NACA 4-digit designation or {x, camber}")
