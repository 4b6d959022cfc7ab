"""solver.controls.effectiveness: rigid and elastic control derivatives and reversal, against
AeroSandbox's full-span wing, against strip theory's closed form, against the typical section's
law, and between its own two ways of finding reversal (the eigenvalue and a sweep's zero
crossing)."""

from __future__ import annotations

import functools
import itertools
import math

import numpy as np
import pytest
from scipy.optimize import brentq

import solver
from solver.controls.effectiveness import (
    antisymmetric_divergence,
    control_effectiveness,
    control_sweep,
    linear_reversal,
)
from solver.controls.roll import roll
from tests import tn2563
from tests.reference import controls_reference
from tests.study import DENSITY, study_arrays

AILERON = {"name": "aileron", "start": 0.55, "end": 0.95, "hinge": 0.75, "kind": "aileron"}
FLAP = {"name": "flap", "start": 0.0, "end": 0.45, "hinge": 0.75, "kind": "flap"}
K3 = solver.SolverOptions(chordwise_panels=3)


@functools.cache
def _study(deflection: float = 0.0, stiffness: float = 1.0) -> solver.Wing:
    return solver.Wing.create(
        **study_arrays(13, stiffness_scale=stiffness),
        control_surfaces=[{**FLAP, "deflection": deflection}, {**AILERON, "deflection": 3.0}],
    )


# ------------------------------------------------------------------------- AeroSandbox


def test_the_reversal_eigenvalue_is_aerosandboxs_reversal_speed():
    """AeroSandbox's full-span wing (N = 13, k = 3): the root in V of its rolling moment per
    degree, Richardson-extrapolated from 3 and 6 deg of aileron at alpha 0 (R odd in delta:
    error O(delta^4)) and found by secant iterations to 1e-11. flexwing's generalised
    eigenvalue at the unloaded jig: within 1e-6 (measured 9e-9)."""
    reference = controls_reference("aileron_k3")
    reversal = linear_reversal(reference.wing, "aileron", reference.rho, reference.options)
    assert reversal.velocity == pytest.approx(reference.data["reversal"]["velocity"], rel=1e-6)
    assert reversal.dynamic_pressure == pytest.approx(
        reference.data["reversal"]["dynamic_pressure"], rel=1e-6
    )


ITERATES = controls_reference("aileron_k3").data["reversal"]["iterations"]


@pytest.mark.parametrize("iterate", ITERATES[:4], ids=lambda i: f"{i['velocity']:.6g}ms")
def test_the_elastic_rolling_derivative_is_aerosandboxs_first_order_term(iterate):
    """At the reversal search's speeds, AeroSandbox's Richardson-extrapolated rolling moment per
    degree (3 and 6 deg) against flexwing's exact elastic derivative: its remainder O(delta^4)
    at 6 deg bounds the agreement to ~1e-5 of the rigid derivative (measured 3e-6)."""
    reference = controls_reference("aileron_k3")
    flight = solver.FlightCondition(iterate["velocity"], 0.0, reference.rho)
    (aileron,) = control_effectiveness(reference.wing, flight, reference.options)
    assert aileron.derivative == pytest.approx(
        iterate["derivative"], abs=2e-5 * abs(aileron.rigid_derivative)
    )


# ------------------------------------------------------------------------------- physics


def test_the_derivatives_are_the_roll_answers_derivatives_in_the_deflection():
    """The aileron's elastic derivative is the linearised roll answer's rolling moment per
    degree, and the rigid derivative its rigid rolling moment's (linear in the deflection:
    exact to round-off); the exact antisymmetric answer at 3 deg agrees to its O(delta^2)
    (measured 8e-4 at 14 m/s)."""
    wing = _study()
    flight = solver.FlightCondition(14.0, 0.0, DENSITY)
    flap, aileron = control_effectiveness(wing, flight, K3)
    assert (aileron.measure, aileron.unit) == ("rolling_moment", "N m/deg")
    assert (flap.measure, flap.unit) == ("lift", "N/deg")
    linear = roll(wing, flight, K3, method="linearised")
    exact = roll(wing, flight, K3)
    assert linear.rolling_moment == pytest.approx(3.0 * aileron.derivative, rel=1e-12)
    assert linear.rigid_rolling_moment == pytest.approx(3.0 * aileron.rigid_derivative, rel=1e-12)
    assert exact.rolling_moment == pytest.approx(3.0 * aileron.derivative, rel=2e-3)


