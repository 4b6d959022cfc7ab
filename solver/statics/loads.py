"""Post-processing of a converged state: deformation, internal loads, panel loads and totals.

No verdicts and no caches here: `solver.solve` attaches the stability verdict, and the rigid
wing's lift comes in as an argument. Panel arrays of the results are per strip (the k chordwise
panels of a strip summed); the internal loads are the outboard sums of every panel's own force
and moment (`solver.model.residual`).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from solver.inputs.spar import TubeSpar
from solver.inputs.wing import Wing
from solver.model.exact_beam import axis_points, exact_internal_loads
from solver.model.geometry import (
    along_span,
    arc_length,
    axis_force,
    in_wing_plane,
    normal_force,
    streamwise_twist,
)
from solver.model.lag_beam import lag_axis_points, lag_internal_loads
from solver.results.equilibrium import Panels, Stations, Totals
from solver.statics.inertia import InertialLoads, deformed_loads, lag_deformed_loads
from solver.statics.system import CoupledSystem
from solver.statics.trefftz import far_field_drag

__all__ = [
    "PanelLoads",
    "RigidLoads",
    "equilibrium_loads",
    "flow_panel_loads",
    "lift_and_drag",
    "outboard_sum",
    "panel_loads",
    "rigid_loads",
]


def outboard_sum(strip_values: np.ndarray) -> np.ndarray:
    """(N-1,) per strip -> (N,) per station: the sum over strips outboard of each station."""
    return np.append(np.cumsum(strip_values[::-1])[::-1], 0.0)


@dataclass(frozen=True)
class PanelLoads:
    """The right half-wing's M = (N-1) k panels at one state and dynamic pressure.

    force: (3, M) [N]; torque: (M,) [N m] (r x F) . e_s about the undeformed elastic axis;
    center: (3, M) [m] deformed force points; quarter_chord: (3, N) [m] the stations';
    leading_edge: (3, N) [m] the stations' deformed leading edges, when the model gives them
    (the flow model's, for hinge lines), else None.
    """

    force: np.ndarray
    torque: np.ndarray
    center: np.ndarray
    quarter_chord: np.ndarray
    leading_edge: np.ndarray | None = None

    def per_strip(self, values: np.ndarray, k: int) -> np.ndarray:
        """(M,) per panel -> (N-1,) summed over each strip's k panels."""
        return values.reshape(-1, k).sum(axis=1)


def panel_loads(system: CoupledSystem, x: np.ndarray, q: float) -> PanelLoads:
    force, torque, center, quarter_chord, *leading_edge = system.panel_loads(x)
    return PanelLoads(q * force, q * torque.ravel(), center, quarter_chord, *leading_edge)


def flow_panel_loads(system: CoupledSystem, x: np.ndarray, q: float) -> PanelLoads:
    """`panel_loads` from the flow model, whatever the flow: with the leading edges."""
    force, torque, center, quarter_chord, leading_edge = system.flow_panel_loads(x)
    return PanelLoads(q * force, q * torque.ravel(), center, quarter_chord, leading_edge)


def lift_and_drag(loads: PanelLoads, alpha_deg: float) -> tuple[float, float]:
    """[N] lift and induced drag of both halves (mirrored panels carry the same Fx and Fz)."""
    alpha = math.radians(alpha_deg)
    fx, fz = 2 * loads.force[0].sum(), 2 * loads.force[2].sum()
    return (
        float(fz * math.cos(alpha) - fx * math.sin(alpha)),
        float(fx * math.cos(alpha) + fz * math.sin(alpha)),
    )


def _bending_moment(wing: Wing, loads: PanelLoads, k: int) -> np.ndarray:
    """(N,) [N m] flapwise bending moment about each station's elastic-axis point, from the
    panels' forces normal to the wing at their arms along the elastic axis (the residual's
    sums, `solver.model.beam`)."""
    arm = along_span(loads.center, wing)
    normal = normal_force(loads.force, wing)
    return outboard_sum(loads.per_strip(normal * arm, k)) - arc_length(wing) * (
        outboard_sum(loads.per_strip(normal, k))
    )


@dataclass(frozen=True)
class RigidLoads:
    """The rigid jig's loads per unit q: what a flexible answer is compared with.

    lift: [m^2] both halves; strip_lift: (N-1,) [m^2] the strips' vertical forces;
    root_bending_moment: [m^3] at the root station. Times q [Pa] gives N and N m.
    """

    lift: float
    strip_lift: np.ndarray
    root_bending_moment: float


def rigid_loads(system: CoupledSystem, state: np.ndarray) -> RigidLoads:
    """The rigid jig's loads per unit q at `state` (an undeformed state of `system`)."""
    per_q = panel_loads(system, state, 1.0)
    lift, _ = lift_and_drag(per_q, system.alpha)
    strips = per_q.per_strip(per_q.force[2], system.chordwise)
    root = float(_bending_moment(system.wing, per_q, system.chordwise)[0])
    return RigidLoads(lift, strips, root)


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
    rigid: RigidLoads,
    unloaded: bool = False,
    safety_factor: float = 1.0,
) -> tuple[Stations, Panels, Totals]:
    """Every reported quantity of the state x at dynamic pressure q [Pa].

    rigid: the rigid jig's loads per unit q that the answer is compared with (at the same alpha,
    or trimmed to the same lift); `unloaded`: they are negligible (`solver.statics.jig`), so the
    lift amplification is not defined.
    """
    wing, layout, k = system.wing, system.layout, system.chordwise
    loads = panel_loads(system, x, q)
    lift, drag = lift_and_drag(loads, system.alpha)
    if system.aerodynamics == "strip":  # two-dimensional sections: `solver.statics.trefftz`
        drag = far_field_drag(system, x, q)
    force, center = loads.force, loads.center
    heave, slope, phi = x[layout.heave].copy(), x[layout.slope].copy(), x[layout.twist].copy()
    twist = streamwise_twist(phi, slope, 0.0, wing.sweep)  # elastic: without the jig twist
    fz = loads.per_strip(force[2], k)
    shear = outboard_sum(loads.per_strip(normal_force(force, wing), k))
    bending_moment = _bending_moment(wing, loads, k)
    torque = outboard_sum(loads.per_strip(loads.torque, k))
    points = axis_points(wing, heave, slope, layout.exact)
    rotation = np.degrees(slope)  # the exact beam's beta, the linear beam's small angle
    lag: dict[str, np.ndarray] = {}
    if layout.lag:  # 3D statics about the deformed stations (`solver.model.lag_beam`)
        psi = x[layout.lag_rotation].copy()
        points = lag_axis_points(wing, heave, (slope, psi))
        bending_moment, torque, lag_moment = lag_internal_loads(
            wing, force, center, (slope, psi), k
        )
        lag = {
            "lag": x[layout.lag_displacement].copy(),
            "lag_rotation": np.degrees(psi),
            "lag_bending_moment": lag_moment,
        }
        slope = np.sin(slope)
    elif layout.exact:  # exact statics about the deformed stations; slope: du/ds = sin(beta)
        bending_moment, torque = exact_internal_loads(wing, force, center, slope, k)
        slope = np.sin(slope)
    elif system.deformed_axis:
        across = axis_force(force, wing)
        torque = torque - heave * outboard_sum(loads.per_strip(across, k))
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
        bending_stiffness=wing.bending_stiffness,
        torsional_stiffness=wing.torsional_stiffness,
        axis_x=points[0],
        axis_y=points[1],
        axis_z=points[2],
        bending_rotation=rotation,
        **lag,
    )
    panels = Panels(
        y=loads.per_strip(in_wing_plane(center, wing)[1], k) / k,
        lift=fz,
        lift_per_span=fz / widths,
        torque=strip_torque,
        rigid_lift_per_span=q * rigid.strip_lift / widths,
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
        rigid_lift=q * rigid.lift,
        lift_amplification=None if unloaded else _amplification(lift, q * rigid.lift),
        tip_heave=float(heave[-1]),
        tip_twist=float(twist[-1]),
        root_bending_moment=float(bending_moment[0]),
        root_torque=float(torque[0]),
        pitching_moment=pitching,
        alpha=system.alpha,
        rigid_root_bending_moment=q * rigid.root_bending_moment,
    )
    inertia = system.inertia
    if inertia is not None:
        load_factor = system.load_per_q * q
        normal = load_factor * math.cos(math.radians(system.alpha))  # `CoupledSystem._loaded`
        lag_weight = None
        if layout.lag:  # the weight about the deformed stations in 3D (`solver.statics.inertia`)
            rotations = (x[layout.slope], x[layout.twist], x[layout.lag_rotation])
            flap, weight_torque, lag_weight = lag_deformed_loads(inertia, wing, rotations)
            inertia = dataclasses.replace(inertia, bending_moment=flap, torque=weight_torque)
        elif layout.exact:  # the weight about the deformed stations (`solver.statics.inertia`)
            deformed = deformed_loads(inertia, wing, x[layout.slope])
            inertia = dataclasses.replace(
                inertia, bending_moment=deformed.bending_moment, torque=deformed.torque
            )
        stations, totals = _with_inertia(stations, totals, inertia, load_factor, normal)
        if lag_weight is not None and stations.lag_bending_moment is not None:
            # The net in-plane moment: the weight's share too (reported net only).
            stations = dataclasses.replace(
                stations, lag_bending_moment=stations.lag_bending_moment + normal * lag_weight
            )
    if wing.spar is not None:
        stations, totals = _with_spar(wing, wing.spar, stations, totals, safety_factor)
    return stations, panels, totals


