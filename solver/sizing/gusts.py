"""Gust load factors: CS-23.341's formula (Pratt's) and CS-23.333(c)'s derived gust velocities.

A vertical gust of velocity U (EAS) met at airspeed V (EAS) turns the wing's lift by
rho0 V U a S / 2 (the angle U/V times the dynamic pressure rho0 V^2 / 2 and the slope a): the
sharp-edged gust's load factor increment rho0 U V a / (2 W/S), times an alleviation factor F for a
graded gust (Megson, Aircraft Structures for Engineering Students, "Gust loads": eq. 8.33 in
section 8.6 of the 3rd edition, 1999; eq. 13.33 in section 13.4 of the 5th, 2012). A real
gust builds up over a distance while the aircraft rises with it and the lift lags (Wagner,
Kuessner): the gust alleviation factor K_g takes both into account for a rigid aircraft free to
plunge, not to pitch, flying into a one-minus-cosine gust 25 mean chords long,
U(s) = (U_de / 2) (1 - cos(2 pi s / 25 c)) (CS-23.333(c)(2)(i)); Pratt's fit of its peak
response against the mass ratio mu_g (Pratt, NACA TN 2964, 1953; Pratt and Walker, NACA
Report 1206, 1954) is CS-23.341(c)'s

    n = 1 +- K_g rho0 U_de V a / (2 W/S),   K_g = 0.88 mu_g / (5.3 + mu_g),
    mu_g = 2 (W/S) / (rho c a g)

rho0 the sea-level density, rho the air's at the altitude [kg/m^3], W/S the wing loading
[N/m^2] at the weight of the case, c the mean geometric chord [m], a the lift-curve slope
[1/rad] (of the airplane's normal force coefficient; the wing's when the tail's gust load is a
separate condition), g = 9.80665 m/s^2, V and U_de equivalent airspeeds [m/s]. The FAR's
imperial form n = 1 +- K_g U_de V a / (498 (W/S)) [U_de ft/s, V kt, W/S lb/ft^2] is the same:
498 = 2 / (rho0 * 1 kt in ft/s) with rho0 = 0.0023769 slug/ft^3.

Derived gust velocities U_de (CS-23.333(c)(1), EAS; ft/s converted exactly, CS-23 rounds them):
at V_C 15.24 m/s (50 ft/s), at V_D 7.62 m/s (25 ft/s), and for the commuter category at V_B
20.1168 m/s (66 ft/s), from sea level to 6,096 m (20,000 ft), each falling linearly to half
(V_C: 7.62, V_D: 3.81 m/s) or, at V_B, 11.5824 m/s (38 ft/s) at 15,240 m (50,000 ft). Below sea
level they keep their sea-level values; above 15,240 m, where the paragraph stops, their values
there (a choice: the rule says nothing).
"""

from __future__ import annotations

from typing import Literal

import numpy as np

from solver.inputs.atmosphere import SEA_LEVEL_DENSITY, STANDARD_GRAVITY

__all__ = [
    "GustSpeed",
    "derived_gust_velocity",
    "gust_alleviation_factor",
    "gust_load_factors",
    "gust_mass_ratio",
    "sharp_edged_gust_increment",
]

GustSpeed = Literal["rough_air", "cruise", "dive"]  # at V_B, V_C, V_D

# U_de [m/s] up to 20,000 ft and at 50,000 ft (CS-23.333(c)(1)(i)-(iii)), from ft/s.
_GUSTS: dict[str, tuple[float, float]] = {
    "rough_air": (66 * 0.3048, 38 * 0.3048),
    "cruise": (50 * 0.3048, 25 * 0.3048),
    "dive": (25 * 0.3048, 12.5 * 0.3048),
}
_FULL_UP_TO = 20_000 * 0.3048  # [m], 6,096
_REDUCED_AT = 50_000 * 0.3048  # [m], 15,240


def derived_gust_velocity(speed: GustSpeed, altitude: float | np.ndarray) -> float | np.ndarray:
    """U_de [m/s EAS] of CS-23.333(c)(1) at `speed` ("rough_air" V_B, "cruise" V_C, "dive"
    V_D) and altitude [m] (a number, or an array)."""
    full, reduced = _GUSTS[speed]
    fraction = np.clip((np.asarray(altitude) - _FULL_UP_TO) / (_REDUCED_AT - _FULL_UP_TO), 0, 1)
    velocity = full + (reduced - full) * fraction
    return float(velocity) if np.ndim(altitude) == 0 else velocity


def gust_mass_ratio(
    wing_loading: float, density: float, mean_chord: float, lift_slope: float
) -> float:
    """mu_g = 2 (W/S) / (rho c a g) [-]: the aircraft's mass against the air's in a cylinder of
    its wing's area and chord, W/S [N/m^2], rho [kg/m^3] at the altitude, c [m], a [1/rad]."""
    return 2.0 * wing_loading / (density * mean_chord * lift_slope * STANDARD_GRAVITY)


def gust_alleviation_factor(mass_ratio: float) -> float:
    """K_g = 0.88 mu_g / (5.3 + mu_g) [-] (CS-23.341(c)): 0.44 at mu_g = 5.3, 0.88 as the
    aircraft grows heavy against the air."""
    return 0.88 * mass_ratio / (5.3 + mass_ratio)


def sharp_edged_gust_increment(
    wing_loading: float,
    airspeed: float,
    gust_velocity: float,
    lift_slope: float,
    alleviation: float = 1.0,
) -> float:
    """Delta n = F rho0 U V a / (2 W/S) [-]: the load factor a gust U [m/s EAS] adds at airspeed
    V [m/s EAS], wing loading W/S [N/m^2], lift slope a [1/rad], times an alleviation factor F
    [-] (1: the sharp-edged gust; K_g: CS-23.341)."""
    return (
        alleviation
        * SEA_LEVEL_DENSITY
        * gust_velocity
        * airspeed
        * lift_slope
        / (2.0 * wing_loading)
    )


def gust_load_factors(
    wing_loading: float,
    airspeed: float,
    gust_velocity: float,
    lift_slope: float,
    mean_chord: float,
    density: float,
) -> tuple[float, float]:
    """(up, down) = 1 +- K_g rho0 U_de V a / (2 W/S) [-], CS-23.341(c): at airspeed V and gust
    U_de [m/s EAS], wing loading W/S [N/m^2], lift slope a [1/rad], mean geometric chord c [m]
    and the air's density rho [kg/m^3] at the altitude (of the mass ratio)."""
    alleviation = gust_alleviation_factor(
        gust_mass_ratio(wing_loading, density, mean_chord, lift_slope)
    )
    increment = sharp_edged_gust_increment(
        wing_loading, airspeed, gust_velocity, lift_slope, alleviation
    )
    return 1.0 + increment, 1.0 - increment
