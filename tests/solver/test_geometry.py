"""solver.geometry: the deformed wing placed as the study's make_wing and AeroSandbox place it."""

from __future__ import annotations

import casadi as ca
import numpy as np

from solver.geometry import panel_geometry, station_points

N = 4
Y = np.array([0.0, 1.0, 2.0, 3.0])
CHORD = np.array([1.0, 0.9, 0.8, 0.7])
EA = 0.4


def _points(heave, twist):
    sym = [ca.SX.sym(name, N) for name in ("u", "t", "y", "c", "ea")]
    points = station_points(*sym)
    panels = panel_geometry(points)
    outputs = [
        points.leading_edge,
        points.trailing_edge,
        points.vortex_vertex,
        panels.collocation,
        panels.normal,
    ]
    function = ca.Function("geometry", sym, outputs)
    return [np.array(v) for v in function(heave, twist, Y, CHORD, np.full(N, EA))]


def test_the_jig_puts_the_elastic_axis_on_the_y_axis():
    le, te, vertex, collocation, normal = _points(np.zeros(N), np.zeros(N))
    np.testing.assert_allclose(le, np.vstack([-EA * CHORD, Y, np.zeros(N)]))
    np.testing.assert_allclose(te, np.vstack([(1 - EA) * CHORD, Y, np.zeros(N)]))
    np.testing.assert_allclose(vertex[0], (0.25 - EA) * CHORD)
    mean_chord = (CHORD[:-1] + CHORD[1:]) / 2
    np.testing.assert_allclose(collocation[0], (0.75 - EA) * mean_chord)
    np.testing.assert_allclose(normal, np.tile([[0.0], [0.0], [1.0]], (1, N - 1)), atol=1e-15)


def test_twist_turns_the_section_nose_up_about_the_elastic_axis_then_heave_lifts_it():
    """LE = R_y(theta) [-x_ea c, y, 0] + [0, 0, u] (the study's make_wing)."""
    twist = np.array([0.0, 2.0, 5.0, 9.0])  # [deg]
    heave = np.array([0.0, 0.01, 0.05, 0.1])  # [m]
    le, te, *_ = _points(heave, twist)
    theta = np.radians(twist)
    np.testing.assert_allclose(le[0], -EA * CHORD * np.cos(theta))
    np.testing.assert_allclose(le[2], EA * CHORD * np.sin(theta) + heave)
    # The trailing edge lies one chord behind, turned nose-up: lower than the leading edge.
    chord_vector = te - le
    np.testing.assert_allclose(np.linalg.norm(chord_vector, axis=0), CHORD, rtol=1e-12)
    assert np.all(chord_vector[2, 1:] < 0)


def test_heave_alone_translates_every_point():
    shift = 0.3
    flat = _points(np.zeros(N), np.zeros(N))
    lifted = _points(np.full(N, shift), np.zeros(N))
    for before, after in zip(flat[:4], lifted[:4], strict=True):
        np.testing.assert_allclose(after[2] - before[2], shift)
        np.testing.assert_allclose(after[:2], before[:2])
