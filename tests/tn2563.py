"""NACA TN 2563's straight wind-tunnel wing, as the OpenAeroStruct control-surface fork models it.

The experiment: a flexible, straight, tapered wing (aspect ratio 8, taper 0.45, 2 ft^2) with
30 % chord ailerons running in from the tip over 20 to 95 % of the semispan, its rolling
moment per degree of aileron measured at dynamic pressures of 10 to 40 psf (NACA TN 2563,
figs. 18-19). The numbers below are those of bbahiam/OpenAeroStruct,
`openaerostruct/examples/control_surfaces/Validation/data_TN2563_fig18_19.py` (digitised from
the report) and its model of the wing (`moment_validation.py`: the planform, the elastic axis
at 38 % of the chord, and the stiffness as a solid circular spar of radius
(2 j / pi)^(1/4) x 0.155 in, j a cubic fit of the relative stiffness it gives along the span,
E = 8.7 GPa, G = 2.82 GPa). That stiffness is the fork's reconstruction, not the report's own
table: it, the digitising and the wind tunnel (thickness, viscosity, the aileron's gaps) are
this comparison's uncertainty.
"""

from __future__ import annotations

import math

import numpy as np

import solver

PSF = 47.8803  # [Pa] per pound per square foot
DENSITY = 1.2  # [kg/m^3] the fork's
AREA = 2 * 0.092903  # [m^2] both halves
ASPECT_RATIO = 8.0
TAPER = 0.45
ELASTIC_AXIS = 0.38
HINGE = 0.70
# Measured rolling-moment coefficient per degree of aileron, Cl = L / (q S b), against q [psf];
# keyed by the aileron's span as a fraction of the semispan, from the tip in.
MEASURED = {
    0.20: [(10, 0.0018592), (20, 0.0015529), (25, 0.0013926), (30, 0.0012038), (35, 0.000894)],
    0.40: [
        (10, 0.0042741),
        (20, 0.0037898),
        (25, 0.0034442),
        (30, 0.0029634),
        (35, 0.0024825),
        (40, 0.0018449),
    ],
    0.60: [(10, 0.0066106), (15, 0.006251), (20, 0.0057987)],
    0.80: [(10, 0.0078574), (15, 0.0073979)],
    0.95: [(10, 0.0085128), (15, 0.0079749)],
}
# The fork's relative torsional stiffness along the semispan (eta = 0.05 ... 1).
_ETA = np.array([0.05, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0])
_RELATIVE = np.array(
    [
        28.43362832,
        24.43362832,
        17.53097345,
        12.04424779,
        8.04424779,
        5.10619469,
        3.12389381,
        1.84955752,
        1.17699115,
        0.92920354,
        1.0,
    ]
)


def wing(span_fraction: float, n: int = 21) -> solver.Wing:
    """The straight wing at n stations with an aileron over the outer `span_fraction`."""
    span = math.sqrt(AREA * ASPECT_RATIO)
    root = 2 * AREA / (span * (1 + TAPER))
    semispan = span / 2
    y = np.linspace(0.0, semispan, n)
    relative = np.polyval(np.polyfit(_ETA, _RELATIVE, 3), y / semispan)
    section = relative * (0.155 * 0.0254) ** 4  # [m^4] J of the solid spar; I = J / 2
    aileron = {
        "name": "aileron",
        "start": 1.0 - span_fraction,
        "end": 1.0,
        "hinge": HINGE,
        "kind": "aileron",
    }
    return solver.Wing.create(
        y,
        root * (1 - (1 - TAPER) * y / semispan),
        ELASTIC_AXIS,
        8.7e9 * section / 2,
        2.82e9 * section,
        control_surfaces=[aileron],
    )


def flight(q_psf: float) -> solver.FlightCondition:
    return solver.FlightCondition(math.sqrt(2 * q_psf * PSF / DENSITY), 0.0, DENSITY)
