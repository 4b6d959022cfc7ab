"""Hinge moments: the moment of a control surface's aft panels' loads about its hinge line, and
each surface's moment with its derivative by its deflection (the loads shifted by their
linearised change)."""

from __future__ import annotations

import numpy as np

from solver.inputs.control_surfaces import strip_weights
from solver.inputs.wing import Wing
from solver.results.controls import HingeMoment
from solver.statics.loads import PanelLoads

__all__ = ["hinge_moments", "hinge_pairs"]


def _shifted(loads: PanelLoads, change: PanelLoads, sign: float) -> PanelLoads:
    """loads + sign * change: a wing's loads and geometry, linearised (both with leading
    edges)."""
    assert loads.leading_edge is not None and change.leading_edge is not None
    return PanelLoads(
        loads.force + sign * change.force,
        loads.torque + sign * change.torque,
        loads.center + sign * change.center,
        loads.quarter_chord + sign * change.quarter_chord,
        loads.leading_edge + sign * change.leading_edge,
    )


def hinge_moments(wing: Wing, loads: PanelLoads, k: int) -> np.ndarray:
    """(surfaces,) [N m] the right half's hinge moment of each surface: the moment of the
    forces of the panels whose force points lie aft of the hinge line about that line, on the
    strips the surface covers (each weighted by the share of its span covered), trailing edge
    down positive. The hinge line of a strip runs between its stations' hinge points, at the
    hinge's fraction of the chord along each deformed chord line."""
    if loads.leading_edge is None:
        raise ValueError("hinge moments need the flow model's panel loads (leading edges)")
    chord_axis = (loads.quarter_chord - loads.leading_edge) / (0.25 * wing.chord)
    moments = np.zeros(len(wing.control_surfaces))
    for index, surface in enumerate(wing.control_surfaces):
        hinge = loads.leading_edge + surface.hinge * wing.chord * chord_axis  # (3, N)
        covered = strip_weights(surface, wing.y)
        total = 0.0
        for strip in np.flatnonzero(covered):
            a, b = hinge[:, strip], hinge[:, strip + 1]
            axis = (b - a) / np.linalg.norm(b - a)
            middle = (a + b) / 2
            chord_direction = (chord_axis[:, strip] + chord_axis[:, strip + 1]) / 2
            for panel in range(strip * k, strip * k + k):
                arm = loads.center[:, panel] - middle
                if arm @ chord_direction <= 0:
                    continue  # ahead of the hinge line: the fixed part of the section
                total += covered[strip] * float(np.cross(arm, loads.force[:, panel]) @ axis)
        moments[index] = total
    return moments


# The fraction of the linearised change at which its hinge moments are central-differenced:
# the moment is bilinear in the loads and the geometry but for the hinge axis's normalisation,
# so the difference's error is ~1e-6 of that term's second order, far below the linearisation's.
_HINGE_STEP = 1e-3


def hinge_pairs(wing: Wing, base: PanelLoads, change: PanelLoads | None) -> list[HingeMoment]:
    """Each surface's hinge moments on both wings. Exact method (`change` None): `base` is
    the right wing's loads and the left's are their rotated image (its hinge moment the
    negative). Linearised: `base` the symmetric equilibrium's and `change` the antisymmetric
    disturbance's: both wings' moments, linear in it."""
    k = base.force.shape[1] // (wing.n_stations - 1)
    on_base = hinge_moments(wing, base, k)
    if change is None:
        on_right, on_left = on_base, -on_base
    else:
        ahead = hinge_moments(wing, _shifted(base, change, _HINGE_STEP), k)
        behind = hinge_moments(wing, _shifted(base, change, -_HINGE_STEP), k)
        linear = (ahead - behind) / (2 * _HINGE_STEP)
        on_right, on_left = on_base + linear, on_base - linear
    return [
        HingeMoment(surface.name, float(r), float(left))
        for surface, r, left in zip(wing.control_surfaces, on_right, on_left, strict=True)
    ]