def test_the_flaps_derivative_is_the_lift_per_degree_of_the_equilibria():
    """The flap's elastic derivative at 4 deg against central differences of the equilibrium's
    lift over +-0.01 deg (truncation ~1e-8 relative, the solves' tolerance ~1e-10)."""
    flight = solver.FlightCondition(14.0, 2.0, DENSITY)
    flap, _ = control_effectiveness(_study(4.0), flight, K3)
    lifts = [solver.solve(_study(4.0 + s), flight, options=K3).lift for s in (0.01, -0.01)]
    assert flap.derivative == pytest.approx((lifts[0] - lifts[1]) / 0.02, rel=1e-6)


@pytest.mark.parametrize("velocity", [2.0, 12.0])
def test_a_rigid_wing_keeps_all_of_its_control(velocity):
    """Stiffness times 1e6: the elastic twist is a millionth of the soft wing's, and the
    effectiveness 1 to ~1e-6 (measured 2e-9 at 2 m/s, 1.4e-7 at 12 m/s)."""
    for control in control_effectiveness(
        _study(stiffness=1e6), solver.FlightCondition(velocity, 2.0, DENSITY), K3
    ):
        assert control.effectiveness == pytest.approx(1.0, abs=1e-5)


def test_effectiveness_falls_from_one_through_zero_at_the_reversal_speed():
    """The study's wing (N = 13, k = 3): the aileron loses its rolling power as q rises, keeps
    nearly all of it at low speed, and its rolling moment changes sign at the reversal speed
    (the exact roll answer's, 0.5 % either side)."""
    wing = _study()
    reversal = linear_reversal(wing, "aileron", DENSITY, K3).velocity
    assert reversal is not None
    slow = control_effectiveness(wing, solver.FlightCondition(3.0, 0.0, DENSITY), K3)[1]
    assert 0.99 < slow.effectiveness < 1.0
    below, above = (
        roll(wing, solver.FlightCondition(reversal * f, 0.0, DENSITY), K3).rolling_moment
        for f in (0.995, 1.005)
    )
    assert below > 0 > above


def test_the_sweeps_zero_crossing_confirms_the_eigenvalue():
    """The sweep's elastic derivative at its own equilibria changes sign between 19 and 20.5
    m/s; interpolated in q with the divergence pole removed (exact for one torsion mode), the
    crossing lands on the eigenvalue within 1e-4 (measured 1.8e-5 on a 1.5 m/s bracket: the
    interpolation's error, second order in the bracket)."""
    sweep = control_sweep(_study(), [10.0, 16.0, 19.0, 20.5, 22.0], 0.0, DENSITY, K3)
    summary = {s.name: s for s in sweep.reversals}["aileron"]
    assert summary.crossing.velocity == pytest.approx(summary.reversal.velocity, rel=1e-4)
    assert summary.first == "reversal"
    assert summary.divergence_pressure == sweep.antisymmetric_divergence.dynamic_pressure
    effectiveness = [p.controls[1].effectiveness for p in sweep.points]
    assert all(a > b for a, b in itertools.pairwise(effectiveness))


def test_which_comes_first_is_said_per_surface():
    """A surface reverses before divergence when its lift acts behind the elastic axis (40 %):
    a 25 % chord surface's thin-airfoil centre of pressure is at 42 % of the chord (the aileron
    reverses at about 19.9 m/s, the antisymmetric divergence is at 25 m/s; the flap at 21.6
    against 23.9 m/s), a 50 % chord flap's at 35 %, ahead of the axis: its effectiveness grows
    with q, and divergence comes first."""
    flight = solver.FlightCondition(10.0, 0.0, DENSITY)
    flap, aileron = control_effectiveness(_study(), flight, K3)
    assert aileron.first == "reversal" and flap.first == "reversal"
    assert aileron.reversal.dynamic_pressure < aileron.divergence_pressure
    wide = solver.Wing.create(**study_arrays(13), control_surfaces=[{**FLAP, "hinge": 0.5}])
    (wide_flap,) = control_effectiveness(wide, flight, solver.SolverOptions(chordwise_panels=4))
    assert wide_flap.first == "divergence" and wide_flap.effectiveness > 1


