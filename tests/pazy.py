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


# --- The wing with its skin, its inertia and flutter -------------------------------------------
#
# Source: the same repository (commit 396710a): the equivalent beam with skin
# (00_Models/01_Pazy_Technion/02_Models_Beam/03_Stiffness_Distributions/stiffness_skin1.xlsx:
# K22, K33, K23 per element), its inertia per keypoint (02_Inertia_Distributions/
# inertia_skin1.xlsx: CONM2 mass, cgx, Iyy in the Nastran frame, x aft, y along the span,
# keypoints at 01_Coordinates/coordinates.txt), the 10 g trailing-edge mass the flutter results
# add at the tip 0.01 m behind the trailing edge (the beam README; sol145.dat's CONM2), and the
# flutter and divergence speeds of MSC Nastran SOL 145 on the built-up finite-element model
# and of UM/NAST on the beam, each with 2D (strip) and 3D (doublet lattice; UM/NAST's unsteady
# vortex lattice) aerodynamics, sea level, about the undeformed wing
# (03_2023_JA_Riso_Cesnik/05_Flutter_Undeformed/00_Comparisons/GFEM_vs_Beam.xlsx; Riso and
# Cesnik, J. Aircraft 2023).

KEYPOINTS = [
    0.0,
    0.0382499984,
    0.0764999976,
    0.114749997,
    0.152999996,
    0.191249995,
    0.229499995,
    0.267749994,
    0.305999993,
    0.344249993,
    0.382499992,
    0.420749991,
    0.45899999,
    0.49724999,
    0.530718683,
    0.549843728,
]  # [m] along the axis
SKIN_TORSION = (
    [7.58259714] * 4 + [6.51183018] * 4 + [6.51583594] * 4 + [7.11892627] * 2 + [17.3730728]
)
SKIN_BENDING = [
    5.24743501,
    4.50448461,
    4.47822861,
    4.47438433,
    4.47481272,
    4.47492882,
    4.47492903,
    4.47492905,
    4.47492889,
    4.47488638,
    4.47471764,
    4.47618354,
    4.48916524,
    4.54819972,
    4.77037999,
]
SKIN_COUPLING = (
    [0.0933080027] * 4
    + [4.22659591e-05] * 4
    + [-0.00102012319] * 4
    + [-0.0809780725] * 2
    + [-1.39455813]
)
# K44 of the same file: the in-plane (lag) bending stiffness per element [N m^2], about 740
# times K33 (`wing.in_plane_bending_stiffness` under the geometrically exact beam).
SKIN_IN_PLANE = [
    3317.57932,
    3278.62894,
    3282.87728,
    3286.53821,
    3288.81887,
    3290.12279,
    3290.7182,
    3290.71311,
    3290.15111,
    3288.92576,
    3286.8598,
    3283.51136,
    3279.04566,
    3271.6443,
    3373.72291,
]
KEYPOINT_MASS = [
    0.0191186108,
    0.0206788141,
    0.020682834,
    0.0206828274,
    0.0206828571,
    0.0206828792,
    0.0206828498,
    0.0206828527,
    0.0206828616,
    0.0206828621,
    0.0206828626,
    0.020682863,
    0.0206828635,
    0.0206828635,
    0.0254479524,
    0.0431558925,
]  # [kg]
KEYPOINT_OFFSET = [
    -6.09115952e-06,
    0.000903114429,
    0.000913241152,
    0.000913181107,
    0.000913136269,
    0.000913139373,
    0.00091314846,
    0.000913133755,
    0.00091313894,
    0.000913138146,
    0.000913137351,
    0.000913136557,
    0.000913135762,
    0.000913135762,
    -0.000811101073,
    0.00509272488,
]  # [m] aft of the axis
KEYPOINT_PITCH_INERTIA = [
    1.21416697e-05,
    1.09721424e-05,
    1.09788396e-05,
    1.09788493e-05,
    1.09788664e-05,
    1.09788786e-05,
    1.09788644e-05,
    1.09788687e-05,
    1.09788717e-05,
    1.09788723e-05,
    1.09788729e-05,
    1.09788735e-05,
    1.09788741e-05,
    1.09788741e-05,
    1.45515348e-05,
    0.00012220022,
]  # [kg m^2] about each keypoint's centre of gravity, about the spanwise axis
TRAILING_EDGE_MASS = 0.010  # [kg]
TRAILING_EDGE_MASS_OFFSET = CHORD * (1.0 - AXIS) + 0.01  # [m] aft of the axis

# UM/NAST's beam in vacuum (03_2023_JA_Riso_Cesnik/01_Modal_Undeformed/06_Beam_Final/
# frequencies_skin1.txt): two bending, torsion, bending [Hz] (its fifth is in-plane).
BEAM_FREQUENCIES = [4.190633791, 28.49324108, 41.87892750, 83.06458617]

# (trailing-edge mass, aerodynamics): (flutter [m/s], flutter [Hz], divergence [m/s]).
NASTRAN = {
    (False, "2D"): (82.9041, 18.1703, 85.4947),
    (False, "3D"): (67.3009, 34.7225, 100.9657),
    (True, "2D"): (74.7739, 16.5871, 85.4975),
    (True, "3D"): (86.525, 16.1591, 100.9688),
}
UM_NAST_FLUTTER = {
    (False, "2D"): (83.6014, 17.7247, 83.6168),
    (False, "3D"): (72.4037, 34.7217, 98.3154),
    (True, "2D"): (75.701, 16.1537, 83.6009),
    (True, "3D"): (91.7714, 12.8041128719477, 98.3148),
}


def pazy_skin_wing(in_plane: bool = False) -> solver.Wing:
    """The equivalent beam with skin on its 16 keypoints, its coupling -K23 (`pazy_wing`);
    `in_plane`: bending in its plane too (K44, `SKIN_IN_PLANE`)."""
    lag = {"in_plane_bending_stiffness": _per_station(SKIN_IN_PLANE)} if in_plane else {}
    return solver.Wing.create(
        np.asarray(KEYPOINTS),
        CHORD,
        AXIS,
        _per_station(SKIN_BENDING),
        _per_station(SKIN_TORSION),
        airfoil="naca0018",
        bending_torsion_coupling=-_per_station(SKIN_COUPLING),
        **lag,
    )


def pazy_skin_mass(trailing_edge_mass: bool) -> solver.MassModel:
    """The keypoints' inertia as concentrated masses at the stations (as the workshop's CONM2
    cards), with the 10 g trailing-edge mass at the tip or without; the distributed mass a
    negligible 1e-9 kg/m (the model asks for one)."""
    masses = [
        solver.ConcentratedMass.create(i, m, inertia, offset)
        for i, (m, inertia, offset) in enumerate(
            zip(KEYPOINT_MASS, KEYPOINT_PITCH_INERTIA, KEYPOINT_OFFSET, strict=True)
        )
    ]
    if trailing_edge_mass:
        tip = len(KEYPOINTS) - 1
        masses.append(
            solver.ConcentratedMass.create(tip, TRAILING_EDGE_MASS, 0.0, TRAILING_EDGE_MASS_OFFSET)
        )
    return solver.MassModel.create(len(KEYPOINTS), 1e-9, AXIS, 1e-15, masses)
