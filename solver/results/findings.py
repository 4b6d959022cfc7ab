"""Where an answer leaves the model's validity: each finding's code, what it means, its numbers
against its limit, and where along a sweep it first appears (`solver.statics.validity` finds
them).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

from solver.results.quantities import quantity

__all__ = [
    "FINDING_CODES",
    "Finding",
    "FindingCode",
    "FindingMeasure",
    "FindingOnset",
    "FindingWhere",
]


# What each finding of `Equilibrium.validity` means (`solver.statics.validity` finds them).
FindingCode = Literal[
    "large_deflection", "large_twist", "section_stall", "near_divergence", "control_deflection"
]
FINDING_CODES: dict[FindingCode, str] = {
    "large_deflection": (
        "the heave (over the semispan) or the bending slope exceeds its limit: the beam is "
        "linear, for small displacements, and keeps each station at its jig span position; "
        "options.structure = 'geometrically_exact' models finite deflections (and does not "
        "raise this finding)"
    ),
    "large_twist": (
        "the twist about the elastic axis exceeds its limit: the beam's torsion is linear, with "
        "small-angle kinematics and the torque about an elastic axis that does not twist"
    ),
    "section_stall": (
        "a strip's section lift coefficient exceeds its airfoil's maximum (wing.cl_max, or "
        "options.validity.cl_max): the inviscid lattice never stalls, a real wing does there, "
        "and carries less lift and less nose-up torque than the answer says"
    ),
    "near_divergence": (
        "the stability margin q / lambda exceeds its limit: close to divergence the answer is "
        "sensitive to every input; `sensitivity` says how much, as d(lift)/d(q) at fixed alpha "
        "over the rigid wing's"
    ),
    "control_deflection": (
        "a control surface's |deflection| exceeds its limit: the lattice's flap lift grows "
        "linearly with the deflection, a real plain flap's falls behind as the flow starts to "
        "separate from it, so the answer overstates the surface's lift, its hinge moment and "
        "the twist they cause (a section pushed past its maximum lift coefficient by a "
        "deflection is section_stall, on either wing)"
    ),
}
FindingMeasure = Literal["heave_fraction", "slope", "twist", "section_cl", "margin", "deflection"]
FindingWhere = Literal["stations", "panels", "wing", "control_surfaces"]
_CODES = "; ".join(f"{code}: {meaning}" for code, meaning in FINDING_CODES.items())


@dataclass(frozen=True, eq=False)
class Finding:
    """Where this answer leaves the model's validity: one finding, its numbers against its limit.

    The answer's numbers are the model's either way; a finding says what they are worth."""

    code: FindingCode = quantity("", f"what was found. {_CODES}")
    message: str = quantity("", "the finding in a sentence, for a person")
    measure: FindingMeasure = quantity(
        "",
        "the quantity judged: heave_fraction (|heave| / semispan at a station), slope "
        "(|du/ds| at a station), twist (|twist about the elastic axis| at a station, deg), "
        "section_cl (a strip's lift per unit span over q and its mean chord), margin (q / lambda "
        "of the whole wing), deflection (|a control surface's deflection|, deg)",
    )
    where: FindingWhere = quantity(
        "",
        "what `indices` count: stations (the arrays of `stations`), panels (the strips of "
        "`panels`), control_surfaces (wing.control_surfaces), or the wing as a whole (no "
        "indices)",
    )
    indices: list[int] = quantity(
        "-", "the stations or strips concerned, root to tip (0 is the root station or strip)"
    )
    y: list[float] = quantity("m", "their spanwise positions (stations.y or panels.y)")
    value: float = quantity(
        "", "the worst value of the measure (the one furthest past its limit), in `unit`"
    )
    limit: float = quantity("", "the limit it is judged against there, in `unit`")
    unit: str = quantity("", "the unit of value and limit ('-' for none)")
    sensitivity: float | None = quantity(
        "-",
        "for near_divergence (else null): d(lift)/d(q) at fixed alpha over the rigid wing's "
        "L_rigid / q, from the equilibrium's tangent dx/dq = -J^-1 r1 (1 for a rigid wing; "
        "about 1 / (1 - margin)^2 for one torsion mode); null where the rigid wing carries no "
        "lift",
        default=None,
    )
    half: Literal["right", "left"] | None = quantity(
        "",
        "which wing the indices are on, in an answer that has both (a roll answer); null "
        "where both wings are alike",
        default=None,
    )


@dataclass(frozen=True, eq=False)
class FindingOnset:
    """From which airspeed on a sweep's equilibria carry a finding."""

    code: FindingCode = quantity("", "what was found (see Finding.code)")
    velocity: float = quantity("m/s", "the lowest airspeed of the sweep whose equilibrium has it")
    velocities: list[float] = quantity(
        "m/s", "every airspeed of the sweep whose equilibrium has it, ascending"
    )
    message: str = quantity("", "the onset in a sentence, for a person")