def _with_inertia(
    stations: Stations, totals: Totals, inertia: InertialLoads, load_factor: float, normal: float
) -> tuple[Stations, Totals]:
    """The wing's own mass's loads at `load_factor` (its wing plane's share `normal`: the load
    factor times cos(alpha)) added to the lift's: the net section loads
    (`solver.statics.inertia`), each part reported."""
    shear = normal * inertia.shear
    bending = normal * inertia.bending_moment
    torque = normal * inertia.torque
    stations = dataclasses.replace(
        stations,
        shear=stations.shear + shear,
        bending_moment=stations.bending_moment + bending,
        torque=stations.torque + torque,
        inertial_shear=shear,
        inertial_bending_moment=bending,
        inertial_torque=torque,
    )
    totals = dataclasses.replace(
        totals,
        root_bending_moment=float(stations.bending_moment[0]),
        root_torque=float(stations.torque[0]),
        load_factor=load_factor,
        wing_mass=inertia.mass,
    )
    return stations, totals


def _with_spar(
    wing: Wing, spar: TubeSpar, stations: Stations, totals: Totals, safety_factor: float
) -> tuple[Stations, Totals]:
    """The spar's stresses, margin and mass added to the answer."""
    stress = spar.stresses(
        stations.bending_moment,
        stations.torque,
        stations.lag_bending_moment,
        wing.in_plane_bending_stiffness,
    )
    worst = int(np.argmax(stress.von_mises))
    largest = float(stress.von_mises[worst])
    margin = spar.material.yield_stress / (safety_factor * largest) - 1 if largest > 0 else None
    root_section = spar.outer_diameter[0] / 2 / spar.second_moment[0]  # [1/m^3]
    stations = dataclasses.replace(
        stations,
        bending_stress=stress.bending,
        shear_stress=stress.shear,
        von_mises_stress=stress.von_mises,
    )
    totals = dataclasses.replace(
        totals,
        max_von_mises_stress=largest,
        max_von_mises_y=float(wing.y[worst]),
        failure_margin=margin,
        spar_mass=spar.mass(wing.arc_length),
        root_bending_stress=float(stress.bending[0]),
        rigid_root_bending_stress=float(totals.rigid_root_bending_moment * root_section),
    )
    return stations, totals
