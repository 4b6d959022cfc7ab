"""Where an answer leaves the model's validity: findings about an equilibrium, and from which
airspeed on a sweep's equilibria carry them.

The model is the design study's: "a linear, small-displacement beam", "torque is taken about
the undeformed elastic axis", and a lattice that, "being inviscid, will never stall no matter
how much wash-in develops". Its equations have answers far past where those idealisations hold
(fuzzing found stable equilibria with 70 deg of tip twist), so every equilibrium says where it
stands (`Equilibrium.validity`, codes and meanings in `solver.results.findings.FINDING_CODES`):

- large_deflection: |heave| / semispan or |du/ds| beyond `ValidityLimits.heave_fraction` or
  `.slope`, at the stations where it is; its message points to the geometrically exact beam
  (`options.structure`), under which it is not raised;
- large_twist: |twist about the elastic axis| beyond `.twist`;
- section_stall: a strip's section lift coefficient, its lift per unit (jig) span over q and its
  mean chord, cl = lift_per_span / (q (c_i + c_i+1) / 2), beyond the airfoil's maximum
  (`wing.cl_max`, the mean of the strip's two stations, or `.cl_max`), either sign. It is the
  Kutta-Joukowski 2 Gamma / (V c) of the strip's circulation to within the tilt of the deformed
  strip and the induced velocities (1 % at the study's 20 m/s);
- near_divergence: the stability margin q / lambda beyond `.divergence_margin`, with how
  sensitive the answer is there: d(lift)/d(q) at fixed alpha over the rigid wing's L_rigid / q.
  The flexible wing's comes from the equilibrium's own tangent, dx/dq = -J^-1 r1 (the residual
  is affine in q), and the lattice's exact lift gradient: dL/dq = l + q (dl/dx) . dx/dq with
  l = L / q. One torsion mode gives 1 / (1 - margin)^2.
- control_deflection: a control surface acting in the answer (flaps in every symmetric answer,
  flaps and ailerons in a roll answer) deflected by more than `CONTROL_DEFLECTION`. A roll
  answer (`roll_findings`) is judged on both wings (`Finding.half`): the left wing's aileron
  deflects the other way, and its sections' lift falls where the right wing's rises, so either
  may stall; its near_divergence is the antisymmetric margin.

A pure post-processing step: it reads the answer and never changes one of its numbers.
"""

from __future__ import annotations

import dataclasses
import math
import typing
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from solver.inputs.flight import OperatingPoint
from solver.inputs.options import ValidityLimits
from solver.inputs.wing import Wing
from solver.numerics.evaluation import Evaluation
from solver.results.controls import RollResponse
from solver.results.equilibrium import Panels, Stability, Stations
from solver.results.findings import Finding, FindingCode, FindingMeasure, FindingOnset, FindingWhere
from solver.results.sweep import AirspeedPoint
from solver.statics.jig import at_rest, is_unloaded
from solver.statics.loads import rigid_loads
from solver.statics.system import CoupledSystem

__all__ = [
    "CONTROL_DEFLECTION",
    "assess",
    "lift_sensitivity",
    "onsets",
    "roll_findings",
    "section_lift_coefficient",
]

# [-] The move, in scaled coordinates, over which `lift_sensitivity` differences the lift.
_LIFT_STEP = 1e-5
# [deg] The |deflection| of a plain control surface past which its measured lift falls behind
# the linear theory's (the lattice's): about 10 deg (Hoerner and Borst, Fluid-Dynamic Lift,
# 1985, ch. 5; ESDU 97011's empirical flap efficiency). To become a ValidityLimits field.
CONTROL_DEFLECTION = 10.0


@dataclass(frozen=True)
class _Exceeded:
    """Where |values| exceed their limits: the indices, and the worst one (largest ratio)."""

    indices: np.ndarray
    worst: int

    @classmethod
    def of(cls, values: np.ndarray, limits: np.ndarray) -> _Exceeded | None:
        ratio = np.abs(values) / limits
        over = np.flatnonzero(ratio > 1)  # NaN compares False: never a finding
        if over.size == 0:
            return None
        return cls(over, int(over[np.argmax(ratio[over])]))


def _finding(
    code: FindingCode,
    message: str,
    measure: FindingMeasure,
    where: FindingWhere,
    exceeded: _Exceeded,
    y: np.ndarray,
    values: np.ndarray,
    limits: np.ndarray,
    unit: str,
) -> Finding:
    worst = exceeded.worst
    return Finding(
        code=code,
        message=message,
        measure=measure,
        where=where,
        indices=[int(i) for i in exceeded.indices],
        y=[float(y[i]) for i in exceeded.indices],
        value=float(values[worst]),
        limit=float(limits[worst]),
        unit=unit,
    )


