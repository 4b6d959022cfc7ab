"""Control-surface references with AeroSandbox 4.2.10: flaps, ailerons, roll and reversal.

DEV-ONLY, like generate_reference.py (its sibling, which it builds on); run it with an
environment that has aerosandbox==4.2.10:

    /work/peers-venv/bin/python tests/reference/generate_controls_reference.py CASE.json OUT.json

AeroSandbox's vortex lattice ignores WingXSec control surfaces (AeroSandbox issues #86, #134),
so a surface is given to it as what flexwing models it as: each section's camber line, the
flap's chord line turned about the hinge and sampled at the lattice's chordwise nodes,
-(x/c - hinge) tan(deflection) aft of the hinge, times the share of the station's tributary span
the surface covers (solver/controls.py states the rule; it is written again here,
independently). Each section gets an airfoil of zero thickness whose upper and lower surfaces
are that camber line through the nodes, so that `Airfoil.local_camber` returns it exactly there.

Two kinds of case (JSON objects):

- "flap" (the key "surfaces" with flaps only, no "full_span"): the symmetric problem, exactly
  generate_reference.py's extended formulation (symmetric=True, trim allowed) with an airfoil
  per section. Output: its extended-1 format, plus "section_camber" (N, k + 1): what
  AeroSandbox placed at each section's nodes.
- "full_span": true: both halves as one unsymmetric wing (symmetric=False, sections from the
  left tip to the right tip), a cantilever beam per half clamped at the root (u = u' = theta =
  0 there, the root section shared), twist nose-up on both halves (a rotation about +y), the
  left half's beam along s = -y. Ailerons deflect the left section's trailing edge up. A roll
  rate p (flexwing's sign: about +x aft, raising the right wing) is AeroSandbox's
  OperatingPoint p = -p (body axes, x forward). Unswept only.
  Keys: the wing's (span, chords, x_ea_over_chord, EI, GJ, airfoil must be symmetric: its
  camber is not used), chordwise_resolution, alpha_deg, velocities, ipopt_tol, surfaces
  (name, start, end as fractions of the semispan, hinge, deflection, kind), and optionally
      roll_rate          [rad/s] p, steady (default 0)
      free_roll          true: p is a variable and the rolling moment is held at zero
      deflection_scales  [...]: solve each velocity at the ailerons' deflections times each
                         scale (e.g. [-2, -1, 0, 1, 2]): the antisymmetric part and the
                         nonlinear coupling of a full-span wing at alpha != 0
      reversal           {"scales": [1, 2], "bracket": [V0, V1]}: the linear reversal speed, the
                         root of D(V) = lim R(delta)/delta found by secant iterations on V, D
                         by Richardson's extrapolation of R/delta over the two scales (R odd
                         in delta at alpha 0: the error is O(delta^4))
  Output ("format": "full-span-1"): case, rho, ys, section_camber {right, left} (N, k + 1),
  equilibria[] {velocity, scale, roll_rate, iterations, inf_pr, solve_s, rolling_moment [N m]
  (sum over every panel of its moment about x through the root: y Fz - z Fy), L [N],
  right/left {u, theta_deg, du, strip_Fz, strip_tau (N - 1), S, M, T (N)}}, rigid[] {velocity,
  scale, rolling_moment} (the jig at the same deflections and rate), reversal {velocity,
  dynamic_pressure, iterations[] {velocity, derivative [N m / deg]}}.
"""

from __future__ import annotations

import json
import math
import sys
import time
from pathlib import Path

import aerosandbox as asb
import aerosandbox.numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

import generate_reference as base

# ------------------------------------------------------------------------ the surfaces' camber


def _nodes(k: int) -> np.ndarray:
    """The lattice's chordwise nodes as AeroSandbox's VLM places them."""
    return np.cosspace(0, 1, k + 1)


