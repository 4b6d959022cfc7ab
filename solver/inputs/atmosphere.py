"""The standard atmosphere (ISA): the air's temperature, pressure, density, speed of sound and
viscosity against altitude, and the conversion between equivalent and true airspeed.

The ICAO Standard Atmosphere (ICAO Doc 7488/3, 1993), to which certification rules refer (CS-
Definitions, "ISA"), is the U.S. Standard Atmosphere, 1976 (NOAA-S/T 76-1562, NASA-TM-X-74335)
below 80 km: seven layers of constant lapse rate in geopotential altitude H, hydrostatic, a
perfect gas, from sea level at T0 = 288.15 K, p0 = 101,325 Pa, rho0 = 1.225 kg/m^3:

    layer   base H [m]   lapse rate [K/m]   base T [K]   base p [Pa] (ICAO; 1976)
    0            0         -0.0065           288.15       101,325
    1       11,000          0                216.65        22,632.04;  22,632.06
    2       20,000         +0.0010           216.65         5,474.877;  5,474.889
    3       32,000         +0.0028           228.65           868.0158;   868.0187
    4       47,000          0                270.65           110.9058;   110.9063
    5       51,000         -0.0028           270.65            66.93853;   66.93887
    6       71,000         -0.0020           214.65             3.956392;   3.956420

The two differ only in the gas constant: ICAO's R = 287.05287 J/(kg K) (R* = 8314.32 J/(kmol
K), M0 = 28.964420 kg/kmol), the 1976 standard's R*/28.9644 = 287.05307; the pressures part by
up to 8e-6 at 80 km, below the 5 digits the tables are compared to. This is ICAO's. Only the lapse
rates and the sea-level values are data: each layer's base temperature and pressure follow from
the layer below (T = Tb + L (H - Hb); p = pb (Tb/T)^(g0/(R L)), or pb exp(-g0 (H - Hb)/(R Tb))
where L = 0), computed once here as the standard defines them.

Altitude is geopotential, H [m], from -5,000 m to 80,000 m (ICAO Doc 7488's range): the layers are
defined in it, the ICAO tables are printed against it, and in the standard atmosphere it is the
pressure altitude an altimeter set to 1013.25 hPa reads. Geometric height Z above sea level
converts by H = r0 Z / (r0 + Z), r0 = 6,356,766 m (`geopotential_altitude`,
`geometric_altitude`); the two differ by 0.16 % at 10 km (Z = 10,000 m is H = 9,984.3 m). Above
79 km geometric (H 79,006 m) the 1976 model's kinetic temperature departs from the
molecular-scale one computed here, by less than 2e-5 up to 80,000 m.

Density is rho0 (p/p0)(T0/T): p/(R T) scaled by rho0 R T0 / p0 = 1 - 1.5e-8, so that sea level is
exactly the 1.225 kg/m^3 the standard states and flexwing's default density
(`solver.inputs.flight.ISA_SEA_LEVEL_DENSITY`): a flight at 0 m and one at that density are the
same, bit for bit.

Speed of sound a = sqrt(gamma R T), gamma = 1.4; dynamic viscosity by Sutherland's law,
mu = beta T^1.5 / (T + S), beta = 1.458e-6 kg/(m s K^0.5), S = 110.4 K (both standards').

Every function takes an altitude as a number or an array (any shape) and answers in kind: a
float for a number, an array of the same shape for an array.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from solver.errors import InvalidInput
from solver.fields import Limits, is_number

__all__ = [
    "ALTITUDE_LIMITS",
    "Air",
    "EARTH_RADIUS",
    "GAS_CONSTANT",
    "HEAT_CAPACITY_RATIO",
    "SEA_LEVEL_DENSITY",
    "SEA_LEVEL_PRESSURE",
    "SEA_LEVEL_SPEED_OF_SOUND",
    "SEA_LEVEL_TEMPERATURE",
    "STANDARD_GRAVITY",
    "density",
    "dynamic_viscosity",
    "equivalent_airspeed",
    "geometric_altitude",
    "geopotential_altitude",
    "pressure",
    "speed_of_sound",
    "standard_atmosphere",
    "temperature",
    "true_airspeed",
]

STANDARD_GRAVITY = 9.80665  # g0 [m/s^2]
GAS_CONSTANT = 287.05287  # R = R*/M0 [J/(kg K)], ICAO Doc 7488's
HEAT_CAPACITY_RATIO = 1.4  # gamma [-]
EARTH_RADIUS = 6_356_766.0  # r0 [m], the 1976 standard's, for geopotential altitude
SEA_LEVEL_TEMPERATURE = 288.15  # T0 [K]
SEA_LEVEL_PRESSURE = 101_325.0  # p0 [Pa]
SEA_LEVEL_DENSITY = 1.225  # rho0 [kg/m^3]
_SUTHERLAND_BETA = 1.458e-6  # [kg/(m s K^0.5)]
_SUTHERLAND_S = 110.4  # [K]

ALTITUDE_LIMITS = Limits(
    ge=-5_000.0,
    le=80_000.0,
    why="the standard atmosphere's range (ICAO Doc 7488), geopotential",
)

# Each layer's base geopotential altitude [m] and lapse rate [K/m]: the standard's data.
_BASES = np.array([0.0, 11_000.0, 20_000.0, 32_000.0, 47_000.0, 51_000.0, 71_000.0])
_LAPSE_RATES = np.array([-0.0065, 0.0, 0.0010, 0.0028, 0.0, -0.0028, -0.0020])


def _layer_bases() -> tuple[np.ndarray, np.ndarray]:
    """Each layer's base temperature [K] and pressure [Pa], from the layer below (once)."""
    temperatures = [SEA_LEVEL_TEMPERATURE]
    pressures = [SEA_LEVEL_PRESSURE]
    for i in range(1, len(_BASES)):
        height = _BASES[i] - _BASES[i - 1]
        below, lapse = temperatures[-1], _LAPSE_RATES[i - 1]
        top = below + lapse * height
        if lapse == 0.0:
            ratio = math.exp(-STANDARD_GRAVITY * height / (GAS_CONSTANT * below))
        else:
            ratio = (below / top) ** (STANDARD_GRAVITY / (GAS_CONSTANT * lapse))
        temperatures.append(top)
        pressures.append(pressures[-1] * ratio)
    return np.array(temperatures), np.array(pressures)