def test_the_antisymmetric_divergence_lies_above_the_symmetric_one():
    """An antisymmetric twist sheds its vorticity at the root too, so a twist costs the wing
    more induced incidence: less lift per twist, a higher divergence pressure (the study's
    wing: about 382 against 359 Pa at k = 1)."""
    wing = solver.Wing.create(**study_arrays())
    symmetric = solver.linear_divergence(wing, DENSITY).dynamic_pressure
    antisymmetric = antisymmetric_divergence(wing, DENSITY).dynamic_pressure
    assert symmetric is not None and antisymmetric is not None
    assert 1.02 * symmetric < antisymmetric < 1.2 * symmetric


# ------------------------------------------------------------- strip theory and the section


HINGE, ELASTIC_AXIS, CHORD, GJ = 0.75, 0.4, 1.0, 1e4
OFFSET = ELASTIC_AXIS - 0.25  # e c: the elastic axis behind the aerodynamic centre [chords]


@functools.cache
def _lattice_section() -> tuple[float, float, float]:
    """The lattice's own section (k = 3): lift slope, lift and quarter-chord moment per radian
    of deflection, from the middle strip of a nearly two-dimensional rigid wing (semispan 400
    chords, strips 20 chords wide). Measured 6.270, 3.295, -0.619 against thin-airfoil
    theory's 2 pi, 3.826, -0.650: the 3 chordwise panels resolve the hinge's kink to 14 %."""
    out = {}
    for deflection, alpha in ((0.0, 2.0), (2.0, 0.0)):
        surface = {**AILERON, "start": 0.0, "end": 1.0, "kind": "flap", "deflection": deflection}
        wing = solver.Wing.create(
            np.linspace(0, 400, 21), CHORD, ELASTIC_AXIS, 1e12, 1e12, control_surfaces=[surface]
        )
        answer = solver.solve(wing, solver.FlightCondition(10, alpha, DENSITY), options=K3)
        q, width = answer.dynamic_pressure, 20.0
        lift = answer.panels.lift[4] / (q * width * CHORD)
        moment = answer.panels.torque[4] / (q * width * CHORD**2) - OFFSET * lift
        out[deflection] = (lift, moment)
    per_radian = math.radians(2.0)
    return out[0.0][0] / per_radian, out[2.0][0] / per_radian, out[2.0][1] / per_radian


def _strip_effectiveness(twist_parameter: float, moment_ratio: float) -> float:
    """Strip theory's aileron effectiveness of a uniform cantilever, full-span aileron,
    constrained roll (Bisplinghoff, Ashley and Halfman, Aeroelasticity, 1955, ch. 8): with
    lambda^2 = q e c^2 a / GJ, theta'' + lambda^2 theta = -lambda^2 (C_Ld / a + C_Md / (e a))
    delta, theta(0) = theta'(L) = 0, the rolling moment over the rigid one is
    1 + (1 + C_Md / (e C_Ld)) (2 (sec lambda L - 1) / (lambda L)^2 - 1); divergence at
    lambda L = pi / 2."""
    x = twist_parameter
    return 1 + (1 + moment_ratio) * (2 * (1 / math.cos(x) - 1) / x**2 - 1)


def _uniform_wing(semispan: float) -> solver.Wing:
    n = int(2 * semispan / CHORD) + 1  # strips one chord wide
    surface = {**AILERON, "start": 0.0, "end": 1.0, "deflection": 0.0}
    return solver.Wing.create(
        np.linspace(0, semispan, n), CHORD, ELASTIC_AXIS, 1e9, GJ, control_surfaces=[surface]
    )


def _strip_pressures(semispan: float) -> tuple[float, float]:
    """Strip theory's reversal and divergence pressures [Pa] with the lattice's section."""
    slope, lift, moment = _lattice_section()
    ratio = moment / (OFFSET * lift)
    reversal = brentq(lambda x: _strip_effectiveness(x, ratio), 0.1, math.pi / 2 - 1e-9)
    scale = GJ / (OFFSET * CHORD**2 * slope * semispan**2)
    return reversal**2 * scale, (math.pi / 2) ** 2 * scale


