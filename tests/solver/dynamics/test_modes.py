"""solver.dynamics.modes: the cantilever's stiffness is the static model's own, and its natural
modes converge to the continuous beam's at second order in the station spacing.

References: the uniform cantilever's closed forms (bending beta_n^2 sqrt(EI / (m L^4)),
beta_1 L = 1.87510, beta_2 L = 4.69409; torsion (2n - 1) pi / 2 sqrt(GJ / (I L^2)): Hodges and
Pierce 2011, sections 3.3 and 3.5; Blevins, Formulas for Natural Frequency and Mode Shape,
table 8-1), the cantilever with a tip mass or tip inertia (its exact frequency equations, same
sources), and the exact coupled bending-torsion frequencies of the continuous Goland wing
(`tests.flutter_reference`).
"""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest
from scipy.optimize import brentq

import solver
from solver import InvalidInput
from solver.dynamics.modes import _Beam, natural_modes, structure
from solver.inputs.mass import ConcentratedMass, MassModel
from solver.statics.jig import at_rest
from solver.statics.system import CoupledSystem
from tests.flutter_reference import goland_continuous, goland_mass, goland_wing
from tests.study import DENSITY, study_wing

LENGTH, EI, GJ, MASS, INERTIA = 6.0, 2e6, 3e5, 20.0, 4.0
BETA = (1.8751040687119611, 4.6940911329741745)
MESHES = (11, 21, 41)


def uniform_wing(n: int, sweep: float = 0.0, length: float = LENGTH) -> solver.Wing:
    return solver.Wing.create(np.linspace(0, length, n), 1.0, 0.35, EI, GJ, sweep=sweep)


def uniform_mass(n: int, center_of_gravity: float = 0.35, **store) -> MassModel:
    concentrated = (ConcentratedMass.create(n - 1, **store),) if store else ()
    return MassModel.create(n, MASS, center_of_gravity, INERTIA, concentrated)


def _frequencies(wing: solver.Wing, mass: MassModel, count: int) -> np.ndarray:
    return np.array([mode.frequency for mode in natural_modes(wing, mass, count).modes])


def _second_order(errors: list[float]) -> None:
    """Each halving of the spacing divides the error by 4: 3.6 to 4.4 (measured 3.9 to 4.1)."""
    for coarse, fine in itertools.pairwise(errors):
        assert coarse / fine == pytest.approx(4.0, abs=0.4)


BENDING = [
    BETA[0] ** 2 * math.sqrt(EI / (MASS * LENGTH**4)),
    BETA[1] ** 2 * math.sqrt(EI / (MASS * LENGTH**4)),
]
TORSION = [(2 * n - 1) * math.pi / 2 * math.sqrt(GJ / (INERTIA * LENGTH**2)) for n in (1, 2)]


@pytest.mark.parametrize(
    ("exact", "bending_share"),
    [(BENDING[0], 1.0), (BENDING[1], 1.0), (TORSION[0], 0.0), (TORSION[1], 0.0)],
    ids=["bending-1", "bending-2", "torsion-1", "torsion-2"],
)
def test_an_uncoupled_cantilever_converges_to_the_closed_forms_at_second_order(
    exact: float, bending_share: float
):
    """Centre of gravity on the elastic axis: bending and torsion decouple (each mode's
    bending share is 1 or 0 to round-off). Errors at N = 41 (measured): 2.0e-4 and 2.4e-3
    (bending), 1.3e-4 and 1.2e-3 (torsion), all from above."""
    errors = []
    for n in MESHES:
        modes = natural_modes(uniform_wing(n), uniform_mass(n), 6).modes
        mode = min(modes, key=lambda m: abs(m.frequency - exact))
        assert mode.bending_share == pytest.approx(bending_share, abs=1e-12)
        errors.append(mode.frequency / exact - 1)
    assert 0 < errors[-1] < 3e-3
    _second_order(errors)


def test_the_goland_wing_converges_to_its_exact_coupled_frequencies():
    """The centre of gravity 10 % chord aft of the elastic axis couples bending and torsion:
    the continuous wing's four lowest frequencies are 48.152, 95.703, 243.73 and 347.58 rad/s
    (exact, `tests.flutter_reference`; uncoupled they would be 49.49, 87.11, 261.3 and
    310.2 rad/s, ContourRoots 2025, Tutorial 11, section 11.3). Second order in N, from above:
    errors at N = 41 of 1.9e-4, 1.5e-4, 1.4e-3 and 2.3e-3."""
    exact = goland_continuous().vacuum_frequencies(400.0)
    assert exact == pytest.approx([48.152, 95.703, 243.73, 347.58], abs=0.01)
    errors = np.array([_frequencies(goland_wing(n), goland_mass(n), 4) / exact - 1 for n in MESHES])
    assert np.all(errors[-1] > 0) and np.all(errors[-1] < 3e-3)
    for mode in range(4):
        _second_order(list(errors[:, mode]))


