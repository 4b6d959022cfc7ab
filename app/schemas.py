"""Request and response models of the HTTP API. Units are SI, angles in degrees.

The examples are the design study's wing (shared/seed, chapter 14): y = linspace(0, 5, 30) m,
chord = sqrt(linspace(2, 0.02, 30)) m, elastic axis at 40 % chord, EI = 2e4 c^3, GJ = 1e3 c^3,
alpha 5 deg, 10 m/s; `/docs` runs them as they are.

Limits that depend on settings (most stations, most sweep points) are checked when a request is
converted to solver inputs (`app.inputs`), so this schema, and the OpenAPI document generated
from it, do not depend on the environment.
"""

from __future__ import annotations

import math
from typing import Annotated, Any, Literal

from pydantic import BaseModel, ConfigDict, Discriminator, Field, Tag

from app.settings import MAX_ARRAY_LENGTH
from solver.wing import ISA_SEA_LEVEL_DENSITY, MIN_STATIONS

__all__ = [
    "SOLVE_EXAMPLES",
    "SWEEP_EXAMPLES",
    "ClusterWorker",
    "Divergence",
    "FitDivergence",
    "Flight",
    "Fold",
    "HealthResponse",
    "InitialGuess",
    "LinearDivergence",
    "NoEquilibrium",
    "Panels",
    "ReadyResponse",
    "SolveRequest",
    "SolveResponse",
    "SolverInfo",
    "SolverOptions",
    "Stability",
    "Stations",
    "SweepFlight",
    "SweepInfo",
    "SweepPoint",
    "SweepRequest",
    "SweepResponse",
    "Totals",
    "VelocityRange",
    "Wing",
    "study_wing",
]


def _significant(x: float) -> float:
    return float(f"{x:.10g}")


def study_wing() -> dict[str, Any]:
    """The design study's wing, to 10 significant digits."""
    n = 30
    y = [_significant(5.0 * i / (n - 1)) for i in range(n)]
    chord = [math.sqrt(2.0 + (0.02 - 2.0) * i / (n - 1)) for i in range(n)]
    return {
        "y": y,
        "chord": [_significant(c) for c in chord],
        "elastic_axis": 0.4,
        "bending_stiffness": [_significant(2e4 * c**3) for c in chord],
        "torsional_stiffness": [_significant(1e3 * c**3) for c in chord],
    }


_STUDY_WING = study_wing()
_STUDY_SWEEP: list[Any] = [6.0, 10.0, 12.0, 15.0, 18.0, 20.0]
_STUDY_SOLVE: dict[str, Any] = {
    "wing": _STUDY_WING,
    "flight": {"velocity": 10.0, "alpha": 5.0, "density": ISA_SEA_LEVEL_DENSITY},
}
_STUDY_SWEEP_REQUEST: dict[str, Any] = {
    "wing": _STUDY_WING,
    "flight": {"alpha": 5.0, "density": ISA_SEA_LEVEL_DENSITY},
    "velocities": _STUDY_SWEEP,
}
# Request-body examples for the OpenAPI document (what /docs pre-fills).
SOLVE_EXAMPLES: dict[str, Any] = {
    "study": {
        "summary": "The design study's wing at 10 m/s, alpha 5 deg",
        "value": _STUDY_SOLVE,
    },
    "beyond_divergence": {
        "summary": "The same wing at 23 m/s: no equilibrium (422, with the fold speed)",
        "value": _STUDY_SOLVE | {"flight": _STUDY_SOLVE["flight"] | {"velocity": 23.0}},
    },
}
SWEEP_EXAMPLES: dict[str, Any] = {
    "study": {
        "summary": "The design study's sweep: 6 to 20 m/s, alpha 5 deg",
        "value": _STUDY_SWEEP_REQUEST,
    },
    "to_the_fold": {
        "summary": "Past the fold: 22 and 23 m/s have no equilibrium",
        "value": _STUDY_SWEEP_REQUEST | {"velocities": [10.0, 15.0, 20.0, 21.0, 22.0, 23.0]},
    },
}

Finite = Annotated[float, Field(allow_inf_nan=False)]
Positive = Annotated[float, Field(gt=0, allow_inf_nan=False)]
FiniteList = Annotated[list[Finite], Field(max_length=MAX_ARRAY_LENGTH)]
StationList = Annotated[list[Finite], Field(min_length=MIN_STATIONS, max_length=MAX_ARRAY_LENGTH)]
PositiveList = Annotated[
    list[Positive], Field(min_length=MIN_STATIONS, max_length=MAX_ARRAY_LENGTH)
]


