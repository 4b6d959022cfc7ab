"""solver.dynamics.aerodynamic_forces: the unsteady lattice's transfer functions for modes and
gusts: the static lattice at zero frequency, Sears' function on a long wing, and the flutter
analysis's own equations."""

from __future__ import annotations

import math

import numpy as np
import pytest
import scipy.special

import solver
from solver import InvalidInput
from solver.dynamics.aerodynamic_forces import generalised_aerodynamic_forces
from solver.dynamics.unsteady import theodorsen
from solver.inputs.mass import MassModel
from tests.flutter_reference import SEA_LEVEL, goland_mass, goland_wing
from tests.solver.dynamics.test_lattice_loads import long_wing


def test_a_slow_gust_loads_the_wing_as_a_change_of_incidence():
    """At k = 0 a gust of angle w_g / V is a change of alpha: the strips' loads per unit q and
    gust angle are d(loads)/d(alpha) of `solver.solve` on a rigid wing (the strips' lift and
    torque, central difference at +-0.5 deg over sin(1 deg): exact for the rigid jig's
    vertical force ~ sin(alpha) cos(alpha)),
    within 1e-6 of the largest, the issue's steady limit. (An uncambered, untwisted jig: it
    carries no circulation at alpha 0, about which the gust's loads are linearised.)"""
    n = 13
    wing = solver.Wing.create(np.linspace(0, 4, n), np.linspace(1.2, 0.6, n), 0.35, 1e12, 1e12)
    mass = MassModel.create(n, 1.0, 0.4, 0.1)
    answer = generalised_aerodynamic_forces(wing, [0.0], mass=mass)
    density, speed, delta = 1.225, 30.0, 0.5
    q = 0.5 * density * speed**2
    panels = [
        solver.solve(wing, solver.FlightCondition(speed, a, density)).panels
        for a in (delta, -delta)
    ]
    # The vertical force of the rigid jig's circulation goes as sin(alpha) cos(alpha).
    scale = math.sin(2 * math.radians(delta)) * q
    lift = (panels[0].lift - panels[1].lift) / scale
    torque = (panels[0].torque - panels[1].torque) / scale
    static = np.concatenate([lift, torque])
    np.testing.assert_allclose(
        answer.gust_loads[0], static, rtol=0, atol=1e-6 * np.abs(static).max()
    )


def test_a_long_wing_meets_a_gust_as_sears_function_says():
    """The middle of an aspect-ratio-160 wing in a sinusoidal gust, its phase taken at
    mid-chord (the elastic axis there, where x = 0): lift per unit span 2 pi rho V b w_g S(k),
    S = (J0 - i J1) C + i J1 (Sears 1941; Bisplinghoff, Ashley and Halfman 1955, eq. 5-422).
    Steady the finite span's 1 %; at k = 0.1 and 0.3 the chordwise discretisation's, first
    order in the panels as for Theodorsen's sections: 2.1 % and 5.0 % on 8 panels. Asserted
    within 3 % and 7 %."""
    wing, strip = long_wing(80.0, 0.5)
    mass = MassModel.create(wing.n_stations, 1.0, 0.5, 0.1)
    reduced = np.array([1e-8, 0.1, 0.3])
    answer = generalised_aerodynamic_forces(
        wing, reduced, mass=mass, options=solver.SolverOptions(chordwise_panels=8)
    )
    width = wing.y[strip + 1] - wing.y[strip]
    b = answer.reference_semichord
    ours = answer.gust_loads[:, strip] / (width * 4 * np.pi * b)  # per q and gust angle
    j0, j1 = scipy.special.j0(reduced), scipy.special.j1(reduced)
    sears = (j0 - 1j * j1) * theodorsen(reduced) + 1j * j1
    errors = np.abs(ours - sears) / np.abs(sears)
    assert errors[0] < 0.015 and errors[1] < 0.03 and errors[2] < 0.07


def test_the_flutter_point_solves_the_modal_equations():
    """At the Goland wing's flutter speed and frequency under the unsteady lattice (the flutter
    analysis's tabulated, interpolated matrices), the modal equations of this function's exact
    ones, (-omega^2 + Omega^2 - q Q(k)) c = 0, are singular: their smallest singular value
    within 1e-5 of their largest. Measured 1.4e-7: the flutter basis also holds the divergence
    shape's remainder (condensed), and interpolates the lattice's matrices (~1e-6)."""
    wing, mass = goland_wing(16), goland_mass(16)
    options = solver.SolverOptions(aerodynamics="unsteady_lattice", chordwise_panels=2)
    result = solver.flutter(wing, mass, np.linspace(10.0, 300.0, 30), SEA_LEVEL, options=options)
    onset = result.flutter
    assert onset is not None
    answer = generalised_aerodynamic_forces(
        wing, [onset.reduced_frequency], mass=mass, options=options
    )
    omega2 = np.array([mode.frequency for mode in answer.modes]) ** 2
    matrix = np.diag(omega2 - onset.frequency**2) - onset.dynamic_pressure * answer.modal[0]
    singular = np.linalg.svd(matrix, compute_uv=False)
    assert singular[-1] < 1e-5 * singular[0]


@pytest.mark.parametrize(
    ("arguments", "field"),
    [
        ({"reduced_frequencies": []}, "reduced_frequencies"),
        ({"reduced_frequencies": [0.1, 12.0]}, "reduced_frequencies[1]"),
        ({"reduced_frequencies": [-0.1]}, "reduced_frequencies[0]"),
        ({"reduced_frequencies": [0.0] * 201}, "reduced_frequencies"),
        ({"modes": 0}, "modes"),
        ({"mass": None}, "wing.mass"),
    ],
    ids=["none", "too-high", "negative", "too-many", "no-modes", "no-mass"],
)
def test_invalid_requests_name_the_field(arguments, field):
    call = {"reduced_frequencies": [0.1], "mass": goland_mass(8), **arguments}
    with pytest.raises(InvalidInput) as raised:
        generalised_aerodynamic_forces(goland_wing(8), call.pop("reduced_frequencies"), **call)
    assert raised.value.field == field
