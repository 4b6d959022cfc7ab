"""The horseshoe vortex's induced velocity, in numbers: the static model's kernel
(`solver.model.vlm`, AeroSandbox's and Drela's form) for arrays of field points and vortices.

A horseshoe of unit circulation has its bound leg from A to B and two trailing legs from B and
from A to +x infinity (geometry axes). With a = P - A, b = P - B and u = (1, 0, 0):

    v = 1/(4 pi) [ (a x b)(1/|a| + 1/|b|) / (|a||b| + a.b) + (a x u)/(|a|(|a| - a.u))
                   - (b x u)/(|b|(|b| - b.u)) ]

A field point on the bound leg itself sees none of it (the static model's `bound_weight`);
the symmetric flow's image of the right half's horseshoe is the mirror one from m(B) to m(A),
m = diag(1, -1, 1), with the same circulation.
"""

from __future__ import annotations

import numpy as np

__all__ = ["horseshoe_velocity", "mirror", "symmetric_horseshoe_velocity"]

_INV_4PI = 1.0 / (4.0 * np.pi)
# A field point this close to a bound leg, relative to the leg's end distances, is on it.
_ON_THE_LEG = 1e-12


def mirror(points: np.ndarray) -> np.ndarray:
    """(..., 3) the points mirrored in the plane y = 0."""
    image = np.array(points, dtype=float, copy=True)
    image[..., 1] *= -1.0
    return image


def horseshoe_velocity(field: np.ndarray, left: np.ndarray, right: np.ndarray) -> np.ndarray:
    """(..., 3) [1/m] the velocity per unit circulation at `field` of the horseshoe from `left`
    (A) to `right` (B), all (..., 3) [m], broadcast together."""
    a = field - left
    b = field - right
    norm_a = np.sqrt(np.einsum("...c,...c->...", a, a))
    norm_b = np.sqrt(np.einsum("...c,...c->...", b, b))
    denominator = norm_a * norm_b + np.einsum("...c,...c->...", a, b)
    on_leg = np.abs(denominator) <= _ON_THE_LEG * norm_a * norm_b
    safe = np.where(on_leg, 1.0, denominator)
    bound = np.where(on_leg, 0.0, (1.0 / norm_a + 1.0 / norm_b) / safe)
    trailing_a = 1.0 / (norm_a * (norm_a - a[..., 0]))
    trailing_b = 1.0 / (norm_b * (norm_b - b[..., 0]))
    velocity = bound[..., None] * np.cross(a, b)
    velocity[..., 1] += trailing_a * a[..., 2] - trailing_b * b[..., 2]
    velocity[..., 2] += -trailing_a * a[..., 1] + trailing_b * b[..., 1]
    return velocity * _INV_4PI


def symmetric_horseshoe_velocity(
    field: np.ndarray, left: np.ndarray, right: np.ndarray
) -> np.ndarray:
    """`horseshoe_velocity` of the right half's horseshoe and its mirror image (the symmetric
    flow of both halves, the static model's)."""
    return horseshoe_velocity(field, left, right) + horseshoe_velocity(
        field, mirror(right), mirror(left)
    )
