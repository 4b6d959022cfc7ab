"""Control effectiveness and roll of a wing that bends in its plane (`wing.in_plane_bending_
stiffness` under the geometrically exact beam, `solver.model.lag_beam`): the flow model carries
the lag unknowns on both halves (its antisymmetric block against the full-span model:
tests/solver/model/test_residual.py; the roll's loads against the full-span statics:
tests/solver/controls/test_roll.py). Here the operations: about the flat jig lag is uncoupled
and every answer is the planar beam's; about a loaded wing the flap's derivative is the lift
of the lag equilibria differenced in the deflection, and the aileron's is the roll answer's."""

from __future__ import annotations

import functools

import numpy as np
import pytest

import solver
from solver.controls.effectiveness import control_effectiveness
from solver.controls.roll import roll
from tests.study import DENSITY, study_arrays

AILERON = {"name": "aileron", "start": 0.55, "end": 0.95, "hinge": 0.75, "kind": "aileron"}
FLAP = {"name": "flap", "start": 0.0, "end": 0.45, "hinge": 0.75, "kind": "flap"}
EXACT_K3 = solver.SolverOptions(chordwise_panels=3, structure="geometrically_exact")
# Twice its flap stiffness in its plane: soft enough that lag moves the loaded wing's answers
# at first order (a wing of a tenth of the aspect ratio would be 100 times stiffer in-plane).
IN_PLANE = 2.0


@functools.cache
def _wing(flap: float = 0.0, in_plane: float | None = IN_PLANE) -> solver.Wing:
    """The study's wing (N = 13) with a flap at `flap` deg and an aileron at 3 deg, with an
    in-plane stiffness `in_plane` times its flap stiffness (None: rigid in its plane)."""
    arrays = study_arrays(13)
    lag = (
        {}
        if in_plane is None
        else {"in_plane_bending_stiffness": in_plane * arrays["bending_stiffness"]}
    )
    return solver.Wing.create(
        **arrays,
        control_surfaces=[{**FLAP, "deflection": flap}, {**AILERON, "deflection": 3.0}],
        **lag,
    )


def test_about_the_flat_jig_lag_leaves_every_control_answer_alone():
    """At alpha 0, flaps neutral, the wing is flat and nothing circulates: a lag displacement
    or rotation moves the panels in their own plane and changes no normalwash, so the lag
    unknowns are uncoupled and the derivatives, reversals, divergence and hinge moments are the
    planar exact beam's to round-off (measured 2e-16)."""
    flight = solver.FlightCondition(14.0, 0.0, DENSITY)
    ours = control_effectiveness(_wing(), flight, EXACT_K3)
    theirs = control_effectiveness(_wing(in_plane=None), flight, EXACT_K3)
    for a, b in zip(ours, theirs, strict=True):
        for name in ("derivative", "rigid_derivative", "divergence_pressure", "hinge_moment"):
            assert getattr(a, name) == pytest.approx(getattr(b, name), rel=1e-12, abs=1e-12), name
        for name in ("reversal", "local_reversal"):
            assert getattr(a, name).velocity == pytest.approx(getattr(b, name).velocity, rel=1e-12)
    linear = roll(_wing(), flight, EXACT_K3, method="linearised")
    planar = roll(_wing(in_plane=None), flight, EXACT_K3, method="linearised")
    assert linear.rolling_moment == pytest.approx(planar.rolling_moment, rel=1e-12)
    assert linear.right.lag is not None and not np.any(linear.right.lag)


def test_the_flaps_derivative_is_the_lift_per_degree_of_the_lag_equilibria():
    """At 4 deg and 14 m/s, flap at 4 deg: the elastic derivative against central differences
    of the lag equilibria's lift over +-0.01 deg (truncation ~1e-8, the solves' tolerance
    ~1e-10; measured 9e-9). Lag moves it by 3e-4 from the planar beam's (the bent wing's
    sections bend along their tilted normals), thirty thousand times that error."""
    flight = solver.FlightCondition(14.0, 4.0, DENSITY)
    flap, _ = control_effectiveness(_wing(4.0), flight, EXACT_K3)
    lifts = [solver.solve(_wing(4.0 + s), flight, options=EXACT_K3).lift for s in (0.01, -0.01)]
    assert flap.derivative == pytest.approx((lifts[0] - lifts[1]) / 0.02, rel=1e-6)
    planar, _ = control_effectiveness(_wing(4.0, None), flight, EXACT_K3)
    assert abs(flap.derivative / planar.derivative - 1) > 1e-4


def test_the_ailerons_derivative_is_the_lag_roll_answers_rolling_moment_per_degree():
    """The aileron's elastic derivative at the loaded wing is the linearised roll answer's
    rolling moment per degree of its 3 deg (both from the flow model's antisymmetric block: to
    round-off); the wings' lag is antisymmetric about the symmetric equilibrium's, and lag
    moves the derivative from the planar beam's (measured 1.5e-3 at 4 deg)."""
    flight = solver.FlightCondition(14.0, 4.0, DENSITY)
    _, aileron = control_effectiveness(_wing(), flight, EXACT_K3)
    answer = roll(_wing(), flight, EXACT_K3, method="linearised")
    assert answer.rolling_moment == pytest.approx(3.0 * aileron.derivative, rel=1e-12)
    assert answer.symmetric is not None and answer.symmetric.stations.lag is not None
    right, left, middle = answer.right.lag, answer.left.lag, answer.symmetric.stations.lag
    assert right is not None and left is not None
    np.testing.assert_allclose((right + left) / 2, middle, rtol=0, atol=1e-15)
    _, planar = control_effectiveness(_wing(in_plane=None), flight, EXACT_K3)
    assert abs(aileron.derivative / planar.derivative - 1) > 5e-4


def test_at_alpha_zero_the_lag_linearisation_is_the_exact_responses_first_order_term():
    """The exact antisymmetric response with lag (the rotated image's lattice on both bent
    halves) is odd in the deflection, so the linearised one differs from it by O(delta^2): 4
    times more at 6 deg than at 3 (within 10 %), 7e-4 of the rolling moment at 3 deg (as the
    planar beam's, tests/solver/controls/test_roll.py)."""
    flight = solver.FlightCondition(14.0, 0.0, DENSITY)
    errors = {}
    for deflection in (3.0, 6.0):
        arrays = study_arrays(13)
        wing = solver.Wing.create(
            **arrays,
            control_surfaces=[{**AILERON, "deflection": deflection}],
            in_plane_bending_stiffness=IN_PLANE * arrays["bending_stiffness"],
        )
        exact = roll(wing, flight, EXACT_K3)
        linear = roll(wing, flight, EXACT_K3, method="linearised")
        assert exact.method == "antisymmetric" and exact.right.lag is not None
        errors[deflection] = abs(linear.rolling_moment / exact.rolling_moment - 1)
    assert 1e-5 < errors[3.0] < 2e-3
    assert errors[6.0] / errors[3.0] == pytest.approx(4.0, rel=0.1)
