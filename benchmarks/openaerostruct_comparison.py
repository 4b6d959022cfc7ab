"""flexwing against OpenAeroStruct 2.12, an independent code (issue 10).

Run: /tmp/oasenv/bin/python benchmarks/openaerostruct_comparison.py   (3 minutes at load 2 on
2 cores, 5-6 at load 3-4, plus ~6 minutes the first time to compile flexwing's libraries for
N = 11, 21 and 41; progress on stderr) in a venv with `openaerostruct==2.12.*`, `openmdao` and
flexwing (`pip install -e .`, or PYTHONPATH=. : run as a script, benchmarks/ and not the current
directory is first on sys.path). OpenAeroStruct (OAS) is a dev-only reference, never a dependency
of flexwing.

What is compared. A rectangular wing, semispan 5 m, chord 1 m, N = 21 stations, elastic axis (EA)
at 35 % chord, uniform EI = 1e5 and GJ = 3e3 N m^2 (of the section normal to the EA), swept
-20, 0, +20 and +35 deg along the EA, at alpha 2 deg, rho 1.225. For each sweep, at the speeds
whose dynamic pressure is 25, 50, 75 and 90 % of the fold of flexwing's branch (default,
undeformed torque axis): lift, tip heave, tip twist (streamwise and about the EA), and the linear
divergence pressure of both codes. Then what causes the differences, what each torque axis does
near divergence, and the wall time per equilibrium.

How OAS is set up (`benchmarks/oas_wing.py`; shared/notes/extended-models.md items 9-13): our own
mesh (left half, tip first, one chordwise panel; sheared along the EA for sweep, sections
streamwise: the planform is ours), checked unchanged by OAS; `fem_model_type "tube"` with
`fem_origin` at the EA, so the beam nodes sit on the EA and its elements run along it; a uniform
tube with E and G chosen so that OAS's own E Iy and G J equal our EI and GJ; aerodynamic loads only
(CL0 = CD0 = 0, no viscous or wave drag, no weight or fuel); the coupled group solved by
OpenMDAO's Newton (`solve_subsystems=True`, assembled direct solver), absolute tolerance 1e-7 at
alpha 2 deg (scaled with alpha) or 1e-8 relative. OAS's displacements are in global axes: its
rotation about the global y axis at the tip IS the streamwise twist (flexwing's `tip_twist`,
phi cos(sweep) - degrees(du/ds) sin(sweep); nose up > 0 on both halves); the twist about the EA
is that rotation vector projected on the left half's axis, sign flipped for the mirror. OAS's
linear divergence pressure: at alpha 0.001 deg the wing is linear, A(q) = L / L_rigid, and 1/A is
fitted by a parabola through q = 0.96, 0.98, 0.99 times flexwing's eigenvalue, its root refined
by points at 0.997 and 0.999 of it. OAS's rigid lift is one stiff (EI, GJ x 1e8) solve per alpha,
scaled by V^2 (exact for its incompressible lattice).

How to read the output: every `d` is OAS / flexwing - 1. (1)-(3) are the comparison; (4)-(5) say
where the differences come from; (7) is the torque-axis study; (8) the timing.

What it shows (N = 21; the comparison is deterministic, only the timings (8) depend on the
machine and its load; measured at commit 3e154f4 on 2 cores, twice: identical but for (8)):
- (1) The setups match: OAS keeps our mesh (<= 6e-17 m), its beam nodes lie on our EA (<= 5e-16
  m), and its E Iy, G J are ours.
- (4) Linear regime (alpha 0.001 deg): unswept, the two codes are the same discrete model: lift
  and twist agree to 3e-9 at every speed; only the tip heave differs (-0.16 to -0.20 %), because
  OAS lumps each panel's force half on each node (with the couple that keeps its moment) and
  integrates the beam exactly for those nodal loads, while flexwing integrates the beam with the
  panel forces at their own points by the trapezoidal rule. The two agree on twist and on the
  slope at the stations for every panel but the one inside the element, whose load enters the
  slope differently (flexwing: its whole moment at the inner station; OAS: half of it at each
  end). At sweep 0 the slope does not reach the flow, so only the heave shows it. Swept, the
  streamwise twist contains -du/ds sin(sweep), and the same O(h^2) slope difference reaches the
  lift (1.3e-4 to 1.5e-3) and the streamwise twist (1e-3 to 5.4e-3, the +35 deg tip twist being
  a small difference of two larger terms; about the EA 1.5e-4 to 1.8e-3). (4b) proves it is
  discretisation: every difference falls 3.9-4.2x per halving of the panel width (N = 11, 21,
  41), except the +35 deg heave difference, which crosses zero between the speeds of (4) and
  falls faster (4.8e-4, 3.5e-5, -5.5e-6).
- (2) Linear divergence pressure: 4e-5 unswept, +-5e-4 at +-20 deg (the same O(h^2) slope term),
  +1.3e-3 at +35 deg. The OAS fit resolves its root only to its last refinement's change (the
  "OAS fit change" column: 3e-2 Pa, 4e-5 of q_div, unswept, so that difference is the fit's; 8 Pa,
  3e-3, at +35 deg, where OAS's Newton is at its residual floor at 0.997-0.999 of q_div).
- (3) At alpha 2 deg at the 25 and 50 % points (L/L_rigid 1.1-1.5): lift within 0.2 % unswept
  and forward-swept, 0.5 % at +20 and 1 % at +35 deg; heave within 0.2 % (0.4 % at +20, 1 % at
  +35); streamwise twist within 0.7 % unswept, 0.5 % at -20, 1.8 % at +20 and 3-5 % at +35 deg
  (about the EA at +35: 1.6-2.8 %; the streamwise twist there is a small difference of two
  terms). At 75 %: lift within 0.6 %, heave 0.9 %, twist 1.8 %. At 90 % of the fold (L/L_rigid
  1.6-3) OAS is 2.0-3.4 % below in lift, 2.8-8.5 % in twist (8.5 % at +35 deg), 2.8-4.7 % in
  heave. Two second-order model differences, both invisible in the linear regime, explain it:
  (a) the lattices: flexwing's trailing legs (AeroSandbox's convention) leave the quarter chord
      along +x, OAS's follow the chord to the trailing edge and then the freestream. On a section
      twisted by t flexwing's collocation point lies c/2 sin t below its own legs; OAS's stays in
      their plane. (5): rigid wings twisted to flexwing's elastic twist at the 90 % point give
      OAS 1.0-1.3 % less lift than flexwing unswept and at -20 deg, 0.5 % at +20 and 0.1 % at +35
      (where the twist is small); flat jigs agree to 1-2.4e-4. Multiplied by the aeroelastic
      feedback (about L/L_rigid) this is about the whole 90 % lift difference at 0 and -20 deg
      (2.7 and 3.9 % against 2.9 and 3.2 %), half of it at +20 (1.1 of 2.0 %) and little of it
      at +35 deg (0.1 of 3.4 %), where (b) dominates.
  (b) the torque's heave lever: flexwing takes each panel force at its heaved point, so the
      in-plane force (Fx cos(sweep) - Fy sin(sweep)), which turns from forward (lift tilted by
      alpha) to aft (induced drag) as the loading grows, has a lever u_p (undeformed axis) or
      u_p - u_i (deformed axis) about the axis. OAS's linear beam carries nodal loads along the
      undeformed beam: a force's lever is its local arm from its own node only, so this term is
      absent. Adding it to OAS (`oas_wing._add_heave_lever`, a diagnostic) gives OAS a fold of
      its own (7b) and moves OAS toward flexwing near the fold when swept aft (7): at 0.95 of the
      fold, +35 deg, OAS's lift goes from 3.5 % to 0.9 % below flexwing's, and at 0.99 from 11 %
      to 3.5 %; unswept it changes little, and at -20 deg it moves OAS 1-2 % further below.
- (7) Folds: flexwing's branch (alpha 2 deg) folds at 0.81-0.88 of the linear divergence speed
  for -20 to +20 deg and at 0.59 of it at +35 deg; the deformed axis moves the fold up by only
  0.4-2.4 % (it removes the station's own heave u_i from the lever but keeps u_p - u_i). Plain
  OAS has no fold up to 1.2 x flexwing's (its lift just keeps growing, tip twist past 20-33 deg;
  4.6 deg at +35). OAS with the heave lever folds at +0.1 % (+35 deg, where the lattices agree)
  to +1.2 % (+20), +3.3 % (-20) and +4.1 % (0 deg; (a) is largest at 0 and -20) of flexwing's
  undeformed-axis fold. So flexwing's fold below the linear divergence speed is the heave
  lever's doing; OAS leaves that term out (a geometrically exact beam would keep only the part
  above the deflected tangent).
- (8) Per equilibrium from the jig, at load average 1.6-2.3 on 2 cores: flexwing median 2.9 ms
  (min 1.5 ms; compiled C, incl. stability), OAS with Newton median 0.58 s (min 0.32 s; 0.22 s
  problem setup): ~200x. At load 3-4 both are 2-2.5x slower (6.7 ms, 1.45 s), the ratio the same.
"""

