"""Deformed-wing geometry as AeroSandbox builds it, in CasADi symbols.

One chordwise panel per strip means only each section's leading edge (LE) and trailing edge (TE)
matter. The conventions below each change the answer by more than 1e-6 relative when done
otherwise (see shared/notes/matching-aerosandbox.md):

- LE_i = R_y(theta_i) [-x_ea c_i, y_i, 0] + [0, 0, u_i]: twist about the global y axis through
  the elastic-axis point, then heave (the study's ``make_wing``).
- The chord is rotated by theta_i about the section's *local* span axis: the normalised y-z
  projection of LE_{i+1} - LE_i, averaged with the previous segment's at interior stations,
  one-sided at the root and tip (AeroSandbox's ``Wing._compute_frame_of_WingXSec``).
- Camber is not modelled: the mesh would add camber at x/c = 0 and 1 only, where a symmetric or
  DAE-11 section has none.

Points are (3, N) matrices of [x, y, z] in geometry axes (x aft, y right, z up) [m].
"""

from __future__ import annotations

from dataclasses import dataclass

import casadi as ca
import numpy as np

__all__ = ["StationPoints", "PanelGeometry", "station_points", "panel_geometry"]

QUARTER_CHORD = 0.25  # bound vortex position along each panel's chord
THREE_QUARTER_CHORD = 0.75  # collocation point position along each panel's chord


@dataclass(frozen=True)
class StationPoints:
    """Per-station points of the deformed wing, each (3, N) [m]."""

    leading_edge: ca.SX
    trailing_edge: ca.SX
    vortex_vertex: ca.SX  # quarter-chord point: horseshoe corners
    three_quarter: ca.SX  # three-quarter-chord point


@dataclass(frozen=True)
class PanelGeometry:
    """Per-panel quantities of the right half-wing, root to tip, each (3, N-1)."""

    collocation: ca.SX  # [m] flow-tangency point, middle of the 3/4-chord line
    vortex_center: ca.SX  # [m] middle of the bound vortex, where forces act
    bound_leg: ca.SX  # [m] bound vortex vector, inboard to outboard vertex
    normal: ca.SX  # [-] unit panel normal, upward for an undeformed wing


def _rows(*rows: ca.SX) -> ca.SX:
    """Stack (1, N) rows into a (3, N) point matrix."""
    return ca.vertcat(*rows)


def station_points(
    heave: ca.SX,
    twist_deg: ca.SX,
    y: ca.SX,
    chord: ca.SX,
    elastic_axis: ca.SX,
) -> StationPoints:
    """Station points of the wing deformed by heave and twist.

    Args:
        heave: (N,) [m] vertical displacement u, positive up.
        twist_deg: (N,) [deg] nose-up rotation theta about the elastic axis.
        y: (N,) [m] jig station positions.
        chord: (N,) [m].
        elastic_axis: (N,) [-] elastic-axis position as a fraction of chord.
    """
    twist = twist_deg * (np.pi / 180.0)
    cos_t, sin_t = ca.cos(twist), ca.sin(twist)
    ea_offset = chord * elastic_axis  # [m] from the LE back to the elastic axis
    le_x = -ea_offset * cos_t
    le_y = y
    le_z = ea_offset * sin_t + heave

    # Local span axis: normalised y-z projection of the LE-to-LE segments.
    seg_y = le_y[1:] - le_y[:-1]
    seg_z = le_z[1:] - le_z[:-1]
    seg_len = ca.sqrt(seg_y**2 + seg_z**2)
    seg_y, seg_z = seg_y / seg_len, seg_z / seg_len
    mid_y = (seg_y[:-1] + seg_y[1:]) / 2
    mid_z = (seg_z[:-1] + seg_z[1:]) / 2
    mid_len = ca.sqrt(mid_y**2 + mid_z**2)
    axis_y = ca.vertcat(seg_y[0], mid_y / mid_len, seg_y[-1])
    axis_z = ca.vertcat(seg_z[0], mid_z / mid_len, seg_z[-1])

    # Chord direction: x rotated by the twist about the local span axis (Rodrigues, axis_x = 0).
    chord_x = cos_t
    chord_y = axis_z * sin_t
    chord_z = -axis_y * sin_t

    def along_chord(fraction: float) -> ca.SX:
        return _rows(
            (le_x + fraction * chord * chord_x).T,
            (le_y + fraction * chord * chord_y).T,
            (le_z + fraction * chord * chord_z).T,
        )

    return StationPoints(
        leading_edge=along_chord(0.0),
        trailing_edge=along_chord(1.0),
        vortex_vertex=along_chord(QUARTER_CHORD),
        three_quarter=along_chord(THREE_QUARTER_CHORD),
    )


def panel_geometry(points: StationPoints) -> PanelGeometry:
    """Panels between consecutive stations (AeroSandbox's VLM conventions)."""
    le, te = points.leading_edge, points.trailing_edge
    front_left, front_right = le[:, :-1], le[:, 1:]
    back_left, back_right = te[:, :-1], te[:, 1:]
    diagonal_1 = front_right - back_left
    diagonal_2 = front_left - back_right
    cross = ca.vertcat(
        diagonal_1[1, :] * diagonal_2[2, :] - diagonal_1[2, :] * diagonal_2[1, :],
        diagonal_1[2, :] * diagonal_2[0, :] - diagonal_1[0, :] * diagonal_2[2, :],
        diagonal_1[0, :] * diagonal_2[1, :] - diagonal_1[1, :] * diagonal_2[0, :],
    )
    cross_norm = ca.sqrt(ca.sum1(cross**2))
    normal = cross / ca.repmat(cross_norm, 3, 1)
    vertex = points.vortex_vertex
    three_quarter = points.three_quarter
    return PanelGeometry(
        collocation=(three_quarter[:, :-1] + three_quarter[:, 1:]) / 2,
        vortex_center=(vertex[:, :-1] + vertex[:, 1:]) / 2,
        bound_leg=vertex[:, 1:] - vertex[:, :-1],
        normal=normal,
    )
