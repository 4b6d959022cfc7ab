"""The certification rules' limit load factors and design speeds, in SI units.

Which text: EASA CS-23 up to Amendment 4 (2015), paragraphs 23.333 to 23.341, the same numbers
as 14 CFR part 23 before Amendment 23-64 (2017), FAR 23.333 to 23.341. CS-23 Amendment 5 (2017)
replaced them with objectives (CS 23.2200, 23.2215) and accepts ASTM F3116 ("Design Loads and
Conditions") as the means of compliance, which carries these same numbers over. CS-25
(Amendment 27): 25.333 to 25.337. The rules state W in pounds, W/S in lb/ft^2 and speeds in
knots; each is converted exactly (1 lbf = 4.4482216152605 N, 1 ft = 0.3048 m, 1 kt = 1852/3600
m/s) and the SI form given. Speeds are equivalent airspeeds (EAS), as the rules select them.

Limit manoeuvring load factors (CS-23.337, CS-25.337), W the design maximum take-off weight:
    normal, commuter   n_max = 2.1 + 24,000 / (W + 10,000) [W in lb], need not exceed 3.8
    utility            n_max = 4.4
    aerobatic          n_max = 6.0
    cs25               n_max = 2.1 + 24,000 / (W + 10,000), at least 2.5, need not exceed 3.8
    n_min = -0.4 n_max (normal, utility, commuter), -0.5 n_max (aerobatic), -1.0 (cs25)
and from V_C to V_D the negative limit varies linearly to 0 (normal, commuter, CS-23.333(b)(3);
cs25, CS-25.337(c)(2)) or to -1.0 (utility, aerobatic, CS-23.333(b)(3)).

Design speeds (CS-23.335, CS-25.335):
    V_S = sqrt(2 W / (rho0 S C_Lmax))                        the 1-g stall speed, EAS
    V_A >= V_S sqrt(n_max)                  (c)(1); need not exceed V_C, (c)(2)
    V_C >= k sqrt(W/S) [kt, W/S in lb/ft^2] (a)(1): k = 33 (normal, utility, commuter),
        36 (aerobatic), falling linearly from W/S = 20 to 28.6 at W/S = 100 (a)(2);
        in SI, V_C >= 0.074346 k sqrt(W/S) [m/s, W/S in N/m^2] (33: 2.4534 sqrt(W/S))
    V_D >= 1.25 V_C                         (b)(1), and
    V_D >= f V_C,min                        (b)(2): f = 1.40 (normal, commuter), 1.50
        (utility), 1.55 (aerobatic), falling linearly from W/S = 20 to 1.35 at W/S = 100 (b)(3)
CS-25.335(a) leaves V_C to the applicant (above V_B by margins of gust): it is required. CS-25.335
(b) asks V_C/M_C <= 0.8 V_D/M_D, or a margin found by an upset manoeuvre: V_D = V_C / 0.8 is the
first, taken when V_D is not given. Past W/S = 100 lb/ft^2 the rules' factors stay at their
values there (the text stops).
"""

from __future__ import annotations

import math

from solver.inputs.atmosphere import SEA_LEVEL_DENSITY
from solver.inputs.envelope import Category

__all__ = [
    "FOOT",
    "KNOT",
    "POUND_FORCE",
    "POUNDS_PER_SQUARE_FOOT",
    "limit_load_factors",
    "minimum_cruise_speed",
    "minimum_dive_speed",
    "minimum_manoeuvring_speed",
    "negative_limit_at_dive",
    "stall_speed",
]

POUND_FORCE = 4.4482216152605  # [N]
FOOT = 0.3048  # [m]
KNOT = 1852.0 / 3600.0  # [m/s]
POUNDS_PER_SQUARE_FOOT = POUND_FORCE / FOOT**2  # [Pa], 47.880