def _number_or_list(value: Any) -> str:
    return "@list" if isinstance(value, list) else "@number"


class _Model(BaseModel):
    # Strict: a JSON value of another type than documented ("10" or true for a number) is
    # invalid input, not converted. Integers are still accepted for numbers.
    model_config = ConfigDict(extra="forbid", strict=True)


# ----------------------------------------------------------------------------------- requests


class Wing(_Model):
    """A symmetric, unswept wing described on its right half at N stations from the root."""

    model_config = ConfigDict(
        extra="forbid", strict=True, json_schema_extra={"examples": [_STUDY_WING]}
    )

    y: StationList = Field(
        description=(
            "[m] spanwise station positions from the root: y[0] = 0, strictly increasing. "
            f"N = len(y) stations, {MIN_STATIONS} <= N <= FLEXWING_MAX_STATIONS (default 150)."
        ),
        examples=[_STUDY_WING["y"]],
    )
    chord: PositiveList = Field(
        description="[m] chord length at each station, > 0; N values.",
        examples=[_STUDY_WING["chord"]],
    )
    elastic_axis: Annotated[
        Annotated[Finite, Tag("@number")] | Annotated[FiniteList, Tag("@list")],
        Discriminator(_number_or_list),
    ] = Field(
        description=(
            "[-] elastic-axis position as a fraction of chord from the leading edge: one number "
            "for every station, or N values."
        ),
        examples=[0.4],
    )
    bending_stiffness: PositiveList = Field(
        description="[N m^2] flapwise bending stiffness EI at each station, > 0; N values.",
        examples=[_STUDY_WING["bending_stiffness"]],
    )
    torsional_stiffness: PositiveList = Field(
        description="[N m^2] torsional stiffness GJ at each station, > 0; N values.",
        examples=[_STUDY_WING["torsional_stiffness"]],
    )


_Velocity = Field(gt=0, allow_inf_nan=False, description="[m/s] airspeed, > 0.", examples=[10.0])
_Alpha = Field(
    gt=-90,
    lt=90,
    allow_inf_nan=False,
    description="[deg] angle of attack of the jig (undeformed) shape.",
    examples=[5.0],
)
_Density = Field(
    default=ISA_SEA_LEVEL_DENSITY,
    gt=0,
    allow_inf_nan=False,
    description="[kg/m^3] air density, > 0.",
    examples=[ISA_SEA_LEVEL_DENSITY],
)


class Flight(_Model):
    """Steady, symmetric flight."""

    velocity: float = _Velocity
    alpha: float = _Alpha
    density: float = _Density


class SweepFlight(_Model):
    """Steady, symmetric flight; the airspeeds come from `velocities`."""

    alpha: float = _Alpha
    density: float = _Density


class SolverOptions(_Model):
    """Newton settings; the defaults suit almost every wing."""

    tolerance: float = Field(
        default=1e-10,
        ge=1e-14,
        le=1e-3,
        description=(
            "[mixed units] max-norm of the residual at convergence: heave rows in m, twist rows "
            "in deg, flow-tangency rows per unit airspeed."
        ),
    )
    max_iterations: int = Field(
        default=30, ge=1, le=200, description="[-] Newton iterations before giving up."
    )
    find_fold: bool = Field(
        default=False,
        description=(
            "Also locate the fold of the equilibrium branch from the jig shape (where torsional "
            "divergence ends it) and report it in `fold`. Costs a continuation run."
        ),
    )


class InitialGuess(_Model):
    """A deformation to start Newton from (e.g. `stations` of an earlier response), N values each.

    Overrides the service's own warm start.
    """

    heave: FiniteList = Field(description="[m] heave at each station.")
    slope: FiniteList | None = Field(
        default=None, description="[-] slope du/dy at each station (default: zeros)."
    )
    twist: FiniteList = Field(description="[deg] twist at each station, positive nose-up.")


class SolveRequest(_Model):
    """One wing at one flight condition."""

    model_config = ConfigDict(
        extra="forbid",
        strict=True,
        json_schema_extra={"examples": [_STUDY_SOLVE]},
    )

    wing: Wing
    flight: Flight
    initial_guess: InitialGuess | None = Field(
        default=None, description="Optional starting deformation for Newton."
    )
    options: SolverOptions | None = Field(default=None, description="Optional solver options.")


class VelocityRange(_Model):
    """`count` airspeeds evenly spaced from `start` to `stop`, both included."""

    start: float = Field(gt=0, allow_inf_nan=False, description="[m/s] first airspeed, > 0.")
    stop: float = Field(gt=0, allow_inf_nan=False, description="[m/s] last airspeed, > 0.")
    count: int = Field(
        ge=1, description="[-] number of airspeeds, <= FLEXWING_MAX_SWEEP_POINTS (default 50)."
    )


