"""The tube spar (`solver.inputs.spar`): its section properties against the analytic formulas and
the peers' (AeroSandbox's mid-wall diameter, OpenAeroStruct's radius), stresses consistent with the
internal loads at every station, margins, mass, and the study's "double penalty"."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

import solver
from tests.study import study_wing

CARBON = solver.Material(
    youngs_modulus=70e9, shear_modulus=27e9, density=1600.0, yield_stress=600e6
)
# A torsionally soft laminate (G / E as the study's GJ / EI = 0.05 / 2): its wing twists like
# the study's, so flexibility shows in the loads.
SOFT = dataclasses.replace(CARBON, shear_modulus=1.75e9)


def _spar_wing(material: solver.Material = CARBON, **changes) -> solver.Wing:
    base = study_wing()
    arguments = {
        "airfoil": "naca0012",
        "spar": solver.SparDesign(solver.ThicknessFraction(0.8), 0.001, material),
    } | changes
    return solver.Wing.create(base.y, base.chord, 0.4, **arguments)


@pytest.mark.parametrize(("outer", "wall"), [(0.05, 0.002), (0.02, 0.01), (1.0, 0.001)])
def test_tube_section_properties_are_the_thick_walled_formulas(outer, wall):
    tube = solver.TubeSpar(np.array([outer]), np.array([wall]), CARBON)
    inner = outer - 2 * wall
    assert tube.area[0] == pytest.approx(math.pi / 4 * (outer**2 - inner**2), rel=1e-14)
    assert tube.second_moment[0] == pytest.approx(math.pi / 64 * (outer**4 - inner**4), rel=1e-14)
    assert tube.polar_moment[0] == pytest.approx(2 * tube.second_moment[0], rel=1e-15)
    # AeroSandbox (TubeSparBendingStructure, thick tube): diameter is the wall's mid-line.
    middle = outer - wall
    asb = math.pi / 64 * ((middle + wall) ** 4 - (middle - wall) ** 4)
    assert tube.second_moment[0] == pytest.approx(asb, rel=1e-12)
    # OpenAeroStruct (SectionPropertiesTube): radius r2 = D/2, r1 = r2 - t.
    r2, r1 = outer / 2, outer / 2 - wall
    assert tube.area[0] == pytest.approx(math.pi * (r2**2 - r1**2), rel=1e-12)
    assert tube.polar_moment[0] == pytest.approx(math.pi * (r2**4 - r1**4) / 2, rel=1e-12)
    assert tube.bending_stiffness[0] == pytest.approx(70e9 * tube.second_moment[0], rel=1e-15)
    assert tube.torsional_stiffness[0] == pytest.approx(27e9 * tube.polar_moment[0], rel=1e-15)


def test_a_thin_tube_tends_to_the_thin_walled_formula():
    outer, wall = 0.1, 1e-4  # t / D = 1e-3: the thin-wall formula is O(t/D) off
    tube = solver.TubeSpar(np.array([outer]), np.array([wall]), CARBON)
    thin = math.pi / 8 * (outer - wall) ** 3 * wall
    assert tube.second_moment[0] == pytest.approx(thin, rel=1e-5)


def test_the_spar_sets_the_wings_stiffness_from_the_sections_thickness():
    wing = _spar_wing()
    outer = 0.8 * 0.12 * wing.chord
    assert np.allclose(wing.spar.outer_diameter, outer, rtol=1e-15)
    inner = outer - 0.002
    assert np.allclose(wing.bending_stiffness, 70e9 * math.pi / 64 * (outer**4 - inner**4))
    assert np.allclose(wing.torsional_stiffness, 27e9 * math.pi / 32 * (outer**4 - inner**4))


@pytest.mark.parametrize("flight", ["alpha", "trimmed"])
def test_stresses_are_the_internal_loads_over_the_section_at_every_station(flight):
    wing = _spar_wing(SOFT)
    if flight == "alpha":
        answer = solver.solve(wing, solver.FlightCondition(12.0, 4.0))
    else:
        answer = solver.trim(wing, solver.FlightCondition(12.0, lift=300.0))
    spar, stations = wing.spar, answer.stations
    radius = spar.outer_diameter / 2
    assert np.allclose(
        stations.bending_stress * spar.second_moment / radius,
        stations.bending_moment,
        rtol=1e-12,
        atol=1e-9,
    )
    assert np.allclose(
        stations.shear_stress * spar.polar_moment / radius, stations.torque, rtol=1e-12, atol=1e-9
    )
    expected = np.sqrt(stations.bending_stress**2 + 3 * stations.shear_stress**2)
    assert np.allclose(stations.von_mises_stress, expected, rtol=1e-14)
    totals = answer.totals
    worst = int(np.argmax(stations.von_mises_stress))
    assert totals.max_von_mises_stress == stations.von_mises_stress[worst]
    assert totals.max_von_mises_y == wing.y[worst]
    assert totals.failure_margin == pytest.approx(
        600e6 / totals.max_von_mises_stress - 1, rel=1e-14
    )
    assert totals.root_bending_stress == stations.bending_stress[0]
    # Tip: no load outboard, no stress.
    assert stations.von_mises_stress[-1] == 0.0


def test_a_round_tube_takes_its_share_of_the_in_plane_moment_as_a_second_bending_stress():
    """Bending about the section's two axes: the tube carries EI_tube / EI_lag of the
    section's in-plane moment (the section bends as one, at one curvature), and on a round
    tube the two bending stresses are the components of one, sqrt(s_f^2 + s_l^2) at the outer
    fibre. A section twice as stiff in its plane as the tube: a pure in-plane moment M stresses
    the tube as M / 2 about one axis would; with a flap moment 2 M / 3 as well, the 3-4-5
    triangle's 5 M / 6 (exact to round-off)."""
    tube = solver.TubeSpar(np.array([0.05]), np.array([0.002]), CARBON)
    moment, stiffness = np.array([120.0]), 2 * tube.bending_stiffness
    fibre = 0.025 / tube.second_moment[0]
    alone = tube.stresses(np.zeros(1), np.zeros(1), moment, stiffness)
    assert alone.bending[0] == 0.0
    assert alone.von_mises[0] == pytest.approx(60.0 * fibre, rel=1e-14)
    both = tube.stresses(moment * 2 / 3, np.zeros(1), moment, stiffness)
    assert both.von_mises[0] == pytest.approx(100.0 * fibre, rel=1e-14)
    plain = tube.stresses(moment * 2 / 3, np.zeros(1))
    assert plain.von_mises[0] == pytest.approx(80.0 * fibre, rel=1e-14)


