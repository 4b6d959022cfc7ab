"""solver.optimization.design_space: a design vector -> the wing it describes, its equilibrium, and
every function the optimiser sees with its exact gradient.

- The gradients (one forward sensitivity at the equilibrium) agree with central differences.
- `design_wing` changes what the design varies (the jig twist; sized, the spar's walls and the
  stiffnesses they give) and keeps every other field of the wing as it was.
"""

from __future__ import annotations

import dataclasses
from typing import Any

import numpy as np
import pytest

import solver
from solver.optimization.design_space import DesignSpace
from tests.study import study_wing

CARBON = solver.Material(
    youngs_modulus=70e9, shear_modulus=27e9, density=1600.0, yield_stress=600e6
)


def _spar_wing(yield_stress: float = 600e6) -> solver.Wing:
    base = study_wing()
    material = dataclasses.replace(CARBON, yield_stress=yield_stress)
    spar = solver.SparDesign(solver.ThicknessFraction(0.8), 0.002, material)
    return solver.Wing.create(base.y, base.chord, 0.4, airfoil="naca0012", spar=spar)


@pytest.mark.parametrize("rigid", [False, True], ids=["flexible", "rigid"])
def test_reduced_gradients_are_exact(rigid: bool):
    """Every function IPOPT sees, against central differences (step 1e-6: error ~1e-8)."""
    wing = _spar_wing()
    problem = solver.DesignProblem(
        solver.DesignCondition(14.0, lift=600.0),
        design=solver.Design(wall_thickness=solver.WallDesign()),
        smoothness_weight=0.01,
        constraints=solver.DesignConstraints(max_tip_heave=1.0),
    )
    space = DesignSpace(wing, problem, solver.SolverOptions(), rigid=rigid)
    v = np.concatenate([np.linspace(3.0, 1.0, 6), np.full(30, 0.002)])
    direction = np.random.default_rng(7).normal(size=v.size)
    direction[6:] *= 1e-4  # walls in metres
    step = 1e-6
    point = space.at(v)
    plus, minus = space._evaluate(v + step * direction), space._evaluate(v - step * direction)
    for name, gradient in point.gradients.items():
        finite = (plus.values[name] - minus.values[name]) / (2 * step)
        exact = gradient @ direction
        scale = max(np.max(np.abs(exact)), 1e-9)
        assert np.max(np.abs(finite - exact)) <= 1e-5 * scale, name


# ----------------------------------------------------------------------- the designed wing

# What a design may change; every other field of the wing must come out as it went in.
DESIGNED = {"jig_twist", "spar", "bending_stiffness", "torsional_stiffness"}


def _rich_wing(spar: bool) -> solver.Wing:
    """A wing that sets every field it can away from its default: cambered sections per
    station, a stall limit, sweep, a built-in twist, the elastic axis varying."""
    base = study_wing(n=12)
    camber = ["naca2412"] * 6 + ["naca0012"] * 6
    given: dict[str, Any] = {
        "airfoil": camber,
        "cl_max": np.linspace(1.4, 1.1, 12),
        "sweep": 8.0,
        "jig_twist": np.linspace(2.0, -1.0, 12),
    }
    elastic_axis = np.linspace(0.35, 0.42, 12)
    if spar:
        tube = solver.SparDesign(solver.ThicknessFraction(0.8), 0.002, CARBON)
        return solver.Wing.create(base.y, base.chord, elastic_axis, spar=tube, **given)
    return solver.Wing.create(
        base.y, base.chord, elastic_axis, base.bending_stiffness, base.torsional_stiffness, **given
    )


def _space(wing: solver.Wing, sized: bool) -> DesignSpace:
    design = solver.Design(
        solver.TwistDesign(control_points=4),
        solver.WallDesign() if sized else None,
    )
    problem = solver.DesignProblem(solver.DesignCondition(12.0, lift=100.0), design)
    return DesignSpace(wing, problem, solver.SolverOptions(), rigid=False)


