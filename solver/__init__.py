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

from solver.cache import CacheInfo, cache_info, clear_caches
from solver.controls import ControlSurface
from solver.divergence import (
    divergence_summary,
    find_fold,
    fit_divergence,
    linear_divergence,
    linear_divergence_pressure,
)
from solver.effectiveness import (
    antisymmetric_divergence,
    control_effectiveness,
    control_sweep,
    linear_reversal,
)
from solver.errors import (
    ConvergenceError,
    InfeasibleDesign,
    InvalidInput,
    NoEquilibrium,
    SolverError,
)
from solver.inputs import (
    ISA_SEA_LEVEL_DENSITY,
    MIN_STATIONS,
    FlightCondition,
    SolverOptions,
    TrimCondition,
    ValidityLimits,
    Wing,
)
from solver.layout import Layout
from solver.optimize import DesignProblem, optimize, trefftz_drag
from solver.results import (
    FINDING_CODES,
    ConstraintValue,
    ControlEffectiveness,
    ControlSweep,
    ControlSweepPoint,
    DivergenceSummary,
    Equilibrium,
    Finding,
    FindingOnset,
    FitDivergence,
    Fold,
    HingeMoment,
    LinearDivergence,
    OptimalDesign,
    OptimizerInfo,
    Panels,
    PointFailure,
    Reversal,
    ReversalSummary,
    RigidOptimum,
    RollResponse,
    RollStability,
    SolveInfo,
    Stability,
    Stations,
    SweepInfo,
    SweepPoint,
    SweepResult,
    Totals,
)
from solver.roll import roll
from solver.solve import solve
from solver.spar import Material, SparDesign, ThicknessFraction, TubeSpar
from solver.sweep import sweep
from solver.trim import rigid_trim_alpha, trim, trim_sweep, trimmed_divergence_limit
from solver.warm import warm_up

__all__ = [
    "ISA_SEA_LEVEL_DENSITY",
    "MIN_STATIONS",
    "CacheInfo",
    "FINDING_CODES",
    "ConstraintValue",
    "ControlEffectiveness",
    "ControlSurface",
    "ControlSweep",
    "ControlSweepPoint",
    "ConvergenceError",
    "DesignProblem",
    "DivergenceSummary",
    "Equilibrium",
    "Finding",
    "FindingOnset",
    "FitDivergence",
    "FlightCondition",
    "Fold",
    "HingeMoment",
    "InfeasibleDesign",
    "InvalidInput",
    "Layout",
    "LinearDivergence",
    "Material",
    "NoEquilibrium",
    "OptimalDesign",
    "OptimizerInfo",
    "Panels",
    "PointFailure",
    "Reversal",
    "ReversalSummary",
    "RigidOptimum",
    "RollResponse",
    "RollStability",
    "SolveInfo",
    "SolverError",
    "SolverOptions",
    "SparDesign",
    "Stability",
    "Stations",
    "SweepInfo",
    "SweepPoint",
    "SweepResult",
    "ThicknessFraction",
    "Totals",
    "TrimCondition",
    "TubeSpar",
    "ValidityLimits",
    "Wing",
    "antisymmetric_divergence",
    "cache_info",
    "clear_caches",
    "control_effectiveness",
    "control_sweep",
    "divergence_summary",
    "find_fold",
    "fit_divergence",
    "linear_divergence",
    "linear_divergence_pressure",
    "linear_reversal",
    "optimize",
    "rigid_trim_alpha",
    "roll",
    "solve",
    "sweep",
    "trefftz_drag",
    "trim",
    "trim_sweep",
    "trimmed_divergence_limit",
    "warm_up",
]
