"""flexwing reprints the design study's numbers (shared/seed/, chapter 14).

The wing is built from the study's own definitions, not from a reference file, and every number
is checked by formatting flexwing's value with the study's own print format: agreement "at the
printed rounding". AeroSandbox's CL divides by the DEFORMED wing's planform area
(`Equilibrium.deformed_area`); its rigid CL by the jig area. The study's density is
AeroSandbox's sea-level ISA value.
"""

from __future__ import annotations

import numpy as np
import pytest

import solver

AEROSANDBOX_SEA_LEVEL_DENSITY = 1.2249991558876672  # [kg/m^3]

# The study's wing (section 14.2) and flight condition.
N = 30
SPAN = 10.0  # [m]
YS = np.linspace(0, SPAN / 2, N)
CHORDS = np.sqrt(np.linspace(2, 0.02, N))
X_EA_OVER_CHORD = 0.40
EI = 2e4 * CHORDS**3
GJ = 1e3 * CHORDS**3
ALPHA = 5.0  # [deg]
V_CRUISE = 10.0  # [m/s]
V_SWEEP = [6, 12, 15, 18, 20]  # solved after the cruise point, each warm-started


@pytest.fixture(scope="module")
def wing() -> solver.Wing:
    return solver.Wing.create(YS, CHORDS, X_EA_OVER_CHORD, EI, GJ)


@pytest.fixture(scope="module")
def study_sweep(wing: solver.Wing) -> dict[float, solver.Equilibrium]:
    """The cruise point, then the study's sweep in its order, each from the previous solution."""
    result = solver.sweep(wing, [V_CRUISE, *V_SWEEP], ALPHA, AEROSANDBOX_SEA_LEVEL_DENSITY)
    assert all(point.equilibrium is not None for point in result.points)
    return {point.velocity: point.equilibrium for point in result.points}


@pytest.fixture(scope="module")
def cruise(study_sweep) -> solver.Equilibrium:
    return study_sweep[V_CRUISE]


def aerosandbox_cl(e: solver.Equilibrium) -> float:
    return e.lift / (e.dynamic_pressure * e.deformed_area)


def rigid_cl(e: solver.Equilibrium) -> float:
    return e.rigid_lift / (e.dynamic_pressure * e.reference_area)


def test_wing_area_and_aspect_ratio(wing: solver.Wing):
    area = wing.planform_area
    aspect_ratio = (2 * wing.semispan) ** 2 / area
    assert f"Wing area:    {area:.2f} m^2" == "Wing area:    9.51 m^2"
    assert f"Aspect ratio: {aspect_ratio:.1f}" == "Aspect ratio: 10.5"


def test_rigid_wing_lift_and_CL(cruise: solver.Equilibrium):
    printed = f"Rigid wing: L = {cruise.rigid_lift:.1f} N, CL = {rigid_cl(cruise):.3f}"
    assert printed == "Rigid wing: L = 259.4 N, CL = 0.445"


def test_flexible_wing_at_cruise(cruise: solver.Equilibrium):
    semispan = SPAN / 2
    amplification = aerosandbox_cl(cruise) / rigid_cl(cruise)  # the study's amp_cruise
    assert f"Tip twist:  {cruise.tip_twist:+.2f} deg" == "Tip twist:  +1.71 deg"
    heave_percent = cruise.tip_heave / semispan * 100
    assert (
        f"Tip heave:  {cruise.tip_heave:.3f} m ({heave_percent:.1f}% of semispan)"
        == "Tip heave:  0.050 m (1.0% of semispan)"
    )
    assert (
        f"Lift:       {cruise.lift:.1f} N flexible vs. {cruise.rigid_lift:.1f} N rigid "
        f"({(amplification - 1) * 100:+.1f}%)"
        == "Lift:       304.1 N flexible vs. 259.4 N rigid (+17.3%)"
    )


@pytest.mark.parametrize(
    ("velocity", "printed"),
    [
        pytest.param(6, "V =  6 m/s: CL = 0.470, tip twist =  0.55 deg", id="6ms"),
        pytest.param(12, "V = 12 m/s: CL = 0.565, tip twist =  2.67 deg", id="12ms"),
        pytest.param(15, "V = 15 m/s: CL = 0.666, tip twist =  4.93 deg", id="15ms"),
        pytest.param(18, "V = 18 m/s: CL = 0.847, tip twist =  8.89 deg", id="18ms"),
        pytest.param(20, "V = 20 m/s: CL = 1.070, tip twist = 13.65 deg", id="20ms"),
    ],
)
def test_airspeed_sweep(study_sweep, velocity: int, printed: str):
    e = study_sweep[velocity]
    line = (
        f"V = {velocity:2d} m/s: CL = {aerosandbox_cl(e):.3f}, tip twist = {e.tip_twist:5.2f} deg"
    )
    assert line == printed


def test_deformation_at_the_top_of_the_sweep(study_sweep):
    top = study_sweep[20]
    amplification = aerosandbox_cl(top) / rigid_cl(study_sweep[V_CRUISE])  # the study's amp_arr
    printed = (
        f"At 20 m/s: tip twist = {top.tip_twist:.1f} deg, "
        f"tip heave = {top.tip_heave:.2f} m ({top.tip_heave / (SPAN / 2) * 100:.0f}% of semispan), "
        f"lift amplification = {amplification:.2f}"
    )
    assert printed == (
        "At 20 m/s: tip twist = 13.7 deg, tip heave = 0.48 m (10% of semispan), "
        "lift amplification = 2.40"
    )


def test_every_sweep_point_is_stable_wash_in(study_sweep):
    """Section 14.3's prediction: elastic axis behind the quarter chord twists the wing nose-up
    and raises its lift; all the study's points lie below divergence."""
    for e in study_sweep.values():
        assert e.stability.stable
        assert np.all(e.twist[1:] > 0)
        assert e.lift > e.rigid_lift
