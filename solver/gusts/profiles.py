"""The gusts of CS-25.341: the discrete 1-cos gust and continuous turbulence's von Karman
spectrum, with the regulation's reference velocities against altitude.

Discrete gust (CS-25.341(a)), s [m] the distance into the gust, H [m] the gradient (half its
length), from 9 m to 107 m:

    U(s) = (U_ds / 2) (1 - cos(pi s / H)),  0 <= s <= 2 H,
    U_ds = U_ref F_g (H / 107 m)^(1/6)   [m/s EAS],

U_ref 17.07 m/s EAS at sea level, falling linearly to 13.41 m/s at 4,572 m (15,000 ft) and to
6.36 m/s at 18,288 m (60,000 ft), halved at V_D (CS-25.341(a)(5)); F_g the flight profile
alleviation factor (CS-25.341(a)(6)): at sea level F_g = (F_gz + F_gm) / 2 with
F_gz = 1 - Z_mo / 76,200 m and F_gm = sqrt(R2 tan(pi R1 / 4)), R1 = MLW / MTOW,
R2 = MZFW / MTOW, rising linearly to 1 at the maximum operating altitude Z_mo.

Continuous turbulence (CS-25.341(b)): the von Karman spectrum of the vertical velocity, with
Omega [rad/m] the spatial frequency and L = 762 m (2,500 ft),

    Phi(Omega) = sigma^2 (L / pi) (1 + (8/3) (1.339 L Omega)^2) / (1 + (1.339 L Omega)^2)^(11/6),

one-sided: its integral over Omega from 0 to infinity is sigma^2. The design gust intensity
U_sigma = U_sigma_ref F_g, U_sigma_ref 27.43 m/s TAS at sea level falling linearly to
24.08 m/s at 7,315 m (24,000 ft), constant above; halved at V_D.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = [
    "GRADIENT_RANGE",
    "TURBULENCE_SCALE",
    "design_gust_velocity",
    "flight_profile_alleviation",
    "one_minus_cosine",
    "reference_gust_velocity",
    "turbulence_intensity",
    "von_karman",
]

GRADIENT_RANGE = (9.0, 107.0)  # [m] CS-25.341(a)(3)'s gust gradients H
REFERENCE_GRADIENT = 107.0  # [m] (350 ft)
TURBULENCE_SCALE = 762.0  # [m] L, CS-25.341(b)(2)
_VON_KARMAN = 1.339

# (altitude [m], U_ref [m/s EAS]) and (altitude [m], U_sigma_ref [m/s TAS]), linear between.
_U_REF = ((0.0, 17.07), (4572.0, 13.41), (18288.0, 6.36))
_U_SIGMA_REF = ((0.0, 27.43), (7315.0, 24.08), (18288.0, 24.08))


def _table(points: tuple[tuple[float, float], ...], altitude: float) -> float:
    heights, values = zip(*points, strict=True)
    return float(np.interp(altitude, heights, values))


def reference_gust_velocity(altitude: float, dive: bool = False) -> float:
    """U_ref [m/s EAS] at `altitude` [m] (CS-25.341(a)(5); the table's ends held beyond it),
    halved at V_D (`dive`)."""
    return _table(_U_REF, altitude) * (0.5 if dive else 1.0)


def turbulence_intensity(altitude: float, dive: bool = False) -> float:
    """U_sigma_ref [m/s TAS] at `altitude` [m] (CS-25.341(b)(3)), halved at V_D."""
    return _table(_U_SIGMA_REF, altitude) * (0.5 if dive else 1.0)


def flight_profile_alleviation(
    takeoff_weight: float,
    landing_weight: float,
    zero_fuel_weight: float,
    max_altitude: float,
    altitude: float,
) -> float:
    """F_g [-] of CS-25.341(a)(6) at `altitude` [m] for the maximum take-off, landing and
    zero-fuel weights [N] and the maximum operating altitude Z_mo [m]."""
    r1, r2 = landing_weight / takeoff_weight, zero_fuel_weight / takeoff_weight
    f_gm = math.sqrt(r2 * math.tan(math.pi * r1 / 4))
    f_gz = 1.0 - max_altitude / 76200.0
    at_sea_level = 0.5 * (f_gz + f_gm)
    if max_altitude <= 0:
        return 1.0
    fraction = min(max(altitude / max_altitude, 0.0), 1.0)
    return at_sea_level + (1.0 - at_sea_level) * fraction


def design_gust_velocity(gradient: float, reference: float, alleviation: float) -> float:
    """U_ds = U_ref F_g (H / 107 m)^(1/6) [m/s, as U_ref] for the gradient H [m]."""
    return reference * alleviation * (gradient / REFERENCE_GRADIENT) ** (1.0 / 6.0)


def one_minus_cosine(
    distance: np.ndarray, gradient: float | np.ndarray, amplitude: float | np.ndarray
) -> np.ndarray:
    """U(s) [as amplitude] of the 1-cos gust of gradient H [m] and peak `amplitude` at
    distances s [m] into it (zero before it and behind it)."""
    s = np.asarray(distance, dtype=float)
    inside = (s >= 0) & (s <= 2 * np.asarray(gradient))
    return np.where(inside, 0.5 * amplitude * (1 - np.cos(np.pi * s / gradient)), 0.0)


def von_karman(
    frequency: np.ndarray, velocity: float, scale: float = TURBULENCE_SCALE
) -> np.ndarray:
    """Phi(omega) [(m/s)^2 / (rad/s)] the one-sided von Karman spectrum of unit intensity
    (sigma = 1 m/s) at circular frequencies omega [rad/s] met at airspeed V [m/s]:
    Phi(Omega = omega / V) / V, so its integral over omega is 1."""
    x = _VON_KARMAN * scale * np.asarray(frequency, dtype=float) / velocity
    return (scale / (math.pi * velocity)) * (1 + (8.0 / 3.0) * x**2) / (1 + x**2) ** (11.0 / 6.0)