from __future__ import annotations

import math
import os
import statistics
import sys
import time
import warnings

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import numpy as np

import solver

warnings.simplefilter("ignore")  # OAS's fuel-burn and cg outputs divide by our zero weights
np.seterr(all="ignore")

import openaerostruct  # noqa: E402
import openmdao  # noqa: E402
from oas_wing import OASWing  # noqa: E402
from openmdao.api import AnalysisError  # noqa: E402

SEMISPAN = 5.0  # [m]
CHORD = 1.0  # [m]
STATIONS = 21
ELASTIC_AXIS = 0.35  # fraction of chord from the leading edge
EI = 1.0e5  # [N m^2]
GJ = 3.0e3  # [N m^2]
ALPHA = 2.0  # [deg]
RHO = 1.225  # [kg/m^3]
SWEEPS = (-20.0, 0.0, 20.0, 35.0)  # [deg], + aft
FRACTIONS = (0.25, 0.5, 0.75, 0.9)  # q / q_fold of flexwing's undeformed-axis branch
TINY_ALPHA = 0.001  # [deg] the linear regime
STIFF = 1e8  # stiffness factor of the rigid reference wings
CONVERGENCE_STATIONS = (11, 21, 41)
CONVERGENCE_SWEEPS = (-20.0, 35.0)


