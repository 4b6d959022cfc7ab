"""The V-n diagram of a flight envelope: its limits, its corners and gust points (the load cases
of `solver.sizing.cases`) and its boundary.

For each weight W and altitude of a `FlightEnvelope`, in equivalent airspeed V [m/s] and load
factor n [-] (CS-23.333(d) Figure 1; CS-25.333(b)):

    positive:  n = min(rho0 V^2 S C_Lmax / (2 W), n_max)            up to V_D
    negative:  n = max(rho0 V^2 S C_Lmin / (2 W), n_min up to V_C, then linear to n at V_D)
    gusts:     n = 1 +- K_g rho0 U_de V a / (2 W/S) at V_C and V_D (and V_B, commuter)

Its named points:

    A+   (V_A, n_max)      where the stall line meets n_max, or at the V_A given
    C+   (V_C, n_max)      D+  (V_D, n_max)
    G-   (V_G, n_min)      where the negative stall line meets the negative limit
    C-   (V_C, n_min)      D-  (V_D, 0 or -1)
    gust C+/C-, gust D+/D-, gust B+/B- (commuter)   (V, 1 +- Delta n)

each n on the envelope's boundary at its speed (a corner past the stall line is the stall
line's value: A+ at a V_A capped at V_D, C+ when V_C is below V_S sqrt(n_max)). Corners that
coincide are one point. The design speeds and load factors are the envelope's or the rules'
(`solver.sizing.regulations`): n_max, n_min, V_C and V_D once, from the maximum take-off weight;
V_S, V_A, V_G and V_B at each weight (V_B at each altitude too). V_A is V_S sqrt(n_max), not capped
at V_C (CS-23.335(c)(2) allows, not asks, it): the corner where the stall line meets n_max is
then a point even past V_C. The gust load factors are CS-23.341's for every category; for cs25
they are FAR 25.341's before Amendment 25-86 (1996), not CS-25.341's tuned discrete gust; only the
V_C and V_D gusts are given (solver.sizing.gusts).

A point whose n is 0 (D- of the normal, commuter and cs25 categories) has no lift to carry; a gust
point can lie beyond its speed's stall line (when V_C is low, or at a V_B that is V_S sqrt(n_g)):
each is kept as the rules place it, for the solve to judge.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal

import numpy as np

from solver import fields
from solver.errors import InvalidInput
from solver.inputs.atmosphere import SEA_LEVEL_DENSITY, density
from solver.inputs.envelope import Category, FlightEnvelope
from solver.sizing import gusts, regulations

__all__ = ["Kind", "VnDiagram", "VnPoint", "vn_diagram", "vn_diagrams"]

Kind = Literal["manoeuvre", "gust"]
_STALL_SAMPLES = 25  # points of each stall curve on the boundary


@dataclass(frozen=True)
class VnPoint:
    """A named point of the V-n diagram: `airspeed` EAS [m/s], `load_factor` [-], at design
    speed `speed` ("V_A", "V_C", ...)."""

    name: str
    speed: str
    airspeed: float
    load_factor: float
    kind: Kind


@dataclass(frozen=True)
class VnDiagram:
    """The manoeuvre and gust envelope at one weight [N] and altitude [m]: speeds EAS [m/s],
    load factors [-]; `boundary_airspeed`, `boundary_load_factor` (K,) the manoeuvre envelope's
    closed boundary (from (0, 0) along the positive stall line, n_max, down at V_D, back along
    the negative limit and stall line), `points` its corners then its gust points."""

    weight: float
    altitude: float
    category: Category
    wing_loading: float  # W/S [N/m^2]
    load_factor_max: float
    load_factor_min: float
    load_factor_at_dive: float  # the negative limit at V_D
    stall_speed: float  # V_S, 1 g at C_Lmax
    inverted_stall_speed: float  # -1 g at C_Lmin
    manoeuvring_speed: float  # V_A
    negative_manoeuvring_speed: float | None  # V_G; None: the negative stall line is the limit
    cruise_speed: float  # V_C
    dive_speed: float  # V_D
    rough_air_speed: float | None  # V_B, commuter only
    gust_mass_ratio: float  # mu_g
    gust_alleviation: float  # K_g
    points: tuple[VnPoint, ...]
    boundary_airspeed: np.ndarray
    boundary_load_factor: np.ndarray


@dataclass(frozen=True)
class _Design:
    """What holds at every weight: the aircraft's area, chord, slope, limits and speeds."""

    wing_area: float
    mean_chord: float
    lift_slope: float
    n_max: float
    n_min: float
    n_dive: float
    cruise: float
    dive: float


def _resolved(envelope: FlightEnvelope, name: str, fallback: float | None) -> float:
    """The envelope's `name`, else `fallback` (the wing's, checked as the envelope's field)."""
    value = getattr(envelope, name)
    if value is not None:
        return float(value)
    if fallback is None:
        raise InvalidInput(name, "is required: give it, or the wing it belongs to")
    return fields.number(name, fallback, fields.spec_of(FlightEnvelope, name))


