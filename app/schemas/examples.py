"""The request examples of the OpenAPI document (what /docs pre-fills): the design study's wing
(shared/seed, chapter 14), y = linspace(0, 5, 30) m, chord = sqrt(linspace(2, 0.02, 30)) m,
elastic axis at 40 % chord, EI = 2e4 c^3, GJ = 1e3 c^3, at 10 m/s and alpha 5 deg; `/docs` runs
them as they are."""

from __future__ import annotations

import math
from typing import Any

from solver import ISA_SEA_LEVEL_DENSITY

__all__ = [
    "CONTROLS_EXAMPLES",
    "LOADS_EXAMPLES",
    "EXAMPLES",
    "FLUTTER_EXAMPLES",
    "GUST_EXAMPLES",
    "GOLAND_FLUTTER",
    "OPTIMIZE_EXAMPLES",
    "ROLL_EXAMPLES",
    "SOLVE_EXAMPLES",
    "STUDY_OPTIMIZE",
    "STUDY_SOLVE",
    "STUDY_SWEEP",
    "STUDY_SWEEP_REQUEST",
    "STUDY_CONTROLS",
    "STUDY_ROLL",
    "STUDY_WING",
    "SWEEP_EXAMPLES",
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


STUDY_WING = study_wing()
STUDY_SWEEP: list[Any] = [6.0, 10.0, 12.0, 15.0, 18.0, 20.0]
STUDY_SOLVE: dict[str, Any] = {
    "wing": STUDY_WING,
    "flight": {"velocity": 10.0, "alpha": 5.0, "density": ISA_SEA_LEVEL_DENSITY},
}
STUDY_SWEEP_REQUEST: dict[str, Any] = {
    "wing": STUDY_WING,
    "flight": {"alpha": 5.0, "density": ISA_SEA_LEVEL_DENSITY},
    "velocities": STUDY_SWEEP,
}
STUDY_OPTIMIZE: dict[str, Any] = {
    "wing": STUDY_WING,
    "flight": {"velocity": 12.0, "weight": 300.0, "density": ISA_SEA_LEVEL_DENSITY},
    "design": {"jig_twist": {"control_points": 6}},
    "objective": "induced_drag",
}
# Request-body examples for the OpenAPI document (what /docs pre-fills).
SOLVE_EXAMPLES: dict[str, Any] = {
    "study": {
        "summary": "The design study's wing at 10 m/s, alpha 5 deg",
        "value": STUDY_SOLVE,
    },
    "beyond_divergence": {
        "summary": "The same wing at 23 m/s: no equilibrium (422, with the fold speed)",
        "value": STUDY_SOLVE | {"flight": STUDY_SOLVE["flight"] | {"velocity": 23.0}},
    },
    "at_its_weight": {
        "summary": "The same wing trimmed to carry its 300 N at 12 m/s: alpha is solved for",
        "value": STUDY_SOLVE
        | {
            "flight": {
                "velocity": 12.0,
                "weight": 300.0,
                "load_factor": 1.0,
                "density": ISA_SEA_LEVEL_DENSITY,
            }
        },
    },
    "tube_spar": {
        "summary": "A carbon tube spar in NACA 0012 sections at its weight: stresses, margin, mass",
        "value": {
            "wing": {k: v for k, v in STUDY_WING.items() if not k.endswith("stiffness")}
            | {
                "airfoil": "naca0012",
                "spar": {
                    "outer_diameter": {"fraction_of_thickness": 0.8},
                    "wall_thickness": 0.001,
                    "material": {
                        "youngs_modulus": 70e9,
                        "shear_modulus": 27e9,
                        "density": 1600.0,
                        "yield_stress": 600e6,
                    },
                },
            },
            "flight": {"velocity": 12.0, "weight": 300.0, "load_factor": 2.5},
            "options": {"safety_factor": 1.5},
        },
    },
    "pull_up": {
        "summary": "A 2 g pull-up at 15 m/s: twice the lift",
        "value": STUDY_SOLVE | {"flight": {"velocity": 15.0, "weight": 300.0, "load_factor": 2.0}},
    },
}
SWEEP_EXAMPLES: dict[str, Any] = {
    "study": {
        "summary": "The design study's sweep: 6 to 20 m/s, alpha 5 deg",
        "value": STUDY_SWEEP_REQUEST,
    },
    "to_the_fold": {
        "summary": "Past the fold: 22 and 23 m/s have no equilibrium",
        "value": STUDY_SWEEP_REQUEST | {"velocities": [10.0, 15.0, 20.0, 21.0, 22.0, 23.0]},
    },
    "at_its_weight": {
        "summary": "The study's wing trimmed to its 300 N from 8 to 26 m/s: alpha per airspeed, "
        "and the trimmed divergence limit",
        "value": STUDY_SWEEP_REQUEST
        | {
            "flight": {"weight": 300.0, "density": ISA_SEA_LEVEL_DENSITY},
            "velocities": [8.0, 10.0, 12.0, 14.0, 16.0, 18.0, 20.0, 22.0, 24.0, 26.0],
        },
    },
}


OPTIMIZE_EXAMPLES: dict[str, Any] = {
    "study": {
        "summary": "The study's closing sketch: the jig twist of its wing carrying 300 N at 12 m/s",
        "value": STUDY_OPTIMIZE,
    },
    "aerosandbox_reference": {
        "summary": "The regularised sketch AeroSandbox solves: every station, penalty 0.01",
        "value": STUDY_OPTIMIZE
        | {"design": {"jig_twist": {"control_points": None}}, "smoothness_weight": 0.01},
    },
    "multipoint": {
        "summary": "The lightest tube spar for the design flight and a 2.5 g pull-up (multipoint)",
        "value": {
            "wing": SOLVE_EXAMPLES["tube_spar"]["value"]["wing"]
            | {
                "spar": SOLVE_EXAMPLES["tube_spar"]["value"]["wing"]["spar"]
                | {
                    "wall_thickness": 0.002,
                    "material": SOLVE_EXAMPLES["tube_spar"]["value"]["wing"]["spar"]["material"]
                    | {"yield_stress": 30e6},
                }
            },
            "flight": {"velocity": 14.0, "weight": 300.0},
            "load_cases": [
                {
                    "name": "pull-up",
                    "flight": {"velocity": 14.0, "weight": 300.0, "load_factor": 2.5},
                }
            ],
            "design": {"wall_thickness": {"lower": 0.0005, "upper": 0.01}},
            "objective": "spar_mass",
        },
    },
}


# The Goland wing (Goland 1945, J. Appl. Mech. 12, A197; as tabulated by Eastep and by
# Bisplinghoff, Ashley and Halfman): semispan 6.096 m, chord 1.8288 m, elastic axis at 33 %,
# centre of gravity at 43 % chord, EI 9.77e6 N m^2, GJ 0.987e6 N m^2, 35.71 kg/m and 8.64 kg m
# about the elastic axis (7.45 kg m about the centre of gravity). Strip theory at sea level:
# flutter at ~137 m/s, ~70 rad/s.
GOLAND_WING: dict[str, Any] = {
    "y": {"semispan": 6.096, "stations": 30},
    "chord": 1.8288,
    "elastic_axis": 0.33,
    "bending_stiffness": 9.77e6,
    "torsional_stiffness": 0.987e6,
    "mass": {"mass_per_length": 35.71, "center_of_gravity": 0.43, "inertia_per_length": 7.446},
}
GOLAND_FLUTTER: dict[str, Any] = {
    "wing": GOLAND_WING,
    "flight": {"alpha": 0.0, "density": ISA_SEA_LEVEL_DENSITY},
    "velocities": {"start": 20.0, "stop": 200.0, "count": 50},
    "options": {"aerodynamics": "strip"},
}
FLUTTER_EXAMPLES: dict[str, Any] = {
    "goland": {
        "summary": "The Goland wing, strip theory at sea level: flutter at ~137 m/s, ~70 rad/s",
        "value": GOLAND_FLUTTER,
    },
    "goland_lattice": {
        "summary": "The same wing with the lattice's 3D steady loading and Theodorsen's lag",
        "value": GOLAND_FLUTTER | {"options": {"aerodynamics": "lattice"}},
    },
    "study_loaded": {
        "summary": "The study's wing, about its equilibrium at 5 deg (a soft, light wing)",
        "value": {
            "wing": STUDY_WING
            | {
                "mass": {
                    "mass_per_length": 1.0,
                    "center_of_gravity": 0.42,
                    "inertia_per_length": 0.02,
                }
            },
            "flight": {"alpha": 5.0, "density": ISA_SEA_LEVEL_DENSITY},
            "velocities": {"start": 2.0, "stop": 21.0, "count": 20},
        },
    },
}


# The study's wing with a flap over the inner 45 % of the semispan (hinge at half chord) and an
# aileron over 55-95 % (hinge at 75 %), on 4 chordwise panels (the aftmost hinge 4 panels carry is
# at 85 % of the chord).
STUDY_SURFACES: list[dict[str, Any]] = [
    {"name": "flap", "start": 0.0, "end": 0.45, "hinge": 0.5, "deflection": 5.0, "kind": "flap"},
    {
        "name": "aileron",
        "start": 0.55,
        "end": 0.95,
        "hinge": 0.75,
        "deflection": 5.0,
        "kind": "aileron",
    },
]
STUDY_ROLL: dict[str, Any] = {
    "wing": STUDY_WING | {"control_surfaces": STUDY_SURFACES},
    "flight": {"velocity": 12.0, "alpha": 5.0, "density": ISA_SEA_LEVEL_DENSITY},
    "options": {"chordwise_panels": 4},
}
STUDY_CONTROLS: dict[str, Any] = {
    "wing": STUDY_ROLL["wing"],
    "flight": {"alpha": 5.0, "density": ISA_SEA_LEVEL_DENSITY},
    "velocities": [6.0, 10.0, 14.0, 18.0, 20.0, 21.0],
    "options": {"chordwise_panels": 4},
}
ROLL_EXAMPLES: dict[str, Any] = {
    "study": {
        "summary": "The study's wing, 5 deg of aileron at 12 m/s, alpha 5 deg: the rolling moment",
        "value": STUDY_ROLL,
    },
    "free_roll": {
        "summary": "The same wing trimmed to its 300 N: the free-roll rate and pb/2V",
        "value": STUDY_ROLL
        | {
            "flight": {"velocity": 12.0, "weight": 300.0, "density": ISA_SEA_LEVEL_DENSITY},
            "free_roll": True,
        },
    },
    "exact": {
        "summary": "At alpha 0, flap neutral: the exactly antisymmetric equilibrium",
        "value": STUDY_ROLL
        | {
            "wing": STUDY_WING | {"control_surfaces": [STUDY_SURFACES[1]]},
            "flight": {"velocity": 12.0, "alpha": 0.0, "density": ISA_SEA_LEVEL_DENSITY},
        },
    },
}
CONTROLS_EXAMPLES: dict[str, Any] = {
    "study": {
        "summary": "The study's flap and aileron from 6 to 21 m/s: the aileron reverses near "
        "20.6 m/s, before the wing diverges",
        "value": STUDY_CONTROLS,
    },
    "at_its_weight": {
        "summary": "The same wing trimmed to its 300 N at each airspeed",
        "value": STUDY_CONTROLS
        | {
            "flight": {"weight": 300.0, "density": ISA_SEA_LEVEL_DENSITY},
            "velocities": [10.0, 12.0, 14.0, 16.0, 18.0, 20.0],
        },
    },
}

STUDY_MASS: dict[str, Any] = {
    "mass_per_length": 1.0,
    "center_of_gravity": 0.42,
    "inertia_per_length": 0.02,
}
LOADS_EXAMPLES: dict[str, Any] = {
    "cases": {
        "summary": "The study's wing with a light mass: a 2.5 g pull-up, a 1 g cruise, and a "
        "rolling pull-out at 2 g",
        "value": {
            "wing": STUDY_WING | {"mass": STUDY_MASS, "control_surfaces": STUDY_SURFACES},
            "cases": [
                {
                    "name": "pull-up",
                    "flight": {"velocity": 12.0, "weight": 300.0, "load_factor": 2.5},
                },
                {"name": "cruise", "flight": {"velocity": 14.0, "weight": 300.0}},
                {
                    "name": "rolling pull-out",
                    "flight": {"velocity": 12.0, "weight": 300.0, "load_factor": 2.0},
                    "aileron": 5.0,
                    "roll_rate": 0.3,
                },
            ],
            "options": {"chordwise_panels": 4},
        },
    },
    "envelope": {
        "summary": "The same wing's CS-23 normal category envelope at two weights: every V-n "
        "corner and gust point, their envelope along the span",
        "value": {
            "wing": STUDY_WING | {"mass": STUDY_MASS},
            "envelope": {
                "weights": [250.0, 300.0],
                "altitudes": [0.0],
                "category": "normal",
                "cl_max": 1.2,
                "cl_min": -0.6,
                "cruise_speed": 12.0,
                "dive_speed": 16.0,
            },
        },
    },
}
GUST_EXAMPLES: dict[str, Any] = {
    "study": {
        "summary": "The study's wing with a light mass, 300 N at 12 m/s: 1-cos gusts from 9 to "
        "107 m and continuous turbulence",
        "value": {
            "wing": STUDY_WING | {"mass": STUDY_MASS},
            "flight": {"velocity": 12.0, "weight": 300.0, "density": ISA_SEA_LEVEL_DENSITY},
        },
    },
    "clamped": {
        "summary": "The same wing held at its root (a wind-tunnel model), strip theory, 5 "
        "gradients",
        "value": {
            "wing": STUDY_WING | {"mass": STUDY_MASS},
            "flight": {"velocity": 12.0, "weight": 300.0, "density": ISA_SEA_LEVEL_DENSITY},
            "gust": {"clamped": True, "gradients": 5, "turbulence": False},
            "options": {"aerodynamics": "strip"},
        },
    },
}
# Operation name -> its examples ({name: {summary, value}}): what /docs offers, the page loads,
# and the first of which the request model shows as its example. Every operation of
# `solver.OPERATION_TABLE` has some (tests/app/schemas/test_examples.py).
EXAMPLES: dict[str, dict[str, Any]] = {
    "solve": SOLVE_EXAMPLES,
    "sweep": SWEEP_EXAMPLES,
    "optimize": OPTIMIZE_EXAMPLES,
    "flutter": FLUTTER_EXAMPLES,
    "roll": ROLL_EXAMPLES,
    "controls": CONTROLS_EXAMPLES,
    "loads": LOADS_EXAMPLES,
    "gust": GUST_EXAMPLES,
}