@pytest.mark.parametrize(
    ("spar", "sized"),
    [(False, False), (True, False), (True, True)],
    ids=["stiffnesses", "spar-kept", "spar-sized"],
)
def test_the_designed_wing_keeps_every_field_the_design_does_not_vary(
    spar: bool, sized: bool
) -> None:
    wing = _rich_wing(spar)
    space = _space(wing, sized)
    walls = np.linspace(0.003, 0.001, 12)
    v = np.concatenate([[1.0, -0.5, 0.25, 2.0], walls if sized else []])
    designed = space.design_wing(v)
    for field in dataclasses.fields(solver.Wing):
        if field.name in DESIGNED:
            continue
        kept = solver.digest(getattr(designed, field.name))
        assert kept == solver.digest(getattr(wing, field.name)), field.name
    assert designed.airfoil is wing.airfoil  # the sections themselves, cambered as they were
    np.testing.assert_array_equal(designed.cl_max, wing.cl_max)  # type: ignore[arg-type]


@pytest.mark.parametrize(
    ("spar", "sized"),
    [(False, False), (True, False), (True, True)],
    ids=["stiffnesses", "spar-kept", "spar-sized"],
)
def test_the_designed_wing_has_the_designs_twist_and_walls(spar: bool, sized: bool) -> None:
    wing = _rich_wing(spar)
    space = _space(wing, sized)
    walls = np.linspace(0.003, 0.001, 12)
    v = np.concatenate([[1.0, -0.5, 0.25, 2.0], walls if sized else []])
    designed = space.design_wing(v)
    # The jig twist is the spline of the control points (it replaces the wing's own), and it
    # is the design's: read-only, so no later change of `v` or of the array can alter it.
    np.testing.assert_array_equal(designed.jig_twist, space.basis @ v[:4])
    assert designed.jig_twist[0] == 1.0 and designed.jig_twist[-1] == pytest.approx(2.0, 1e-12)
    assert not designed.jig_twist.flags.writeable
    if sized:
        assert designed.spar is not None and wing.spar is not None
        np.testing.assert_array_equal(designed.spar.wall_thickness, walls)
        np.testing.assert_array_equal(designed.spar.outer_diameter, wing.spar.outer_diameter)
        assert designed.spar.material == wing.spar.material
        np.testing.assert_array_equal(designed.bending_stiffness, designed.spar.bending_stiffness)
        np.testing.assert_array_equal(
            designed.torsional_stiffness, designed.spar.torsional_stiffness
        )
        # EI = E pi/64 (D^4 - d^4), GJ = G pi/32 (D^4 - d^4), d = D - 2 t: of the new walls.
        outer = wing.spar.outer_diameter
        fourth = outer**4 - (outer - 2 * walls) ** 4
        ei, gj = (
            CARBON.youngs_modulus * np.pi / 64 * fourth,
            CARBON.shear_modulus * np.pi / 32 * fourth,
        )
        np.testing.assert_allclose(designed.bending_stiffness, ei, rtol=1e-12)
        np.testing.assert_allclose(designed.torsional_stiffness, gj, rtol=1e-12)
    else:
        assert designed.spar is wing.spar
        np.testing.assert_array_equal(designed.bending_stiffness, wing.bending_stiffness)
        np.testing.assert_array_equal(designed.torsional_stiffness, wing.torsional_stiffness)


def test_the_designed_wing_solves_as_a_wing_built_from_its_fields() -> None:
    """What `design_wing` answers is a wing like any other: rebuilt by `Wing.create` from its
    fields it is the same wing (its canonical identity)."""
    wing = _rich_wing(spar=False)
    designed = _space(wing, sized=False).design_wing(np.array([1.0, -0.5, 0.25, 2.0]))
    rebuilt = solver.Wing.create(
        designed.y,
        designed.chord,
        designed.elastic_axis,
        designed.bending_stiffness,
        designed.torsional_stiffness,
        airfoil=["naca2412"] * 6 + ["naca0012"] * 6,
        cl_max=designed.cl_max,
        sweep=designed.sweep,
        jig_twist=designed.jig_twist,
    )
    assert rebuilt.key == designed.key
