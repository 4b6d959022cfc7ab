"""Physics of the extended model: what sweep, camber and built-in twist do, the invariants they
keep, and divergence, fold and stability for them.

The rectangular wing here: semispan 10 m, chord 1 m, elastic axis at 40 % chord, EI 2e5 and GJ
2e4 N m^2 (EI/GJ = 10), N = 30; its linear divergence pressure is 668 Pa unswept.
"""

from __future__ import annotations

import numpy as np
import pytest

import solver
from solver import FlightCondition, SolverOptions
from tests.study import study_wing

SWEEPS = [-20.0, -10.0, 0.0, 10.0, 20.0]


def _rectangle(sweep: float = 0.0, **kwargs) -> solver.Wing:
    return solver.Wing.create(np.linspace(0, 10, 30), 1.0, 0.4, 2e5, 2e4, sweep=sweep, **kwargs)


def test_aft_sweep_raises_the_divergence_pressure_and_forward_sweep_lowers_it():
    """Bending an aft-swept wing up washes it out (t = phi cos - u' sin): bending relieves the
    torsional feedback, and beyond a few degrees (here ~15, for EI/GJ = 10) the wing does not
    diverge at any pressure the model can mean. Forward sweep adds wash-in: earlier divergence."""
    pressures = [solver.linear_divergence_pressure(_rectangle(s)) for s in SWEEPS]
    assert all(p is not None for p in pressures)
    assert np.all(np.diff(pressures) > 0), pressures
    assert pressures[-1] > 100 * pressures[2]  # 20 deg: effectively no divergence


def test_aft_sweep_lowers_the_lift_amplification_until_the_wing_washes_out():
    q = 300.0  # [Pa], 45 % of the unswept wing's divergence pressure
    amplification = [
        solver.solve(
            _rectangle(s), FlightCondition(np.sqrt(2 * q / 1.225), 3.0)
        ).totals.lift_amplification
        for s in SWEEPS
    ]
    assert np.all(np.diff(amplification) < 0), amplification
    assert amplification[0] > amplification[2] > 1  # forward and unswept: wash-in
    assert amplification[-1] < 1  # 20 deg aft: the wing unloads itself


def test_a_cambered_sections_nose_down_moment_lowers_the_wash_in():
    """With chordwise panels the lattice sees the camber's pitching moment (nose-down): the
    study's wing cut from a NACA 4412 twists less nose-up than from a NACA 0012 at the same
    angle of attack (AeroSandbox: +0.19 deg against +1.76 deg, tests/reference)."""
    options = SolverOptions(chordwise_panels=4)
    condition = FlightCondition(10.0, 5.0, 1.225)
    symmetric = solver.solve(
        solver.Wing.create(**_study_arrays(), airfoil="naca0012"), condition, options=options
    )
    cambered = solver.solve(
        solver.Wing.create(**_study_arrays(), airfoil="naca4412"), condition, options=options
    )
    assert cambered.tip_twist < 0.5 * symmetric.tip_twist
    assert cambered.lift > symmetric.lift  # camber adds lift all the same
    assert cambered.totals.pitching_moment < symmetric.totals.pitching_moment


def _study_arrays() -> dict:
    wing = study_wing()
    return {
        "y": wing.y,
        "chord": wing.chord,
        "elastic_axis": 0.4,
        "bending_stiffness": wing.bending_stiffness,
        "torsional_stiffness": wing.torsional_stiffness,
    }


def test_washout_built_in_lowers_the_lift_and_the_tip_load():
    plain = solver.solve(study_wing(), FlightCondition(10.0, 5.0, 1.225))
    twisted = solver.solve(
        solver.Wing.create(**_study_arrays(), jig_twist=np.linspace(0, -3, 30)),
        FlightCondition(10.0, 5.0, 1.225),
    )
    assert twisted.lift < plain.lift
    assert twisted.panels.lift_per_span[-1] < plain.panels.lift_per_span[-1]


@pytest.mark.parametrize("sweep", [-15.0, 25.0])
def test_a_swept_wing_at_minus_alpha_is_the_mirror_image(sweep: float):
    wing = _rectangle(sweep)
    up = solver.solve(wing, FlightCondition(20.0, 3.0, 1.225))
    down = solver.solve(wing, FlightCondition(20.0, -3.0, 1.225))
    for name in ("heave", "slope", "twist", "axis_twist", "bending_moment", "torque"):
        a, b = getattr(up.stations, name), getattr(down.stations, name)
        np.testing.assert_allclose(-b, a, rtol=1e-9, atol=1e-12 * np.abs(a).max())
    assert down.totals.induced_drag == pytest.approx(up.totals.induced_drag, rel=1e-9)


@pytest.mark.parametrize(
    "wing",
    [
        pytest.param(lambda: _rectangle(30.0), id="swept-30"),
        pytest.param(
            lambda: solver.Wing.create(**_study_arrays(), airfoil="naca4412"), id="naca4412-k3"
        ),
    ],
)
def test_a_very_stiff_wing_gives_the_rigid_answer(wing):
    base = wing()
    stiff = solver.Wing.create(
        base.y,
        base.chord,
        base.elastic_axis,
        np.minimum(base.bending_stiffness * 1e7, 1e12),  # the largest stiffness accepted
        np.minimum(base.torsional_stiffness * 1e7, 1e12),
        sweep=base.sweep,
        airfoil=list(base.airfoil),
    )
    e = solver.solve(
        stiff, FlightCondition(15.0, 4.0, 1.225), options=SolverOptions(chordwise_panels=3)
    )
    assert abs(e.totals.lift_amplification - 1) < 1e-6
    np.testing.assert_allclose(e.panels.lift_per_span, e.panels.rigid_lift_per_span, rtol=1e-5)


@pytest.mark.parametrize(
    ("wing", "options"),
    [
        pytest.param(
            lambda: solver.Wing.create(np.linspace(0, 10, 30), 1.0, 0.4, 2e6, 2e4, sweep=-10.0),
            SolverOptions(),
            id="forward-swept",
        ),
        pytest.param(
            lambda: solver.Wing.create(**_study_arrays(), airfoil="naca2412"),
            SolverOptions(chordwise_panels=3),
            id="cambered-k3",
        ),
        pytest.param(
            lambda: study_wing(), SolverOptions(torque_axis="deformed"), id="deformed-axis"
        ),
    ],
)
def test_divergence_fit_fold_and_stability_work_for_the_extended_model(wing, options):
    """A sweep to past the fold: stable points below it, no equilibrium beyond, the fold between
    the last answered speed and the first refused, the fit and the linear estimate present, and
    every stability margin rising with speed."""
    result = solver.airspeed_sweep(
        wing(), list(np.linspace(8, 40, 17)), solver.FlightCondition(None, 3.0, 1.225), options
    )
    fold = result.divergence.fold.velocity
    assert fold is not None
    answered = [p for p in result.points if p.status == "equilibrium"]
    refused = [p for p in result.points if p.status != "equilibrium"]
    assert answered and refused
    assert max(p.velocity for p in answered) < fold < min(p.velocity for p in refused)
    margins = [p.equilibrium.stability.margin for p in answered]
    assert np.all(np.diff(margins) > 0) and margins[-1] < 1
    assert result.divergence.linear.dynamic_pressure is not None
    assert result.divergence.fit.dynamic_pressure is not None
