"""The limits the service's settings set on a request, beyond what the solver's inputs state:
most stations (FLEXWING_MAX_STATIONS), most vortex panels (FLEXWING_MAX_PANELS), most sweep
points (FLEXWING_MAX_SWEEP_POINTS), most load cases (FLEXWING_MAX_LOAD_CASES). The published
schema marks them (`x-flexwing-limit`).

`station_and_point_errors` reads the request model (cheap: a batch checks every item before
it is accepted); `panel_errors` and `case_errors` the solver input it became.
"""

from __future__ import annotations

from typing import Any

from pydantic import BaseModel

import solver
from app.problems import FieldError
from app.schemas.derive import RequestModel
from app.settings import Settings

__all__ = ["case_errors", "panel_errors", "station_and_point_errors"]


def _stations(model: BaseModel) -> int | None:
    """N of the request's wing, from its `y` (a list, or {semispan, stations})."""
    wing = getattr(model, "wing", None)
    y = getattr(wing, "y", None)
    if isinstance(y, list):
        return len(y)
    count = getattr(y, "stations", None)
    return count if isinstance(count, int) else None


def _long_lists(model: Any, path: str, limit: int, errors: list[FieldError]) -> None:
    """Every per-station list (of the wing, its spar, the guess) longer than `limit`."""
    if not isinstance(model, RequestModel):
        return
    for name in type(model).model_fields:
        value = getattr(model, name)
        where = f"{path}.{name}" if path else name
        if isinstance(value, list) and name in model.__per_station__ and len(value) > limit:
            errors.append(
                FieldError(
                    where,
                    f"has {len(value)} values; at most {limit} are allowed (FLEXWING_MAX_STATIONS)",
                )
            )
        elif isinstance(value, RequestModel):
            _long_lists(value, where, limit, errors)


def station_and_point_errors(model: BaseModel, settings: Settings) -> list[FieldError]:
    """What the published schema says of FLEXWING_MAX_STATIONS and FLEXWING_MAX_SWEEP_POINTS:
    N and every per-station list at most `max_stations` long, at most `max_sweep_points`
    airspeeds."""
    errors: list[FieldError] = []
    limit = settings.max_stations
    n = _stations(model)
    y = getattr(getattr(model, "wing", None), "y", None)
    if n is not None and n > limit:
        where = "wing.y" if isinstance(y, list) else "wing.y.stations"
        errors.append(
            FieldError(
                where,
                f"has {n} stations; at most {limit} are allowed (FLEXWING_MAX_STATIONS)",
            )
        )
    else:
        _long_lists(model, "", limit, errors)
    velocities = getattr(model, "velocities", None)
    if velocities is not None:
        count = len(velocities) if isinstance(velocities, list) else velocities.count
        if not 1 <= count <= settings.max_sweep_points:
            errors.append(
                FieldError(
                    "velocities" if isinstance(velocities, list) else "velocities.count",
                    f"asks for {count} airspeeds; 1 to {settings.max_sweep_points} are allowed "
                    "(FLEXWING_MAX_SWEEP_POINTS)",
                )
            )
    return errors


def panel_errors(task: Any, settings: Settings) -> list[FieldError]:
    """The lattice the options give the wing, within FLEXWING_MAX_PANELS."""
    wing: solver.Wing | None = getattr(task, "wing", None)
    options: solver.SolverOptions = getattr(task, "options", None) or solver.SolverOptions()
    if wing is None:
        return []
    strips, k = wing.n_stations - 1, options.chordwise_panels
    if strips * k <= settings.max_panels:
        return []
    return [
        FieldError(
            "options.chordwise_panels",
            f"gives {strips} strips x {k} = {strips * k} panels on each half wing; at most "
            f"{settings.max_panels} are allowed (FLEXWING_MAX_PANELS)",
        )
    ]


def case_errors(task: Any, settings: Settings) -> list[FieldError]:
    """A sizing input's load cases, given and derived from its envelope together, within
    FLEXWING_MAX_LOAD_CASES (counted without deriving them: `solver.LoadsInput.case_count`);
    a design problem's load cases (`solver.DesignProblem.load_cases`) likewise."""
    limit = settings.max_load_cases
    design_cases = getattr(getattr(task, "problem", None), "load_cases", None)
    if design_cases is not None and len(design_cases) > limit:
        return [
            FieldError(
                "load_cases",
                f"gives {len(design_cases)} load cases; at most {limit} are allowed "
                "(FLEXWING_MAX_LOAD_CASES)",
            )
        ]
    count = getattr(task, "case_count", None)
    if count is None or count <= limit:
        return []
    given = len(task.cases)
    return [
        FieldError(
            "cases",
            f"gives {count} load cases ({given} given, {count - given} from the envelope); at "
            f"most {limit} are allowed (FLEXWING_MAX_LOAD_CASES)",
        )
    ]
