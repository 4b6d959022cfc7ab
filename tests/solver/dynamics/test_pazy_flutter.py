"""Flutter of the Pazy wing with its skin (the third Aeroelastic Prediction Workshop's
large-deflection wing, `tests.pazy`), about its undeformed shape at sea level, against the
workshop's published MSC Nastran SOL 145 (the built-up finite-element model with strip theory
and with the doublet lattice) and UM/NAST (the equivalent beam with strip theory and with its
unsteady vortex lattice): Riso and Cesnik, J. Aircraft 2023, data in the AePW3-LDWG repository.

The two configurations flutter in different modes: without the 10 g trailing-edge mass the
doublet lattice finds the torsion-dominated mode at ~35 Hz first, strip theory the first
torsion-bending coupling at ~18 Hz; with it, both find the ~16 Hz mode. Which mode flutters
first is what the 3D unsteady wake decides here, and what the quasi-3D lattice gets wrong.
"""

from __future__ import annotations

import numpy as np
import pytest

import solver
from solver import SolverOptions
from tests.pazy import (
    BEAM_FREQUENCIES,
    DENSITY,
    NASTRAN,
    UM_NAST_FLUTTER,
    pazy_skin_mass,
    pazy_skin_wing,
)

SPEEDS = np.linspace(40.0, 120.0, 41)
HZ = 1.0 / (2.0 * np.pi)


def _flutter(trailing_edge_mass: bool, aerodynamics: str, chordwise: int = 1):
    options = SolverOptions(aerodynamics=aerodynamics, chordwise_panels=chordwise)
    return solver.flutter(
        pazy_skin_wing(), pazy_skin_mass(trailing_edge_mass), SPEEDS, DENSITY, options=options
    )


def test_the_pazy_beams_natural_frequencies_are_um_nasts():
    """Two bending modes, torsion, a third bending mode: 4.195, 28.82, 42.01, 84.72 Hz against
    UM/NAST's 4.191, 28.49, 41.88, 83.06 (measured 0.1, 1.2, 0.3, 2.0 %; the two beams'
    discretisations of the same 15 elements and 16 lumped keypoints)."""
    modes = solver.natural_modes(pazy_skin_wing(), pazy_skin_mass(False), 4).modes
    frequencies = [mode.frequency * HZ for mode in modes]
    assert frequencies == pytest.approx(BEAM_FREQUENCIES, rel=0.025)


@pytest.mark.parametrize("trailing_edge_mass", [False, True], ids=["clean", "trailing_edge_mass"])
def test_strip_theory_flutters_as_nastrans_strip_theory(trailing_edge_mass):
    """Theodorsen's strips against SOL 145's (and UM/NAST's) 2D aerodynamics: 82.93 m/s at
    18.20 Hz and 75.09 m/s at 16.58 Hz against Nastran's 82.90 at 18.17 and 74.77 at 16.59
    (measured +0.04 % and +0.4 %); divergence at 83.65 m/s against UM/NAST's 83.60 on the
    same beam (+0.06 %; Nastran's built-up model, 85.49)."""
    result = _flutter(trailing_edge_mass, "strip")
    speed, frequency, _ = NASTRAN[(trailing_edge_mass, "2D")]
    assert result.flutter is not None
    assert result.flutter.velocity == pytest.approx(speed, rel=0.01)
    assert result.flutter.frequency * HZ == pytest.approx(frequency, rel=0.01)
    assert result.divergence is not None
    assert result.divergence.velocity == pytest.approx(
        UM_NAST_FLUTTER[(trailing_edge_mass, "2D")][2], rel=0.005
    )


@pytest.mark.parametrize("trailing_edge_mass", [False, True], ids=["clean", "trailing_edge_mass"])
def test_the_unsteady_lattice_flutters_within_5_percent_of_the_doublet_lattice(
    trailing_edge_mass,
):
    """8 chordwise panels on the 15 strips: 68.56 m/s at 34.1 Hz and 86.43 m/s at 16.18 Hz
    against the doublet lattice's 67.30 at 34.72 and 86.53 at 16.16 (measured +1.9 % and -0.1 %;
    the issue's target 5 %); UM/NAST's unsteady vortex lattice, 72.40 and 91.77, is +7.6 % and
    +6.1 % from it. The same mode as Nastran's, at its frequency (within 2 %)."""
    result = _flutter(trailing_edge_mass, "unsteady_lattice", 8)
    speed, frequency, _ = NASTRAN[(trailing_edge_mass, "3D")]
    assert result.flutter is not None and result.aerodynamic_model == "unsteady_lattice"
    assert result.flutter.velocity == pytest.approx(speed, rel=0.05)
    assert result.flutter.frequency * HZ == pytest.approx(frequency, rel=0.03)


def test_the_quasi_3d_lattice_misses_the_clean_wings_flutter_that_the_unsteady_one_finds():
    """Without the trailing-edge mass the quasi-3D lattice (3D steady loading, Theodorsen's 2D
    lag) flutters at 81.5 m/s, +21 % from the doublet lattice; the unsteady lattice on the same
    4 panels, 70.0 m/s (+4 %)."""
    quasi = _flutter(False, "lattice", 4).flutter
    unsteady = _flutter(False, "unsteady_lattice", 4).flutter
    speed = NASTRAN[(False, "3D")][0]
    assert quasi is not None and unsteady is not None
    assert quasi.velocity > 1.15 * speed
    assert unsteady.velocity == pytest.approx(speed, rel=0.05)


def test_the_pazy_flutter_speed_converges_with_the_chordwise_panels():
    """Without the trailing-edge mass on 2, 4, 8 panels: each change at most 3/4 of the one
    before (the lattice's first order, as on the Goland wing), from above, towards Nastran's."""
    speeds = [_flutter(False, "unsteady_lattice", k).flutter.velocity for k in (2, 4, 8)]  # type: ignore[union-attr]
    assert speeds[0] > speeds[1] > speeds[2]
    assert speeds[1] - speeds[2] < 0.75 * (speeds[0] - speeds[1])
