"""solver.statics.inertia: the wing's own mass under the load factor relieves the lift's loads.

Closed forms: a uniform mass's shear, bending moment and torque at the root; a wing whose mass is
distributed like its lift (strip theory's uniform loading of a rectangular wing, the centre of
gravity at the quarter chord where the lift acts) carries no section loads at all, and does not
deform. Without `wing.mass`, answers are unchanged."""

from __future__ import annotations

import math

import numpy as np
import pytest

import solver
from solver.statics.inertia import GRAVITY
from tests.study import study_wing

SEMISPAN, STATIONS = 5.0, 11
MU = 3.0  # [kg/m] uniform mass per length


def _rectangle(center_of_gravity: float = 0.25, **changes) -> solver.Wing:
    mass = solver.MassModel.create(STATIONS, MU, center_of_gravity, 0.1)
    return solver.Wing.create(
        np.linspace(0.0, SEMISPAN, STATIONS), 1.0, 0.4, 5e4, 1e4, mass=mass, **changes
    )


@pytest.mark.parametrize("load_factor", [1.0, 2.5, -1.0])
def test_a_uniform_masss_root_loads_are_its_weights_closed_forms(load_factor: float) -> None:
    """Shear -n g mu s, bending -n g mu s^2 / 2, torque +n g mu s d (d the centre of gravity
    aft of the elastic axis: nose up), of the apparent weight's share normal to the wing's
    plane, cos(alpha): exact for a uniform mass (the strips' trapezoids are)."""
    wing = _rectangle(center_of_gravity=0.5)
    equilibrium = solver.solve(
        wing, solver.FlightCondition(12.0, lift=200.0, load_factor=load_factor)
    )
    stations = equilibrium.stations
    alpha = math.radians(equilibrium.totals.alpha)
    weight = load_factor * GRAVITY * MU * math.cos(alpha)
    assert stations.inertial_shear[0] == pytest.approx(-weight * SEMISPAN, rel=1e-12)
    assert stations.inertial_bending_moment[0] == pytest.approx(
        -weight * SEMISPAN**2 / 2, rel=1e-12
    )
    assert stations.inertial_torque[0] == pytest.approx(weight * SEMISPAN * 0.1, rel=1e-12)
    assert equilibrium.totals.load_factor == pytest.approx(load_factor, rel=1e-12)
    assert equilibrium.totals.wing_mass == pytest.approx(2 * MU * SEMISPAN, rel=1e-12)


def test_a_wing_whose_mass_is_distributed_like_its_lift_carries_nothing() -> None:
    """Strip theory loads an untwisted rectangular wing uniformly, at the quarter chord: a
    uniform mass there, the wing the whole aircraft (its weight the lift carries), leaves no
    section load anywhere and no deformation, at any load factor and however soft the wing.
    Tolerance: the residual's (1e-10) over the loads' scale, a hundredfold."""
    wing = _rectangle()
    weight = 2 * MU * SEMISPAN * GRAVITY  # [N] the wing is the aircraft
    strip = solver.SolverOptions(aerodynamics="strip")
    for load_factor in (1.0, 3.0):
        flight = solver.FlightCondition(15.0, weight=weight, load_factor=load_factor)
        equilibrium = solver.solve(wing, flight, options=strip)
        scale = load_factor * weight * SEMISPAN
        stations = equilibrium.stations
        assert np.max(np.abs(stations.shear)) <= 1e-8 * load_factor * weight
        assert np.max(np.abs(stations.bending_moment)) <= 1e-8 * scale
        assert np.max(np.abs(stations.torque)) <= 1e-8 * scale
        assert np.max(np.abs(stations.heave)) <= 1e-8 * SEMISPAN
        assert np.max(np.abs(stations.twist)) <= 1e-6  # [deg]
        # Undeformed, it trims at the rigid wing's alpha.
        assert equilibrium.totals.alpha == pytest.approx(equilibrium.totals.rigid_alpha, abs=1e-8)


def test_the_weight_relieves_the_flexible_wings_bending_and_its_twist() -> None:
    """The study wing with a mass at 2.5 g: less root bending than its lift alone gives (the
    inertial part is the difference), and a mass ahead of the elastic axis twists it nose down,
    so it trims at a higher alpha than with the mass behind."""
    base = study_wing()
    flight = solver.FlightCondition(12.0, weight=300.0, load_factor=2.5)
    bare = solver.solve(base, flight)
    ahead = solver.Wing.create(
        base.y,
        base.chord,
        0.4,
        base.bending_stiffness,
        base.torsional_stiffness,
        mass=solver.MassModel.create(base.n_stations, 2.0, 0.3, 0.05),
    )
    loaded = solver.solve(ahead, flight)
    assert loaded.totals.lift == pytest.approx(bare.totals.lift, rel=1e-9)  # both carry n W
    relief = loaded.stations.inertial_bending_moment[0]
    assert relief < 0
    assert loaded.totals.root_bending_moment < bare.totals.root_bending_moment
    assert loaded.stations.inertial_torque[0] < 0  # the mass ahead: nose down
    behind = dataclasses_with_cg(ahead, 0.5)
    assert solver.solve(behind, flight).totals.alpha < loaded.totals.alpha


def dataclasses_with_cg(wing: solver.Wing, center_of_gravity: float) -> solver.Wing:
    assert wing.mass is not None
    mass = solver.MassModel.create(
        wing.n_stations, wing.mass.mass_per_length, center_of_gravity, 0.05
    )
    return solver.Wing.create(
        wing.y, wing.chord, 0.4, wing.bending_stiffness, wing.torsional_stiffness, mass=mass
    )


def test_without_a_mass_or_a_load_factor_at_alpha_answers_are_unchanged() -> None:
    """Inertia relief needs the wing's mass; at a given alpha, also a load factor."""
    base = study_wing()
    heavy = dataclasses_with_cg(
        solver.Wing.create(
            base.y,
            base.chord,
            0.4,
            base.bending_stiffness,
            base.torsional_stiffness,
            mass=solver.MassModel.create(base.n_stations, 2.0, 0.4, 0.05),
        ),
        0.4,
    )
    at_alpha = solver.FlightCondition(10.0, 5.0)
    plain = solver.solve(base, at_alpha)
    with_mass = solver.solve(heavy, at_alpha)
    assert np.array_equal(plain.state, with_mass.state)
    assert with_mass.stations.inertial_shear is None and with_mass.totals.load_factor is None
    pulled = solver.solve(heavy, solver.FlightCondition(10.0, 5.0, load_factor=2.0))
    assert pulled.totals.load_factor == 2.0
    assert pulled.totals.root_bending_moment < plain.totals.root_bending_moment
