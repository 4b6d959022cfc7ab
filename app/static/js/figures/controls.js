// Control effectiveness against airspeed: each control surface's elastic over rigid derivative,
// its reversal speed and the wing's divergence speeds marked.

import { COLORS, colorOf, draw, fmt, line, points, record, speedAxisEnd } from "./chart.js";

/** Each control surface's effectiveness (elastic over rigid derivative) against airspeed, its
 * linear reversal speed and the wing's symmetric and antisymmetric divergence speeds marked. */
export function drawControls(controls) {
  const solved = controls.points.filter((p) => p.status === "equilibrium");
  const names = controls.reversals.map((r) => r.name);
  const series = {};
  const datasets = [];
  const vlines = [];
  const marks = { reversal: {}, crossing: {}, first: {} };
  controls.reversals.forEach((summary, i) => {
    const color = colorOf(i);
    const at = solved.map((p) => p.controls.find((c) => c.name === summary.name));
    const V = solved.map((p) => p.velocity);
    const E = at.map((c) => c?.effectiveness ?? null);
    const label = summary.name === summary.kind ? summary.name : `${summary.name} (${summary.kind})`;
    series[`effectiveness_${summary.name}`] = { label, x: V, y: E };
    datasets.push(line(label, points(V, E), color, { pointRadius: 3, pointStyle: "circle" }));
    marks.reversal[summary.name] = summary.reversal.velocity;
    marks.crossing[summary.name] = summary.crossing?.velocity ?? null;
    marks.first[summary.name] = summary.first;
    if (summary.reversal.velocity != null) {
      vlines.push({ x: summary.reversal.velocity, label: `${summary.name} reversal ${fmt(summary.reversal.velocity, 2)} m/s`, color, dash: [6, 4] });
    }
  });
  const symmetric = controls.symmetric_divergence.velocity;
  const antisymmetric = controls.antisymmetric_divergence.velocity;
  if (symmetric != null) vlines.push({ x: symmetric, label: `divergence ${fmt(symmetric, 2)} m/s`, color: COLORS.fold });
  if (antisymmetric != null && names.length && controls.reversals.some((r) => r.kind === "aileron")) {
    vlines.push({ x: antisymmetric, label: `antisymmetric divergence ${fmt(antisymmetric, 2)} m/s`, color: COLORS.fold, dash: [2, 3] });
  }
  marks.symmetric_divergence = symmetric;
  marks.antisymmetric_divergence = antisymmetric;
  const xmax = speedAxisEnd([...controls.points.map((p) => p.velocity), ...vlines.map((l) => l.x)]);
  draw("chart-effectiveness", {
    title: "Control effectiveness falls to zero at reversal",
    datasets,
    xTitle: "airspeed V [m/s]",
    yTitle: "effectiveness: elastic / rigid derivative [-]",
    x: { min: 0, max: xmax },
    // From 0 (reversal) up, with headroom above 1 for the speeds' labels (one row each).
    y: { suggestedMin: 0, suggestedMax: 1 + 0.13 * (vlines.length + 1) },
    pointLegend: true,
    plugins: { annotations: { vlines, hlines: [{ y: 0 }, { y: 1, color: "#e0e0e0" }] } },
  });
  record("controls", series, marks, { surfaces: names });
}