_BASE_TEMPERATURES, _BASE_PRESSURES = _layer_bases()
SEA_LEVEL_SPEED_OF_SOUND = math.sqrt(
    HEAT_CAPACITY_RATIO * GAS_CONSTANT * SEA_LEVEL_TEMPERATURE
)  # a0 [m/s], 340.294 (340.29399)


def _altitudes(altitude: object, name: str = "altitude") -> np.ndarray:
    """`altitude` as a float array, finite and within `ALTITUDE_LIMITS`, else `InvalidInput`."""
    if not (is_number(altitude) or isinstance(altitude, np.ndarray | list | tuple)):
        raise InvalidInput(name, "must be a number or an array of numbers")
    try:
        values = np.asarray(altitude, dtype=float)
    except (TypeError, ValueError):
        raise InvalidInput(name, "must be a number or an array of numbers") from None
    if not np.all(np.isfinite(values)):
        raise InvalidInput(name, "must be a finite number")
    if not np.all(ALTITUDE_LIMITS.contains(values)):
        raise InvalidInput(
            name,
            f"must be from {ALTITUDE_LIMITS.ge:g} to {ALTITUDE_LIMITS.le:g} m "
            f"({ALTITUDE_LIMITS.why})",
        )
    return values


def _answer(values: np.ndarray, like: float | np.ndarray) -> float | np.ndarray:
    """A float for a number given, the array for an array."""
    return float(values) if np.ndim(like) == 0 else values


def _state(altitude: object) -> tuple[np.ndarray, np.ndarray]:
    """(temperature [K], pressure [Pa]) at the geopotential altitudes, each of their shape."""
    h = _altitudes(altitude)
    # The layer of each altitude; below sea level the first layer continues (to -5 km).
    layer = np.clip(np.searchsorted(_BASES, h, side="right") - 1, 0, len(_BASES) - 1)
    base_h, lapse = _BASES[layer], _LAPSE_RATES[layer]
    base_t, base_p = _BASE_TEMPERATURES[layer], _BASE_PRESSURES[layer]
    t = base_t + lapse * (h - base_h)
    isothermal = lapse == 0.0
    # Both branches are evaluated everywhere: the other branch's lapse is a harmless 1.
    gradient = (base_t / t) ** (
        STANDARD_GRAVITY / (GAS_CONSTANT * np.where(isothermal, 1.0, lapse))
    )
    constant = np.exp(-STANDARD_GRAVITY * (h - base_h) / (GAS_CONSTANT * base_t))
    p = base_p * np.where(isothermal, constant, gradient)
    return t, p


@dataclass(frozen=True)
class Air:
    """The standard atmosphere at an altitude (`standard_atmosphere`): floats for one altitude,
    arrays of its shape for an array."""

    altitude: float | np.ndarray  # H [m], geopotential
    temperature: float | np.ndarray  # T [K]
    pressure: float | np.ndarray  # p [Pa]
    density: float | np.ndarray  # rho [kg/m^3]
    speed_of_sound: float | np.ndarray  # a [m/s]
    dynamic_viscosity: float | np.ndarray  # mu [Pa s]