def _tributary_weights(ys: np.ndarray, start: float, end: float) -> np.ndarray:
    """Share of each station's span, midpoint to midpoint (root and tip: to the ends), covered
    by [start, end] [m]."""
    n = len(ys)
    weights = np.zeros(n)
    for i in range(n):
        low = ys[0] if i == 0 else 0.5 * (ys[i - 1] + ys[i])
        high = ys[-1] if i == n - 1 else 0.5 * (ys[i] + ys[i + 1])
        weights[i] = max(0.0, min(high, end) - max(low, start)) / (high - low)
    return weights


def section_camber(case: dict, ys: np.ndarray, side: int) -> np.ndarray:
    """(N, k + 1) camber / chord at the nodes of each station of the right (side +1) or left
    (-1) half: ailerons turn the other way on the left."""
    k = int(case.get("chordwise_resolution", 1))
    x = _nodes(k)
    semispan = ys[-1]
    camber = np.zeros((len(ys), k + 1))
    for surface in case.get("surfaces", []):
        sign = 1.0 if surface.get("kind", "flap") == "flap" else float(side)
        start, end = surface["start"] * semispan, surface["end"] * semispan
        shape = -np.maximum(x - surface["hinge"], 0.0) * math.tan(
            math.radians(sign * surface["deflection"])
        )
        camber += np.outer(_tributary_weights(ys, start, end), shape)
    return camber


def camber_airfoil(camber: np.ndarray, k: int) -> asb.Airfoil:
    """A zero-thickness airfoil whose mean line passes through `camber` at the k + 1 nodes:
    upper and lower surfaces both the piecewise-linear line, so local_camber is exact there."""
    x = np.array(_nodes(k), dtype=float)
    upper = np.stack([x[::-1], camber[::-1]], axis=1)  # trailing edge to leading edge
    lower = np.stack([x[1:], camber[1:]], axis=1)  # leading edge (shared) to trailing edge
    return asb.Airfoil(name="camber line", coordinates=np.concatenate([upper, lower]))


class SectionAirfoils(base.WingModel):
    """generate_reference's wing with an airfoil per section (the flaps' camber lines)."""

    def __init__(self, case: dict):
        super().__init__(case)
        self.section_camber = section_camber(case, self.ys, +1)
        self.section_airfoils = [camber_airfoil(c, self.nc) for c in self.section_camber]

    def make_wing(self, heave=None, twist=None) -> asb.Wing:
        wing = super().make_wing(heave, twist)
        for xsec, airfoil in zip(wing.xsecs, self.section_airfoils, strict=True):
            xsec.airfoil = airfoil
        return wing


# ------------------------------------------------------------------------- the full-span wing


