"""The Pazy wing bent by its lift, in its plane too (`tests.pazy`, the equivalent beam with skin
and its in-plane stiffness K44, under the geometrically exact beam): its natural frequencies
about the bent equilibrium and its hump flutter, against the workshop's published UM/NAST
(Riso and Cesnik, J. Fluids and Structures 2023 and J. Aircraft 2023; AePW3-LDWG repository,
04_2023_JFS_Riso_Cesnik/02_Modal_Deformed and 03_2023_JA_Riso_Cesnik/06_Flutter_Deformed).

Bent up, the wing's torsion carries its outer part fore and aft (a section twisting about its
tangent swings whatever is raised above it), and the keypoints' lumped masses swing with it:
the torsion frequency falls towards the second bending's, and the in-plane one with it, as the
tip rises. Where they meet, near 31 Hz, the wing flutters in the hump mode of Drachinsky and
Raveh's tests, over a band of airspeed that narrows and falls as the root angle grows.
"""

from __future__ import annotations

import numpy as np
import pytest
import scipy.linalg

import solver
from solver.dynamics.modes import structure
from solver.model.lag_beam import bent_station_load_rows, bent_strip_load_rows
from solver.statics.system import CoupledSystem
from tests.pazy import DENSITY, pazy_skin_mass, pazy_skin_wing

HZ = 1.0 / (2.0 * np.pi)
LATTICE = solver.SolverOptions(structure="geometrically_exact", aerodynamics="lattice")

# UM/NAST with its vortex lattice, the wing without skin at 7 deg (modal_deformed_aoa7_UVLM_
# sweep.txt): tip heave [% semispan], torsion and in-plane frequencies [Hz] (the file's third
# and fifth, tracked from the undeformed modes), straight and at 25 to 40 m/s.
UVLM_BENT = np.array(
    [
        [0.0, 38.2143, 104.1929],
        [9.81436, 36.7044, 77.7136],
        [11.99007, 35.9174, 72.1164],
        [14.40096, 34.8443, 66.9887],
        [17.04286, 33.4496, 62.5990],
        [19.90509, 31.7462, 59.0591],
        [22.96974, 29.8143, 56.3444],
        [26.21093, 27.8736, 54.3326],
    ]
)


def _bent_frequencies(velocity: float) -> tuple[float, np.ndarray]:
    """The tip heave [% semispan] of the equilibrium at 7 deg and `velocity` [m/s] (the
    lattice) and the natural frequencies [Hz] about it, ascending: the exact beam's tangent
    rows, the lift's geometric stiffness at its circulation (q J1), the strips' and the
    keypoints' inertia on the bent wing."""
    wing = pazy_skin_wing(in_plane=True)
    answer = solver.solve(wing, solver.FlightCondition(velocity, 7.0, DENSITY), options=LATTICE)
    system = CoupledSystem.of(wing, 7.0, LATTICE)
    layout, x, q = system.layout, answer.state, answer.dynamic_pressure
    evaluation = system.evaluate(x)
    rotations = (x[layout.slope], x[layout.twist], x[layout.lag_rotation])
    beam = structure(
        wing,
        pazy_skin_mass(False),
        rows=evaluation.jacobian0[layout.structure_rows, layout.structure],
        in_plane_bending_stiffness=wing.in_plane_bending_stiffness,
        strip_load_rows=bent_strip_load_rows(wing, *rotations),
        flap_rotation=rotations[0],
        station_load_rows=bent_station_load_rows(wing, *rotations),
    )
    geometric = beam.strip_loads_of(
        evaluation.jacobian1[layout.load_rows][:, layout.structure] @ beam.states
    )
    values = scipy.linalg.eigvals(beam.stiffness - q * geometric, beam.mass)
    tip = 100 * float(answer.stations.axis_z[-1]) / wing.semispan
    return tip, np.sort(np.sqrt(values.real)) * HZ