def test_with_lag_the_spars_von_mises_stress_takes_its_in_plane_bending():
    """A spar wing bending in its plane (EI_lag three times the tube's) under the exact beam,
    at 4 deg: the reported von Mises stress is the flap bending, the tube's share of the
    in-plane moment and the torsional shear at the outer fibre (1e-12), and the in-plane
    bending raises it (the in-plane moment is a few per cent of the flap moment here)."""
    wing = _spar_wing(SOFT)
    lag = dataclasses.replace(wing, in_plane_bending_stiffness=3 * wing.bending_stiffness)
    options = solver.SolverOptions(structure="geometrically_exact")
    stations = solver.solve(lag, solver.FlightCondition(12.0, 4.0), options=options).stations
    assert stations.lag_bending_moment is not None and stations.von_mises_stress is not None
    in_plane = stations.lag_bending_moment / 3 * wing.spar.outer_diameter / 2
    in_plane = in_plane / wing.spar.second_moment
    expected = np.sqrt(stations.bending_stress**2 + in_plane**2 + 3 * stations.shear_stress**2)
    np.testing.assert_allclose(stations.von_mises_stress, expected, rtol=1e-12, atol=0)
    flap_only = np.sqrt(stations.bending_stress**2 + 3 * stations.shear_stress**2)
    assert stations.von_mises_stress[0] > flap_only[0]


def test_the_safety_factor_divides_the_allowable_stress():
    wing, flight = _spar_wing(), solver.FlightCondition(12.0, 4.0)
    plain = solver.solve(wing, flight).totals.failure_margin
    factored = solver.solve(wing, flight, options=solver.SolverOptions(safety_factor=1.5)).totals
    assert factored.failure_margin == pytest.approx((1 + plain) / 1.5 - 1, rel=1e-12)


