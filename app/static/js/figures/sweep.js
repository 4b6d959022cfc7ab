// Figure 14.4: approaching torsional divergence: tip twist and the study's lift amplification
// against airspeed, its fitted 1/A law, and the fold, linear and fitted divergence speeds.

import { COLORS, draw, fmt, line, points, record } from "./chart.js";

/** What the sweep's amplification A is, by the fit's `amplification` kind. */
export const AMPLIFICATION_WORDS = {
  CL: "CL / CL_rigid, CL on the deformed area as the study computes it",
  lift: "L / L_rigid",
  lift_effectiveness: "the trimmed wing's lift effectiveness, its lift-curve slope over the rigid wing's",
};

/** The study's amplification A of a sweep point, as the fit defines it (fit.amplification). */
export function amplification(equilibrium, kind) {
  const { totals } = equilibrium;
  if (kind === "lift_effectiveness") return totals.lift_effectiveness ?? null;
  if (!totals.rigid_lift) return null;
  const ratio = totals.lift / totals.rigid_lift;
  return kind === "CL" ? (ratio * totals.reference_area) / totals.deformed_area : ratio;
}

/** Tip twist and lift amplification against airspeed, the fitted 1/A law, and the speeds. */
export function drawSweep(sweep) {
  const { fit, linear, fold } = sweep.divergence;
  const solved = sweep.points.filter((p) => p.status === "equilibrium");
  const failed = sweep.points.filter((p) => p.status !== "equilibrium");
  const kind = fit.amplification;
  const V = solved.map((p) => p.velocity);
  const twist = solved.map((p) => p.equilibrium.totals.tip_twist);
  const A = solved.map((p) => amplification(p.equilibrium, kind));
  const series = {
    tip_twist: { label: "tip twist", x: V, y: twist },
    amplification: { label: "coupled model", x: V, y: A },
    no_equilibrium: { label: "no equilibrium", x: failed.map((p) => p.velocity), y: failed.map(() => 0) },
  };
  const marks = {
    fold_kind: fold.kind ?? "fold",
    fold_velocity: fold.velocity,
    linear_velocity: linear.velocity,
    fit_velocity: fit.velocity,
    fit_slope: fit.slope,
    fit_intercept: fit.intercept,
  };
  const vlines = [];
  const trimmedLimit = fold.kind === "trimmed_stability_limit";
  if (fold.velocity != null) {
    const label = trimmedLimit
      ? `trimmed divergence ${fmt(fold.velocity, 2)} m/s: unstable beyond`
      : `fold ${fmt(fold.velocity, 2)} m/s: equilibria end`;
    vlines.push({ x: fold.velocity, label, color: COLORS.fold });
  }
  if (linear.velocity != null) vlines.push({ x: linear.velocity, label: `linear divergence ${fmt(linear.velocity, 2)} m/s`, color: COLORS.linear, dash: [6, 4] });
  if (fit.velocity != null) vlines.push({ x: fit.velocity, label: `fit: V_div ${fmt(fit.velocity, 2)} m/s`, color: COLORS.fit, dash: [2, 3] });
  const regions = fold.velocity != null ? [{ from: fold.velocity, to: 1e9, color: "rgba(216, 67, 21, 0.07)" }] : [];
  const xmax = 5 * Math.ceil((1.03 * Math.max(...sweep.points.map((p) => p.velocity), ...vlines.map((l) => l.x))) / 5);
  const ampSets = [];
  if (fit.slope != null && fit.intercept != null && fit.velocity != null && fit.dynamic_pressure != null) {
    // The study draws the fit from 0 to 92 % of its divergence speed.
    const fitV = Array.from({ length: 300 }, (_, i) => (0.92 * fit.velocity * i) / 299);
    // The fit is in q; its divergence point gives the sweep's density (an altitude's too).
    const density = (2 * fit.dynamic_pressure) / (fit.velocity * fit.velocity);
    const fitA = fitV.map((v) => 1 / (fit.intercept + fit.slope * 0.5 * density * v * v));
    series.amplification_fit = { label: "A = 1/(1 - q/q_div)", x: fitV, y: fitA };
    ampSets.push(line("fit: A = 1/(intercept + slope q)", points(fitV, fitA), COLORS.fit, { borderDash: [6, 4], borderWidth: 1.5, pointStyle: "line" }));
  }
  ampSets.push(line("coupled model", points(V, A), COLORS.flexible, { showLine: false, pointRadius: 4, pointStyle: "circle" }));
  const noEq = { label: "no equilibrium", data: points(series.no_equilibrium.x, series.no_equilibrium.y), borderColor: COLORS.fold, backgroundColor: COLORS.fold, pointStyle: "crossRot", pointRadius: 7, borderWidth: 2 };
  if (failed.length) ampSets.push(noEq);
  const speed = { min: 0, max: xmax };
  draw("chart-tiptwist", {
    title: "Twist runs away as airspeed rises",
    datasets: [line("tip twist", points(V, twist), COLORS.flexible, { pointRadius: 4 }), ...(failed.length ? [{ ...noEq, data: points(series.no_equilibrium.x, series.no_equilibrium.y) }] : [])],
    xTitle: "airspeed V [m/s]",
    yTitle: "tip twist [deg]",
    x: speed,
    legend: failed.length > 0,
    pointLegend: true,
    plugins: { annotations: { vlines, regions, vlineLabels: false } },
  });
  draw("chart-amp", {
    title: kind === "lift_effectiveness" ? "Lift effectiveness follows the divergence law" : "Lift amplification follows the divergence law",
    datasets: ampSets,
    xTitle: "airspeed V [m/s]",
    yTitle: { CL: "amplification CL / CL_rigid [-]", lift_effectiveness: "lift effectiveness [-]" }[kind] ?? "amplification L / L_rigid [-]",
    x: speed,
    y: { min: 0 },
    pointLegend: true,
    plugins: { annotations: { vlines, regions } },
  });
  const onsets = (sweep.validity ?? []).map((o) => ({ code: o.code, velocity: o.velocity }));
  record("14.4", series, marks, { amplification: kind, points_used: fit.points_used, onsets });
}
