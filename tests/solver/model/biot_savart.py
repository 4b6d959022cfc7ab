"""Independent references for the horseshoe kernels' tests: Biot-Savart's law for straight
vortex segments, written out with numpy."""

from __future__ import annotations

import numpy as np

__all__ = ["horseshoe", "segment"]


def segment(point: np.ndarray, start: np.ndarray, end: np.ndarray) -> np.ndarray:
    """Velocity at `point` of a unit-strength straight vortex segment start -> end (Biot-Savart,
    Katz & Plotkin eq. 10.115), per unit circulation."""
    r0, r1, r2 = end - start, point - start, point - end
    cross = np.cross(r1, r2)
    return (
        cross
        / (4 * np.pi * cross @ cross)
        * (r0 @ (r1 / np.linalg.norm(r1) - r2 / np.linalg.norm(r2)))
    )


def horseshoe(point, left, right, far=1e7):
    """Trailing leg in from +x infinity to `left`, bound leg to `right`, trailing leg out."""
    downstream = np.array([far, 0.0, 0.0])
    return (
        segment(point, left + downstream, left)
        + segment(point, left, right)
        + segment(point, right, right + downstream)
    )
