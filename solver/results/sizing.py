"""Sizing loads' answers: each load case's section loads, and the loads envelope over all of
them (per station the largest and smallest shear, bending moment and torque with the case that
gives each, the correlated loads at chosen stations and their convex hull, the tube spar's
margins under the envelope), with the V-n diagrams the cases came from.

Loads are the section loads the structure carries (`solver.results.equilibrium.Stations`: the
lift's less the wing's own mass's under the load factor), at the N stations, root to tip; a
rolling case's `shear`, `bending_moment` and `torque` are its right wing's, `left_*` its left
wing's, and the envelope takes both.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

import numpy as np

from solver.results.quantities import quantity

__all__ = [
    "CaseLoads",
    "CorrelatedLoads",
    "LoadsEnvelope",
    "LoadsInfo",
    "SparEnvelope",
    "SpanwiseEnvelope",
    "VnBoundary",
]

CaseStatus = Literal["equilibrium", "no_equilibrium", "not_converged", "invalid", "unstable"]
CaseKind = Literal["given", "manoeuvre", "gust", "gust_dynamic"]


@dataclass(frozen=True, eq=False)
class CaseLoads:
    """One load case: its flight, and its section loads or why it has none."""

    name: str = quantity("", "the case's name, as given or as derived from its V-n point")
    kind: CaseKind = quantity(
        "",
        "given: a case of the request; manoeuvre or gust: a V-n point of the envelope; "
        "gust_dynamic: the flexible wing's 1-cos gusts' total loads (1 g + gust), up or down, "
        "each station's extreme over time (not simultaneous along the span)",
    )
    status: CaseStatus = quantity(
        "",
        "equilibrium: answered; no_equilibrium: the wing cannot fly it (past divergence, past "
        "the lift it can carry, a trim it cannot reach); not_converged; invalid: the case "
        "cannot be posed on this wing (an aileron deflection without ailerons); unstable: "
        "a gust condition past flutter or divergence",
    )
    reason: str | None = quantity("", "why there are no loads, else null", default=None)
    velocity: float = quantity("m/s", "true airspeed", default=0.0)
    equivalent_airspeed: float = quantity("m/s", "equivalent airspeed", default=0.0)
    density: float = quantity("kg/m^3", "the air's density", default=0.0)
    weight: float = quantity("N", "the aircraft's weight", default=0.0)
    load_factor: float = quantity("-", "n: the lift carried is n times the weight", default=0.0)
    alpha: float | None = quantity("deg", "the trimmed angle of attack", default=None)
    shear: np.ndarray | None = quantity("N", "(N,) section shear", default=None)
    bending_moment: np.ndarray | None = quantity(
        "N m", "(N,) flapwise bending moment", default=None
    )
    torque: np.ndarray | None = quantity("N m", "(N,) torque about the elastic axis", default=None)
    left_shear: np.ndarray | None = quantity(
        "N", "rolling cases: (N,) the left wing's shear (its stations from the root)", default=None
    )
    left_bending_moment: np.ndarray | None = quantity(
        "N m", "rolling cases: (N,) the left wing's bending moment", default=None
    )
    left_torque: np.ndarray | None = quantity(
        "N m", "rolling cases: (N,) the left wing's torque", default=None
    )
    lag_bending_moment: np.ndarray | None = quantity(
        "N m",
        "with lag bending (wing.in_plane_bending_stiffness): (N,) the in-plane (chordwise) "
        "bending moment, as /solve's stations.lag_bending_moment; null without",
        default=None,
    )
    left_lag_bending_moment: np.ndarray | None = quantity(
        "N m", "rolling cases with lag bending: (N,) the left wing's in-plane moment", default=None
    )
    tip_heave: float | None = quantity("m", "tip displacement", default=None)
    tip_twist: float | None = quantity("deg", "tip streamwise twist (elastic)", default=None)
    solve_time: float = quantity("s", "wall time of this case's solve", default=0.0)

    @property
    def answered(self) -> bool:
        return self.status == "equilibrium"


@dataclass(frozen=True, eq=False)
class SpanwiseEnvelope:
    """Per station, the extremes of each section load over every answered case, and the case
    that gives each (an index into `LoadsEnvelope.cases`)."""

    y: np.ndarray = quantity("m", "(N,) station positions")
    max_shear: np.ndarray = quantity("N", "(N,) largest shear")
    max_shear_case: list[int] = quantity("-", "(N,) the case giving it")
    min_shear: np.ndarray = quantity("N", "(N,) smallest shear")
    min_shear_case: list[int] = quantity("-", "(N,) the case giving it")
    max_bending_moment: np.ndarray = quantity("N m", "(N,) largest bending moment")
    max_bending_moment_case: list[int] = quantity("-", "(N,) the case giving it")
    min_bending_moment: np.ndarray = quantity("N m", "(N,) smallest bending moment")
    min_bending_moment_case: list[int] = quantity("-", "(N,) the case giving it")
    max_torque: np.ndarray = quantity("N m", "(N,) largest torque")
    max_torque_case: list[int] = quantity("-", "(N,) the case giving it")
    min_torque: np.ndarray = quantity("N m", "(N,) smallest torque")
    min_torque_case: list[int] = quantity("-", "(N,) the case giving it")
    max_lag_bending_moment: np.ndarray | None = quantity(
        "N m", "with lag bending: (N,) largest in-plane bending moment; null without", default=None
    )
    max_lag_bending_moment_case: list[int] | None = quantity(
        "-", "with lag bending: (N,) the case giving it", default=None
    )
    min_lag_bending_moment: np.ndarray | None = quantity(
        "N m", "with lag bending: (N,) smallest in-plane bending moment; null without", default=None
    )
    min_lag_bending_moment_case: list[int] | None = quantity(
        "-", "with lag bending: (N,) the case giving it", default=None
    )


@dataclass(frozen=True, eq=False)
class CorrelatedLoads:
    """Bending moment against torque at one station over every answered case (the 'potato
    plot'), and the convex hull of those points."""

    station: int = quantity("-", "the station's index")
    y: float = quantity("m", "its position")
    cases: list[int] = quantity("-", "(C,) the flown cases' indices (a rolling case twice)")
    bending_moment: np.ndarray = quantity("N m", "(C,) each case's bending moment there")
    torque: np.ndarray = quantity("N m", "(C,) each case's torque there")
    hull: list[int] = quantity(
        "-",
        "the hull's vertices, counter-clockwise in (bending moment, torque), as positions in "
        "`cases`",
    )


@dataclass(frozen=True, eq=False)
class SparEnvelope:
    """The tube spar under the envelope: per station the largest von Mises stress over the
    cases (each case's own bending and torque together), at limit load and at ultimate load (the
    limit times the factor of safety), and the margins of safety against the material's yield
    stress."""

    limit_von_mises: np.ndarray = quantity("Pa", "(N,) largest von Mises stress at limit load")
    critical_case: list[int] = quantity("-", "(N,) the case giving it")
    ultimate_factor: float = quantity("-", "the factor of safety (CS 23.303, 25.303: 1.5)")
    limit_margin: list[float | None] = quantity(
        "-",
        "(N,) yield / limit stress - 1 (negative: the spar yields at limit load); null where "
        "no case loads it (the tip)",
    )
    ultimate_margin: list[float | None] = quantity(
        "-",
        "(N,) yield / (factor x limit stress) - 1 (negative: it fails at ultimate load); null "
        "where no case loads it",
    )
    least_ultimate_margin: float = quantity("-", "the smallest ultimate margin")
    least_margin_station: int = quantity("-", "where it is")


@dataclass(frozen=True, eq=False)
class VnBoundary:
    """One V-n diagram of the envelope (a weight at an altitude): its boundary and named
    points, against equivalent airspeed."""

    weight: float = quantity("N", "the aircraft's weight")
    altitude: float = quantity("m", "geopotential altitude")
    airspeed: np.ndarray = quantity("m/s", "the boundary's equivalent airspeeds, in order")
    load_factor: np.ndarray = quantity("-", "the boundary's load factors")
    points: list[str] = quantity("", "the named points (A+, C+, D-, gust...)")
    point_airspeed: np.ndarray = quantity("m/s", "their equivalent airspeeds")
    point_load_factor: np.ndarray = quantity("-", "their load factors")


@dataclass(frozen=True)
class LoadsInfo:
    cases: int = quantity("-", "load cases")
    answered: int = quantity("-", "cases with loads")
    solve_time: float = quantity(
        "s",
        "the cases' solve times summed, and the envelope's (the cases may have run at once on "
        "several workers: the answer's wait is less)",
    )


@dataclass(frozen=True, eq=False)
class LoadsEnvelope:
    """The loads of every case, their envelope along the span, correlated loads, the spar's
    margins and the V-n diagrams."""

    cases: list[CaseLoads] = quantity("", "every case, in order (given, then derived)")
    envelope: SpanwiseEnvelope | None = quantity(
        "", "the extremes along the span (null when no case has loads)"
    )
    correlated: list[CorrelatedLoads] = quantity(
        "", "bending moment against torque at the chosen stations"
    )
    spar: SparEnvelope | None = quantity("", "the tube spar's margins (null without one)")
    vn: list[VnBoundary] = quantity("", "the V-n diagrams of the envelope description")
    info: LoadsInfo = quantity("", "counts and timing")
