"""Request models -> validated solver inputs, or an invalid-input problem naming every bad field.

Pydantic has already checked types, finiteness and ranges item by item (`app.schemas`). This step
adds what needs the settings (most stations, most sweep points) and what `solver.Wing.create` and
`solver.FlightCondition` check (the root at y = 0, increasing stations, matching lengths).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from app import schemas
from app.problems import FieldError, Problem
from app.schemas import LIMITS
from app.settings import Settings
from solver import (
    DesignProblem,
    FlightCondition,
    InvalidInput,
    Layout,
    Material,
    SolverOptions,
    SparDesign,
    ThicknessFraction,
    TrimCondition,
    ValidityLimits,
    Wing,
)

__all__ = [
    "OptimizeInput",
    "SolveInput",
    "SweepInput",
    "optimize_input",
    "solve_input",
    "solver_options",
    "station_limit_errors",
    "sweep_input",
]


@dataclass(frozen=True)
class SolveInput:
    wing: Wing
    flight: FlightCondition | TrimCondition  # at a given alpha, or trimmed to a lift
    options: SolverOptions
    initial_guess: np.ndarray | None


@dataclass(frozen=True)
class SweepInput:
    """A sweep at `alpha` [deg], or trimmed to `lift` [N] when `lift` is not None."""

    wing: Wing
    velocities: tuple[float, ...]
    alpha: float | None
    lift: float | None
    density: float
    options: SolverOptions


_OPTION_NAMES = {f.name for f in dataclasses.fields(SolverOptions)}


def solver_options(model: schemas.SolverOptions | None) -> SolverOptions:
    values = (model or schemas.SolverOptions()).model_dump()
    values["validity"] = ValidityLimits(**values["validity"])
    return SolverOptions(**{k: v for k, v in values.items() if k in _OPTION_NAMES})


def _options(
    model: schemas.SolverOptions | None,
    wing: Wing | None,
    settings: Settings,
    errors: list[FieldError],
) -> SolverOptions:
    """The solver options, and the lattice they give `wing` within FLEXWING_MAX_PANELS."""
    options = solver_options(model)
    if wing is not None:
        strips, k = wing.n_stations - 1, options.chordwise_panels
        if strips * k > settings.max_panels:
            errors.append(
                FieldError(
                    "options.chordwise_panels",
                    f"gives {strips} strips x {k} = {strips * k} panels on each half wing; at "
                    f"most {settings.max_panels} are allowed (FLEXWING_MAX_PANELS)",
                )
            )
    return options


def _stations(model: schemas.Wing) -> list[float] | np.ndarray:
    if isinstance(model.y, schemas.StationSpacing):
        return np.linspace(0.0, model.y.semispan, model.y.stations)
    return model.y


def station_limit_errors(request: schemas.SolveRequest, settings: Settings) -> list[FieldError]:
    """What the published schema says of FLEXWING_MAX_STATIONS (`x-flexwing-limit`): N and every
    per-station list (of the wing, its spar and the initial guess) at most `max_stations` long.

    A batch checks these before it accepts its items (the document states them, so a body that
    breaks one is invalid as a whole); the rest of an item is checked when it is solved."""
    limit = settings.max_stations
    errors = []
    y = request.wing.y
    if isinstance(y, schemas.StationSpacing) and y.stations > limit:
        errors.append(
            FieldError("wing.y.stations", f"must be at most {limit} (FLEXWING_MAX_STATIONS)")
        )
    groups = {
        "wing": request.wing,
        "wing.spar": request.wing.spar,
        "initial_guess": request.initial_guess,
    }
    for path, group in groups.items():
        for name in type(group).model_fields if group is not None else ():
            values = getattr(group, name)
            if isinstance(values, list) and len(values) > limit:
                errors.append(
                    FieldError(
                        f"{path}.{name}",
                        f"has {len(values)} values; at most {limit} are allowed "
                        "(FLEXWING_MAX_STATIONS)",
                    )
                )
    return errors


def _wing(model: schemas.Wing, settings: Settings, errors: list[FieldError]) -> Wing | None:
    y = _stations(model)
    n = len(y)
    if n > settings.max_stations:
        field = "wing.y" if isinstance(model.y, list) else "wing.y.stations"
        errors.append(
            FieldError(
                field,
                f"has {n} stations; at most {settings.max_stations} are allowed "
                "(FLEXWING_MAX_STATIONS)",
            )
        )
        return None
    semispan = LIMITS["semispan"]
    # Only of stations that rise from the root: of any others the solver says what is wrong.
    rising = len(y) > 0 and y[0] == 0 and bool(np.all(np.diff(y) > 0))
    if rising and y[-1] < semispan.minimum:
        errors.append(
            FieldError(
                "wing.y", f"the semispan (the last station) must be at least {semispan.minimum:g} m"
            )
        )
        return None
    try:
        return Wing.create(
            y,
            model.chord,
            model.elastic_axis,
            model.bending_stiffness,
            model.torsional_stiffness,
            sweep=model.sweep,
            jig_twist=model.jig_twist,
            airfoil=_airfoil(model.airfoil),
            spar=None if model.spar is None else _spar(model.spar),
            cl_max=model.cl_max,
        )
    except InvalidInput as error:
        errors.append(FieldError(f"wing.{error.field}", error.reason))
        return None


def _spar(model: schemas.TubeSpar) -> SparDesign:
    """The request's spar as `solver.Wing.create` takes it."""
    outer = model.outer_diameter
    return SparDesign(
        outer_diameter=(
            ThicknessFraction(outer.fraction_of_thickness)
            if isinstance(outer, schemas.ThicknessFraction)
            else outer
        ),
        wall_thickness=model.wall_thickness,
        material=Material(**model.material.model_dump()),
    )


