"""solver.model.geometry: the deformed lattice, placed as the study's make_wing and AeroSandbox
do."""

from __future__ import annotations

import casadi as ca
import numpy as np
import pytest

import solver
from solver.model.geometry import chordwise_nodes, lattice
from solver.model.layout import Layout

N = 4
Y = np.array([0.0, 1.0, 2.0, 3.0])
CHORD = np.array([1.0, 0.9, 0.8, 0.7])
EA = 0.4


def _lattice(heave, twist, *, slope=None, jig=None, k=1, camber=None, **fields):
    """The lattice's points at a state, the wing's parameters read by name from the compiled
    model's parameter vector (`Layout.unpack`), packed from a wing with `fields`."""
    wing = solver.Wing.create(
        Y, CHORD, EA, 1.0, 1.0, jig_twist=0.0 if jig is None else jig, **fields
    )
    layout = Layout(N, k)
    p = ca.SX.sym("p", layout.n_parameters)
    state = [ca.SX.sym(name, N) for name in ("u", "s", "t")]
    lat = lattice(*state, layout.unpack(p), k)
    outputs = [lat.left, lat.right, lat.collocation, lat.normal, lat.quarter_chord, lat.center]
    function = ca.Function("lattice", [*state, p], outputs)
    values = layout.pack(
        layout.wing_values(wing)
        | {
            "camber": np.zeros((N, k + 1)) if camber is None else camber,
            "alpha": 0.0,
            "deformed_axis": 0.0,
        }
    )
    result = function(heave, np.zeros(N) if slope is None else slope, twist, values)
    return [np.array(v) for v in result]


def test_chordwise_nodes_are_cosine_spaced_from_edge_to_edge():
    np.testing.assert_allclose(chordwise_nodes(4), [0, 0.1464466094, 0.5, 0.8535533906, 1])
    np.testing.assert_array_equal(chordwise_nodes(1), [0.0, 1.0])


def test_the_jig_puts_the_elastic_axis_on_the_y_axis():
    left, right, collocation, normal, quarter, _ = _lattice(np.zeros(N), np.zeros(N))
    np.testing.assert_allclose(left[0], (0.25 - EA) * CHORD[:-1])
    np.testing.assert_allclose(right[0], (0.25 - EA) * CHORD[1:])
    mean_chord = (CHORD[:-1] + CHORD[1:]) / 2
    np.testing.assert_allclose(collocation[0], (0.75 - EA) * mean_chord)
    np.testing.assert_allclose(normal, np.tile([[0.0], [0.0], [1.0]], (1, N - 1)), atol=1e-15)
    np.testing.assert_allclose(quarter[0], (0.25 - EA) * CHORD)


def test_twist_turns_the_section_nose_up_about_the_elastic_axis_then_heave_lifts_it():
    """LE = R_y(theta) [-x_ea c, y, 0] + [0, 0, u] (the study's make_wing): the quarter-chord
    point of an untwisted neighbourhood sits at (0.25 - x_ea) c along the turned chord."""
    twist = np.array([0.0, 2.0, 5.0, 9.0])  # [deg]
    heave = np.array([0.0, 0.01, 0.05, 0.1])  # [m]
    *_, quarter, _ = _lattice(heave, twist)
    theta = np.radians(twist)
    # The quarter chord lies (x_ea - 0.25) c ahead of the elastic axis along the turned chord,
    # lifted by the heave. The local span axis, tilted by the heave and twist between stations,
    # moves it by second-order amounts (6e-5 m here): 1e-4 m, against the 0.01-0.1 m that a
    # twist of the wrong sign or a missing heave would be off.
    np.testing.assert_allclose(
        quarter[2], heave + (EA - 0.25) * CHORD * np.sin(theta), rtol=0, atol=1e-4
    )
    np.testing.assert_allclose(quarter[0], (0.25 - EA) * CHORD * np.cos(theta), rtol=1e-3)


def test_sweep_moves_each_section_aft_by_y_tan_sweep():
    swept = _lattice(np.zeros(N), np.zeros(N), sweep=30.0)[4]
    straight = _lattice(np.zeros(N), np.zeros(N))[4]
    np.testing.assert_allclose(swept[0] - straight[0], Y * np.tan(np.radians(30.0)))
    np.testing.assert_allclose(swept[1:], straight[1:])


def test_bending_an_aft_swept_wing_up_washes_it_out():
    """t = phi cos(sweep) - degrees(du/ds) sin(sweep): a positive slope turns sections nose-down."""
    slope = np.array([0.0, 0.1, 0.2, 0.3])
    bent = _lattice(np.zeros(N), np.zeros(N), slope=slope, sweep=30.0)[3]  # normals
    # A nose-down section's normal leans forward (negative x).
    assert np.all(bent[0] < 0)


def test_jig_twist_is_what_the_flow_sees_like_elastic_twist():
    jig = np.array([1.0, 2.0, 3.0, 4.0])
    by_jig = _lattice(np.zeros(N), np.zeros(N), jig=jig)
    by_twist = _lattice(np.zeros(N), jig)
    for a, b in zip(by_jig, by_twist, strict=True):
        np.testing.assert_array_equal(a, b)


@pytest.mark.parametrize("k", [2, 4])
def test_chordwise_panels_tile_each_strip_leading_to_trailing_edge(k: int):
    left, _right, _collocation, _normal, _, center = _lattice(np.zeros(N), np.zeros(N), k=k)
    assert left.shape == (3, (N - 1) * k)
    x = chordwise_nodes(k)
    # Panel i k + j of a flat wing: its bound vortex at a quarter of panel j.
    for j in range(k):
        expected = (x[j] + 0.25 * (x[j + 1] - x[j]) - EA) * CHORD[:-1]
        np.testing.assert_allclose(left[0, j::k], expected)
    assert np.all(np.diff(center[1].reshape(N - 1, k)[:, 0]) > 0)  # strips root to tip


def test_camber_lifts_the_nodes_along_the_section_normal():
    k = 2
    camber = np.tile([0.0, 0.04, 0.0], (N, 1))
    flat = _lattice(np.zeros(N), np.zeros(N), k=k)
    cambered = _lattice(np.zeros(N), np.zeros(N), k=k, camber=camber)
    # The leading panel's back edge is the mid-chord node, lifted by 4 % of the chord.
    lift = cambered[2][2, 0::k] - flat[2][2, 0::k]  # collocation z of the leading panels
    mean_chord = (CHORD[:-1] + CHORD[1:]) / 2
    np.testing.assert_allclose(lift, 0.75 * 0.04 * mean_chord, rtol=1e-12)