def _span(y: np.ndarray, indices: np.ndarray) -> str:
    """'at y = 4.83 m' or 'from y = 3.1 to 5 m'."""
    first, last = float(y[indices[0]]), float(y[indices[-1]])
    return f"at y = {first:.3g} m" if indices.size == 1 else f"from y = {first:.3g} to {last:.3g} m"


_EXACT_BEAM = (
    "options.structure = 'geometrically_exact' models finite deflections and rotations "
    "(the large_deflection finding is then not raised)."
)


def _deflection(wing: Wing, stations: Stations, limits: ValidityLimits) -> list[Finding]:
    found = []
    fraction = stations.heave / wing.semispan
    bound = np.full(fraction.shape, limits.heave_fraction)
    exceeded = _Exceeded.of(fraction, bound)
    if exceeded is not None:
        worst = exceeded.worst
        found.append(
            _finding(
                "large_deflection",
                f"The heave reaches {100 * abs(fraction[worst]):.3g} % of the semispan "
                f"({stations.heave[worst]:.3g} m at y = {stations.y[worst]:.3g} m), beyond the "
                f"{100 * limits.heave_fraction:.3g} % up to which a linear, small-displacement "
                "beam holds; it is above that "
                f"{_span(stations.y, exceeded.indices)}. {_EXACT_BEAM}",
                "heave_fraction",
                "stations",
                exceeded,
                stations.y,
                fraction,
                bound,
                "-",
            )
        )
    bound = np.full(stations.slope.shape, limits.slope)
    exceeded = _Exceeded.of(stations.slope, bound)
    if exceeded is not None:
        worst = exceeded.worst
        slope = float(stations.slope[worst])
        found.append(
            _finding(
                "large_deflection",
                f"The bending slope reaches {slope:.3g} ({math.degrees(math.atan(slope)):.3g} deg) "
                f"at y = {stations.y[worst]:.3g} m, beyond the {limits.slope:.3g} up to which the "
                "linear beam's small-angle kinematics hold; it is above that "
                f"{_span(stations.y, exceeded.indices)}. {_EXACT_BEAM}",
                "slope",
                "stations",
                exceeded,
                stations.y,
                stations.slope,
                bound,
                "-",
            )
        )
    return found


def _twist(stations: Stations, limits: ValidityLimits) -> list[Finding]:
    bound = np.full(stations.axis_twist.shape, limits.twist)
    exceeded = _Exceeded.of(stations.axis_twist, bound)
    if exceeded is None:
        return []
    worst = exceeded.worst
    twist = float(stations.axis_twist[worst])
    return [
        _finding(
            "large_twist",
            f"The twist about the elastic axis reaches {twist:+.3g} deg "
            f"({'nose-up' if twist > 0 else 'nose-down'}) at y = {stations.y[worst]:.3g} m, "
            f"beyond the {limits.twist:.3g} deg up to which the beam's linear torsion (small "
            "angles, torque about an elastic axis that does not twist) holds; it is above that "
            f"{_span(stations.y, exceeded.indices)}.",
            "twist",
            "stations",
            exceeded,
            stations.y,
            stations.axis_twist,
            bound,
            "deg",
        )
    ]


def section_lift_coefficient(wing: Wing, panels: Panels, q: float) -> np.ndarray:
    """(N-1,) [-] each strip's section lift coefficient: its lift per unit jig span over q and
    the strip's mean chord."""
    return panels.lift_per_span / (q * 0.5 * (wing.chord[1:] + wing.chord[:-1]))


def _strip_cl_max(wing: Wing, limits: ValidityLimits) -> np.ndarray:
    """(N-1,) [-] the maximum lift coefficient of each strip: the mean of its stations'."""
    if wing.cl_max is None:
        return np.full(wing.n_stations - 1, limits.cl_max)
    return 0.5 * (wing.cl_max[1:] + wing.cl_max[:-1])


def _stall(wing: Wing, panels: Panels, q: float, limits: ValidityLimits) -> list[Finding]:
    cl = section_lift_coefficient(wing, panels, q)
    bound = _strip_cl_max(wing, limits)
    exceeded = _Exceeded.of(cl, bound)
    if exceeded is None:
        return []
    worst = exceeded.worst
    source = "wing.cl_max" if wing.cl_max is not None else "the default for thin airfoils"
    count = exceeded.indices.size
    return [
        _finding(
            "section_stall",
            f"The section lift coefficient reaches {cl[worst]:.2f} at y = {panels.y[worst]:.3g} "
            f"m, beyond the airfoil's maximum {bound[worst]:.2f} ({source}): "
            f"{count} strip{'s' if count > 1 else ''} "
            f"{_span(panels.y, exceeded.indices)} would stall, where the inviscid lattice "
            "never does, and carry less lift and less nose-up torque than this answer says.",
            "section_cl",
            "panels",
            exceeded,
            panels.y,
            cl,
            bound,
            "-",
        )
    ]