def stations(n: int = STATIONS) -> np.ndarray:
    return np.linspace(0.0, SEMISPAN, n)


def fw_wing(sweep: float, n: int = STATIONS, stiff: float = 1.0, jig_twist=0.0) -> solver.Wing:
    return solver.Wing.create(
        stations(n),
        np.full(n, CHORD),
        ELASTIC_AXIS,
        EI * stiff,
        GJ * stiff,
        sweep=sweep,
        jig_twist=jig_twist,
    )


def oas_wing(sweep: float, n: int = STATIONS, stiff: float = 1.0, **kw) -> OASWing:
    return OASWing(
        stations(n), np.full(n, CHORD), ELASTIC_AXIS, EI * stiff, GJ * stiff, sweep, **kw
    )


def options(axis: str = "undeformed") -> solver.SolverOptions:
    return solver.SolverOptions(torque_axis=axis)


def velocity(q: float) -> float:
    return math.sqrt(2.0 * q / RHO)


def fw_solve(wing, v, alpha=ALPHA, axis="undeformed"):
    """(equilibrium or None beyond the fold, wall time [s])."""
    started = time.perf_counter()
    try:
        eq = solver.solve(wing, solver.FlightCondition(v, alpha, RHO), options=options(axis))
    except solver.NoEquilibrium:
        eq = None
    return eq, time.perf_counter() - started


def oas_try(model: OASWing, v, alpha=ALPHA, from_jig=True):
    """OAS's equilibrium, or None when its Newton fails (the state is then put back)."""
    saved = model.state()
    try:
        return model.solve(v, alpha, RHO, from_jig=from_jig)
    except (AnalysisError, RuntimeError, ArithmeticError, np.linalg.LinAlgError):
        # Newton gave up, or its matrix went singular or NaN (OpenMDAO's RuntimeError)
        model.restore(saved)
        return None


def _timer(what: str, since: float | None = None) -> float:
    """Progress on stderr: how long each part took."""
    now = time.perf_counter()
    if since is not None:
        print(f"  {what}: {now - since:.1f} s", file=sys.stderr, flush=True)
    return now


def rel(a: float, b: float) -> float:
    return a / b - 1.0


