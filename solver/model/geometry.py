"""The deformed wing's lattice, placed as the design study's make_wing and AeroSandbox place it, in
CasADi symbols.

Each conventions below changes the answer by more than 1e-6 relative when done otherwise
(tests/reference/CONVENTIONS.md, shared/notes/matching-aerosandbox.md):

- The elastic axis (EA) is the line x = y tan(sweep) in the wing plane; station i's EA point is
  (y_i tan(sweep), y_i, 0). Sections stay streamwise.
- What the flow sees at station i is the streamwise angle
      t_i = phi_i cos(sweep) - degrees(du/ds)_i sin(sweep) + jig_i   [deg]
  (phi: twist about the EA; du/ds: the beam's slope; bending an aft-swept wing up washes it out).
- Leading edge: LE_i = EA_i + R_y(t_i) [-x_ea c_i, 0, 0] + [0, 0, u_i]: a rotation about the
  GLOBAL y axis through the EA point, then the heave (the study's make_wing).
- The section's axes are turned by t_i about its LOCAL span axis: the normalised y-z projection of
  LE_{i+1} - LE_i, averaged with the previous segment's inside, one-sided at root and tip
  (AeroSandbox's Wing._compute_frame_of_WingXSec). Its up axis is scaled by sqrt(2/(1 + cos d))
  inside (d: the angle between the two segments).
- Chordwise nodes x_j = 0.5 - 0.5 cos(pi j / k), j = 0..k (cosine spacing), each at
  LE_i + x_j c_i x_sec + camber_ij c_i z_sec (camber as a fraction of chord, in the section's
  own frame).
- Panel (strip i, chordwise j) is index i k + j; its bound vortex runs from 0.75 front + 0.25 back
  of its left edge to the same point of its right edge; its collocation point is midway in span on
  its 3/4 line; its normal is (FR - BL) x (FL - BR), normalised.
- Dihedral: the half-wing above, placed in its own plane (y along it, z normal to it), is turned
  about the x axis through the root by the dihedral angle, tips up for a positive one
  (R_x(dihedral) applied to every point and direction); the left half is its mirror image in y,
  the flat left half turned by -dihedral. The beam lives in the wing's plane: y is a station's
  distance from the root along it, the heave is normal to it, the elastic axis runs along the
  turned e_s, and the beam's loads are the panel forces resolved into the wing's frame
  (`in_wing_plane`). AeroSandbox's sections at R_x(dihedral) LE_i, with the same twists, are
  this lattice (its span axes and camber scale are the flat ones turned).

Points are (3, ...) matrices of [x, y, z] in geometry axes (x aft, y right, z up) [m].
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import casadi as ca
import numpy as np

__all__ = [
    "Lattice",
    "along_span",
    "arc_length",
    "axis_force",
    "chordwise_nodes",
    "in_wing_plane",
    "lag_reference_line",
    "lag_segment_chords",
    "lattice",
    "normal_force",
    "reference_line",
    "segment_chords",
    "span_axis",
    "streamwise_twist",
]

DEG = np.pi / 180.0


def chordwise_nodes(k: int) -> np.ndarray:
    """(k + 1,) [-] cosine-spaced node positions along the chord, 0 to 1 (AeroSandbox's)."""
    nodes = 0.5 - 0.5 * np.cos(np.pi * np.arange(k + 1) / k)
    nodes[0], nodes[-1] = 0.0, 1.0
    return nodes


# The kinematics of the swept beam, each written once: symbolic (CasADi) inside the model,
# numeric (numpy arrays, float angles) in the answers, the same formula either way. `wing` is
# what carries the wing's parameters by name: the numeric `solver.inputs.wing.Wing`, or the
# compiled model's parameters (`solver.model.layout.Layout.unpack`). A vector is its three
# components (x, y, z): a sequence of arrays or symbols, or a (3, ...) array.
Vector = Sequence[Any] | np.ndarray


def _cos_sin(angle_deg: Any) -> tuple[Any, Any]:
    """cos and sin of an angle [deg]: CasADi's of a symbol, math's of a number."""
    if isinstance(angle_deg, ca.SX | ca.MX | ca.DM):
        return ca.cos(angle_deg * DEG), ca.sin(angle_deg * DEG)
    return math.cos(angle_deg * DEG), math.sin(angle_deg * DEG)


def streamwise_twist(phi: Any, slope: Any, jig: Any, sweep_deg: Any) -> Any:
    """[deg] what the flow sees: phi cos(sweep) - degrees(du/ds) sin(sweep) + jig, with phi
    [deg] the twist about the elastic axis, du/ds [-] the beam's slope and jig [deg]."""
    cos, sin = _cos_sin(sweep_deg)
    return phi * cos - slope / DEG * sin + jig


def arc_length(wing: Any) -> Any:
    """(N,) [m] distance of each station from the root along the straight, swept elastic axis:
    y / cos(sweep)."""
    return wing.y / _cos_sin(wing.sweep)[0]


def in_wing_plane(vector: Vector, wing: Any) -> tuple[Any, Any, Any]:
    """A vector's components in the wing's frame, turned back by the dihedral about x: x, y along
    the wing's plane (a point's distance from the root along it), z normal to it (the heave's
    direction)."""
    cos, sin = _cos_sin(wing.dihedral)
    return vector[0], vector[1] * cos + vector[2] * sin, vector[2] * cos - vector[1] * sin


def span_axis(wing: Any) -> tuple[Any, Any]:
    """The elastic axis's unit direction e_s = (sin, cos, 0) of the sweep in the wing's frame
    (`in_wing_plane`): its x and y components (in geometry axes, (sin, cos cos(dihedral),
    cos sin(dihedral)))."""
    cos, sin = _cos_sin(wing.sweep)
    return sin, cos


def along_span(vector: Vector, wing: Any) -> Any:
    """A vector's component along the elastic axis, v . e_s: a point's distance along the axis
    from the root's plane normal to it, a moment's torque about the axis."""
    e_x, e_y = span_axis(wing)
    x, y, _ = in_wing_plane(vector, wing)
    return e_x * x + e_y * y


def normal_force(force: Vector, wing: Any) -> Any:
    """[N] a force's component normal to the wing's plane, along the heave: what the beam's
    shear and bending carry (z up at dihedral 0)."""
    return in_wing_plane(force, wing)[2]


def axis_force(force: Vector, wing: Any) -> Any:
    """[N] the in-plane force across the elastic axis, F . (e_s x n) = Fx cos(sweep) -
    Fy' sin(sweep) (n the wing plane's normal, Fy' the force's component along the plane,
    `in_wing_plane`): what a heaved axis point turns into torque."""
    cos, sin = _cos_sin(wing.sweep)
    x, y, _ = in_wing_plane(force, wing)
    return x * cos - y * sin


def _sinc(x: Any) -> Any:
    """sin(x)/x, smooth through 0 (its Taylor series below 1e-3: error < 1e-19)."""
    small = x * x
    series = 1 - small / 6 + small * small / 120
    if isinstance(x, ca.SX | ca.MX):
        symbol: Any = x
        safe_symbol: Any = ca.if_else(symbol == 0, 1, symbol)
        return ca.if_else(ca.fabs(symbol) < 1e-3, series, ca.sin(symbol) / safe_symbol)
    # Complex arrays pass as they are: the roll's linearised statics differentiate through
    # this by a complex step (`solver.controls.roll`).
    x = np.asarray(x) if np.iscomplexobj(x) else np.asarray(x, dtype=float)
    safe = np.where(x == 0.0, 1.0, x)
    return np.where(np.abs(x) < 1e-3, series, np.sin(safe) / safe)


def segment_chords(beta: Any, h: Any) -> tuple[Any, Any]:
    """(N-1,) the segments' chords along the jig axis and the normal [m], of rotations beta (N,)
    [rad] and lengths h (N-1,) [m]: h sinc(db/2) (cos b, sin b) (`solver.model.exact_beam`)."""
    cos: Any = ca.cos if isinstance(beta, ca.SX | ca.MX) else np.cos
    sin: Any = ca.sin if isinstance(beta, ca.SX | ca.MX) else np.sin
    middle = (beta[:-1] + beta[1:]) / 2
    length = h * _sinc((beta[1:] - beta[:-1]) / 2)
    return length * cos(middle), length * sin(middle)


def reference_line(beta: Any, h: Any) -> tuple[Any, Any]:
    """(N,) S_i, u_i [m]: the deformed axis's stations along the jig axis and the normal, from
    the root (a running sum of `segment_chords`)."""
    along, normal = segment_chords(beta, h)
    if isinstance(beta, ca.SX | ca.MX):
        return ca.vertcat(0, ca.cumsum(along)), ca.vertcat(0, ca.cumsum(normal))
    return np.concatenate([[0.0], np.cumsum(along)]), np.concatenate([[0.0], np.cumsum(normal)])


def lag_segment_chords(beta: Any, psi: Any, h: Any) -> tuple[Any, Any, Any]:
    """(N-1,) the segments' chords along the jig axis e_s, the normal n and e_c = e_s x n [m],
    of the flap rotations beta (N,) [rad], the lag rotations psi (N,) [rad] and the lengths h
    (N-1,) [m]: h sinc(db/2) sinc(dp/2) t(b, p), t = cos b (cos p e_s - sin p e_c) + sin b n at
    the segment's mean rotations b, p, db and dp their differences (`solver.model.lag_beam`;
    at psi = 0 `segment_chords` and a zero across)."""
    symbolic = isinstance(beta, ca.SX | ca.MX)
    cos: Any = ca.cos if symbolic else np.cos
    sin: Any = ca.sin if symbolic else np.sin
    flap, lag = (beta[:-1] + beta[1:]) / 2, (psi[:-1] + psi[1:]) / 2
    length = h * _sinc((beta[1:] - beta[:-1]) / 2) * _sinc((psi[1:] - psi[:-1]) / 2)
    in_plane = length * cos(flap)
    return in_plane * cos(lag), length * sin(flap), -in_plane * sin(lag)


def lag_reference_line(beta: Any, psi: Any, h: Any) -> tuple[Any, Any, Any]:
    """(N,) S_i, u_i, v_i [m]: the deformed axis's stations along e_s, n and e_c from the root
    (a running sum of `lag_segment_chords`)."""
    parts = lag_segment_chords(beta, psi, h)
    if isinstance(beta, ca.SX | ca.MX):
        return tuple(ca.vertcat(0, ca.cumsum(part)) for part in parts)  # type: ignore[return-value]
    return tuple(np.concatenate([[0.0], np.cumsum(part)]) for part in parts)  # type: ignore[return-value]


def _turned(points: ca.SX, cos: ca.SX, sin: ca.SX) -> ca.SX:
    """(3, n) points or directions turned about the x axis: R_x(dihedral) points."""
    y, z = points[1, :], points[2, :]
    return ca.vertcat(points[0, :], y * cos - z * sin, y * sin + z * cos)


@dataclass(frozen=True)
class Lattice:
    """The right half-wing's panels, index i k + j, each (3, M) [m] unless said.

    left, right: bound-vortex vertices; center: force point (middle of the bound vortex);
    leg: bound vortex vector; collocation: flow-tangency point; normal: unit normal [-].
    quarter_chord: (3, N) quarter-chord points of the stations, camber left out (AeroSandbox's
    reference-area points); leading_edge: (3, N) the stations' deformed leading edges (the
    chord axis is their difference over a quarter chord).
    """

    left: ca.SX
    right: ca.SX
    center: ca.SX
    leg: ca.SX
    collocation: ca.SX
    normal: ca.SX
    quarter_chord: ca.SX
    leading_edge: ca.SX


def _cross(a: ca.SX, b: ca.SX) -> ca.SX:
    """Column-wise cross product of (3, n) matrices."""
    return ca.vertcat(
        a[1, :] * b[2, :] - a[2, :] * b[1, :],
        a[2, :] * b[0, :] - a[0, :] * b[2, :],
        a[0, :] * b[1, :] - a[1, :] * b[0, :],
    )


def _span_axes(le_y: ca.SX, le_z: ca.SX) -> tuple[ca.SX, ca.SX, ca.SX]:
    """Local span axis (y, z components) and the up axis's scale at each station."""
    seg_y = le_y[1:] - le_y[:-1]
    seg_z = le_z[1:] - le_z[:-1]
    seg_len = ca.sqrt(seg_y**2 + seg_z**2)
    seg_y, seg_z = seg_y / seg_len, seg_z / seg_len
    mid_y = (seg_y[:-1] + seg_y[1:]) / 2
    mid_z = (seg_z[:-1] + seg_z[1:]) / 2
    mid_len = ca.sqrt(mid_y**2 + mid_z**2)
    cos_between = seg_y[:-1] * seg_y[1:] + seg_z[:-1] * seg_z[1:]
    axis_y = ca.vertcat(seg_y[0], mid_y / mid_len, seg_y[-1])
    axis_z = ca.vertcat(seg_z[0], mid_z / mid_len, seg_z[-1])
    scale = ca.vertcat(1, ca.sqrt(2 / (1 + cos_between)), 1)
    return axis_y, axis_z, scale


def _exact_leading_edges(
    heave: ca.SX, beta: ca.SX, wing: Any, ea_offset: ca.SX, cos_t: ca.SX, sin_t: ca.SX
) -> tuple[ca.SX, ca.SX, ca.SX]:
    """The leading edges on the exact beam's reference line: the elastic-axis point at
    S_i e_s + u_i n, the chord's offset -x_ea c (cos t, 0, -sin t) turned about the deformed
    axis's y-z direction (a_y, a_z) (Rodrigues: (-x_ea c cos t, -x_ea c a_z sin t,
    x_ea c a_y sin t))."""
    s = arc_length(wing)
    along, _ = reference_line(beta, s[1:] - s[:-1])
    cos_sweep, sin_sweep = _cos_sin(wing.sweep)
    tangent_y, tangent_z = ca.cos(beta) * cos_sweep, ca.sin(beta)
    norm = ca.sqrt(tangent_y**2 + tangent_z**2)
    axis_y, axis_z = tangent_y / norm, tangent_z / norm
    return (
        along * sin_sweep - ea_offset * cos_t,
        along * cos_sweep - ea_offset * axis_z * sin_t,
        heave + ea_offset * axis_y * sin_t,
    )


def _about_normal(x: ca.SX, y: ca.SX, cos_psi: ca.SX, sin_psi: ca.SX) -> tuple[ca.SX, ca.SX]:
    """The x, y components of vectors turned about the wing's normal (z in its plane) by the
    lag rotation psi: positive turns y (outboard) toward -x (forward)."""
    return x * cos_psi - y * sin_psi, x * sin_psi + y * cos_psi


def _lag_leading_edges(
    heave: ca.SX,
    beta: ca.SX,
    lag: tuple[ca.SX, ca.SX],
    wing: Any,
    ea_offset: ca.SX,
    cos_t: ca.SX,
    sin_t: ca.SX,
) -> tuple[ca.SX, ca.SX, ca.SX]:
    """The leading edges on the reference line with lag (`solver.model.lag_beam`): the
    elastic-axis point at S_i e_s + v_i e_c + u_i n (S, v from `lag_reference_line`, u the
    heave), the chord's offset of `_exact_leading_edges` turned about the normal by psi_i (R =
    R_n(psi) R_ec(beta) R_es(phi): the lag turn last)."""
    displacement, psi = lag
    s = arc_length(wing)
    along, _, _ = lag_reference_line(beta, psi, s[1:] - s[:-1])
    cos_sweep, sin_sweep = _cos_sin(wing.sweep)
    tangent_y, tangent_z = ca.cos(beta) * cos_sweep, ca.sin(beta)
    norm = ca.sqrt(tangent_y**2 + tangent_z**2)
    axis_y, axis_z = tangent_y / norm, tangent_z / norm
    offset_x, offset_y = _about_normal(
        -ea_offset * cos_t, -ea_offset * axis_z * sin_t, ca.cos(psi), ca.sin(psi)
    )
    # e_c = (cos(sweep), -sin(sweep), 0) in the wing's plane.
    return (
        along * sin_sweep + displacement * cos_sweep + offset_x,
        along * cos_sweep - displacement * sin_sweep + offset_y,
        heave + ea_offset * axis_y * sin_t,
    )


def lattice(
    heave: ca.SX,
    slope: ca.SX,
    phi: ca.SX,
    wing: Any,
    k: int,
    exact: bool = False,
    lag: tuple[ca.SX, ca.SX] | None = None,
) -> Lattice:
    """The deformed lattice of the compiled model's parameters `wing` (`Layout.unpack`).

    Args:
        heave: (N,) [m] u; slope: (N,) [-] du/ds; phi: (N,) [deg] twist about the EA.
        wing: read by name: y (N,) [m]; chord (N,) [m] streamwise; elastic_axis (N,) [-]
            fraction of chord; jig_twist (N,) [deg] built-in twist; camber (N (k + 1),) [-]
            camber / chord at the chordwise nodes, station-major; sweep [deg] of the elastic
            axis, positive aft; dihedral [deg] of the wing's plane, tips up.
        k: chordwise panels.
        exact: the geometrically exact beam's placement (`solver.model.exact_beam`): slope is
            the bending rotation beta [rad], the elastic-axis points sit on its reference line
            (foreshortened: y_i = S_i cos(sweep)), and each section's chord turns by its twist
            about the deformed axis's direction in the y-z plane instead of the global y axis.
        lag: with lag bending (`solver.model.lag_beam`, the exact beam's), (v, psi) (N,) each,
            the lag displacement [m] along e_c and rotation [rad] about the normal: the
            elastic-axis points move by v e_c and each section, its chord and up axes, turns
            about the normal by psi.
    """
    y, chord, elastic_axis = wing.y, wing.chord, wing.elastic_axis
    n = y.shape[0]
    camber = ca.reshape(wing.camber, k + 1, n).T
    twist = streamwise_twist(phi, slope, wing.jig_twist, wing.sweep) * DEG
    cos_t, sin_t = ca.cos(twist), ca.sin(twist)
    ea_offset = chord * elastic_axis
    if lag is not None:
        le_x, le_y, le_z = _lag_leading_edges(heave, slope, lag, wing, ea_offset, cos_t, sin_t)
    elif exact:
        le_x, le_y, le_z = _exact_leading_edges(heave, slope, wing, ea_offset, cos_t, sin_t)
    else:
        le_x = y * ca.tan(wing.sweep * DEG) - ea_offset * cos_t
        le_y = y
        le_z = ea_offset * sin_t + heave
    axis_y, axis_z, scale = _span_axes(le_y, le_z)
    # Chord axis: x turned by the twist about the local span axis (Rodrigues, axis_x = 0); up
    # axis: (x cross span axis) turned likewise, times the scale.
    chord_axis = ca.vertcat((cos_t).T, (axis_z * sin_t).T, (-axis_y * sin_t).T)
    up_axis = ca.vertcat((scale * sin_t).T, (-scale * axis_z * cos_t).T, (scale * axis_y * cos_t).T)
    if lag is not None:  # the section turned about the normal by its lag rotation
        cos_psi, sin_psi = ca.cos(lag[1]).T, ca.sin(lag[1]).T
        chord_axis = ca.vertcat(
            *_about_normal(chord_axis[0, :], chord_axis[1, :], cos_psi, sin_psi), chord_axis[2, :]
        )
        up_axis = ca.vertcat(
            *_about_normal(up_axis[0, :], up_axis[1, :], cos_psi, sin_psi), up_axis[2, :]
        )
    le = ca.vertcat(le_x.T, le_y.T, le_z.T)
    chord_row = chord.T
    nodes = [
        le
        + ca.repmat(chord_row * x, 3, 1) * chord_axis
        + ca.repmat(chord_row * camber[:, j].T, 3, 1) * up_axis
        for j, x in enumerate(chordwise_nodes(k))
    ]
    order = [j * (n - 1) + i for i in range(n - 1) for j in range(k)]

    def panels(corner: list[ca.SX]) -> ca.SX:
        return ca.horzcat(*corner)[:, order]

    front_left = panels([nodes[j][:, :-1] for j in range(k)])
    back_left = panels([nodes[j + 1][:, :-1] for j in range(k)])
    front_right = panels([nodes[j][:, 1:] for j in range(k)])
    back_right = panels([nodes[j + 1][:, 1:] for j in range(k)])
    left = 0.75 * front_left + 0.25 * back_left
    right = 0.75 * front_right + 0.25 * back_right
    collocation = 0.5 * (0.25 * front_left + 0.75 * back_left) + 0.5 * (
        0.25 * front_right + 0.75 * back_right
    )
    cross = _cross(front_right - back_left, front_left - back_right)
    normal = cross / ca.repmat(ca.sqrt(ca.sum1(cross**2)), 3, 1)
    quarter_chord = le + ca.repmat(chord_row * 0.25, 3, 1) * chord_axis
    # The flat half-wing, built whole in its own plane, then turned by the dihedral: each point
    # set and direction on its own, so that at dihedral 0 every value and derivative is the flat
    # wing's to the bit (y cos 0 - z sin 0 = y).
    cos, sin = _cos_sin(wing.dihedral)
    return Lattice(
        left=_turned(left, cos, sin),
        right=_turned(right, cos, sin),
        center=_turned((left + right) / 2, cos, sin),
        leg=_turned(right - left, cos, sin),
        collocation=_turned(collocation, cos, sin),
        normal=_turned(normal, cos, sin),
        quarter_chord=_turned(quarter_chord, cos, sin),
        leading_edge=_turned(le, cos, sin),
    )
