"""The Pazy wing of the third Aeroelastic Prediction Workshop's large-deflection group: its public
equivalent beam and the published nonlinear static aeroelastic results of that beam.

Source: Riso and Cesnik's data in the workshop's repository, github.com/UM-A2SRL/AePW3-LDWG
(commit 435c112 for the results, 8b6c10b for the beam):

- the beam without skin ("skin0", wo_skin), 15 elements on a 0.5498 m reference axis at 44.1 %
  of the 0.0989 m chord (01_2022_SciTech_Riso_Cesnik/02_Models_Beam/03_Stiffness_Distributions/
  stiffness_wo_skin.txt; the chord, axis length and axis position as AeroBeams.jl takes them
  from the same data): K22 torsion GJ, K33 out-of-plane bending EI, K23 their coupling
  [N m^2], per element root to tip; NACA 0018 sections;
- UM/NAST's nonlinear beam (Su and Cesnik's geometrically exact strain-based formulation)
  coupled with a vortex lattice, no weight, root angles of attack 5 and 7 deg, sea-level air:
  the tip's vertical displacement [% semispan] and twist [deg] against the airspeed [m/s]
  (03_2023_JA_Riso_Cesnik/04_Static_Aeroelastic/02_Beam/
  static_aeroelastic_sweep_aoa{5,7}_skin0_{disp,rot}_UVLM.txt; Riso and Cesnik, "Geometrically
  Nonlinear Effects in Wing Aeroelastic Dynamics at Large Deflections", J. Aircraft 2023).
"""

from __future__ import annotations

import numpy as np

import solver

LENGTH = 0.549843728  # [m] the beam's reference axis
CHORD = 0.0989  # [m]
AXIS = 0.44096  # [-] of the chord from the leading edge
DENSITY = 1.225  # [kg/m^3]

TORSION = [7.28013126] * 4 + [6.44680609] * 4 + [6.45076354] * 4 + [7.04835928] * 2 + [17.16135]
BENDING = [
    4.59193373,
    4.44735598,
    4.42761615,
    4.42434873,
    4.42455633,
    4.42464442,
    4.42465,
    4.42464493,
    4.42464464,
    4.42460298,
    4.42441646,
    4.42583965,
    4.43874113,
    4.49851113,
    4.71030765,
]
COUPLING = (
    [0.106725354] * 4 + [-4.76189e-06] * 4 + [-0.001047135] * 4 + [-0.081077133] * 2 + [-1.40414551]
)

# airspeed [m/s]: (tip vertical displacement [% semispan], tip twist [deg]), UM/NAST-UVLM.
UM_NAST = {
    5.0: {
        10.0: (1.07359112361270, 0.0682392065772178),
        20.0: (4.43543433595340, 0.279461690804469),
        30.0: (10.4755521162080, 0.648866201332442),
        40.0: (19.6333081098088, 1.18025968491366),
        50.0: (31.7585589824219, 1.82045846813040),
        60.0: (45.3437641979396, 2.43429160704838),
    },
    7.0: {
        10.0: (1.49545611730152, 0.0948431395824675),
        20.0: (6.16296771540547, 0.384717858825331),
        30.0: (14.4009613945554, 0.871466247389877),
        40.0: (26.2109298667809, 1.50595657075103),
        50.0: (40.1892511342785, 2.14698381588840),
        60.0: (53.7604895951815, 2.64082543885264),
    },
}


def _per_station(elements: list[float]) -> np.ndarray:
    """Element values -> stations at the elements' ends (the mean of the two elements meeting
    there, each end its own element's)."""
    e = np.asarray(elements, dtype=float)
    return np.concatenate([[e[0]], (e[:-1] + e[1:]) / 2, [e[-1]]])


def pazy_wing(coupled: bool = True, refinement: int = 1) -> solver.Wing:
    """The equivalent beam on 16 stations (the elements' ends), or each element cut in
    `refinement` equal parts (15 refinement + 1 stations, each part the element's stiffness),
    symmetric sections.

    Its coupling is -K23: in Su and Cesnik's frame the chordwise axis b_y points to the leading
    edge, so a positive out-of-plane curvature bends the tip down while a positive twist rate
    turns the nose up; here bending up and nose up are both positive
    (`Wing.bending_torsion_coupling`). This reading of the frame is ours, from the
    formulation's papers, and the published twists agree with it (within 1 % to 30 m/s; with
    +K23 they are 10 to 15 % lower)."""
    n = len(BENDING) * refinement + 1

    def stations(elements: list[float]) -> np.ndarray:
        return _per_station(list(np.repeat(elements, refinement)))

    coupling = -stations(COUPLING) if coupled else 0.0
    return solver.Wing.create(
        np.linspace(0.0, LENGTH, n),
        CHORD,
        AXIS,
        stations(BENDING),
        stations(TORSION),
        airfoil="naca0018",
        bending_torsion_coupling=coupling,
    )
