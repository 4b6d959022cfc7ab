"""flexwing's numerical core: static aeroelastic equilibrium of a flexible wing.

A vortex lattice (1 to 8 chordwise panels per strip; the study's model has one) and a cantilever
beam share the heave and twist unknowns; the coupled equations are solved as one nonlinear system
by Newton's method on an exact CasADi Jacobian, compiled once per mesh size. See the design
study in shared/seed/.

This module is the package's public face: the web service and users import from here only.

Importing the package before numpy sets OPENBLAS_NUM_THREADS=1 unless it is already set: the
solver's dense systems are small (119 x 119 at N = 30), and threaded OpenBLAS on a shared machine
makes them 100x slower (measured: 0.3 ms single-threaded, up to 460 ms threaded during a compile).
"""

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

from solver.controls.effectiveness import (
    antisymmetric_divergence,
    control_effectiveness,
    control_sweep,
    linear_reversal,
)
from solver.controls.roll import roll
from solver.deprecated import renamed
from solver.dynamics.aerodynamic_forces import (
    MAX_REDUCED_FREQUENCY,
    generalised_aerodynamic_forces,
)
from solver.dynamics.flutter import FlutterOptions, flutter
from solver.dynamics.modes import natural_modes
from solver.errors import (
    ConvergenceError,
    DynamicInstability,
    FoldedWing,
    InfeasibleDesign,
    InvalidInput,
    NoEquilibrium,
    OptimizerNotConverged,
    SolverError,
)
from solver.fields import Limits, Spec, digest, spec_of, specs
from solver.gusts.analysis import gust_analysis, gust_load_cases
from solver.inputs.airfoil import MAX_CAMBER
from solver.inputs.atmosphere import (
    Air,
    equivalent_airspeed,
    geometric_altitude,
    geopotential_altitude,
    standard_atmosphere,
    true_airspeed,
)
from solver.inputs.control_surfaces import ControlSurface
from solver.inputs.design import (
    Design,
    DesignCondition,
    DesignConstraints,
    DesignLoadCase,
    DesignProblem,
    TwistDesign,
    WallDesign,
)
from solver.inputs.envelope import FlightEnvelope
from solver.inputs.flight import (
    FLIGHT_RULE,
    ISA_SEA_LEVEL_DENSITY,
    FlightCondition,
    OperatingPoint,
    VelocityRange,
)
from solver.inputs.gust import GustCondition, GustSettings
from solver.inputs.load_case import FlightCase
from solver.inputs.mass import ConcentratedMass, MassModel
from solver.inputs.options import InitialGuess, SolverOptions, ValidityLimits
from solver.inputs.spar import Material, SparDesign, ThicknessFraction, TubeSpar
from solver.inputs.wing import MIN_STATIONS, StationSpacing, Wing
from solver.model.layout import Layout
from solver.numerics.cache import CacheInfo, cache_info, clear_caches
from solver.numerics.warm import is_compiled, warm_up
from solver.operations.controls import ControlsInput, RollInput
from solver.operations.design import OptimizeInput
from solver.operations.dynamics import FlutterInput
from solver.operations.gust import GustInput
from solver.operations.sizing import CaseInput, GustCaseInput, LoadsInput
from solver.operations.statics import SolveInput, SweepInput
from solver.operations.table import OPERATION_TABLE, OPERATIONS, TAGS, Operation, SpreadInput
from solver.optimization.optimize import optimize
from solver.results.aerodynamic_forces import GeneralisedAerodynamicForces
from solver.results.controls import (
    ControlEffectiveness,
    ControlSweep,
    ControlSweepPoint,
    HingeMoment,
    Reversal,
    ReversalSummary,
    RollResponse,
    RollStability,
)
from solver.results.design import (
    ConstraintValue,
    DesignCaseResult,
    OptimalDesign,
    OptimizerInfo,
    RigidOptimum,
)
from solver.results.equilibrium import (
    Equilibrium,
    Fold,
    Panels,
    SolveInfo,
    Stability,
    Stations,
    Totals,
)
from solver.results.findings import FINDING_CODES, Finding, FindingOnset
from solver.results.flutter import (
    DivergenceOnset,
    FlutterInfo,
    FlutterOnset,
    FlutterPoint,
    FlutterResult,
    ModeShape,
    NaturalModes,
    NoFlutter,
)
from solver.results.gusts import GustCase, GustLoadCase, GustResult, TurbulenceLoads
from solver.results.quantities import Progress
from solver.results.sizing import (
    CaseLoads,
    CorrelatedLoads,
    LoadsEnvelope,
    SpanwiseEnvelope,
    SparEnvelope,
)
from solver.results.sweep import (
    AirspeedPoint,
    AirspeedSweep,
    AirspeedSweepInfo,
    DivergenceSummary,
    FitDivergence,
    LinearDivergence,
    PointFailure,
)
from solver.sizing.cases import LoadCase, load_cases
from solver.sizing.vn import VnDiagram, VnPoint, vn_diagram, vn_diagrams
from solver.statics.airspeed_sweep import airspeed_sweep
from solver.statics.divergence import (
    divergence_summary,
    find_fold,
    fit_divergence,
    linear_divergence,
    linear_divergence_pressure,
)
from solver.statics.solve import solve
from solver.statics.trefftz import trefftz_drag
from solver.statics.trim import rigid_trim_alpha, trim, trimmed_divergence_limit

