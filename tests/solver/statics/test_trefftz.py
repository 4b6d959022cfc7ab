"""solver.statics.trefftz: the far-field (Trefftz-plane) induced drag of the planar wake,
D_T = q G^T A G for strip circulations G per unit airspeed.

- An elliptic loading's drag is the classical minimum L^2 / (q pi b^2) up to the mesh's
  discretisation error, which is measured here (the midpoint downwash of straight trailing
  vortices at the stations): always low, first order in the strip width, C / (N - 1) with

      sine-spaced stations:  C = 0.611 at N = 31 (-2.04 %), 0.6165 at 481 (-0.128 %), 0.6167 at 961
      uniform stations:      C = 0.4163 at N = 30 (-1.44 %), 0.4174 at 150, 0.4176 at 961

  (C rises slowly with N: 0.598 and 0.413 at N = 11).
- No loading has zero or negative drag (the symmetric part of A is positive definite): a zigzag
  twist cannot game it, the reason the optimiser can use it.
- `trefftz_drag` of an equilibrium scales with q at a fixed loading shape (a stiff wing), and
  no loading of the mesh carrying the same lift has less.
"""

from __future__ import annotations

import functools

import numpy as np
import pytest

import solver
from solver.statics.system import CoupledSystem
from solver.statics.trefftz import strip_sum, trefftz_drag, trefftz_matrix
from tests import study

SEMISPAN = 5.0
# The band of C = (N - 1) |relative error| of an elliptic loading on meshes of 30 stations or
# more, measured above, widened by about 1 % on either side.
ERROR_BAND = {"sine": (0.605, 0.623), "uniform": (0.412, 0.422)}


def _stations(spacing: str, n: int) -> np.ndarray:
    if spacing == "sine":  # denser towards the tip, where an elliptic loading falls steeply
        return SEMISPAN * np.sin(np.linspace(0, np.pi / 2, n))
    return np.linspace(0, SEMISPAN, n)


def _elliptic_error(spacing: str, n: int) -> float:
    """D_T / (L^2 / (q pi b^2)) - 1 of the elliptic loading sampled at the strips' middles."""
    y = _stations(spacing, n)
    middle = (y[1:] + y[:-1]) / 2
    circulation = np.sqrt(1 - (middle / SEMISPAN) ** 2)
    drag = circulation @ trefftz_matrix(y) @ circulation  # per unit q
    lift = 4 * np.sum(circulation * np.diff(y))  # per unit q, both halves
    return float(drag / (lift**2 / (np.pi * (2 * SEMISPAN) ** 2)) - 1)


MESHES = [("sine", 31), ("sine", 61), ("sine", 481), ("uniform", 30), ("uniform", 150)]


@pytest.mark.parametrize(("spacing", "n"), MESHES, ids=[f"{s}-{n}" for s, n in MESHES])
def test_an_elliptic_loadings_trefftz_drag_is_the_classical_minimum(spacing: str, n: int):
    """Low by the measured discretisation error, within its band."""
    error = _elliptic_error(spacing, n)
    low, high = ERROR_BAND[spacing]
    assert -high / (n - 1) <= error <= -low / (n - 1)


@pytest.mark.parametrize(
    ("spacing", "n"),
    [("sine", 31), ("uniform", 30), ("sine", 121)],
    ids=["sine-31", "uniform-30", "sine-121"],
)
def test_the_error_halves_as_the_strips_halve(spacing: str, n: int):
    """First order: twice the strips, half the error (measured ratios 0.501 to 0.502)."""
    ratio = _elliptic_error(spacing, 2 * n - 1) / _elliptic_error(spacing, n)
    assert ratio == pytest.approx(0.5, abs=0.005)


@pytest.mark.parametrize(("spacing", "n"), MESHES, ids=[f"{s}-{n}" for s, n in MESHES])
def test_no_loading_has_zero_or_negative_drag(spacing: str, n: int):
    """The symmetric part of A is positive definite, so any loading, a zigzag too, costs drag
    with margin: its least eigenvalue falls with the strip width, as 1.15 / (N - 1) to
    1.16 / (N - 1) for uniform stations and 1.54 / (N - 1) to 1.57 / (N - 1) for sine-spaced
    ones (measured on these meshes); the bound is 0.5 / (N - 1)."""
    a = trefftz_matrix(_stations(spacing, n))
    assert a.shape == (n - 1, n - 1)
    assert np.all(np.isfinite(a))
    least = np.linalg.eigvalsh((a + a.T) / 2).min()
    assert least > 0.5 / (n - 1)


def test_a_zigzag_on_an_elliptic_loading_raises_its_drag_at_the_same_lift():
    y = _stations("uniform", 31)  # 30 strips of equal width: an alternating zigzag lifts 0
    middle, width = (y[1:] + y[:-1]) / 2, np.diff(y)
    elliptic = np.sqrt(1 - (middle / SEMISPAN) ** 2)
    zigzag = 0.05 * (-1.0) ** np.arange(30)
    assert np.sum(zigzag * width) == pytest.approx(0.0, abs=1e-15)
    a = trefftz_matrix(y)
    base, gamed = elliptic @ a @ elliptic, (elliptic + zigzag) @ a @ (elliptic + zigzag)
    assert gamed > 1.1 * base  # measured: +19.6 % for a zigzag of 5 % of the root's circulation


# ------------------------------------------------------------------------ of an equilibrium