def lift_sensitivity(
    system: CoupledSystem, flight: OperatingPoint, x: np.ndarray, evaluation: Evaluation
) -> float | None:
    """[-] d(lift)/d(q) at fixed alpha of the equilibrium x over the rigid wing's L_rigid / q,
    or None where the rigid wing carries no lift (or J is singular there).

    `evaluation`: r0, r1, J0, J1 at x (the Jacobians at x or one Newton step away)."""
    q = flight.dynamic_pressure
    rigid_state = at_rest(system).rigid_state(system.alpha)
    if is_unloaded(system, rigid_state):
        return None
    # Not `jig(system)`: a trimmed answer's alpha has no jig of its own, and its evaluation
    # would cost a Jacobian; the rigid loads alone are one panel-loads call.
    rigid = rigid_loads(system, rigid_state).lift  # [m^2] L_rigid / q, linear in q
    try:
        rate = np.linalg.solve(evaluation.jacobian(q), -evaluation.r1)  # dx/dq
    except np.linalg.LinAlgError:
        return None
    lift, derivative = _lift_along(system, x, rate)
    ratio = (lift + q * derivative) / rigid  # [m^2] dL/dq over L_rigid / q
    return ratio if math.isfinite(ratio) else None


def _lift_along(system: CoupledSystem, x: np.ndarray, direction: np.ndarray) -> tuple[float, float]:
    """[m^2] the lift per unit q at x and its derivative d(lift)/dx . direction, from the
    residual function's lift a move of `_LIFT_STEP` (scaled coordinates of
    `solver.numerics.continuation`) ahead of x and behind it: a central difference (truncation
    ~1e-10 relative, round-off ~1e-11) and their mean. Two residual evaluations, against the coupled
    evaluation (a Jacobian) that the exact gradient would take."""
    size = float(np.linalg.norm(direction / system.scale(1.0)[:-1]))
    if not (math.isfinite(size) and size > 0):
        *_, lift = system.residual_with_lift(x)
        return lift, 0.0 if size == 0 else math.nan
    step = _LIFT_STEP / size
    *_, ahead = system.residual_with_lift(x + step * direction)
    *_, behind = system.residual_with_lift(x - step * direction)
    return (ahead + behind) / 2, (ahead - behind) / (2 * step)


def _near_divergence(
    system: CoupledSystem,
    flight: OperatingPoint,
    x: np.ndarray,
    evaluation: Evaluation,
    stability: Stability,
    limits: ValidityLimits,
) -> list[Finding]:
    margin = stability.margin
    if not margin > limits.divergence_margin:
        return []
    sensitivity = lift_sensitivity(system, flight, x, evaluation)
    local = stability.local_divergence_pressure
    how = (
        "the rigid wing carries no lift to compare with"
        if sensitivity is None
        else f"d(lift)/d(q) is {sensitivity:.3g} times the rigid wing's"
    )
    return [
        Finding(
            code="near_divergence",
            message=(
                f"q is {100 * margin:.3g} % of the local divergence pressure"
                + ("" if local is None else f" ({local:.4g} Pa)")
                + f", beyond {100 * limits.divergence_margin:.3g} % of it: here the answer is "
                f"sensitive to every input ({how}), and a small error in the stiffness, the lift "
                "slope or the airspeed moves it much."
            ),
            measure="margin",
            where="wing",
            indices=[],
            y=[],
            value=float(margin),
            limit=float(limits.divergence_margin),
            unit="-",
            sensitivity=sensitivity,
        )
    ]


def _controls(wing: Wing, symmetric_only: bool) -> list[Finding]:
    """control_deflection for each surface acting in the answer past `CONTROL_DEFLECTION`."""
    found = []
    for index, surface in enumerate(wing.control_surfaces):
        if symmetric_only and not surface.symmetric:
            continue
        if not abs(surface.deflection) > CONTROL_DEFLECTION:
            continue
        start, end = surface.extent(wing.semispan)
        found.append(
            Finding(
                code="control_deflection",
                message=(
                    f"The {surface.kind} {surface.name!r} is deflected {surface.deflection:+.3g} "
                    f"deg, beyond the {CONTROL_DEFLECTION:.3g} deg up to which a plain flap's "
                    "lift grows linearly with its deflection as the lattice's does: a real one's "
                    "falls behind as the flow separates from it, and this answer overstates its "
                    "lift, its hinge moment and the twist they cause."
                ),
                measure="deflection",
                where="control_surfaces",
                indices=[index],
                y=[0.5 * (start + end)],
                value=float(surface.deflection),
                limit=CONTROL_DEFLECTION,
                unit="deg",
            )
        )
    return found