def _design(
    envelope: FlightEnvelope,
    wing_area: float | None,
    mean_chord: float | None,
    lift_slope: float | None,
) -> _Design:
    area = _resolved(envelope, "wing_area", wing_area)
    category = envelope.category
    loading = envelope.design_weight / area
    rule_max, rule_min = regulations.limit_load_factors(category, envelope.design_weight)
    n_max = rule_max if envelope.load_factor_max is None else envelope.load_factor_max
    n_min = rule_min if envelope.load_factor_min is None else envelope.load_factor_min
    cruise = envelope.cruise_speed
    if cruise is None:
        cruise = regulations.minimum_cruise_speed(category, loading)
    dive = envelope.dive_speed
    if dive is None:
        dive = regulations.minimum_dive_speed(category, loading, cruise)
    elif dive <= cruise:
        raise InvalidInput("dive_speed", f"must be above V_C = {cruise:.6g} m/s (CS-23.335(a))")
    for name, limit, phrase in (
        ("manoeuvring_speed", dive, "V_D"),
        ("rough_air_speed", cruise, "V_C"),
    ):
        value = getattr(envelope, name)
        if value is not None and value > limit:
            raise InvalidInput(name, f"must not exceed {phrase} = {limit:.6g} m/s")
    return _Design(
        wing_area=area,
        mean_chord=_resolved(envelope, "mean_chord", mean_chord),
        lift_slope=_resolved(envelope, "lift_slope", lift_slope),
        n_max=n_max,
        n_min=n_min,
        n_dive=max(regulations.negative_limit_at_dive(category), n_min),
        cruise=cruise,
        dive=dive,
    )


def vn_diagram(
    envelope: FlightEnvelope,
    weight: float,
    altitude: float,
    *,
    wing_area: float | None = None,
    mean_chord: float | None = None,
    lift_slope: float | None = None,
) -> VnDiagram:
    """The V-n diagram of `envelope` at `weight` [N] and geopotential `altitude` [m]; the wing's
    area [m^2], mean geometric chord [m] and lift slope [1/rad] where the envelope has none."""
    fields.number("weight", weight, fields.spec_of(FlightEnvelope, "weights"))
    fields.number("altitude", altitude, fields.spec_of(FlightEnvelope, "altitudes"))
    return _diagram(
        envelope, _design(envelope, wing_area, mean_chord, lift_slope), weight, altitude
    )