def table(title: str, header: list[str], rows: list[list[str]]) -> None:
    print(f"\n{title}\n")
    print("| " + " | ".join(header) + " |")
    print("| " + " | ".join("---" for _ in header) + " |")
    for row in rows:
        print("| " + " | ".join(row) + " |")
    sys.stdout.flush()


def oas_linear_divergence(model: OASWing, rigid_per_q: float, guess: float) -> tuple[float, float]:
    """(q_div [Pa], the last refinement's change [Pa]): 1/A(q) = 0 at alpha 0.001 deg."""

    def inverse_amplification(q: float) -> float:
        result = model.solve(velocity(q), TINY_ALPHA, RHO)
        return rigid_per_q * q / result.lift

    qs = [f * guess for f in (0.96, 0.98, 0.99)]
    values = [inverse_amplification(q) for q in qs]
    estimate, change = _parabola_root(qs, values, guess), math.inf
    for closer in (0.997, 0.999):  # refine until the root stops moving
        try:
            value = inverse_amplification(closer * estimate)
        except AnalysisError:  # OAS's residual floor this close to divergence
            break
        qs.append(closer * estimate)
        values.append(value)
        refined = _parabola_root(qs[-3:], values[-3:], estimate)
        estimate, change = refined, abs(refined - estimate)
        if change < 1e-6 * estimate:
            break
    return estimate, change


def _parabola_root(qs, values, near: float) -> float:
    roots = np.roots(np.polyfit(qs, values, 2))
    roots = roots[np.isreal(roots)].real
    return float(roots[np.argmin(np.abs(roots - near))])