__all__ = [
    "FINDING_CODES",
    "FLIGHT_RULE",
    "ISA_SEA_LEVEL_DENSITY",
    "MAX_CAMBER",
    "MAX_REDUCED_FREQUENCY",
    "MIN_STATIONS",
    "OPERATIONS",
    "OPERATION_TABLE",
    "Operation",
    "TAGS",
    "Air",
    "airspeed_sweep",
    "AirspeedPoint",
    "AirspeedSweep",
    "AirspeedSweepInfo",
    "cache_info",
    "CacheInfo",
    "clear_caches",
    "ConcentratedMass",
    "ConstraintValue",
    "ControlEffectiveness",
    "ControlSurface",
    "ControlSweep",
    "ControlSweepPoint",
    "antisymmetric_divergence",
    "control_effectiveness",
    "control_sweep",
    "ConvergenceError",
    "DynamicInstability",
    "GustCase",
    "GustCaseInput",
    "GustCondition",
    "GustInput",
    "GustLoadCase",
    "GustResult",
    "GustSettings",
    "TurbulenceLoads",
    "gust_analysis",
    "gust_load_cases",
    "Design",
    "DesignCondition",
    "DesignCaseResult",
    "DesignConstraints",
    "DesignLoadCase",
    "DesignProblem",
    "digest",
    "divergence_summary",
    "DivergenceOnset",
    "DivergenceSummary",
    "Equilibrium",
    "equivalent_airspeed",
    "find_fold",
    "Finding",
    "FindingOnset",
    "fit_divergence",
    "FitDivergence",
    "FlightCondition",
    "FoldedWing",
    "FlightEnvelope",
    "FlightCase",
    "CaseInput",
    "CaseLoads",
    "CorrelatedLoads",
    "LoadsEnvelope",
    "LoadsInput",
    "SpreadInput",
    "SparEnvelope",
    "SpanwiseEnvelope",
    "flutter",
    "FlutterInfo",
    "ControlsInput",
    "FlutterInput",
    "geometric_altitude",
    "geopotential_altitude",
    "load_cases",
    "LoadCase",
    "RollInput",
    "FlutterOnset",
    "FlutterOptions",
    "FlutterPoint",
    "FlutterResult",
    "Fold",
    "generalised_aerodynamic_forces",
    "GeneralisedAerodynamicForces",
    "HingeMoment",
    "InfeasibleDesign",
    "InitialGuess",
    "InvalidInput",
    "is_compiled",
    "Layout",
    "Limits",
    "linear_divergence",
    "linear_divergence_pressure",
    "LinearDivergence",
    "linear_reversal",
    "MassModel",
    "Material",
    "ModeShape",
    "natural_modes",
    "NaturalModes",
    "NoEquilibrium",
    "NoFlutter",
    "OperatingPoint",
    "OptimalDesign",
    "OptimizerNotConverged",
    "optimize",
    "OptimizeInput",
    "OptimizerInfo",
    "Panels",
    "Progress",
    "PointFailure",
    "Reversal",
    "ReversalSummary",
    "rigid_trim_alpha",
    "RigidOptimum",
    "roll",
    "RollResponse",
    "RollStability",
    "solve",
    "SolveInfo",
    "SolveInput",
    "SolverError",
    "SolverOptions",
    "SparDesign",
    "Spec",
    "spec_of",
    "specs",
    "Stability",
    "standard_atmosphere",
    "Stations",
    "StationSpacing",
    "SweepInput",
    "ThicknessFraction",
    "Totals",
    "trefftz_drag",
    "trim",
    "trimmed_divergence_limit",
    "true_airspeed",
    "TubeSpar",
    "TwistDesign",
    "ValidityLimits",
    "VelocityRange",
    "vn_diagram",
    "vn_diagrams",
    "VnDiagram",
    "VnPoint",
    "WallDesign",
    "warm_up",
    "Wing",
]


def __getattr__(name: str) -> object:
    """Renamed public names, for a release, with a DeprecationWarning (`solver.deprecated`)."""
    return renamed(name)