def _diagram(
    envelope: FlightEnvelope, design: _Design, weight: float, altitude: float
) -> VnDiagram:
    loading = weight / design.wing_area
    q_per_v2 = 0.5 * SEA_LEVEL_DENSITY / loading  # n per V^2 at C_L = 1
    up, down = q_per_v2 * envelope.cl_max, q_per_v2 * abs(envelope.cl_min)
    stall, inverted = math.sqrt(1.0 / up), math.sqrt(1.0 / down)
    cruise, dive = design.cruise, design.dive
    if stall >= cruise:
        raise InvalidInput(
            "cruise_speed" if envelope.cruise_speed is not None else "cl_max",
            f"the stall speed V_S = {stall:.6g} m/s at {weight:g} N is not below V_C = "
            f"{cruise:.6g} m/s: no manoeuvre envelope",
        )
    slope = (design.n_dive - design.n_min) / (dive - cruise)

    corner = regulations.minimum_manoeuvring_speed(stall, design.n_max)
    inverted_corner = _negative_corner(down, design, slope)

    def negative_limit(v: float) -> float:
        return design.n_min + slope * max(v - cruise, 0.0)

    # Past a corner the limit itself, exactly (the stall line meets it there to round-off).
    def positive(v: float) -> float:
        return design.n_max if v >= corner else min(up * v * v, design.n_max)

    def negative(v: float) -> float:
        if inverted_corner is not None and v >= inverted_corner:
            return negative_limit(v)
        return max(-down * v * v, negative_limit(v))

    manoeuvring = envelope.manoeuvring_speed
    if manoeuvring is None:
        manoeuvring = min(corner, dive)
    elif manoeuvring < min(corner, cruise) * (1.0 - 1e-12):
        raise InvalidInput(
            "manoeuvring_speed",
            f"must be at least V_S sqrt(n_max) = {corner:.6g} m/s at {weight:g} N "
            "(CS-23.335(c)(1), CS-25.335(c)(1)), or V_C",
        )
    rho = float(density(altitude))
    mass_ratio = gusts.gust_mass_ratio(loading, rho, design.mean_chord, design.lift_slope)
    alleviation = gusts.gust_alleviation_factor(mass_ratio)

    def gust(v: float, at: gusts.GustSpeed) -> float:
        u = float(gusts.derived_gust_velocity(at, altitude))
        return gusts.sharp_edged_gust_increment(loading, v, u, design.lift_slope, alleviation)

    rough_air = None
    gust_speeds: list[tuple[str, str, gusts.GustSpeed, float]] = []
    if envelope.category == "commuter":
        rough_air = envelope.rough_air_speed
        if rough_air is None:
            rough_air = _rough_air_speed(up, gust(1.0, "rough_air"), stall, gust(cruise, "cruise"))
            rough_air = min(rough_air, cruise)
        gust_speeds.append(("B", "V_B", "rough_air", rough_air))
    gust_speeds += [("C", "V_C", "cruise", cruise), ("D", "V_D", "dive", dive)]

    corners = [
        ("A+", "V_A", manoeuvring, positive(manoeuvring)),
        ("C+", "V_C", cruise, positive(cruise)),
        ("D+", "V_D", dive, positive(dive)),
    ]
    if inverted_corner is not None:
        corners.append(("G-", "V_G", inverted_corner, negative(inverted_corner)))
    corners += [("C-", "V_C", cruise, negative(cruise)), ("D-", "V_D", dive, negative(dive))]
    points: list[VnPoint] = []
    for name, speed, v, n in corners:
        if all((p.airspeed, p.load_factor) != (v, n) for p in points):
            points.append(VnPoint(name, speed, v, n, "manoeuvre"))
    for letter, speed, at, v in gust_speeds:
        increment = gust(v, at)
        points.append(VnPoint(f"gust {letter}+", speed, v, 1.0 + increment, "gust"))
        points.append(VnPoint(f"gust {letter}-", speed, v, 1.0 - increment, "gust"))

    top = min(corner, dive)
    upper = [*np.linspace(0.0, top, _STALL_SAMPLES), *([dive] if top < dive else [])]
    bottom = dive if inverted_corner is None else inverted_corner
    lower = [
        dive,
        *([cruise] if bottom < cruise else []),
        *np.linspace(bottom, 0.0, _STALL_SAMPLES),
    ]
    boundary = [(v, positive(v)) for v in upper] + [(v, negative(v)) for v in lower]
    boundary = [p for i, p in enumerate(boundary) if i == 0 or p != boundary[i - 1]]
    return VnDiagram(
        weight=float(weight),
        altitude=float(altitude),
        category=envelope.category,
        wing_loading=loading,
        load_factor_max=design.n_max,
        load_factor_min=design.n_min,
        load_factor_at_dive=design.n_dive,
        stall_speed=stall,
        inverted_stall_speed=inverted,
        manoeuvring_speed=manoeuvring,
        negative_manoeuvring_speed=inverted_corner,
        cruise_speed=cruise,
        dive_speed=dive,
        rough_air_speed=rough_air,
        gust_mass_ratio=mass_ratio,
        gust_alleviation=alleviation,
        points=tuple(points),
        boundary_airspeed=_frozen([v for v, _ in boundary]),
        boundary_load_factor=_frozen([n for _, n in boundary]),
    )


def _frozen(values: list[float]) -> np.ndarray:
    array = np.array(values, dtype=float)
    array.setflags(write=False)
    return array


def _negative_corner(down: float, design: _Design, slope: float) -> float | None:
    """V_G [m/s]: where the negative stall line n = -down V^2 meets the negative limit (n_min to
    V_C, then rising by `slope` per m/s); None if it stays above the limit up to V_D."""
    if design.n_min >= 0.0:
        return None
    flat = math.sqrt(-design.n_min / down)
    if flat <= design.cruise:
        return flat
    # down V^2 + slope V + (n_min - slope V_C) = 0, the root past V_C.
    c = design.n_min - slope * design.cruise
    root = (-slope + math.sqrt(slope * slope - 4.0 * down * c)) / (2.0 * down)
    return root if root <= design.dive else None


def _rough_air_speed(
    up: float, gust_per_speed: float, stall: float, gust_at_cruise: float
) -> float:
    """V_B [m/s] of CS-23.335(d)(1): the lesser of where the positive stall line n = up V^2
    meets the rough-air gust line n = 1 + gust_per_speed V, and V_S sqrt(n_g), n_g the positive
    gust load factor at V_C (1 + gust_at_cruise)."""
    meet = (gust_per_speed + math.sqrt(gust_per_speed**2 + 4.0 * up)) / (2.0 * up)
    return min(meet, stall * math.sqrt(1.0 + gust_at_cruise))


def vn_diagrams(
    envelope: FlightEnvelope,
    *,
    wing_area: float | None = None,
    mean_chord: float | None = None,
    lift_slope: float | None = None,
) -> tuple[VnDiagram, ...]:
    """The V-n diagram at every weight and altitude of `envelope`, weight by weight (see
    `vn_diagram` for the wing's values)."""
    design = _design(envelope, wing_area, mean_chord, lift_slope)
    return tuple(
        _diagram(envelope, design, weight, altitude)
        for weight in envelope.weights
        for altitude in envelope.altitudes
    )