@pytest.mark.parametrize("velocity", [30.0, 35.0], ids=["30ms", "35ms"])
def test_pd1_bent_up_the_torsion_and_in_plane_frequencies_fall_as_um_nasts(velocity):
    """At 7 deg the tip rises 14.0 and 19.4 % of the semispan at 30 and 35 m/s; the torsion
    frequency falls to 0.903 and 0.817 of its straight 42.01 Hz, the in-plane one to 0.648 and
    0.577 of its 111.75 Hz; UM/NAST-VLM's at the same tip heave (its wing without skin, its
    own straight 38.21 and 104.19 Hz): 0.917, 0.839 and 0.651, 0.573 (measured: -1.5, -2.6,
    -0.4, +0.6 %). Held to 4 %: the two beams' skins differ, and the fall is the whole effect
    (with the keypoints' masses on the jig's load rows, before round 4's fix, the torsion rose:
    1.004 and 1.006)."""
    straight = _bent_frequencies(0.1)[1]
    tip, bent = _bent_frequencies(velocity)
    theirs = UVLM_BENT
    torsion = np.interp(tip, theirs[:, 0], theirs[:, 1]) / theirs[0, 1]
    in_plane = np.interp(tip, theirs[:, 0], theirs[:, 2]) / theirs[0, 2]
    # Ours: the torsion the third, the in-plane the fifth straight; bent, the in-plane one
    # falls below the third bending (85 Hz) and is the fourth.
    assert bent[2] / straight[2] == pytest.approx(torsion, rel=0.04)
    assert bent[3] / straight[4] == pytest.approx(in_plane, rel=0.04)


def test_pd2_at_7_deg_the_wing_flutters_in_the_hump_mode_where_um_nast_does():
    """The lattice's loads with Theodorsen's lag on the 36 lowest natural modes (the bent
    wing's swing needs the higher in-plane modes: the default twelve miss the hump; 30 modes
    put it at 38.35 to 42.39 m/s, 36 at 37.65 to 40.07, all 45 at 37.63 to 40.05), at 7 deg:
    the root near 31 Hz grows from 37.65 m/s to 40.07 m/s at 30.5 Hz (measured, the least
    damping in 25-35 Hz interpolated to zero between airspeeds 1 m/s apart); UM/NAST's from
    37.19 to 41.48 m/s at 30.5 Hz (its strip theory with tip loss; the test's 29.4 Hz). Held to
    3 % in onset and frequency, 5 % in offset."""
    speeds = np.arange(36.0, 42.01, 1.0)
    result = solver.flutter(
        pazy_skin_wing(in_plane=True),
        pazy_skin_mass(False),
        speeds,
        DENSITY,
        alpha=7.0,
        options=LATTICE,
        flutter_options=solver.FlutterOptions(modes=36),
    )
    roots = np.array(result.roots)
    frequency, damping = np.abs(roots.imag) * HZ, -roots.real / np.abs(roots)
    band = (frequency > 25.0) & (frequency < 35.0)
    least = np.where(band, damping, np.inf).min(axis=1)
    crossings = [
        speeds[i] + (speeds[i + 1] - speeds[i]) * least[i] / (least[i] - least[i + 1])
        for i in range(speeds.size - 1)
        if (least[i] < 0) != (least[i + 1] < 0)
    ]
    assert len(crossings) == 2, least  # it grows, then it is damped again
    onset, offset = crossings
    assert onset == pytest.approx(37.19, rel=0.03)
    assert offset == pytest.approx(41.48, rel=0.05)
    first = int(np.argmax(least < 0))
    hump = np.where(band[first], damping[first], np.inf).argmin()
    assert frequency[first, hump] == pytest.approx(30.5, rel=0.03)
    # The answer's flutter is the hump's onset: the mesh's highest modes, which grow by 1e-9 to
    # 1e-4 of critical from the lowest airspeeds at thousands of Hz (k of 6 to 300), are past
    # the reduced frequency that counts (5).
    assert result.flutter is not None
    assert result.flutter.velocity == pytest.approx(onset, rel=2e-3)
    assert result.flutter.frequency * HZ == pytest.approx(30.5, rel=0.03)