@functools.cache
def _solved(stiffness: float | None, velocity: float) -> solver.Equilibrium:
    wing = study.study_wing()
    if stiffness is not None:
        wing = solver.Wing.create(wing.y, wing.chord, 0.4, stiffness, stiffness)
    return solver.solve(wing, study.flight(velocity))


def test_a_stiff_wings_trefftz_drag_scales_with_the_dynamic_pressure():
    """At a fixed loading shape D_T / q is a constant: a wing 1e7 times stiffer than the
    study's, at 5 and 40 m/s, agrees to 1e-6 (measured 8e-8: at 40 m/s it still twists
    3e-7 deg)."""
    slow, fast = _solved(1e11, 5.0), _solved(1e11, 40.0)
    assert abs(fast.totals.tip_twist) < 1e-6
    per_q = [trefftz_drag(e) / e.dynamic_pressure for e in (slow, fast)]
    assert per_q[1] == pytest.approx(per_q[0], rel=1e-6)


def test_the_study_wing_washes_in_so_its_drag_grows_faster_than_q():
    """The elastic axis behind the quarter chord twists the study's wing nose-up with q: the
    lift per q, and with it the far-field drag per q, grows with the airspeed."""
    per_q = [trefftz_drag(_solved(None, v)) / _solved(None, v).dynamic_pressure for v in (6, 10)]
    assert per_q[1] > 1.1 * per_q[0]  # measured 0.0629 -> 0.0773 m^2


def test_no_loading_of_the_mesh_carrying_the_same_lift_has_less_drag():
    """The least of q G^T A G over loadings G of equal lift 4 q sum(G dy) is
    L^2 / (q c^T S^-1 c), c = 4 dy, S = (A + A^T) / 2: the equilibrium's is at least that
    (measured 4e-4 above it at 10 m/s: the study's chord is nearly elliptic)."""
    equilibrium = _solved(None, 10.0)
    system = CoupledSystem.of(equilibrium.wing, equilibrium.flight.alpha, equilibrium.options)
    strips = strip_sum(system) @ equilibrium.state[system.layout.circulation]
    q, y = equilibrium.dynamic_pressure, equilibrium.wing.y
    a = trefftz_matrix(y)
    c = 4 * np.diff(y)
    lift = q * c @ strips
    assert lift == pytest.approx(equilibrium.totals.lift, rel=2e-3)  # the near field's
    least = lift**2 / (q * c @ np.linalg.solve((a + a.T) / 2, c))
    drag = trefftz_drag(equilibrium)
    assert drag == pytest.approx(q * strips @ a @ strips, rel=1e-12)
    assert least <= drag <= 1.01 * least


def test_strip_theorys_induced_drag_is_the_far_field_drag_of_its_lift():
    """Strip theory's sections see no downwash, so its near field has no drag: the induced
    drag it reports is the Trefftz-plane drag of its own lift distribution (the same function
    of the same state, so equal to round-off), positive, and not less than the least drag of
    any loading carrying that lift on the mesh."""
    options = solver.SolverOptions(aerodynamics="strip")
    equilibrium = solver.solve(study.study_wing(), study.flight(10.0), options=options)
    drag = equilibrium.totals.induced_drag
    assert drag == pytest.approx(trefftz_drag(equilibrium), rel=1e-12)
    q, y = equilibrium.dynamic_pressure, equilibrium.wing.y
    a = trefftz_matrix(y)
    c = 4 * np.diff(y)
    least = equilibrium.totals.lift**2 / (q * c @ np.linalg.solve((a + a.T) / 2, c))
    # The lift is the near field's (the far field's 4 q sum(G dy) agrees to 2e-3: the
    # previous test), so the bound holds to that.
    assert drag >= least * (1 - 4e-3)
    assert equilibrium.totals.CDi == pytest.approx(
        drag / (q * equilibrium.totals.reference_area), rel=1e-12
    )


@pytest.mark.parametrize("dihedral", [0.0, 8.0, -20.0])
def test_a_dihedral_wings_wake_is_a_v_whose_normalwash_biot_savart_gives(dihedral: float):
    """The wake lies in each half's plane: trailing vortices at y (cos, sin) of the dihedral,
    their mirror images, of opposite sense, at y (-cos, sin); the normalwash at the strips'
    middles along the plane's normal (-sin, cos), each point vortex's v = G (-dz, dy) /
    (2 pi r^2), summed directly. Round-off only."""
    y = _stations("sine", 12)
    middle, width = (y[1:] + y[:-1]) / 2, np.diff(y)
    c, s = np.cos(np.radians(dihedral)), np.sin(np.radians(dihedral))
    shed = np.zeros((y.size, y.size - 1))  # trailing strengths: inboard minus outboard strip
    shed[np.arange(1, y.size), np.arange(y.size - 1)] = 1.0
    shed[np.arange(1, y.size - 1), np.arange(1, y.size - 1)] = -1.0

    def normalwash(at: np.ndarray, vortex: np.ndarray) -> float:
        apart = at - vortex
        velocity = np.array([-apart[1], apart[0]]) / (2 * np.pi * apart @ apart)
        return float(velocity @ np.array([-s, c]))

    kernel = np.zeros((y.size - 1, y.size))
    for i, m in enumerate(middle):
        for j, station in enumerate(y[1:], start=1):  # the root's vortex meets its image
            at = m * np.array([c, s])
            kernel[i, j] = normalwash(at, station * np.array([c, s])) - normalwash(
                at, station * np.array([-c, s])
            )
    expected = -2 * np.diag(width) @ kernel @ shed
    np.testing.assert_allclose(trefftz_matrix(y, dihedral), expected, rtol=1e-12, atol=1e-14)