def _list_or_range(value: Any) -> str:
    return "@list" if isinstance(value, list) else "@range"


class SweepRequest(_Model):
    """One wing over several airspeeds, solved in the given order, each point warm-started from
    the previous equilibrium."""

    model_config = ConfigDict(
        extra="forbid",
        strict=True,
        json_schema_extra={"examples": [_STUDY_SWEEP_REQUEST]},
    )

    wing: Wing
    flight: SweepFlight
    velocities: Annotated[
        Annotated[list[Positive], Tag("@list"), Field(max_length=MAX_ARRAY_LENGTH)]
        | Annotated[VelocityRange, Tag("@range")],
        Discriminator(_list_or_range),
    ] = Field(
        description=(
            "[m/s] airspeeds, solved in this order: a list (1 to FLEXWING_MAX_SWEEP_POINTS "
            "values, default 50) or {start, stop, count}."
        ),
        examples=[_STUDY_SWEEP],
    )
    options: SolverOptions | None = Field(default=None, description="Optional solver options.")


# ---------------------------------------------------------------------------------- responses


class Stations(BaseModel):
    """Deformation and internal loads at the N structural stations, root to tip."""

    y: list[float] = Field(description="[m] station positions.")
    heave: list[float] = Field(description="[m] vertical displacement, positive up.")
    slope: list[float] = Field(description="[-] heave slope du/dy.")
    twist: list[float] = Field(description="[deg] twist about the elastic axis, nose-up > 0.")
    shear: list[float] = Field(description="[N] vertical shear force carried at the station.")
    bending_moment: list[float] = Field(description="[N m] flapwise bending moment.")
    torque: list[float] = Field(description="[N m] torque about the elastic axis.")


class Panels(BaseModel):
    """Aerodynamic loads on the N - 1 right-half panels (strips between stations), root to tip."""

    y: list[float] = Field(description="[m] spanwise load location (deformed bound vortex).")
    lift: list[float] = Field(description="[N] vertical force on the panel.")
    lift_per_span: list[float] = Field(description="[N/m] vertical force per jig strip width.")
    torque: list[float] = Field(description="[N m] torque about the elastic axis.")


class Totals(BaseModel):
    """Whole-wing results (both halves)."""

    lift: float = Field(description="[N] lift, perpendicular to the freestream.")
    induced_drag: float = Field(description="[N] induced drag, along the freestream.")
    CL: float = Field(description="[-] lift coefficient on the jig planform area.")
    CDi: float = Field(description="[-] induced-drag coefficient on the jig planform area.")
    CL_deformed_area: float = Field(
        description=(
            "[-] lift coefficient on the deformed wing's planform area, the convention of "
            "AeroSandbox and of the design study."
        )
    )
    reference_area: float = Field(description="[m^2] jig planform area, both halves.")
    deformed_area: float = Field(description="[m^2] deformed planform area, both halves.")
    rigid_lift: float = Field(description="[N] lift of the rigid jig shape, same condition.")
    lift_amplification: float | None = Field(
        description="[-] lift / rigid_lift; null when the rigid wing carries no lift."
    )
    tip_heave: float = Field(description="[m] heave at the tip.")
    tip_twist: float = Field(description="[deg] twist at the tip.")
    root_bending_moment: float = Field(description="[N m] bending moment at the root.")
    root_torque: float = Field(description="[N m] torque at the root.")


class Stability(BaseModel):
    """Static aeroelastic stability of this equilibrium, and the wing's linear divergence."""

    stable: bool = Field(description="The equilibrium is statically stable.")
    margin: float = Field(
        description=(
            "[-] q / local divergence pressure at this equilibrium; 1 at instability, 0 when the "
            "deformed wing cannot diverge."
        )
    )
    local_divergence_pressure: float | None = Field(
        description="[Pa] divergence dynamic pressure linearised at this equilibrium, or null."
    )
    divergence_dynamic_pressure: float | None = Field(
        description="[Pa] classical linear divergence at the unloaded jig, or null if none."
    )
    divergence_velocity: float | None = Field(
        description="[m/s] airspeed of that divergence at this density, or null."
    )


class SolverInfo(BaseModel):
    """How the answer was obtained."""

    iterations: int = Field(description="[-] Newton iterations.")
    residual_norm: float = Field(description="[mixed units] max-norm of the final residual.")
    warm_start: bool = Field(
        description="Newton started from a stored or supplied equilibrium, not the jig shape."
    )
    seconds: float = Field(description="[s] solver time in the worker (0 if cached).")
    cached: bool = Field(description="Answered from the result cache without solving.")


