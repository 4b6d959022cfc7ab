"""Gust loads' answers: each 1-cos gust's response (load factor, the stations' incremental
shear, bending moment and torque envelopes, tip deflection, in time), the tuned gusts, the
envelope of total loads (1 g plus gust, up and down), continuous turbulence's A-bar and design
loads, and Pratt's K_g beside the model.

Signs: loads as the static answer's (`solver.results.equilibrium.Stations`: shear and bending
moment positive for lift up, torque nose-up); an up gust's response, a down gust's is its
negative (the model is linear)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from solver.results.quantities import quantity

__all__ = ["GustCase", "GustLoadCase", "GustResult", "TurbulenceLoads"]


@dataclass(frozen=True, eq=False)
class GustCase:
    """The response to one 1-cos up gust."""

    name: str = quantity("", "the case's name ('1-cos H = 52 m up at 12 m/s')")
    gradient: float = quantity("m", "the gust gradient H (half its length; 0: a given profile)")
    gust_velocity: float = quantity("m/s", "U_ds as a true airspeed: the gust's peak (|w| max)")
    max_load_factor: float = quantity("-", "the largest load factor, 1 + Delta n")
    min_load_factor: float = quantity("-", "the smallest load factor (the rebound)")
    max_shear: np.ndarray = quantity("N", "(N,) largest incremental shear")
    min_shear: np.ndarray = quantity("N", "(N,) smallest incremental shear")
    max_bending_moment: np.ndarray = quantity("N m", "(N,) largest incremental bending moment")
    min_bending_moment: np.ndarray = quantity("N m", "(N,) smallest incremental bending moment")
    max_torque: np.ndarray = quantity("N m", "(N,) largest incremental torque")
    min_torque: np.ndarray = quantity("N m", "(N,) smallest incremental torque")
    max_tip_heave: float = quantity("m", "largest elastic tip deflection (from the root)")
    time: np.ndarray = quantity("s", "(T,) the histories' times (at most 200)")
    load_factor: np.ndarray = quantity("-", "(T,) the load factor n")
    tip_heave: np.ndarray = quantity("m", "(T,) incremental elastic tip deflection")
    tip_twist: np.ndarray = quantity("deg", "(T,) incremental streamwise tip twist")
    root_shear: np.ndarray = quantity("N", "(T,) incremental root shear")
    root_bending_moment: np.ndarray = quantity("N m", "(T,) incremental root bending moment")
    root_torque: np.ndarray = quantity("N m", "(T,) incremental root torque")


@dataclass(frozen=True, eq=False)
class TurbulenceLoads:
    """Continuous turbulence (CS-25.341(b)): A-bar, the rms of each output per unit rms gust
    velocity (von Karman, L = 762 m), and the design loads P_1g +- U_sigma A-bar."""

    intensity: float = quantity("m/s", "U_sigma, the design gust intensity (TAS)")
    load_factor: float = quantity("-", "A-bar of the load factor [1 / (m/s)]")
    shear: np.ndarray = quantity("N / (m/s)", "(N,) A-bar of the shear")
    bending_moment: np.ndarray = quantity("N m / (m/s)", "(N,) A-bar of the bending moment")
    torque: np.ndarray = quantity("N m / (m/s)", "(N,) A-bar of the torque")
    max_shear: np.ndarray = quantity("N", "(N,) P_1g + U_sigma A-bar")
    min_shear: np.ndarray = quantity("N", "(N,) P_1g - U_sigma A-bar")
    max_bending_moment: np.ndarray = quantity("N m", "(N,) P_1g + U_sigma A-bar")
    min_bending_moment: np.ndarray = quantity("N m", "(N,) P_1g - U_sigma A-bar")
    max_torque: np.ndarray = quantity("N m", "(N,) P_1g + U_sigma A-bar")
    min_torque: np.ndarray = quantity("N m", "(N,) P_1g - U_sigma A-bar")


@dataclass(frozen=True, eq=False)
class GustLoadCase:
    """The 1-cos gusts' envelope of total loads (1 g plus the tuned gusts, up and down) as one
    load case of the loads envelope."""

    name: str = quantity("", "the case's name")
    y: np.ndarray = quantity("m", "(N,) station positions")
    max_shear: np.ndarray = quantity("N", "(N,) largest total shear")
    min_shear: np.ndarray = quantity("N", "(N,) smallest total shear")
    max_bending_moment: np.ndarray = quantity("N m", "(N,) largest total bending moment")
    min_bending_moment: np.ndarray = quantity("N m", "(N,) smallest total bending moment")
    max_torque: np.ndarray = quantity("N m", "(N,) largest total torque")
    min_torque: np.ndarray = quantity("N m", "(N,) smallest total torque")


@dataclass(frozen=True, eq=False)
class GustResult:
    """The flexible wing's gust loads at one flight condition."""

    velocity: float = quantity("m/s", "true airspeed")
    equivalent_airspeed: float = quantity("m/s", "equivalent airspeed")
    density: float = quantity("kg/m^3", "the air's density")
    weight: float = quantity("N", "the aircraft's weight")
    alpha: float = quantity("deg", "the 1 g trimmed angle of attack linearised about")
    clamped: bool = quantity("", "the root held (no plunge): a wind-tunnel model")
    reference_velocity: float = quantity("m/s", "U_ref (EAS), halved at V_D")
    alleviation: float = quantity("-", "F_g, the flight profile alleviation factor")
    lift_slope: float = quantity("1/rad", "the wing's quasi-steady lift slope to a uniform gust")
    mass_ratio: float = quantity("-", "mu_g = 2 (W/S) / (rho c a g)")
    pratt_alleviation: float = quantity("-", "Pratt's K_g = 0.88 mu_g / (5.3 + mu_g)")
    pratt_load_factor: float = quantity(
        "-",
        "Pratt's 1 + K_g rho0 U V a / (2 W/S) with the tuned gust's U_ds and the model's a "
        "(CS-23.341)",
    )
    frequencies: np.ndarray = quantity("rad/s", "(r,) the retained modes' frequencies in vacuum")
    y: np.ndarray = quantity("m", "(N,) station positions")
    one_g_shear: np.ndarray = quantity("N", "(N,) the 1 g trimmed shear")
    one_g_bending_moment: np.ndarray = quantity("N m", "(N,) the 1 g trimmed bending moment")
    one_g_torque: np.ndarray = quantity("N m", "(N,) the 1 g trimmed torque")
    gusts: list[GustCase] = quantity("", "each gradient's response (up gusts)")
    profile: GustCase | None = quantity("", "the given gust profile's response (null: none)")
    tuned_load_factor: int = quantity("-", "index in `gusts` of the largest load factor")
    tuned_bending_moment: int = quantity("-", "index of the largest root bending moment")
    tuned_torque: int = quantity("-", "index of the largest root |torque|")
    envelope: GustLoadCase = quantity(
        "", "total loads over every gradient, up and down, and the given profile as given"
    )
    turbulence: TurbulenceLoads | None = quantity("", "continuous turbulence (null if not asked)")
    findings: list[str] = quantity("", "where the request leaves the regulation's ranges")
    solve_time: float = quantity("s", "wall time")