def test_a_high_aspect_ratio_wing_tends_to_strip_theory_at_first_order_in_one_over_aspect_ratio():
    """A uniform wing with a full-span aileron (chord 1 m, elastic axis at 40 %, GJ 1e4 N m^2,
    k = 3, strips a chord wide) at aspect ratios 20 and 40, against strip theory's closed form
    with the lattice's own section (so that only the third dimension differs). The lattice's
    reversal and antisymmetric divergence pressures lie above strip theory's, by 4.2 % and 27 %
    at AR 20 and 2.3 % and 15 % at AR 40 (measured): the induced downwash, which strip theory
    leaves out, lowers the lift per unit twist, most near the tips where the twist is largest,
    and more for the antisymmetric loading's twist than for the aileron's own lift (which the
    reversal balances against). Both differences must halve as the aspect ratio doubles
    (ratio 0.5 +- 0.15: first order in 1/AR), and stay positive."""
    excess = {}
    for semispan in (10.0, 20.0):
        wing = _uniform_wing(semispan)
        reversal = linear_reversal(wing, "aileron", DENSITY, K3).dynamic_pressure
        divergence = antisymmetric_divergence(wing, DENSITY, K3).dynamic_pressure
        strip_reversal, strip_divergence = _strip_pressures(semispan)
        assert reversal is not None and divergence is not None
        excess[semispan] = (reversal / strip_reversal - 1, divergence / strip_divergence - 1)
    for which in (0, 1):
        assert excess[10.0][which] > excess[20.0][which] > 0
        assert excess[20.0][which] / excess[10.0][which] == pytest.approx(0.5, abs=0.15)


@pytest.mark.parametrize("fraction", [0.25, 0.5, 0.75])
def test_the_effectiveness_follows_the_typical_sections_law(fraction):
    """One torsion mode (the typical section: Megson, Aircraft Structures, ch. 27; Hodges and
    Pierce, ch. 2) gives the effectiveness (1 - q/q_R) / (1 - q/q_D). With the lattice's own
    reversal and antisymmetric divergence pressures, the AR 20 wing's effectiveness follows it
    within 5e-4 at a quarter, half and three quarters of its reversal pressure (measured
    0.9e-4 to 1.5e-4): its aileron response is one torsion mode to that accuracy."""
    wing = _uniform_wing(10.0)
    q_r = linear_reversal(wing, "aileron", DENSITY, K3).dynamic_pressure
    q_d = antisymmetric_divergence(wing, DENSITY, K3).dynamic_pressure
    assert q_r is not None and q_d is not None
    q = fraction * q_r
    flight = solver.FlightCondition(math.sqrt(2 * q / DENSITY), 0.0, DENSITY)
    (aileron,) = control_effectiveness(wing, flight, K3)
    assert aileron.effectiveness == pytest.approx((1 - q / q_r) / (1 - q / q_d), abs=5e-4)


# --------------------------------------------------------------- a wind-tunnel experiment


@pytest.mark.parametrize("span_fraction", list(tn2563.MEASURED))
def test_the_wind_tunnel_wings_rolling_power_is_nacas_within_the_comparisons_uncertainty(
    span_fraction,
):
    """NACA TN 2563's straight, flexible wind-tunnel wing with 30 % chord ailerons over the
    outer 20 to 95 % of the semispan (tests/tn2563.py: the OpenAeroStruct control-surface
    fork's digitised data and reconstructed stiffness), k = 5, N = 21.

    At 10 psf, where the wing is nearly rigid, the rolling moment per degree is the measured
    one within 7 % (measured +6, -0.3, -6, -4, -6 %): the lattice is thin and inviscid, and a
    real plain aileron loses a few percent of its lift to the boundary layer and its gap. As q
    rises, flexwing's effectiveness (normalised at 10 psf) falls faster than the measured one,
    by at most 0.13 at the highest q measured (0.06 at 35 psf for the 20 % aileron, 0.12 at
    40 psf for the 40 %): the reconstructed torsional stiffness, a cubic through digitised
    ratios, is the likeliest part of it. Its linear reversal at 45-51 psf lies where the
    measurements' own trend extrapolates to zero (beyond 40 psf)."""
    model = tn2563.wing(span_fraction)
    options = solver.SolverOptions(chordwise_panels=5)
    computed = [
        solver.control_effectiveness(model, tn2563.flight(q), options)[0].coefficient_derivative
        for q, _ in tn2563.MEASURED[span_fraction]
    ]
    measured = [value for _, value in tn2563.MEASURED[span_fraction]]
    assert computed[0] == pytest.approx(measured[0], rel=0.07)
    for ours, theirs in zip(computed, measured, strict=True):
        assert ours / computed[0] == pytest.approx(theirs / measured[0], abs=0.13)
    reversal = linear_reversal(model, "aileron", tn2563.DENSITY, options).dynamic_pressure
    assert reversal is not None
    assert 40.0 < reversal / tn2563.PSF < 60.0
