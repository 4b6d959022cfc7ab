"""The unsteady lattice's gust answer (solver.gusts.lattice_model, frequency_response): the
same aircraft and outputs as the state-space model, the lattice's 3D unsteady aerodynamics in
the frequency domain (Nastran SOL 146's way)."""

from __future__ import annotations

import math

import numpy as np
import pytest

import solver
from solver.gusts.discrete import discrete_response, peaks
from solver.gusts.frequency_response import lattice_discrete_responses, top_frequency
from solver.gusts.lattice_model import lattice_gust_model
from solver.gusts.model import gust_model
from solver.operations.gust import GustInput
from tests.solver.gusts.wings import LIGHT_MASS, RHO, STUDY_FLIGHT, rectangle, study
from tests.study import DENSITY, study_arrays

UNSTEADY = solver.SolverOptions(aerodynamics="unsteady_lattice")


@pytest.mark.parametrize(("clamped", "tolerance"), [(True, 0.01), (False, 0.03)])
def test_ul1_a_slender_wing_in_a_long_gust_answers_as_the_lagged_lattice(
    clamped: bool, tolerance: float
) -> None:
    # A rigid rectangle of aspect ratio 40 in a 1-cos gust 25 chords long (k = pi b / H =
    # 0.063): the unsteady lattice against the state space with the same steady lattice and
    # Kuessner's and Wagner's 2D lags. Measured: root bending +0.35 %, load factor +0.12 %
    # clamped; -2.2 %, -2.6 % free (the plunge's lag: the 3D wake's against Wagner's). In
    # shorter gusts they part (H = 5 chords: +15 %, +14 %): one chordwise panel meets the
    # gust at its three-quarter chord at once, where Kuessner's lift builds as it crosses.
    wing = rectangle(semispan=20.0, stations=9)
    flight = solver.FlightCondition(50.0, density=RHO, weight=2e4)
    n = wing.n_stations
    model = lattice_gust_model(wing, flight, UNSTEADY, 4, clamped, top_frequency(50.0, 25.0))
    model.check_stable()
    lattice = peaks(lattice_discrete_responses(model, np.array([25.0]), np.ones(1))[0].outputs)
    state = peaks(discrete_response(gust_model(wing, flight, None, 4, clamped), 25.0, 1.0).outputs)
    assert lattice[0][n] == pytest.approx(state[0][n], rel=tolerance)
    assert lattice[0][3 * n] == pytest.approx(state[0][3 * n], rel=tolerance)


def test_ul2_a_very_long_gust_on_a_clamped_wing_gives_the_static_increment() -> None:
    # As the state-space model's test: a gust 6 km long at 12 m/s, the loads the static
    # model's at alpha +- U / V (central difference). Measured: bending +0.40 %, shear
    # -0.17 %, tip heave +0.43 % (the modes past the lattice's k = 10 left out; the static
    # pair about alpha without the trim's inertia relief): within 1 %.
    wing = solver.Wing.create(**study_arrays(n=9), mass=LIGHT_MASS)
    model = lattice_gust_model(wing, STUDY_FLIGHT, UNSTEADY, None, True)
    model.check_stable()
    amplitude = 0.01
    response = lattice_discrete_responses(model, np.array([3000.0]), np.array([amplitude]))
    high = peaks(response[0].outputs)[0]
    alpha = model.equilibrium.totals.alpha
    turn = math.degrees(amplitude / 12.0)
    up, down = (
        solver.solve(
            wing, solver.FlightCondition(12.0, alpha + s * turn, DENSITY), options=UNSTEADY
        )
        for s in (1, -1)
    )
    n = wing.n_stations
    bending = (up.stations.bending_moment[0] - down.stations.bending_moment[0]) / 2
    assert high[n] == pytest.approx(bending, rel=0.01)
    assert high[0] == pytest.approx((up.stations.shear[0] - down.stations.shear[0]) / 2, rel=0.01)
    heave = (up.totals.tip_heave - down.totals.tip_heave) / 2
    assert high[3 * n + 1] == pytest.approx(heave, rel=0.01)


