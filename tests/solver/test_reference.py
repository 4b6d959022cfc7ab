"""flexwing reproduces AeroSandbox's equilibria of the study's formulation.

Every STABLE equilibrium AeroSandbox computed for the shared wings (the design study's `seed`
and `rect_public`) and for the wings in tests/reference/data is solved again with flexwing, as
a user asks for it (a plain solve at that airspeed), and compared station by station.

Tolerance: 1e-6 relative, the agreement the project promises, measured as
max_i |flexwing_i - aerosandbox_i| / max_i |aerosandbox_i|. Both codes solve the same
discrete equations; what separates them is where each solver stops. IPOPT's reference points
leave up to ~4e-10 in the constraints (a few 1e-8 relative in the state, worst seen 6.5e-8 on
rect_public at 15 m/s); flexwing's Newton stops at 1e-10. So 1e-6 leaves a margin of >10x over
the stopping noise, while every known formulation slip is caught by orders of magnitude:
rotating the chord about the global instead of the local span axis costs 3-5e-4, a cambered
section's end camber 2.7e-2, dropping the heave-times-chordwise-force torque far more. (Not
caught, deliberately: rho = 1.225 instead of AeroSandbox's 1.2249991558876672 moves loads by
7e-7; the tests use the reference's rho.)
"""

from __future__ import annotations

import functools

import numpy as np
import pytest

import solver
from tests.reference import Reference, own_references, reference_param

RELATIVE_TOLERANCE = 1e-6

# AeroSandbox's points that are NOT compared here: equilibria beyond torsional divergence, on a
# statically unstable branch that never joins the one from the jig shape (the shared README's
# notes). Reporting them as unstable is the divergence tests' business.
BEYOND_DIVERGENCE = {("rect_public", 20), ("rect_public", 25)}

REFERENCES = [reference_param("seed"), reference_param("rect_public")] + [
    pytest.param(reference, id=reference.name) for reference in own_references()
]


def _compared_velocities(reference: Reference) -> list[float]:
    return [
        e["velocity"]
        for e in reference.equilibria
        if (reference.name, e["velocity"]) not in BEYOND_DIVERGENCE
    ]


def _points() -> list:
    """One pytest.param (reference, velocity) per compared equilibrium."""
    points = []
    for param in REFERENCES:
        (reference,) = param.values
        if reference is None:  # shared file absent: keep one skipped placeholder
            points.append(pytest.param(None, None, id=param.id, marks=param.marks))
            continue
        points.extend(
            pytest.param(reference, velocity, id=f"{reference.name}-{velocity:g}ms")
            for velocity in _compared_velocities(reference)
        )
    return points


@functools.cache
def _flexwing_sweep(reference: Reference) -> dict[float, solver.Equilibrium]:
    """flexwing at the reference's compared velocities, each a plain solve."""
    return {
        velocity: solver.solve(
            reference.wing, solver.FlightCondition(velocity, reference.alpha, reference.rho)
        )
        for velocity in _compared_velocities(reference)
    }


def relative_difference(ours, theirs) -> float:
    """max |ours - theirs| / max |theirs| over stations (or of a scalar)."""
    ours, theirs = np.atleast_1d(ours), np.atleast_1d(theirs)
    assert ours.shape == theirs.shape
    return float(np.max(np.abs(ours - theirs)) / np.max(np.abs(theirs)))


def _cl_on_deformed_area(e: solver.Equilibrium) -> float:
    """AeroSandbox's CL: lift over q times the DEFORMED wing's planform area."""
    return e.totals.CL_deformed_area


# quantity -> (flexwing value from an Equilibrium, key in the reference equilibrium)
QUANTITIES = {
    "heave": (lambda e: e.stations.heave, "u"),
    "slope": (lambda e: e.stations.slope, "du"),
    "twist": (lambda e: e.stations.twist, "theta_deg"),
    "shear": (lambda e: e.stations.shear, "S"),
    "bending_moment": (lambda e: e.stations.bending_moment, "M"),
    "torque": (lambda e: e.stations.torque, "T"),
    "panel_lift": (lambda e: e.panels.lift, "Fz"),
    "panel_torque": (lambda e: e.panels.torque, "tau"),
    "lift": (lambda e: e.totals.lift, "L"),
    "induced_drag": (lambda e: e.totals.induced_drag, "D"),
    "CL_deformed_area": (_cl_on_deformed_area, "CL"),
}


@pytest.mark.parametrize("quantity", list(QUANTITIES))
@pytest.mark.parametrize(("reference", "velocity"), _points())
def test_equilibrium_matches_aerosandbox(reference: Reference, velocity: float, quantity: str):
    ours_of, key = QUANTITIES[quantity]
    ours = ours_of(_flexwing_sweep(reference)[velocity])
    theirs = reference.equilibrium_at(velocity)[key]
    assert relative_difference(ours, theirs) <= RELATIVE_TOLERANCE


@pytest.mark.parametrize(("reference", "velocity"), _points())
def test_every_compared_reference_point_is_a_stable_equilibrium(
    reference: Reference, velocity: float
):
    """The references hold stable points only (besides the listed beyond-divergence ones)."""
    assert _flexwing_sweep(reference)[velocity].stability.stable


@pytest.mark.parametrize("reference", REFERENCES)
def test_rigid_lift_matches_aerosandbox(reference: Reference):
    """The jig shape's lift (a plain linear VLM solve) agrees to round-off; 1e-6 as above."""
    rigid = reference.rigid
    flexible = _flexwing_sweep(reference)[rigid["velocity"]]
    assert relative_difference(flexible.totals.rigid_lift, rigid["L"]) <= RELATIVE_TOLERANCE


@pytest.mark.parametrize("reference", REFERENCES)
def test_jig_planform_area_and_rigid_CL_match_aerosandbox(reference: Reference):
    """AeroSandbox's jig area and rigid CL (on that area). The area is exact geometry: 1e-12."""
    rigid = reference.rigid
    flexible = _flexwing_sweep(reference)[rigid["velocity"]]
    assert relative_difference(reference.wing.planform_area, rigid["S_ref"]) <= 1e-12
    totals = flexible.totals
    rigid_cl = totals.rigid_lift / (flexible.dynamic_pressure * totals.reference_area)
    assert relative_difference(rigid_cl, rigid["CL"]) <= RELATIVE_TOLERANCE
