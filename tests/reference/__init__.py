"""Reference equilibria computed with AeroSandbox, and where to find them.

Two sources, same file format (see `generate_reference.py` for the format). To regenerate one
of ours with any Python that has AeroSandbox 4.2.10:

    cd tests/reference
    /tmp/asbenv/bin/python generate_reference.py data/case_X.json data/ref_X.json

- shared: ``case_*.json`` / ``ref_*.json`` in the ``shared/reference`` directory that sits next to
  the repository root (CI clones the repository into X/main with X/shared beside it). The
  environment variable FLEXWING_SHARED_REFERENCE overrides the location. Tests that need it are
  skipped, with the reason, when it is absent.
- own: ``data/`` next to this file, committed with the repository:

  taper_forward_ea  N = 17, linear taper 1.0 -> 0.4 m, elastic axis at 15 % chord (AHEAD of the
                    quarter chord: nose-down twist, lift relief, no divergence), EI ~ c^2 and
                    GJ ~ c (not c^3), alpha 6 deg, 15-45 m/s.
  negative_alpha    N = 25, mild taper, elastic axis at 35 % chord, EI and GJ tapering linearly
                    in y independently of the chord, alpha -3 deg (negative lift, nose-down
                    wash-in), 8-17 m/s (below the 21 m/s linear divergence speed).
  stepped_spar      N = 30, elliptic-like planform with a 0.12 m tip chord, stepped EI and GJ
                    (three spar sections), elastic axis at 30 % chord, alpha 8 deg, NACA 0012,
                    10-25 m/s: heave up to 10 % of the semispan, where the heave-times-chordwise-
                    force torque turns the tip twist back (3.4 deg at 18 m/s, 0.2 deg at 25 m/s).
  coarse_rect       N = 5 (three interior stations), rectangular, elastic axis at mid-chord,
                    alpha 3 deg, 6-12 m/s (up to a lift amplification of 2).

  Extended-model references (issues 10-12; ``"format": "extended-1"`` or ``"design-1"``, see
  generate_reference.py and CONVENTIONS.md) live in the same folder but are NOT returned by
  `own_references()`, which keeps returning only the study's formulation: use
  `extended_references()`. They are swept_aft, swept_forward, swept_aft_deformed_axis,
  jig_twisted, deformed_axis, k4_symmetric, k4_cambered, k4_dae11_trim, trim_study, trim_swept,
  combined (format extended-1) and design_study (design-1).
"""

from __future__ import annotations

import json
import os
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path

import numpy as np
import pytest

import solver

__all__ = [
    "OWN_DATA_DIR",
    "Reference",
    "load_reference",
    "extended_references",
    "own_references",
    "reference_param",
    "shared_reference_dir",
]

OWN_DATA_DIR = Path(__file__).resolve().parent / "data"
_REPO_ROOT = Path(__file__).resolve().parents[2]
_SHARED_ENV = "FLEXWING_SHARED_REFERENCE"


def shared_reference_dir() -> Path | None:
    """The shared reference directory, or None if it is not there."""
    override = os.environ.get(_SHARED_ENV)
    directory = Path(override) if override else _REPO_ROOT / ".." / "shared" / "reference"
    return directory.resolve() if directory.is_dir() else None


def _shared_missing_reason() -> str:
    return (
        f"shared AeroSandbox references not found at {_REPO_ROOT.parent / 'shared' / 'reference'}"
        f" (clone the repository next to `shared/`, or set {_SHARED_ENV})"
    )


@dataclass(frozen=True, eq=False)
class Reference:
    """One ``ref_NAME.json``: a wing, its flight conditions and AeroSandbox's answers."""

    name: str
    path: Path
    data: dict = field(repr=False)

    @property
    def case(self) -> dict:
        return self.data["case"]

    @property
    def rho(self) -> float:
        """[kg/m^3] AeroSandbox's sea-level ISA density."""
        return float(self.data["rho"])

    @property
    def alpha(self) -> float:
        """[deg]"""
        return float(self.case["alpha_deg"])

    @property
    def rigid(self) -> dict:
        return self.data["rigid"]

    @property
    def equilibria(self) -> list[dict]:
        """AeroSandbox's converged points, in the order it solved them."""
        return self.data["equilibria"]

    def equilibrium_at(self, velocity: float) -> dict:
        (point,) = [e for e in self.equilibria if e["velocity"] == velocity]
        return point

    @cached_property
    def wing(self) -> solver.Wing:
        """The wing as flexwing takes it; an extended case's camber is the line AeroSandbox put
        at the chordwise nodes (its airfoil's coordinates, not the analytic mean line)."""
        case = self.case
        model = self.data.get("model", {})
        return solver.Wing.create(
            y=np.asarray(self.data["ys"]),
            chord=case["chords"],
            elastic_axis=case["x_ea_over_chord"],
            bending_stiffness=case["EI"],
            torsional_stiffness=case["GJ"],
            sweep=model.get("sweep_deg", 0.0),
            jig_twist=model.get("jig_twist_deg", 0.0),
            airfoil=self.data.get("camber_line"),
        )

    @property
    def options(self) -> solver.SolverOptions:
        model = self.data.get("model", {})
        return solver.SolverOptions(
            chordwise_panels=model.get("chordwise_resolution", 1),
            torque_axis=model.get("torque_axis", "undeformed"),
        )

    @property
    def trimmed_lift(self) -> float | None:
        """[N] the lift a trimmed case holds, or None at a given alpha."""
        trim = self.case.get("trim")
        return None if trim is None else float(trim["lift"])


def load_reference(path: Path) -> Reference:
    data = json.loads(Path(path).read_text())
    return Reference(name=data["case"]["name"], path=Path(path), data=data)


def _all_own_references() -> list[Reference]:
    return [load_reference(path) for path in sorted(OWN_DATA_DIR.glob("ref_*.json"))]


def own_references() -> list[Reference]:
    """The study-formulation wings committed in data/ (no "format" key), sorted by name."""
    return [reference for reference in _all_own_references() if "format" not in reference.data]


def extended_references() -> list[Reference]:
    """The extended-model ("extended-1") and design ("design-1") references in data/, by name."""
    return [reference for reference in _all_own_references() if "format" in reference.data]


def reference_param(name: str):
    """A pytest.param holding the shared reference NAME, or skipped with the reason it is absent."""
    directory = shared_reference_dir()
    path = None if directory is None else directory / f"ref_{name}.json"
    if path is None or not path.is_file():
        return pytest.param(None, id=name, marks=pytest.mark.skip(reason=_shared_missing_reason()))
    return pytest.param(load_reference(path), id=name)