def _airfoil(spec: object) -> object:
    """The request's airfoil as `solver.Wing.create` takes it."""
    if isinstance(spec, list):
        return [_airfoil(one) for one in spec]
    if isinstance(spec, schemas.CamberTable):
        return {"x": spec.x, "camber": spec.camber}
    return spec


def _lift(model: schemas.Flight | schemas.SweepFlight) -> float | None:
    """[N] the lift a trimmed flight holds; None at a given alpha."""
    if isinstance(model, schemas.FlightAtLift | schemas.SweepFlightAtLift):
        return model.lift
    if isinstance(model, schemas.FlightAtWeight | schemas.SweepFlightAtWeight):
        return model.load_factor * model.weight
    return None


def _flight(
    velocity: float,
    model: schemas.Flight | schemas.SweepFlight,
    errors: list[FieldError],
) -> FlightCondition | TrimCondition | None:
    lift = _lift(model)
    try:
        if lift is None:
            assert isinstance(model, schemas.FlightAtAlpha | schemas.SweepFlightAtAlpha)
            return FlightCondition(velocity=velocity, alpha=model.alpha, density=model.density)
        return TrimCondition(velocity=velocity, lift=lift, density=model.density)
    except InvalidInput as error:
        field = error.field
        if field == "lift" and isinstance(
            model, schemas.FlightAtWeight | schemas.SweepFlightAtWeight
        ):
            field = "load_factor"  # the weight is positive by schema: a zero load factor
        errors.append(FieldError(f"flight.{field}", error.reason))
        return None


def _initial_state(
    guess: schemas.InitialGuess, n: int, chordwise: int, errors: list[FieldError]
) -> np.ndarray | None:
    """The solver state of a guessed deformation on N stations with k chordwise panels per
    strip; circulations start at zero (Newton's first step, on the exact Jacobian, sets them)."""
    layout = Layout(n, chordwise)
    state = np.zeros(layout.n_unknowns)
    for name, values, part in (
        ("heave", guess.heave, layout.heave),
        ("slope", guess.slope, layout.slope),
        ("twist", guess.twist, layout.twist),
    ):
        if values is None:
            continue
        if len(values) != n:
            errors.append(
                FieldError(f"initial_guess.{name}", f"has {len(values)} values but y has {n}")
            )
            continue
        state[part] = values
    return None if errors else state