@pytest.mark.parametrize("sweep", [0.0, 30.0], ids=["straight", "swept-30"])
def test_spar_mass_is_density_times_volume_of_both_halves(sweep):
    y = np.linspace(0.0, 5.0, 11)
    wing = solver.Wing.create(y, 1.0, 0.4, sweep=sweep, spar=solver.SparDesign(0.05, 0.002, CARBON))
    answer = solver.solve(wing, solver.FlightCondition(10.0, 2.0))
    area = math.pi / 4 * (0.05**2 - 0.046**2)
    length = 5.0 / math.cos(math.radians(sweep))  # along the elastic axis
    assert answer.totals.spar_mass == pytest.approx(2 * 1600.0 * area * length, rel=1e-12)


def test_without_a_spar_there_are_no_stresses_and_none_are_invented():
    answer = solver.solve(study_wing(), solver.FlightCondition(10.0, 5.0))
    for name in ("bending_stress", "shear_stress", "von_mises_stress"):
        assert getattr(answer.stations, name) is None
    for name in (
        "max_von_mises_stress",
        "max_von_mises_y",
        "failure_margin",
        "spar_mass",
        "root_bending_stress",
        "rigid_root_bending_stress",
    ):
        assert getattr(answer.totals, name) is None
    assert np.array_equal(answer.stations.bending_stiffness, study_wing().bending_stiffness)


def test_the_double_penalty_at_the_same_alpha_more_lift_and_further_outboard():
    """The study: the flexible wing carries more lift than the rigid one, and carries it further
    out, so its root bending stress grows by more than its lift."""
    answer = solver.solve(_spar_wing(SOFT), solver.FlightCondition(16.0, 4.0))
    totals = answer.totals
    stress_ratio = totals.root_bending_stress / totals.rigid_root_bending_stress
    assert totals.lift_amplification > 1.05
    assert stress_ratio > totals.lift_amplification


def test_at_the_same_lift_the_flexible_spar_is_still_more_stressed_at_the_root():
    answer = solver.trim(_spar_wing(SOFT), solver.FlightCondition(16.0, lift=300.0))
    totals = answer.totals
    assert totals.lift == pytest.approx(totals.rigid_lift, rel=1e-9)
    assert totals.root_bending_stress > 1.05 * totals.rigid_root_bending_stress  # measured 1.086
    # ... and a stiff spar (carbon's G) hardly twists: nearly the rigid wing's stress.
    stiff = solver.trim(_spar_wing(CARBON), solver.FlightCondition(16.0, lift=300.0)).totals
    assert stiff.root_bending_stress == pytest.approx(stiff.rigid_root_bending_stress, rel=0.01)


@pytest.mark.parametrize(
    ("arguments", "field"),
    [
        ({"bending_stiffness": 1e4}, "spar"),
        ({"airfoil": None}, "spar.outer_diameter"),
        (
            {"airfoil": "naca2412", "spar": solver.SparDesign(0.05, 0.03, CARBON)},
            "spar.wall_thickness",
        ),
        ({"spar": solver.SparDesign(-0.05, 0.001, CARBON)}, "spar.outer_diameter"),
    ],
    ids=[
        "spar-and-stiffness",
        "fraction-without-thickness",
        "wall-past-centre",
        "negative-diameter",
    ],
)
def test_a_spar_that_cannot_be_built_is_invalid_input(arguments, field):
    with pytest.raises(solver.InvalidInput) as raised:
        _spar_wing(**arguments)
    assert raised.value.field == field


def test_a_material_must_be_physical():
    with pytest.raises(solver.InvalidInput) as raised:
        dataclasses.replace(CARBON, yield_stress=0.0)
    assert raised.value.field == "yield_stress"


def test_a_wing_without_stiffness_or_spar_is_invalid_input():
    with pytest.raises(solver.InvalidInput) as raised:
        solver.Wing.create([0.0, 1.0, 2.0], 1.0, 0.4)
    assert raised.value.field == "bending_stiffness"