def main() -> None:
    overall = time.perf_counter()
    print(
        f"flexwing vs OpenAeroStruct {openaerostruct.__version__} (OpenMDAO {openmdao.__version__})"
    )
    print(
        f"rectangular wing: semispan {SEMISPAN} m, chord {CHORD} m, N = {STATIONS}, EA at "
        f"{ELASTIC_AXIS:.0%} chord, EI = {EI:g}, GJ = {GJ:g} N m^2; alpha {ALPHA} deg, rho {RHO}"
    )
    # Load (or compile) flexwing's library for these mesh sizes before anything is timed.
    for n in sorted({STATIONS, *CONVERGENCE_STATIONS}):
        solver.warm_up(n, timeout=600)

    setup_rows, divergence_rows, main_rows, linear_rows = [], [], [], []
    frozen_rows, axis_rows, fold_rows = [], [], []
    fw_times, fw_first, oas_times, oas_setup = [], [], [], []
    for sweep in SWEEPS:
        wing = fw_wing(sweep)
        mark = _timer("")
        started = time.perf_counter()
        oas = oas_wing(sweep)
        oas_setup.append(time.perf_counter() - started)
        oas_rigid = oas_wing(sweep, stiff=STIFF)
        folds = {
            axis: solver.find_fold(wing, ALPHA, RHO, velocity_limit=150.0, options=options(axis))
            for axis in ("undeformed", "deformed")
        }
        q_fold = folds["undeformed"].dynamic_pressure
        v_fold = folds["undeformed"].velocity

        # OAS's rigid lift is exactly quadratic in V: one stiff solve per alpha gives it.
        rigid_per_q = {
            a: oas_rigid.solve(10.0, a, RHO).lift / (0.5 * RHO * 100.0) for a in (ALPHA, TINY_ALPHA)
        }

        # (1) the setup
        oas.solve(velocity(0.5 * q_fold), ALPHA, RHO)
        mesh_change, node_offset = oas.check_mesh()
        ei_oas, gj_oas = oas.stiffness()
        setup_rows.append(
            [
                f"{sweep:+.0f}",
                f"{mesh_change:.1e}",
                f"{node_offset:.1e}",
                f"{ei_oas:.6g}",
                f"{gj_oas:.6g}",
            ]
        )

        mark = _timer(f"{sweep:+.0f} setup", mark)
        # (2) linear divergence pressure
        q_fw = solver.linear_divergence_pressure(wing, options())
        q_oas, change = oas_linear_divergence(oas, rigid_per_q[TINY_ALPHA], q_fw)
        divergence_rows.append(
            [
                f"{sweep:+.0f}",
                f"{q_fw:.2f}",
                f"{q_oas:.2f}",
                f"{rel(q_oas, q_fw):+.1e}",
                f"{change:.0e}",
                f"{velocity(q_fw):.2f}",
                f"{v_fold:.2f}",
                f"{folds['deformed'].velocity:.2f}",
            ]
        )

        mark = _timer(f"{sweep:+.0f} divergence", mark)
        # (3) the comparison at 25-90 % of the fold, and (4) the same speeds at alpha 0.001 deg
        near = None
        for fraction in FRACTIONS:
            q = fraction * q_fold
            v = velocity(q)
            eq, seconds = fw_solve(wing, v)
            fw_first.append(seconds)  # the first solve of this wing at this speed
            eq, seconds = fw_solve(wing, v)
            fw_times.append(seconds)
            r = oas.solve(v, ALPHA, RHO)
            oas_times.append(r.seconds)
            t = eq.totals
            main_rows.append(
                [
                    f"{sweep:+.0f}",
                    f"{v:.2f}",
                    f"{q:.1f}",
                    f"{t.lift / t.rigid_lift:.4f}",
                    f"{r.lift:.2f}",
                    f"{t.lift:.2f}",
                    f"{rel(r.lift, t.lift):+.2%}",
                    f"{r.tip_heave:.5f}",
                    f"{t.tip_heave:.5f}",
                    f"{rel(r.tip_heave, t.tip_heave):+.2%}",
                    f"{r.tip_stream_twist:.4f}",
                    f"{t.tip_twist:.4f}",
                    f"{rel(r.tip_stream_twist, t.tip_twist):+.2%}",
                    f"{r.tip_axis_twist:.4f}",
                    f"{eq.stations.axis_twist[-1]:.4f}",
                ]
            )
            lin, _ = fw_solve(wing, v, TINY_ALPHA)
            rl = oas.solve(v, TINY_ALPHA, RHO)
            lt = lin.totals
            linear_rows.append(
                [
                    f"{sweep:+.0f}",
                    f"{q:.1f}",
                    f"{lt.lift / lt.rigid_lift:.4f}",
                    f"{rel(rl.lift, lt.lift):+.1e}",
                    f"{rel(rl.tip_heave, lt.tip_heave):+.1e}",
                    f"{rel(rl.tip_stream_twist, lt.tip_twist):+.1e}",
                    f"{rel(rl.tip_axis_twist, lin.stations.axis_twist[-1]):+.1e}",
                ]
            )
            near = (v, eq)

        mark = _timer(f"{sweep:+.0f} main and linear tables", mark)
        # (5) the lattices alone, at the elastic twist of the 90 % point (heave left out)
        v, eq = near
        twist = np.asarray(eq.stations.twist)
        fw_frozen, _ = fw_solve(fw_wing(sweep, stiff=STIFF, jig_twist=twist), v)
        oas_frozen = oas_wing(sweep, stiff=STIFF, jig_twist=twist).solve(v, ALPHA, RHO)
        flat = eq.totals.rigid_lift
        frozen_rows.append(
            [
                f"{sweep:+.0f}",
                f"{v:.2f}",
                f"{twist[-1]:.3f}",
                f"{rel(rigid_per_q[ALPHA] * 0.5 * RHO * v * v, flat):+.1e}",
                f"{oas_frozen.lift:.2f}",
                f"{fw_frozen.totals.rigid_lift:.2f}",
                f"{rel(oas_frozen.lift, fw_frozen.totals.rigid_lift):+.2%}",
                f"{rel(eq.totals.lift, fw_frozen.totals.rigid_lift):+.2%}",
            ]
        )

        # (7) torque axes near divergence: flexwing undeformed / deformed from the jig; OAS, and
        # OAS with the heave lever of flexwing's undeformed axis (oas_wing._add_heave_lever),
        # each continued in V from 90 % of the fold
        v_def = folds["deformed"].velocity
        speeds = [0.95 * v_fold, 0.99 * v_fold]
        if v_def > 1.002 * v_fold:
            speeds.append(0.5 * (v_fold + v_def))
        speeds += [1.05 * max(v_fold, v_def), 1.1 * v_fold, 1.2 * v_fold]
        mark = _timer(f"{sweep:+.0f} frozen lattices", mark)
        oas_path = _continue(oas, v_fold, speeds)
        mark = _timer(f"{sweep:+.0f} OAS continuation", mark)
        lever_path = _continue(oas_wing(sweep, heave_lever=True), v_fold, speeds)
        mark = _timer(f"{sweep:+.0f} OAS + lever continuation", mark)
        for v in speeds:
            cells = [f"{sweep:+.0f}", f"{v:.2f}", f"{v / v_fold:.3f}"]
            for axis in ("undeformed", "deformed"):
                eq, _ = fw_solve(wing, v, axis=axis)
                cells.append(
                    "no equilibrium"
                    if eq is None
                    else f"{eq.totals.lift:.0f} / {eq.totals.tip_twist:.2f}"
                )
            for path in (oas_path, lever_path):
                r = path["at"].get(v)
                cells.append("-" if r is None else f"{r.lift:.0f} / {r.tip_stream_twist:.2f}")
            axis_rows.append(cells)
        fold_rows.append(
            [
                f"{sweep:+.0f}",
                f"{v_fold:.3f}",
                f"{v_def:.3f}",
                _fold_text(lever_path),
                _fold_text(oas_path),
                f"{velocity(q_fw):.2f}",
                f"{velocity(q_oas):.2f}",
            ]
        )
        print(f"sweep {sweep:+.0f} done ({time.perf_counter() - overall:.0f} s)", flush=True)

    table(
        "(1) Setup: OAS leaves our mesh unchanged [m]; its beam nodes' distance from our EA [m]; "
        "its E Iy and G J [N m^2]",
        ["sweep [deg]", "mesh change", "nodes off EA", "E Iy", "G J"],
        setup_rows,
    )
    table(
        "(2) Linear divergence pressure [Pa]: flexwing's eigenvalue vs OAS's 1/A = 0 at alpha "
        "0.001 deg; V [m/s] of it, and of flexwing's folds at alpha 2 deg",
        [
            "sweep [deg]",
            "q_div flexwing",
            "q_div OAS",
            "d",
            "OAS fit change",
            "V_div",
            "fold V (undeformed axis)",
            "fold V (deformed axis)",
        ],
        divergence_rows,
    )
    table(
        "(3) alpha 2 deg, flexwing's default torque axis (undeformed): lift [N], tip heave [m], "
        "tip twist [deg] streamwise and about the EA",
        [
            "sweep",
            "V",
            "q",
            "L/L_rigid",
            "lift OAS",
            "lift fw",
            "d",
            "heave OAS",
            "heave fw",
            "d",
            "twist OAS",
            "twist fw",
            "d",
            "EA twist OAS",
            "EA twist fw",
        ],
        main_rows,
    )
    table(
        "(4) The same speeds at alpha 0.001 deg (both codes linear): OAS / flexwing - 1",
        ["sweep", "q", "L/L_rigid", "d lift", "d heave", "d twist", "d EA twist"],
        linear_rows,
    )
    convergence_rows = _convergence()
    table(
        "(4b) alpha 0.001 deg at 75 % of the N = 21 fold pressure, refined mesh: "
        "OAS / flexwing - 1",
        ["sweep", "N", "q", "d lift", "d heave", "d twist"],
        convergence_rows,
    )
    table(
        "(5) The lattices alone: rigid wings at alpha 2 deg, jig twisted to flexwing's elastic "
        "streamwise twist at the 90 % point (no heave); lift [N]",
        [
            "sweep",
            "V",
            "tip twist",
            "d flat jig",
            "OAS",
            "flexwing",
            "d twisted jig",
            "flexwing elastic / twisted jig - 1",
        ],
        frozen_rows,
    )
    table(
        "(7) Torque axes near divergence, lift [N] / tip streamwise twist [deg]; OAS and OAS + "
        "heave lever continued in V from 90 % of the fold ('-': their branch ended before)",
        [
            "sweep",
            "V",
            "V / fold",
            "flexwing undeformed",
            "flexwing deformed",
            "OAS",
            "OAS + heave lever",
        ],
        axis_rows,
    )
    table(
        "(7b) Where the branch from the jig ends [m/s] at alpha 2 deg",
        [
            "sweep",
            "flexwing fold, undeformed axis",
            "flexwing fold, deformed axis",
            "OAS + heave lever: last converged (first lost)",
            "OAS: last converged (first lost)",
            "V_div flexwing",
            "V_div OAS",
        ],
        fold_rows,
    )
    table(
        "(8) Wall time per equilibrium from the jig, same process, the (3) points [s]",
        ["code", "median", "min", "max", "problem setup"],
        [
            [
                "flexwing (compiled C, incl. the stability eigenproblem)",
                f"{statistics.median(fw_times):.4f}",
                f"{min(fw_times):.4f}",
                f"{max(fw_times):.4f}",
                f"first solve of each point: median {statistics.median(fw_first):.4f}",
            ],
            [
                "OAS 2.12, Newton",
                f"{statistics.median(oas_times):.3f}",
                f"{min(oas_times):.3f}",
                f"{max(oas_times):.3f}",
                f"{statistics.median(oas_setup):.2f}",
            ],
        ],
    )
    ratio = statistics.median(oas_times) / statistics.median(fw_times)
    print(f"\nOAS / flexwing, medians: {ratio:.0f}x; total {time.perf_counter() - overall:.0f} s")