def assess(
    system: CoupledSystem,
    flight: OperatingPoint,
    limits: ValidityLimits,
    x: np.ndarray,
    evaluation: Evaluation,
    stations: Stations,
    panels: Panels,
    stability: Stability,
) -> list[Finding]:
    """Every finding about the equilibrium x at `flight`, in the order of FINDING_CODES.

    `stations`, `panels`, `stability`: the answer's own numbers (`solver.statics.verdict.judge`);
    `evaluation`: r0, r1, J0, J1 at x. Reads them only."""
    wing = system.wing
    return [
        # The exact beam models finite deflections: no small-deflection finding.
        *([] if system.layout.exact else _deflection(wing, stations, limits)),
        *_twist(stations, limits),
        *_stall(wing, panels, flight.dynamic_pressure, limits),
        *_near_divergence(system, flight, x, evaluation, stability, limits),
        *_controls(wing, symmetric_only=True),
    ]


def _on(half: typing.Literal["right", "left"], findings: list[Finding]) -> list[Finding]:
    """The findings of one wing of a roll answer, marked and said so."""
    return [
        dataclasses.replace(f, half=half, message=f"On the {half} wing: {f.message}")
        for f in findings
    ]


def roll_findings(response: RollResponse, limits: ValidityLimits) -> list[Finding]:
    """Every finding about a roll answer, in the order of FINDING_CODES: deflection, twist and
    stall on each wing (right first), the antisymmetric divergence margin, the surfaces'
    deflections."""
    wing, q = response.wing, response.flight.dynamic_pressure
    found: dict[str, list[Finding]] = {code: [] for code in typing.get_args(FindingCode)}
    halves: tuple[tuple[typing.Literal["right", "left"], Stations, Panels], ...] = (
        ("right", response.right, response.right_panels),
        ("left", response.left, response.left_panels),
    )
    for half, stations, panels in halves:
        on_wing = [
            *_deflection(wing, stations, limits),
            *_twist(stations, limits),
            *_stall(wing, panels, q, limits),
        ]
        for finding in _on(half, on_wing):
            found[finding.code].append(finding)
    margin = response.stability.margin
    if margin > limits.divergence_margin:
        local = response.stability.antisymmetric_divergence_pressure
        found["near_divergence"].append(
            Finding(
                code="near_divergence",
                message=(
                    f"q is {100 * margin:.3g} % of the antisymmetric divergence pressure"
                    + ("" if local is None else f" ({local:.4g} Pa)")
                    + f", beyond {100 * limits.divergence_margin:.3g} % of it: the roll "
                    "response is sensitive to every input here."
                ),
                measure="margin",
                where="wing",
                indices=[],
                y=[],
                value=float(margin),
                limit=float(limits.divergence_margin),
                unit="-",
            )
        )
    found["control_deflection"] = _controls(wing, symmetric_only=False)
    return [finding for code in typing.get_args(FindingCode) for finding in found[code]]


def onsets(points: Sequence[AirspeedPoint]) -> list[FindingOnset]:
    """From which airspeed on each finding appears among the points' equilibria, one entry per
    code found, in the order of FINDING_CODES."""
    seen: dict[FindingCode, set[float]] = {}
    for point in points:
        if point.equilibrium is None:
            continue
        for finding in point.equilibrium.validity:
            seen.setdefault(finding.code, set()).add(float(point.velocity))
    solved = sorted({float(p.velocity) for p in points if p.equilibrium is not None})
    found = []
    for code in typing.get_args(FindingCode):
        if code not in seen:
            continue
        velocities = sorted(seen[code])
        first = velocities[0]
        beyond = [v for v in solved if v >= first]
        name = code.replace("_", " ").capitalize()
        message = f"{name} from {first:.4g} m/s on" + (
            ", at every faster airspeed of the sweep that has an equilibrium."
            if len(beyond) == len(velocities)
            else f", at {len(velocities)} of the {len(beyond)} airspeeds from there on that have "
            "an equilibrium."
        )
        found.append(
            FindingOnset(
                code=code,
                velocity=first,
                velocities=velocities,
                message=message,
            )
        )
    return found