def standard_atmosphere(altitude: float | np.ndarray) -> Air:
    """Everything the standard atmosphere says at geopotential altitude H [m] (a number, or an
    array of any shape), computed once."""
    t, p = _state(altitude)
    return Air(
        altitude=_answer(np.asarray(altitude, dtype=float), altitude),
        temperature=_answer(t, altitude),
        pressure=_answer(p, altitude),
        density=_answer(_density(t, p), altitude),
        speed_of_sound=_answer(np.sqrt(HEAT_CAPACITY_RATIO * GAS_CONSTANT * t), altitude),
        dynamic_viscosity=_answer(_SUTHERLAND_BETA * t**1.5 / (t + _SUTHERLAND_S), altitude),
    )


def _density(t: np.ndarray, p: np.ndarray) -> np.ndarray:
    # rho0 (p/p0)(T0/T): p/(R T) to 1.5e-8, exactly rho0 at sea level (module docstring).
    return SEA_LEVEL_DENSITY * (p / SEA_LEVEL_PRESSURE) * (SEA_LEVEL_TEMPERATURE / t)


def temperature(altitude: float | np.ndarray) -> float | np.ndarray:
    """T [K] at geopotential altitude H [m] (a number, or an array of any shape)."""
    return _answer(_state(altitude)[0], altitude)


def pressure(altitude: float | np.ndarray) -> float | np.ndarray:
    """p [Pa] at geopotential altitude H [m]."""
    return _answer(_state(altitude)[1], altitude)


def density(altitude: float | np.ndarray) -> float | np.ndarray:
    """rho [kg/m^3] at geopotential altitude H [m]: p/(R T), sea level exactly 1.225 (module
    docstring)."""
    return _answer(_density(*_state(altitude)), altitude)


def speed_of_sound(altitude: float | np.ndarray) -> float | np.ndarray:
    """a = sqrt(gamma R T) [m/s] at geopotential altitude H [m]."""
    t, _ = _state(altitude)
    return _answer(np.sqrt(HEAT_CAPACITY_RATIO * GAS_CONSTANT * t), altitude)


def dynamic_viscosity(altitude: float | np.ndarray) -> float | np.ndarray:
    """mu [Pa s] at geopotential altitude H [m], by Sutherland's law."""
    t, _ = _state(altitude)
    return _answer(_SUTHERLAND_BETA * t**1.5 / (t + _SUTHERLAND_S), altitude)


def geopotential_altitude(geometric: float | np.ndarray) -> float | np.ndarray:
    """H = r0 Z / (r0 + Z) [m] of geometric height Z [m] above sea level."""
    z = np.asarray(geometric, dtype=float)
    return _answer(EARTH_RADIUS * z / (EARTH_RADIUS + z), geometric)


def geometric_altitude(geopotential: float | np.ndarray) -> float | np.ndarray:
    """Z = r0 H / (r0 - H) [m] of geopotential altitude H [m]."""
    h = np.asarray(geopotential, dtype=float)
    return _answer(EARTH_RADIUS * h / (EARTH_RADIUS - h), geopotential)


def _speeds(value: object, name: str) -> np.ndarray:
    if not (is_number(value) or isinstance(value, np.ndarray | list | tuple)):
        raise InvalidInput(name, "must be a number or an array of numbers")
    try:
        speeds = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise InvalidInput(name, "must be a number or an array of numbers") from None
    if not np.all(np.isfinite(speeds)) or np.any(speeds < 0.0):
        raise InvalidInput(name, "must be a finite airspeed of at least 0 m/s")
    return speeds


def true_airspeed(
    equivalent: float | np.ndarray, altitude: float | np.ndarray
) -> float | np.ndarray:
    """V_TAS = V_EAS sqrt(rho0 / rho(H)) [m/s] of equivalent airspeed V_EAS [m/s] at geopotential
    altitude H [m] (the same dynamic pressure rho V^2 / 2; numbers or broadcastable arrays)."""
    speeds = _speeds(equivalent, "equivalent_airspeed")
    ratio = SEA_LEVEL_DENSITY / np.asarray(density(altitude))
    shape_of = equivalent if np.ndim(equivalent) else altitude
    return _answer(speeds * np.sqrt(ratio), shape_of)


def equivalent_airspeed(
    true: float | np.ndarray, altitude: float | np.ndarray
) -> float | np.ndarray:
    """V_EAS = V_TAS sqrt(rho(H) / rho0) [m/s] of true airspeed V_TAS [m/s] at geopotential
    altitude H [m]."""
    speeds = _speeds(true, "true_airspeed")
    ratio = np.asarray(density(altitude)) / SEA_LEVEL_DENSITY
    shape_of = true if np.ndim(true) else altitude
    return _answer(speeds * np.sqrt(ratio), shape_of)