def test_a_tip_store_converges_to_the_cantilever_with_a_tip_mass():
    """A concentrated mass M at the tip: 1 + cos(bL) cosh(bL) + (M / (m L)) bL (cos(bL)
    sinh(bL) - sin(bL) cosh(bL)) = 0 (Blevins table 8-1, case 4); with its inertia J about the
    elastic axis, torsion obeys (J / (I L)) lL tan(lL) = 1, l = omega sqrt(I / GJ). Here
    M = 2 m L and J = I L: the first bending frequency drops to 0.329 of the bare
    cantilever's. Second order, errors at N = 41 below 5e-4."""
    store = {"mass": 2 * MASS * LENGTH, "inertia": INERTIA * LENGTH, "offset": 0.0}

    def bending(x: float) -> float:
        ratio = store["mass"] / (MASS * LENGTH)
        return (
            1
            + math.cos(x) * math.cosh(x)
            + ratio * x * (math.cos(x) * math.sinh(x) - math.sin(x) * math.cosh(x))
        )

    beta_l = brentq(bending, 0.5, BETA[0])
    lambda_l = brentq(lambda x: x * math.tan(x) - 1.0, 0.1, math.pi / 2 - 1e-9)
    exact = [
        beta_l**2 * math.sqrt(EI / (MASS * LENGTH**4)),
        lambda_l / LENGTH * math.sqrt(GJ / INERTIA),
    ]
    assert exact[0] / BENDING[0] == pytest.approx(0.329, abs=0.001)
    errors = np.array(
        [_frequencies(uniform_wing(n), uniform_mass(n, **store), 2) / exact - 1 for n in MESHES]
    )
    assert np.all(np.abs(errors[-1]) < 5e-4)
    for mode in range(2):
        _second_order(list(np.abs(errors[:, mode])))


def test_the_structure_rows_are_the_compiled_models():
    """The root clamps, the heave kinematics and the slope and twist differences: the same
    matrix as the compiled model's J0 (its structure rows in its structure unknowns)."""
    wing = goland_wing(9)
    system = CoupledSystem(wing, 0.0)
    layout = system.layout
    j0 = at_rest(system).evaluation.jacobian0
    beam = _Beam(wing.y, wing.bending_stiffness, wing.torsional_stiffness)
    np.testing.assert_array_equal(
        beam.structure_rows(), j0[layout.structure_rows, layout.structure]
    )


@pytest.mark.parametrize("coupling", [0.0, 0.4], ids=["uncoupled", "bending_torsion_coupled"])
@pytest.mark.parametrize("aerodynamics", ["lattice", "strip"])
def test_the_load_rows_are_the_compiled_models(aerodynamics: str, coupling: float):
    """At a deformed, loaded state (a swept, tapered wing with 2 chordwise panels), the
    trapezoid rows of the panels' own loads (moments of the vertical forces at their force
    points' arms along the axis, torques about the axis) are the model's r1 load rows, to
    round-off; with a bending-torsion coupling K = `coupling` sqrt(EI GJ) too."""
    n = 9
    chord = np.linspace(1.2, 0.6, n)
    ei, gj = 4e4 * chord**3, 2e3 * chord**3
    wing = solver.Wing.create(
        np.linspace(0, 5, n),
        chord,
        0.35,
        ei,
        gj,
        sweep=20.0,
        bending_torsion_coupling=coupling * np.sqrt(ei * gj),
    )
    system = CoupledSystem(wing, 4.0, 2, aerodynamics=aerodynamics)
    layout = system.layout
    rng = np.random.default_rng(3)
    x = np.zeros(layout.n_unknowns)
    x[layout.heave] = rng.uniform(-0.1, 0.1, n)
    x[layout.slope] = rng.uniform(-0.03, 0.03, n)
    x[layout.twist] = rng.uniform(-3, 3, n)
    x[layout.circulation] = rng.uniform(0.0, 0.1, layout.n_panels)
    force, torque, center, _ = system.panel_loads(x)
    sweep = math.radians(wing.sweep)
    arm = center[0] * math.sin(sweep) + center[1] * math.cos(sweep)
    arc = wing.y / math.cos(sweep)
    strip_of = np.repeat(np.arange(n - 1), 2)
    moment = np.array(
        [np.sum(force[2][strip_of >= i] * (arm[strip_of >= i] - arc[i])) for i in range(n)]
    )
    twist_torque = np.array([np.sum(torque[0][strip_of >= i]) for i in range(n)])
    beam = _Beam(
        arc, wing.bending_stiffness, wing.torsional_stiffness, wing.bending_torsion_coupling
    )
    rows = beam.load_rows(moment[:, None], twist_torque[:, None])[:, 0]
    r1 = system.residual(x)[1][layout.load_rows]
    np.testing.assert_allclose(rows, r1, rtol=1e-12, atol=1e-14 * np.abs(r1).max())