class Fold(BaseModel):
    """The fold of the equilibrium branch from the jig shape: past it there is no equilibrium."""

    velocity: float | None = Field(description="[m/s] airspeed at the fold, or null.")
    dynamic_pressure: float | None = Field(description="[Pa] dynamic pressure at the fold.")
    tip_twist: float | None = Field(description="[deg] tip twist at the fold.")
    lift: float | None = Field(description="[N] lift at the fold.")
    searched_to_velocity: float | None = Field(description="[m/s] how far the branch was followed.")
    reason: str | None = Field(description="Why a value is null, else null.")


class SolveResponse(BaseModel):
    """A static aeroelastic equilibrium."""

    stations: Stations
    panels: Panels
    totals: Totals
    stability: Stability
    solver: SolverInfo
    fold: Fold | None = Field(
        default=None, description="Present when options.find_fold was requested."
    )


class NoEquilibrium(BaseModel):
    """Why a sweep point has no equilibrium."""

    reason: str = Field(description="What the solver reported.")
    fold_velocity: float | None = Field(
        description="[m/s] where the equilibrium branch ends, when known."
    )


class SweepPoint(BaseModel):
    velocity: float = Field(description="[m/s] requested airspeed.")
    status: Literal["equilibrium", "no_equilibrium", "not_converged"] = Field(
        description=(
            "equilibrium: `equilibrium` holds the result; no_equilibrium: beyond the fold; "
            "not_converged: Newton failed. Both failures fill `no_equilibrium`."
        )
    )
    equilibrium: SolveResponse | None = Field(description="The equilibrium, as /solve returns.")
    no_equilibrium: NoEquilibrium | None = Field(description="Why there is none.")


class LinearDivergence(BaseModel):
    """Classical linear divergence at the unloaded jig (alpha = 0)."""

    dynamic_pressure: float | None = Field(description="[Pa], or null.")
    velocity: float | None = Field(description="[m/s] at the sweep's density, or null.")
    reason: str | None = Field(description="Why the values are null, else null.")


class FitDivergence(BaseModel):
    """The design study's estimate: 1/A = intercept + slope q fitted over stable sweep points."""

    slope: float | None = Field(description="[1/Pa] slope of 1/A against q.")
    intercept: float | None = Field(description="[-] intercept (single-mode theory: 1).")
    dynamic_pressure: float | None = Field(description="[Pa] where 1/A reaches 0.")
    velocity: float | None = Field(description="[m/s] at the sweep's density.")
    reason: str | None = Field(description="Why the values are null, else null.")
    amplification: Literal["CL", "lift"] = Field(
        description=(
            "What A is: 'CL' (the study's: CL on the deformed area over the rigid CL on the jig "
            "area) or 'lift' (L / L_rigid)."
        )
    )
    points_used: int = Field(description="[-] stable equilibria in the fit.")


class Divergence(BaseModel):
    """Three torsional-divergence estimates that check each other."""

    linear: LinearDivergence
    fit: FitDivergence
    fold: Fold


class SweepInfo(BaseModel):
    seconds: float = Field(description="[s] solver time in the worker (0 if cached).")
    cached: bool = Field(description="Answered from the result cache without solving.")


class SweepResponse(BaseModel):
    """One point per requested airspeed, in request order, and the divergence estimates."""

    points: list[SweepPoint]
    divergence: Divergence
    solver: SweepInfo


class HealthResponse(BaseModel):
    status: Literal["ok"] = Field(description="The process is alive.")


class ClusterWorker(BaseModel):
    """One worker of a Dask cluster (FLEXWING_EXECUTOR=dask)."""

    address: str = Field(description="Its address, e.g. tcp://10.0.0.7:40123.")
    name: str = Field(description="Its name (dask worker --name).")
    threads: int = Field(description="[-] threads it runs tasks on.")
    warm: bool = Field(description="It has compiled or loaded the warm mesh sizes.")
    pid: int | None = Field(description="Its process id on its machine, once warm.")


class ReadyResponse(BaseModel):
    ready: bool = Field(description="Workers are warm and accepting solves.")
    workers: int = Field(description="[-] configured worker count.")
    pids: list[int] = Field(description="Process ids of the local workers (empty if remote).")
    warm_stations: list[int] = Field(description="Mesh sizes N warmed in every worker.")
    detail: str = Field(description="What the pool is doing.")
    cluster: list[ClusterWorker] | None = Field(
        default=None,
        description="FLEXWING_EXECUTOR=dask: the cluster's workers and whether each is warm.",
    )
