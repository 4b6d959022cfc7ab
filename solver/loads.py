"""Post-processing of a converged state: deformation, internal loads, panel loads and totals.

No verdicts and no caches here: `solver.solve` attaches the stability verdict, and the rigid
wing's lift comes in as an argument.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from solver.results import Panels, Stations, Totals
from solver.system import CoupledSystem

__all__ = ["PanelLoads", "equilibrium_loads", "lift_and_drag", "outboard_sum", "panel_loads"]


def outboard_sum(panel_values: np.ndarray) -> np.ndarray:
    """(N-1,) per panel -> (N,) per station: the sum over panels outboard of each station."""
    return np.append(np.cumsum(panel_values[::-1])[::-1], 0.0)


@dataclass(frozen=True)
class PanelLoads:
    """The right half-wing's panels at one state and dynamic pressure.

    force: (3, N-1) [N]; torque: (N-1,) [N m] about the elastic axis; center: (3, N-1) [m]
    deformed force points; vertex: (3, N) [m] deformed quarter-chord points at the stations.
    """

    force: np.ndarray
    torque: np.ndarray
    center: np.ndarray
    vertex: np.ndarray


def panel_loads(system: CoupledSystem, x: np.ndarray, q: float) -> PanelLoads:
    force, torque, center, vertex = system.panel_loads(x)
    return PanelLoads(q * force, q * torque.ravel(), center, vertex)


def lift_and_drag(loads: PanelLoads, alpha_deg: float) -> tuple[float, float]:
    """[N] lift and induced drag of both halves (mirrored panels carry the same Fx and Fz)."""
    alpha = math.radians(alpha_deg)
    fx, fz = 2 * loads.force[0].sum(), 2 * loads.force[2].sum()
    return (
        float(fz * math.cos(alpha) - fx * math.sin(alpha)),
        float(fx * math.cos(alpha) + fz * math.sin(alpha)),
    )


def _deformed_area(chord: np.ndarray, vertex: np.ndarray) -> float:
    """[m^2] AeroSandbox's planform area: mean chord times y-z distance of quarter-chord points."""
    span_yz = np.hypot(np.diff(vertex[1]), np.diff(vertex[2]))
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
    rigid_panel_lift: np.ndarray,
    unloaded: bool = False,
) -> tuple[Stations, Panels, Totals]:
    """Every reported quantity of the state x at dynamic pressure q [Pa].

    rigid_lift: [N] the rigid jig's, and rigid_panel_lift (N-1,) [N] its panels'; `unloaded`:
    it is negligible (`solver.jig`), so the lift amplification is not defined.
    """
    wing, layout = system.wing, system.layout
    loads = panel_loads(system, x, q)
    lift, drag = lift_and_drag(loads, system.alpha)
    lift_force = loads.force[2]
    panel_y = loads.center[1]
    shear = outboard_sum(lift_force)
    bending_moment = outboard_sum(lift_force * panel_y) - wing.y * shear
    torque = outboard_sum(loads.torque)
    heave, twist = x[layout.heave].copy(), x[layout.twist].copy()
    stations = Stations(
        y=wing.y,
        heave=heave,
        slope=x[layout.slope].copy(),
        twist=twist,
        shear=shear,
        bending_moment=bending_moment,
        torque=torque,
    )
    widths = np.diff(wing.y)
    panels = Panels(
        y=panel_y,
        lift=lift_force,
        lift_per_span=lift_force / widths,
        torque=loads.torque,
        rigid_lift_per_span=rigid_panel_lift / widths,
    )
    area = wing.planform_area
    deformed_area = _deformed_area(wing.chord, loads.vertex)
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
    )
    return stations, panels, totals
