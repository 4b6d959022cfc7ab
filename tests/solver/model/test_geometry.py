"""solver.model.geometry: the deformed lattice, placed as the study's make_wing and AeroSandbox
do."""

from __future__ import annotations

import math

import casadi as ca
import numpy as np
import pytest

import solver
from solver.model.geometry import (
    along_span,
    axis_force,
    chordwise_nodes,
    in_wing_plane,
    lattice,
    normal_force,
)
from solver.model.layout import Layout
from solver.statics.jig import at_rest
from solver.statics.loads import rigid_loads
from solver.statics.system import CoupledSystem

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


def _turn(points: np.ndarray, dihedral: float) -> np.ndarray:
    """R_x(dihedral) points (3, n): tips up for a positive dihedral."""
    c, s = math.cos(math.radians(dihedral)), math.sin(math.radians(dihedral))
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]]) @ points


@pytest.mark.parametrize("dihedral", [7.0, -4.0], ids=["dihedral", "anhedral"])
def test_a_dihedral_turns_the_whole_deformed_half_wing_about_x_through_the_root(dihedral):
    """Every point and the normals of the heaved, twisted, swept, cambered lattice are the flat
    one's turned by R_x(dihedral): the heave is normal to the wing's plane, y lies along it.
    Round-off only (1e-15 m on a 3 m wing)."""
    state = (np.array([0.0, 0.02, 0.05, 0.1]), np.array([0.0, 1.0, 2.0, 4.0]))
    kwargs = {"slope": np.array([0.0, 0.01, 0.02, 0.04]), "k": 2, "sweep": 20.0}
    kwargs["camber"] = np.tile([0.0, 0.03, 0.0], (N, 1))
    flat = _lattice(*state, **kwargs)
    turned = _lattice(*state, dihedral=dihedral, **kwargs)
    for ours, theirs in zip(turned, flat, strict=True):
        np.testing.assert_allclose(ours, _turn(theirs, dihedral), rtol=0, atol=1e-15)
    assert np.sign(turned[5][2, -1]) == np.sign(dihedral)  # the tip's force point


def test_at_dihedral_zero_the_wing_frame_is_the_geometry_frame_to_the_bit():
    """What makes a dihedral of 0 answer as the flat wing did, bit for bit: y cos 0 + z sin 0 is
    y, z cos 0 - y sin 0 is z, and the beam's projections are the flat ones."""
    wing = solver.Wing.create(Y, CHORD, EA, 1.0, 1.0, sweep=25.0)
    rng = np.random.default_rng(2)
    vectors = rng.normal(size=(3, 50)) * 10.0 ** rng.integers(-8, 8, size=(3, 50))
    x, y, z = in_wing_plane(vectors, wing)
    np.testing.assert_array_equal(np.array([x, y, z]), vectors)
    sweep = math.radians(25.0)
    np.testing.assert_array_equal(
        along_span(vectors, wing), math.sin(sweep) * vectors[0] + math.cos(sweep) * vectors[1]
    )
    np.testing.assert_array_equal(normal_force(vectors, wing), vectors[2])
    np.testing.assert_array_equal(
        axis_force(vectors, wing), vectors[0] * math.cos(sweep) - vectors[1] * math.sin(sweep)
    )


def test_the_beams_projections_turn_with_the_wing():
    """A load on the turned wing is resolved as the same load on the flat wing: along the
    axis, normal to the plane, across the axis (round-off)."""
    flat = solver.Wing.create(Y, CHORD, EA, 1.0, 1.0, sweep=25.0)
    turned = solver.Wing.create(Y, CHORD, EA, 1.0, 1.0, sweep=25.0, dihedral=12.0)
    vectors = np.random.default_rng(4).normal(size=(3, 20))
    moved = _turn(vectors, 12.0)
    for project in (along_span, normal_force, axis_force):
        np.testing.assert_allclose(project(moved, turned), project(vectors, flat), atol=1e-15)
    np.testing.assert_allclose(np.array(in_wing_plane(moved, turned)), vectors, atol=1e-15)


def _rigid_lift(dihedral: float, alpha: float, semispan: float) -> float:
    """[m^2] the rigid rectangular wing's lift per unit q (chord 0.5 m, 11 stations)."""
    wing = solver.Wing.create(np.linspace(0.0, semispan, 11), 0.5, 0.4, 1e4, 1e3, dihedral=dihedral)
    system = CoupledSystem(wing, alpha)
    return rigid_loads(system, at_rest(system).rigid_state(alpha)).lift


@pytest.mark.parametrize("dihedral", [5.0, 15.0])
def test_a_dihedral_wing_lifts_cos_squared_of_the_flat_one_as_the_halves_part(dihedral):
    """Each half sees V sin(alpha) cos(dihedral) normal to its plane, and its normal force
    lifts cos(dihedral) of itself: L(dihedral) / L(0) = cos^2 + k (1 - cos^2), where k is the
    halves' mutual induction, which a longer span makes smaller (measured on these rectangular
    wings at alpha 1e-4 deg, the linear limit: k = 0.08 at aspect ratio 10, 0.018 at 40, 0.007
    at 80). At vanishing alpha the answer is even in the dihedral: turning z to -z turns a
    dihedral into an anhedral and alpha into -alpha, and the lift is odd in alpha (relative
    1e-5: its nonlinear part is O(alpha) ~ 2e-6)."""
    alpha, cos2 = 1e-4, math.cos(math.radians(dihedral)) ** 2
    share = {}
    for semispan in (2.5, 10.0, 20.0):  # aspect ratios 10, 40, 80
        ratio = _rigid_lift(dihedral, alpha, semispan) / _rigid_lift(0.0, alpha, semispan)
        share[semispan] = (ratio - cos2) / (1 - cos2)
    assert 0 < share[20.0] < share[10.0] < share[2.5] < 0.15
    assert share[20.0] < 0.02
    anhedral = _rigid_lift(-dihedral, alpha, 10.0) / _rigid_lift(dihedral, alpha, 10.0)
    assert abs(anhedral - 1) < 1e-5