def test_ul3_the_transform_and_the_tables_are_converged() -> None:
    # The study wing, free, the shortest and longest gusts: a period twice as long moves the
    # peaks by < 2e-5 (measured), twice the tabulated reduced frequencies by < 2.4e-3 (root
    # bending) and < 3.3e-5 (load factor) (measured).
    wing = study()
    n = wing.n_stations
    top = top_frequency(12.0, 9.0)
    model = lattice_gust_model(wing, STUDY_FLIGHT, UNSTEADY, 4, False, top)
    finer = lattice_gust_model(wing, STUDY_FLIGHT, UNSTEADY, 4, False, top, nodes=32)
    gradients, amplitudes = np.array([9.0, 107.0]), np.ones(2)
    base = lattice_discrete_responses(model, gradients, amplitudes)
    longer = lattice_discrete_responses(model, gradients, amplitudes, stretch=2.0)
    tabled = lattice_discrete_responses(finer, gradients, amplitudes)
    for one, two, three in zip(base, longer, tabled, strict=True):
        a, b, c = (peaks(r.outputs)[0] for r in (one, two, three))
        assert b[n] == pytest.approx(a[n], rel=1e-4)
        assert b[3 * n] == pytest.approx(a[3 * n], rel=1e-4)
        assert c[n] == pytest.approx(a[n], rel=5e-3)
        assert c[3 * n] == pytest.approx(a[3 * n], rel=5e-3)


def test_ul4_the_answer_keeps_its_form_and_the_response_starts_with_the_gust() -> None:
    result = solver.gust_analysis(
        study(), STUDY_FLIGHT, solver.GustSettings(gradients=3, modes=2), UNSTEADY
    )
    assert len(result.gusts) == 3 and result.turbulence is not None
    for case in result.gusts:
        # Nothing before the gust arrives (causal) but the band limit's precursor, the peak
        # after it.
        assert abs(case.root_bending_moment[0]) < 1e-2 * np.abs(case.root_bending_moment).max()
        assert case.max_load_factor > 1.0


@pytest.mark.parametrize(
    ("changes", "field"),
    [({"weight": None}, "flight.weight"), ({"mass": None}, "wing.mass")],
    ids=["no-weight", "no-mass"],
)
def test_ul5_bad_input_is_refused_naming_the_field(changes: dict, field: str) -> None:
    wing = study() if "mass" not in changes else solver.Wing.create(**study_arrays())
    flight = STUDY_FLIGHT if "weight" not in changes else solver.FlightCondition(12.0, 5.0, RHO)
    with pytest.raises(solver.InvalidInput) as caught:
        GustInput(wing=wing, flight=flight, options=UNSTEADY)
    assert caught.value.field == field


def test_ul6_the_gust_answers_stability_is_flutters() -> None:
    # The Goland wing, clamped, 1.02 kg/m^3, 4 chordwise panels on 8 strips: the p-k method
    # on the same lattice flutters at 169.5 m/s (docs/accuracy.md's convergence). The gust
    # model's argument-principle count (it has no state matrix) agrees: answered at 155 m/s,
    # DynamicInstability at 185 m/s, said to be flutter (on 16 strips, where p-k gives 172.2
    # m/s at 68.2 rad/s: answered at 165, flutter at 67.3 rad/s at 175, measured).
    from solver.inputs.gust import GustSettings
    from tests.flutter_reference import GOLAND, goland_mass

    wing = solver.Wing.create(
        np.linspace(0, GOLAND["semispan"], 9),
        GOLAND["chord"],
        GOLAND["elastic_axis"],
        GOLAND["bending_stiffness"],
        GOLAND["torsional_stiffness"],
        mass=goland_mass(9),
    )
    options = solver.SolverOptions(aerodynamics="unsteady_lattice", chordwise_panels=4)
    settings = GustSettings(clamped=True, turbulence=False)

    def answer(velocity: float) -> solver.GustResult:
        flight = solver.FlightCondition(velocity, 0.5, 1.02)
        return solver.gust_analysis(wing, flight, settings, options)

    assert answer(155.0).envelope is not None
    with pytest.raises(solver.DynamicInstability) as unstable:
        answer(185.0)
    assert "flutter" in str(unstable.value)