def test_the_stiffness_and_states_reproduce_a_static_equilibrium():
    """w = K^{-1} (the loads' equivalent strip loads), and the unknowns z = Z w, at an
    equilibrium of the study's wing at 18 m/s (lift amplification 1.6): the flexibility form is
    the static model's. Newton's tolerance (1e-10 on the slope and twist rows) bounds the
    difference in the deformation: 1e-8 of its largest value."""
    wing = study_wing(12)
    equilibrium = solver.solve(wing, solver.FlightCondition(18.0, 5.0, DENSITY))
    system = CoupledSystem(wing, 5.0)
    layout = system.layout
    beam = structure(wing, MassModel.create(12, 1.0, 0.4, 0.1))
    x, n = equilibrium.state, wing.n_stations
    w = np.concatenate([x[1:n], np.radians(x[2 * n + 1 : 3 * n])])
    load_rows = equilibrium.dynamic_pressure * system.residual(x)[1][layout.load_rows]
    deformation = np.linalg.solve(beam.stiffness, beam.strip_loads_of(load_rows))
    np.testing.assert_allclose(deformation, w, rtol=0, atol=1e-8 * np.abs(w).max())
    z = x[layout.structure]
    np.testing.assert_allclose(beam.states @ w, z, rtol=0, atol=1e-8 * np.abs(z).max())


def test_sweep_changes_nothing_but_the_axis_length():
    """With the centre of gravity on the elastic axis the beam does not know its sweep: a
    wing swept 30 deg whose axis is as long as the unswept one's vibrates as it does."""
    n, sweep = 15, 30.0
    straight = _frequencies(uniform_wing(n), uniform_mass(n), 4)
    swept_wing = uniform_wing(n, sweep, LENGTH * math.cos(math.radians(sweep)))
    np.testing.assert_allclose(_frequencies(swept_wing, uniform_mass(n), 4), straight, rtol=1e-10)


def test_a_spar_alone_vibrates_with_its_own_mass():
    """No non-structural mass: the tube's density x area is the beam's mass, and the first
    bending frequency tends to 1.8751^2 sqrt(EI / (rho A L^4)) (N = 41: within 3e-4)."""
    material = solver.Material(70e9, 27e9, 2700.0, 300e6)
    n = 41
    wing = solver.Wing.create(
        np.linspace(0, 3, n), 0.5, 0.4, spar=solver.SparDesign(0.05, 0.002, material)
    )
    assert wing.spar is not None
    mass = MassModel.create(n, 0.0, 0.4, 0.0)
    linear_mass = 2700.0 * float(wing.spar.area[0])
    exact = BETA[0] ** 2 * math.sqrt(float(wing.bending_stiffness[0]) / (linear_mass * 3.0**4))
    assert _frequencies(wing, mass, 1)[0] == pytest.approx(exact, rel=3e-4)


def test_each_shape_is_scaled_to_a_unit_upward_edge_displacement():
    wing, mass = goland_wing(16), goland_mass(16)
    chord, ahead = wing.chord, wing.elastic_axis * wing.chord
    for mode in natural_modes(wing, mass, 4).modes:
        twist = np.radians(mode.twist)
        edges = np.concatenate([mode.heave + ahead * twist, mode.heave - (chord - ahead) * twist])
        assert edges[np.argmax(np.abs(edges))] == pytest.approx(1.0, rel=1e-12)
        assert mode.heave[0] == 0 and mode.twist[0] == 0
        np.testing.assert_array_equal(mode.twist, mode.axis_twist)  # unswept


def test_the_first_goland_mode_is_bending_and_the_second_torsion():
    """Bending share (kinetic energy in heave): 0.976 and 0.191; the bending mode twists
    nose-down where it heaves up (the centre of gravity lags behind the elastic axis)."""
    first, second = natural_modes(goland_wing(), goland_mass(), 2).modes
    assert first.bending_share == pytest.approx(0.976, abs=0.005)
    assert second.bending_share == pytest.approx(0.191, abs=0.005)
    assert first.heave[-1] > 0 and first.twist[-1] < 0


def test_vibration_needs_a_mass_model():
    with pytest.raises(InvalidInput) as raised:
        natural_modes(goland_wing(9), None)
    assert raised.value.field == "wing.mass"


def test_a_mass_model_of_another_mesh_is_refused():
    with pytest.raises(InvalidInput) as raised:
        natural_modes(goland_wing(9), goland_mass(10))
    assert raised.value.field == "wing.mass"


def test_all_modes_by_default_and_a_count_within_the_mesh():
    wing, mass = goland_wing(9), goland_mass(9)
    assert len(natural_modes(wing, mass).modes) == 16
    with pytest.raises(InvalidInput):
        natural_modes(wing, mass, 17)