class FullSpan:
    """Both halves as one unsymmetric wing, a clamped beam per half."""

    def __init__(self, case: dict):
        self.case = case
        self.chords = np.array(case["chords"], dtype=float)
        self.N = N = len(self.chords)
        self.ys = np.linspace(0, float(case["span"]) / 2, N)
        self.x_ea = float(case["x_ea_over_chord"])
        self.EI = np.array(case["EI"], dtype=float)
        self.GJ = np.array(case["GJ"], dtype=float)
        self.nc = int(case.get("chordwise_resolution", 1))
        self.alpha = float(case["alpha_deg"])
        if case.get("sweep_deg", 0.0) != 0.0:
            raise ValueError("full-span cases are unswept")
        self.outboard = (np.arange(N - 1)[None, :] >= np.arange(N)[:, None]).astype(float)

    def cambers(self, scale: float) -> tuple[np.ndarray, np.ndarray]:
        """Right and left section camber with the ailerons' deflections times `scale`."""
        case = dict(self.case)
        case["surfaces"] = [
            dict(s, deflection=s["deflection"] * (scale if s.get("kind") == "aileron" else 1.0))
            for s in self.case.get("surfaces", [])
        ]
        right, left = section_camber(case, self.ys, +1), section_camber(case, self.ys, -1)
        if np.any(right[0] != left[0]):
            raise ValueError("a surface at the root would need two sections at y = 0")
        return right, left

    def make_wing(self, u_r, th_r, u_l, th_l, right, left) -> asb.Wing:
        N, k = self.N, self.nc
        xsecs = []
        order = [("left", i) for i in range(N - 1, 0, -1)] + [("right", i) for i in range(N)]
        for side, i in order:
            y = self.ys[i] if side == "right" else -self.ys[i]
            u, theta = (u_r[i], th_r[i]) if side == "right" else (u_l[i], th_l[i])
            camber = right[i] if side == "right" else left[i]
            xyz_le = np.array([-self.chords[i] * self.x_ea, y, 0])
            xyz_le = np.rotation_matrix_3D(angle=np.radians(theta), axis="y") @ xyz_le
            xyz_le += np.array([0, 0, u])
            xsecs.append(
                asb.WingXSec(
                    xyz_le=xyz_le,
                    chord=self.chords[i],
                    twist=theta,
                    airfoil=camber_airfoil(camber, k),
                )
            )
        return asb.Wing(symmetric=False, xsecs=xsecs)

    def make_vlm(self, wing, velocity, roll_rate) -> asb.VortexLatticeMethod:
        return asb.VortexLatticeMethod(
            airplane=asb.Airplane(wings=[wing], xyz_ref=[0, 0, 0]),
            op_point=asb.OperatingPoint(velocity=velocity, alpha=self.alpha, p=-roll_rate),
            spanwise_resolution=1,
            chordwise_resolution=self.nc,
        )

    def halves(self, vlm):
        """Per half, root to tip: per-strip Fz, tau (moment about +y, nose-up on both halves),
        and the panels' spanwise arms s (|y|), as (N - 1, k) arrays of expressions."""
        N, k = self.N, self.nc

        def strips(index):
            sl = slice(index * k, (index + 1) * k)
            return (
                vlm.forces_geometry[sl, 2],
                vlm.moments_geometry[sl, 1],
                vlm.vortex_centers[sl, 1],
            )

        right = [strips(N - 1 + i) for i in range(N - 1)]
        left = [strips(N - 2 - i) for i in range(N - 1)]
        return right, left

    def loads(self, half, sign: float):
        """S, M, T at the stations of one half (sign +1 right, -1 left: s = sign * y)."""
        fz = np.concatenate([h[0] for h in half])
        tau = np.concatenate([h[1] for h in half])
        s = sign * np.concatenate([h[2] for h in half])
        outboard = (
            (np.arange((self.N - 1) * self.nc) // self.nc)[None, :] >= np.arange(self.N)[:, None]
        ).astype(float)
        S = outboard @ fz
        M = outboard @ (fz * s) - self.ys * S
        T = outboard @ tau
        return S, M, T, fz, tau


def _strip_sums(values, n_strips: int, k: int) -> list[float]:
    values = np.asarray(values, dtype=float).ravel()
    return [float(v) for v in values.reshape(n_strips, k).sum(axis=1)]


class FullSpanProblem:
    """The coupled full-span problem at one aileron scale: an Opti with the velocity (and,
    steady, the roll rate) as parameters, or the roll rate as a variable (free roll)."""

    def __init__(self, model: FullSpan, scale: float, free_roll: bool, options):
        self.model, self.scale, self.options = model, scale, options
        N = model.N
        opti = asb.Opti()
        self.opti = opti
        self.u_r = opti.variable(init_guess=np.zeros(N))
        self.th_r = opti.variable(init_guess=np.zeros(N))
        self.u_l = opti.variable(init_guess=np.zeros(N))
        self.th_l = opti.variable(init_guess=np.zeros(N))
        self.velocity = opti.parameter(value=10.0)
        if free_roll:
            self.roll_rate = opti.variable(init_guess=0.0)
        else:
            self.roll_rate = opti.parameter(value=0.0)
        right, left = model.cambers(scale)
        self.camber = (right, left)
        wing = model.make_wing(self.u_r, self.th_r, self.u_l, self.th_l, right, left)
        vlm = model.make_vlm(wing, self.velocity, self.roll_rate)
        self.aero = vlm.run()
        self.free = free_roll
        half_r, half_l = model.halves(vlm)
        S_r, M_r, T_r, fz_r, tau_r = model.loads(half_r, +1.0)
        S_l, M_l, T_l, fz_l, tau_l = model.loads(half_l, -1.0)
        self.du_r = opti.derivative_of(
            self.u_r, with_respect_to=model.ys, derivative_init_guess=np.zeros(N)
        )
        self.du_l = opti.derivative_of(
            self.u_l, with_respect_to=model.ys, derivative_init_guess=np.zeros(N)
        )
        for du, th, M, T in ((self.du_r, self.th_r, M_r, T_r), (self.du_l, self.th_l, M_l, T_l)):
            opti.constrain_derivative(
                variable=du, with_respect_to=model.ys, derivative=M / model.EI
            )
            opti.constrain_derivative(
                variable=th, with_respect_to=model.ys, derivative=np.degrees(T / model.GJ)
            )
        opti.subject_to(
            [
                self.u_r[0] == 0,
                self.du_r[0] == 0,
                self.th_r[0] == 0,
                self.u_l[0] == 0,
                self.du_l[0] == 0,
                self.th_l[0] == 0,
            ]
        )
        self.rolling_moment = np.sum(vlm.moments_geometry[:, 0])
        if free_roll:
            opti.subject_to(self.rolling_moment / 100 == 0)
        self.outputs = {
            "right": (self.u_r, self.th_r, self.du_r, fz_r, tau_r, S_r, M_r, T_r),
            "left": (self.u_l, self.th_l, self.du_l, fz_l, tau_l, S_l, M_l, T_l),
        }
        self.last = None

    def solve(self, velocity: float, roll_rate: float = 0.0) -> dict:
        opti = self.opti
        if self.last is not None:
            opti.set_initial_from_sol(self.last)
        mapping = {self.velocity: float(velocity)}
        if not self.free:
            mapping[self.roll_rate] = float(roll_rate)
        started = time.perf_counter()
        sol = opti.solve(parameter_mapping=mapping, verbose=False, options=self.options)
        self.last = sol
        out = {
            "velocity": velocity,
            "scale": self.scale,
            "roll_rate": float(sol(self.roll_rate)),
            "iterations": int(sol.stats()["iter_count"]),
            "inf_pr": base._final_inf_pr(sol),
            "solve_s": time.perf_counter() - started,
            "rolling_moment": float(sol(self.rolling_moment)),
            "L": float(sol(self.aero["L"])),
        }
        N, k = self.model.N, self.model.nc
        for side, (u, th, du, fz, tau, S, M, T) in self.outputs.items():
            out[side] = {
                "u": base._floats(sol(u)),
                "theta_deg": base._floats(sol(th)),
                "du": base._floats(sol(du)),
                "strip_Fz": _strip_sums(sol(fz), N - 1, k),
                "strip_tau": _strip_sums(sol(tau), N - 1, k),
                "S": base._floats(sol(S)),
                "M": base._floats(sol(M)),
                "T": base._floats(sol(T)),
            }
        print(
            f"V = {velocity:g} m/s, scale {self.scale:g}: rolling moment "
            f"{out['rolling_moment']:.8g} N m, p = {out['roll_rate']:.6g} rad/s "
            f"({out['iterations']} iterations, {out['solve_s']:.1f} s)",
            file=sys.stderr,
        )
        return out


def _rigid_rolling_moment(
    model: FullSpan, scale: float, velocity: float, roll_rate: float
) -> float:
    N = model.N
    right, left = model.cambers(scale)
    zeros = np.zeros(N)
    wing = model.make_wing(zeros, zeros, zeros, zeros, right, left)
    vlm = model.make_vlm(wing, float(velocity), float(roll_rate))
    vlm.run()
    vc = np.asarray(vlm.vortex_centers, dtype=float)
    k = model.nc
    strips = vc[:, 1].reshape(2 * (N - 1), k).mean(axis=1)
    chordwise = np.diff(vc[:, 0].reshape(2 * (N - 1), k), axis=1)
    if not (np.all(np.diff(strips) > 0) and np.all(chordwise > 0)):
        raise RuntimeError(
            "unexpected panel order: strips from the left tip to the right, leading to trailing "
            "edge within each"
        )
    return float(np.sum(vlm.moments_geometry[:, 0]))


def _reversal(model: FullSpan, spec: dict, options) -> dict:
    """The root of D(V), D the Richardson-extrapolated rolling moment per degree."""
    low, high = (float(v) for v in spec["bracket"])
    s1, s2 = (float(s) for s in spec.get("scales", [1.0, 2.0]))
    deflection = max(
        abs(s["deflection"]) for s in model.case["surfaces"] if s.get("kind") == "aileron"
    )
    problems = [FullSpanProblem(model, s, False, options) for s in (s1, s2)]
    history = []

    def derivative(velocity: float) -> float:
        r1, r2 = (p.solve(velocity)["rolling_moment"] for p in problems)
        d1, d2 = r1 / (s1 * deflection), r2 / (s2 * deflection)
        # R odd in the deflection: R / delta = D + c delta^2 + O(delta^4).
        value = (s2**2 * d1 - s1**2 * d2) / (s2**2 - s1**2)
        history.append({"velocity": velocity, "derivative": value})
        return value

    v0, v1 = low, high
    f0, f1 = derivative(v0), derivative(v1)
    for _ in range(30):
        if abs(v1 - v0) <= 1e-11 * v1:
            break
        v0, v1, f0 = v1, v1 - f1 * (v1 - v0) / (f1 - f0), f1
        f1 = derivative(v1)
    return {"velocity": v1, "dynamic_pressure": 0.5 * _density() * v1**2, "iterations": history}


def _density() -> float:
    """[kg/m^3] AeroSandbox's sea-level ISA density (what every case flies in)."""
    return float(asb.OperatingPoint(velocity=10.0).atmosphere.density())


def generate_full_span(case: dict) -> dict:
    model = FullSpan(case)
    options = base._ipopt_options(case)
    free = bool(case.get("free_roll", False))
    rate = float(case.get("roll_rate", 0.0))
    scales = [float(s) for s in case.get("deflection_scales", [1.0])]
    equilibria, rigid = [], []
    for scale in scales:
        problem = FullSpanProblem(model, scale, free, options)
        for velocity in case["velocities"]:
            point = problem.solve(velocity, rate)
            equilibria.append(point)
            rigid.append(
                {
                    "velocity": velocity,
                    "scale": scale,
                    "rolling_moment": _rigid_rolling_moment(
                        model, scale, velocity, point["roll_rate"]
                    ),
                }
            )
    right, left = model.cambers(1.0)
    out = {
        "case": case,
        "format": "full-span-1",
        "rho": _density(),
        "ys": base._floats(model.ys),
        "section_camber": {"right": base._rows(right), "left": base._rows(left)},
        "equilibria": equilibria,
        "rigid": rigid,
    }
    if "reversal" in case:
        out["reversal"] = _reversal(model, case["reversal"], options)
    return out


def generate_flap(case: dict) -> dict:
    out = base.generate(case, model_class=SectionAirfoils)
    model = SectionAirfoils(case)
    wing = model.make_wing()
    x = _nodes(model.nc)
    out["section_camber"] = base._rows(
        [np.asarray(xsec.airfoil.local_camber(x_over_c=x), dtype=float) for xsec in wing.xsecs]
    )
    return out


def main(argv: list[str]) -> int:
    if len(argv) != 3:
        print(f"usage: {argv[0]} CASE.json OUT.json", file=sys.stderr)
        return 2
    case = json.loads(Path(argv[1]).read_text())
    reference = generate_full_span(case) if case.get("full_span") else generate_flap(case)
    Path(argv[2]).write_text(json.dumps(reference, indent=1) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