def _continue(model: OASWing, v_fold: float, speeds: list[float], step: float = 0.05) -> dict:
    """OAS's branch followed in V from 0.9 v_fold by Newton from the previous equilibrium, in
    steps of at most `step` v_fold through `speeds`. A step that fails, or whose lift drops
    or whose tip twist jumps by more than 15 deg (Newton jumped off the branch: lift grows
    with V along it, continuously, up to a fold), ends the branch;
    three bisections then bracket its end. Returns {"at": {V: result}, "last": V, "failed": V
    or None}."""
    targets = sorted(set(speeds))
    grid = [0.9 * v_fold]
    for v in targets:
        while v - grid[-1] > step * v_fold * 1.0001:
            grid.append(grid[-1] + step * v_fold)
        grid.append(v)
    # plain OAS converges in 2-4 iterations from a neighbour; with the heave lever and sweep
    # its Jacobian misses two terms and it converges linearly
    model.newton.options["maxiter"] = 12 if model.newton.options["maxiter"] <= 30 else 20
    at, previous = {}, oas_try(model, grid[0])
    last, failed, state = grid[0], None, model.state()

    def advance(v):
        result = oas_try(model, v, from_jig=False)
        if (
            result is None
            or result.lift < previous.lift
            or abs(result.tip_stream_twist - previous.tip_stream_twist) > 15.0
        ):
            model.restore(state)
            return None
        return result

    for v in grid[1:]:
        result = advance(v)
        if result is None:
            failed = v
            break
        previous, last, state = result, v, model.state()
        if v in targets:
            at[v] = result
    if failed is not None:
        for _ in range(3):
            mid = 0.5 * (last + failed)
            result = advance(mid)
            if result is None:
                failed = mid
            else:
                previous, last, state = result, mid, model.state()
    return {"at": at, "last": last, "failed": failed}


def _fold_text(path: dict) -> str:
    if path["failed"] is None:
        return f"none up to {path['last']:.2f}"
    return f"{path['last']:.3f} ({path['failed']:.3f})"


def _convergence() -> list[list[str]]:
    rows = []
    for sweep in CONVERGENCE_SWEEPS:
        q = (
            0.75
            * solver.find_fold(fw_wing(sweep), ALPHA, RHO, velocity_limit=150.0).dynamic_pressure
        )
        v = velocity(q)
        for n in CONVERGENCE_STATIONS:
            eq, _ = fw_solve(fw_wing(sweep, n), v, TINY_ALPHA)
            r = oas_wing(sweep, n).solve(v, TINY_ALPHA, RHO)
            t = eq.totals
            rows.append(
                [
                    f"{sweep:+.0f}",
                    f"{n}",
                    f"{q:.1f}",
                    f"{rel(r.lift, t.lift):+.1e}",
                    f"{rel(r.tip_heave, t.tip_heave):+.1e}",
                    f"{rel(r.tip_stream_twist, t.tip_twist):+.1e}",
                ]
            )
    return rows


if __name__ == "__main__":
    main()
