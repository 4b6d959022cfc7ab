"""Post-processing of a converged state: deformation, internal loads, panel loads and totals.

No verdicts and no caches here: `solver.solve` attaches the stability verdict, and the rigid
wing's lift comes in as an argument. Panel arrays of the results are per strip (the k chordwise
panels of a strip summed); the internal loads are the outboard sums of every panel's own force
and moment (`solver.residual`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from solver.geometry import DEG
from solver.results import Panels, Stations, Totals
from solver.system import CoupledSystem

__all__ = ["PanelLoads", "equilibrium_loads", "lift_and_drag", "outboard_sum", "panel_loads"]


def outboard_sum(strip_values: np.ndarray) -> np.ndarray:
    """(N-1,) per strip -> (N,) per station: the sum over strips outboard of each station."""
    return np.append(np.cumsum(strip_values[::-1])[::-1], 0.0)


@dataclass(frozen=True)
class PanelLoads:
    """The right half-wing's M = (N-1) k panels at one state and dynamic pressure.

    force: (3, M) [N]; torque: (M,) [N m] (r x F) . e_s about the undeformed elastic axis;
    center: (3, M) [m] deformed force points; quarter_chord: (3, N) [m] the stations'.
    """

    force: np.ndarray
    torque: np.ndarray
    center: np.ndarray
    quarter_chord: np.ndarray

    def per_strip(self, values: np.ndarray, k: int) -> np.ndarray:
        """(M,) per panel -> (N-1,) summed over each strip's k panels."""
        return values.reshape(-1, k).sum(axis=1)


def panel_loads(system: CoupledSystem, x: np.ndarray, q: float) -> PanelLoads:
    force, torque, center, quarter_chord = system.panel_loads(x)
    return PanelLoads(q * force, q * torque.ravel(), center, quarter_chord)


def lift_and_drag(loads: PanelLoads, alpha_deg: float) -> tuple[float, float]:
    """[N] lift and induced drag of both halves (mirrored panels carry the same Fx and Fz)."""
    alpha = math.radians(alpha_deg)
    fx, fz = 2 * loads.force[0].sum(), 2 * loads.force[2].sum()
    return (
        float(fz * math.cos(alpha) - fx * math.sin(alpha)),
        float(fx * math.cos(alpha) + fz * math.sin(alpha)),
    )


def _deformed_area(chord: np.ndarray, quarter_chord: np.ndarray) -> float:
    """[m^2] AeroSandbox's planform area: mean chord times y-z distance of quarter-chord points."""
    span_yz = np.hypot(np.diff(quarter_chord[1]), np.diff(quarter_chord[2]))
    return float(np.sum((chord[1:] + chord[:-1]) * span_yz))


def _amplification(lift: float, rigid_lift: float | None) -> float | None:
    """L / L_rigid [-], None where the rigid wing carries no (meaningful) lift."""
    if not rigid_lift:
        return None
    ratio = lift / rigid_lift
    return ratio if math.isfinite(ratio) else None


def equilibrium_loads(
    system: CoupledSystem,
    x: np.ndarray,
    q: float,
    rigid_lift: float,
    rigid_strip_lift: np.ndarray,
    unloaded: bool = False,
) -> tuple[Stations, Panels, Totals]:
    """Every reported quantity of the state x at dynamic pressure q [Pa].

    rigid_lift: [N] the rigid jig's, and rigid_strip_lift (N-1,) [N] its strips'; `unloaded`:
    it is negligible (`solver.jig`), so the lift amplification is not defined.
    """
    wing, layout, k = system.wing, system.layout, system.chordwise
    loads = panel_loads(system, x, q)
    lift, drag = lift_and_drag(loads, system.alpha)
    sweep = wing.sweep * DEG
    e_s = np.array([math.sin(sweep), math.cos(sweep), 0.0])
    force, center = loads.force, loads.center
    heave, slope, phi = x[layout.heave].copy(), x[layout.slope].copy(), x[layout.twist].copy()
    twist = phi * math.cos(sweep) - np.degrees(slope) * math.sin(sweep)  # streamwise, elastic
    fz = loads.per_strip(force[2], k)
    shear = outboard_sum(fz)
    arc = wing.y / math.cos(sweep)  # [m] along the elastic axis
    bending_moment = outboard_sum(loads.per_strip(force[2] * (e_s @ center), k)) - arc * shear
    torque = outboard_sum(loads.per_strip(loads.torque, k))
    if system.deformed_axis:
        axis_force = force[0] * math.cos(sweep) - force[1] * math.sin(sweep)
        torque = torque - heave * outboard_sum(loads.per_strip(axis_force, k))
    strip_torque = loads.per_strip(loads.torque, k)
    widths = np.diff(wing.y)
    stations = Stations(
        y=wing.y,
        heave=heave,
        slope=slope,
        twist=twist,
        axis_twist=phi,
        shear=shear,
        bending_moment=bending_moment,
        torque=torque,
    )
    panels = Panels(
        y=loads.per_strip(center[1], k) / k,
        lift=fz,
        lift_per_span=fz / widths,
        torque=strip_torque,
        rigid_lift_per_span=rigid_strip_lift / widths,
    )
    area = wing.planform_area
    deformed_area = _deformed_area(wing.chord, loads.quarter_chord)
    # Both halves: the mirrored panel's moment about the y axis equals this one's.
    pitching = 2 * float(np.sum(center[2] * force[0] - center[0] * force[2]))
    totals = Totals(
        lift=lift,
        induced_drag=drag,
        CL=lift / (q * area),
        CDi=drag / (q * area),
        CL_deformed_area=lift / (q * deformed_area),
        reference_area=area,
        deformed_area=deformed_area,
        rigid_lift=rigid_lift,
        lift_amplification=None if unloaded else _amplification(lift, rigid_lift),
        tip_heave=float(heave[-1]),
        tip_twist=float(twist[-1]),
        root_bending_moment=float(bending_moment[0]),
        root_torque=float(torque[0]),
        pitching_moment=pitching,
    )
    return stations, panels, totals
