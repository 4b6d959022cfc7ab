"""The loads envelope: per station the largest and smallest shear, bending moment and torque
(and with lag bending the in-plane moment) over every case that was flown, each with its case;
the correlated loads at chosen stations (bending moment against torque, and their convex hull:
the stress engineer's 'potato plot'); the tube spar's von Mises stresses under the envelope at
limit and at ultimate load, and its margins of safety.

A rolling case loads its two wings apart: both count, each at its own stations (the left wing's
in its mirrored frame, root outboard, like the right's). Every extreme is one of the cases'
own numbers, exactly (no interpolation): the envelope of cases solved one by one is the same.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from scipy.spatial import ConvexHull, QhullError

from solver.inputs.wing import Wing
from solver.results.sizing import CaseLoads, CorrelatedLoads, SpanwiseEnvelope, SparEnvelope

__all__ = ["ULTIMATE_FACTOR", "correlated_loads", "spanwise_envelope", "spar_envelope"]

# CS 23.303 / CS 25.303: ultimate loads are the limit loads times 1.5.
ULTIMATE_FACTOR = 1.5

_QUANTITIES = ("shear", "bending_moment", "torque", "lag_bending_moment")


def _wings(case: CaseLoads) -> list[dict[str, np.ndarray]]:
    """A flown case's loads, one mapping per wing it loads apart (one, or two when rolling);
    the in-plane moment only with lag bending."""
    right = {name: getattr(case, name) for name in _QUANTITIES if getattr(case, name) is not None}
    if case.left_shear is None:
        return [right]
    left = {
        name: getattr(case, f"left_{name}")
        for name in _QUANTITIES
        if getattr(case, f"left_{name}") is not None
    }
    return [right, left]


def _flown(cases: Sequence[CaseLoads]) -> list[tuple[int, dict[str, np.ndarray]]]:
    """(case index, one wing's loads) of every flown case's every wing, in case order."""
    return [(i, wing) for i, case in enumerate(cases) if case.answered for wing in _wings(case)]


def spanwise_envelope(y: np.ndarray, cases: Sequence[CaseLoads]) -> SpanwiseEnvelope | None:
    """The extremes of each section load at every station `y` (N,) [m] over the flown
    `cases`, with the case giving each (the first in case order on a tie); None if none flew."""
    flown = _flown(cases)
    if not flown:
        return None
    index = np.array([i for i, _ in flown])
    values: dict[str, object] = {}
    for name in _QUANTITIES:
        if not all(name in wing for _, wing in flown):  # the in-plane moment, without lag
            continue
        table = np.vstack([wing[name] for _, wing in flown])  # (wings, N)
        top, bottom = np.argmax(table, axis=0), np.argmin(table, axis=0)
        columns = np.arange(table.shape[1])
        values[f"max_{name}"] = table[top, columns]
        values[f"max_{name}_case"] = index[top].tolist()
        values[f"min_{name}"] = table[bottom, columns]
        values[f"min_{name}_case"] = index[bottom].tolist()
    return SpanwiseEnvelope(y=y, **values)  # type: ignore[arg-type]


def correlated_loads(
    y: np.ndarray, cases: Sequence[CaseLoads], stations: Sequence[int]
) -> tuple[CorrelatedLoads, ...]:
    """Bending moment against torque at each of `stations` over the flown cases' wings, with
    the convex hull of the points (all of them when fewer than three, or all on a line)."""
    flown = _flown(cases)
    found = []
    for station in stations:
        index = np.array([i for i, _ in flown], dtype=int)
        bending = np.array([wing["bending_moment"][station] for _, wing in flown])
        torque = np.array([wing["torque"][station] for _, wing in flown])
        found.append(
            CorrelatedLoads(
                station=int(station),
                y=float(y[station]),
                cases=index.tolist(),
                bending_moment=bending,
                torque=torque,
                hull=_hull(bending, torque).tolist(),
            )
        )
    return tuple(found)


def _hull(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """The points' convex hull, counter-clockwise (Qhull), or every point where it has none."""
    points = np.column_stack([x, y])
    if len(points) < 3:
        return np.arange(len(points))
    scale = np.ptp(points, axis=0)
    scale[scale == 0] = 1.0
    try:  # scaled: bending moments and torques differ by orders of magnitude
        return np.asarray(ConvexHull(points / scale).vertices)
    except QhullError:  # on a line: its two ends bound it
        along = (points / scale) @ np.array([1.0, 1.0])
        return np.array(sorted({int(np.argmin(along)), int(np.argmax(along))}))


def spar_envelope(wing: Wing, cases: Sequence[CaseLoads]) -> SparEnvelope | None:
    """The tube spar's largest von Mises stress per station over the flown cases' wings, each
    case's bending and torque together, and its margins against yield at limit and at ultimate
    load (`ULTIMATE_FACTOR`); None without a spar or a flown case."""
    spar = wing.spar
    flown = _flown(cases)
    if spar is None or not flown:
        return None
    index = np.array([i for i, _ in flown])
    stress = np.vstack(
        [
            spar.stresses(
                w["bending_moment"],
                w["torque"],
                w.get("lag_bending_moment"),
                wing.in_plane_bending_stiffness,
            ).von_mises
            for _, w in flown
        ]
    )
    worst = np.argmax(stress, axis=0)
    limit = stress[worst, np.arange(stress.shape[1])]
    yield_stress = spar.material.yield_stress
    loaded = limit > 0
    ultimate = np.full(limit.shape, np.inf)
    ultimate[loaded] = yield_stress / (ULTIMATE_FACTOR * limit[loaded]) - 1
    least = int(np.argmin(ultimate))

    def margins(factor: float) -> list[float | None]:
        return [float(yield_stress / (factor * s) - 1) if s > 0 else None for s in limit]

    return SparEnvelope(
        limit_von_mises=limit,
        critical_case=index[worst].tolist(),
        ultimate_factor=ULTIMATE_FACTOR,
        limit_margin=margins(1.0),
        ultimate_margin=margins(ULTIMATE_FACTOR),
        least_ultimate_margin=float(ultimate[least]),
        least_margin_station=least,
    )