def solve_input(request: schemas.SolveRequest, settings: Settings) -> SolveInput:
    errors: list[FieldError] = []
    wing = _wing(request.wing, settings, errors)
    flight = _flight(request.flight.velocity, request.flight, errors)
    options = _options(request.options, wing, settings, errors)
    guess = None
    if request.initial_guess is not None and isinstance(flight, TrimCondition):
        errors.append(
            FieldError(
                "initial_guess",
                "a starting deformation is for flight at a given alpha; a trimmed solve starts "
                "from the rigid jig trimmed to the same lift",
            )
        )
    elif request.initial_guess is not None and wing is not None:
        guess = _initial_state(
            request.initial_guess, wing.n_stations, options.chordwise_panels, errors
        )
    if errors or wing is None or flight is None:
        raise Problem.invalid(errors)
    return SolveInput(wing, flight, options, guess)


def _velocities(
    request: schemas.SweepRequest, settings: Settings, errors: list[FieldError]
) -> list[float]:
    v = request.velocities
    count = len(v) if isinstance(v, list) else v.count
    if not 1 <= count <= settings.max_sweep_points:
        errors.append(
            FieldError(
                "velocities" if isinstance(v, list) else "velocities.count",
                f"asks for {count} airspeeds; 1 to {settings.max_sweep_points} are allowed "
                "(FLEXWING_MAX_SWEEP_POINTS)",
            )
        )
        return []
    if isinstance(v, list):
        return v
    return [v.start] if count == 1 else np.linspace(v.start, v.stop, count).tolist()


def sweep_input(request: schemas.SweepRequest, settings: Settings) -> SweepInput:
    errors: list[FieldError] = []
    wing = _wing(request.wing, settings, errors)
    velocities = _velocities(request, settings, errors)
    f = request.flight
    # Airspeeds are in range by schema; this checks the rest with the solver's rules.
    _flight(velocities[0] if velocities else 1.0, f, errors)
    options = _options(request.options, wing, settings, errors)
    if errors or wing is None:
        raise Problem.invalid(errors)
    alpha = f.alpha if isinstance(f, schemas.SweepFlightAtAlpha) else None
    return SweepInput(wing, tuple(velocities), alpha, _lift(f), f.density, options)


@dataclass(frozen=True)
class OptimizeInput:
    wing: Wing
    problem: DesignProblem
    options: SolverOptions


# solver.DesignProblem's fields -> where the request gives them.
_DESIGN_FIELDS = {
    "lift": "flight.lift",
    "velocity": "flight.velocity",
    "density": "flight.density",
    "alpha": "flight.alpha",
    "control_points": "design.jig_twist.control_points",
    "twist_bounds": "design.jig_twist",
    "wall_thickness_bounds": "design.wall_thickness",
    "size_spar": "design.wall_thickness",
    "objective": "objective",
    "smoothness_weight": "smoothness_weight",
    "max_tip_heave": "constraints.max_tip_heave",
    "max_stability_margin": "constraints.max_stability_margin",
}


def optimize_input(request: schemas.OptimizeRequest, settings: Settings) -> OptimizeInput:
    errors: list[FieldError] = []
    wing = _wing(request.wing, settings, errors)
    f, design = request.flight, request.design
    lift = f.lift if isinstance(f, schemas.OptimizeFlightAtLift) else f.load_factor * f.weight
    walls = design.wall_thickness
    problem = None
    try:
        problem = DesignProblem(
            lift=lift,
            velocity=f.velocity,
            density=f.density,
            alpha=f.alpha,
            control_points=design.jig_twist.control_points,
            objective=request.objective,
            smoothness_weight=request.smoothness_weight,
            twist_bounds=(design.jig_twist.lower, design.jig_twist.upper),
            size_spar=walls is not None,
            wall_thickness_bounds=(walls.lower, walls.upper) if walls else (5e-4, 0.05),
            max_tip_heave=request.constraints.max_tip_heave,
            max_stability_margin=request.constraints.max_stability_margin,
        )
    except InvalidInput as error:
        field = _DESIGN_FIELDS.get(error.field, error.field)
        if error.field == "lift" and isinstance(f, schemas.OptimizeFlightAtWeight):
            field = "flight.load_factor"
        errors.append(FieldError(field, error.reason))
    if walls is not None and wing is not None and wing.spar is None:
        errors.append(FieldError("design.wall_thickness", "the wing has no spar to size"))
    options = _options(request.options, wing, settings, errors)
    if errors or wing is None or problem is None:
        raise Problem.invalid(errors)
    return OptimizeInput(wing, problem, options)