def _between(wing_loading: float, at_20: float, at_100: float) -> float:
    """A factor falling linearly with W/S [Pa] from `at_20` at 20 lb/ft^2 to `at_100` at 100
    lb/ft^2, constant outside (CS-23.335(a)(2), (b)(3))."""
    psf = wing_loading / POUNDS_PER_SQUARE_FOOT
    fraction = min(max((psf - 20.0) / 80.0, 0.0), 1.0)
    return at_20 + (at_100 - at_20) * fraction


def limit_load_factors(category: Category, max_takeoff_weight: float) -> tuple[float, float]:
    """(n_max, n_min) [-], the limit manoeuvring load factors of CS-23.337 / CS-25.337 for the
    design maximum take-off weight W [N] (n_min the one up to V_C)."""
    pounds = max_takeoff_weight / POUND_FORCE
    by_weight = 2.1 + 24_000.0 / (pounds + 10_000.0)
    if category in ("normal", "commuter"):
        n_max = min(by_weight, 3.8)
    elif category == "utility":
        n_max = 4.4
    elif category == "aerobatic":
        n_max = 6.0
    elif category == "cs25":
        return min(max(by_weight, 2.5), 3.8), -1.0
    else:
        raise ValueError(f"unknown category {category!r}")
    return n_max, -(0.5 if category == "aerobatic" else 0.4) * n_max


def negative_limit_at_dive(category: Category) -> float:
    """The negative limit manoeuvring load factor at V_D [-]: 0 (normal, commuter: CS-23.333(b)
    (3); cs25: CS-25.337(c)(2)) or -1.0 (utility, aerobatic: CS-23.333(b)(3))."""
    return -1.0 if category in ("utility", "aerobatic") else 0.0


def stall_speed(
    weight: float, wing_area: float, lift_coefficient: float, density: float = SEA_LEVEL_DENSITY
) -> float:
    """V_S = sqrt(2 W / (rho S |C_L|)) [m/s]: the speed where lift coefficient C_L [-] carries
    weight W [N] on area S [m^2] at 1 g; EAS at the default sea-level density rho [kg/m^3]
    (C_L = C_Lmax: the 1-g stall; C_Lmin: the inverted one)."""
    return math.sqrt(2.0 * weight / (density * wing_area * abs(lift_coefficient)))


def minimum_manoeuvring_speed(stall_speed: float, load_factor_max: float) -> float:
    """V_S sqrt(n_max) [m/s]: the least design manoeuvring speed V_A (CS-23.335(c)(1),
    CS-25.335(c)(1)), where the stall line reaches n_max."""
    return stall_speed * math.sqrt(load_factor_max)


def minimum_cruise_speed(category: Category, wing_loading: float) -> float:
    """V_C,min [m/s EAS] of CS-23.335(a) at the maximum take-off wing loading W/S [N/m^2]:
    k sqrt(W/S) knots with W/S in lb/ft^2, k = 33 (36 aerobatic) falling to 28.6 from 20 to
    100 lb/ft^2. CS-25 has none (ValueError)."""
    if category == "cs25":
        raise ValueError("CS-25.335(a) derives no minimum cruising speed")
    k = _between(wing_loading, 36.0 if category == "aerobatic" else 33.0, 28.6)
    return k * math.sqrt(wing_loading / POUNDS_PER_SQUARE_FOOT) * KNOT


def minimum_dive_speed(category: Category, wing_loading: float, cruise_speed: float) -> float:
    """V_D,min [m/s EAS] for design cruising speed V_C [m/s EAS] at the maximum take-off wing
    loading W/S [N/m^2]: CS-23.335(b), the larger of 1.25 V_C and f V_C,min (f = 1.40 normal and
    commuter, 1.50 utility, 1.55 aerobatic, falling to 1.35 from 20 to 100 lb/ft^2); CS-25.335
    (b), V_C / 0.8."""
    if category == "cs25":
        return cruise_speed / 0.8
    factor = {"normal": 1.40, "commuter": 1.40, "utility": 1.50, "aerobatic": 1.55}[category]
    by_loading = _between(wing_loading, factor, 1.35) * minimum_cruise_speed(category, wing_loading)
    return max(1.25 * cruise_speed, by_loading)
