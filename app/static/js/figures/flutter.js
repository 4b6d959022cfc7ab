// Flutter: the V-g and V-f diagrams of every mode, the flutter and divergence speeds marked,
// and the first modes' shapes in vacuum.

import { COLORS, colorOf, draw, fmt, line, points, record, speedAxisEnd } from "./chart.js";

/** The answer's aerodynamic_model, as the diagrams' titles name it. */
const SHORT = { strip_theory: "strip theory", quasi_3d_lattice: "quasi-3D lattice", unsteady_lattice: "unsteady lattice" };

/** V-g and V-f: every mode's damping ratio and frequency against airspeed, the flutter and
 * divergence speeds marked; and the first modes' shapes (heave, twist) along the span. */
export function drawFlutter(flutter, { shapes = 3, model } = {}) {
  // Issue 42: each diagram says which aerodynamic model gave it.
  const short = SHORT[flutter.aerodynamic_model] ?? flutter.aerodynamics;
  const by = short ? ` (${short})` : "";
  const solved = flutter.points.filter((p) => p.status === "solved" && p.damping);
  const V = solved.map((p) => p.velocity);
  const series = {};
  const vg = [];
  const vf = [];
  const modeCount = Math.max(flutter.modes.length, ...solved.map((p) => p.damping.length));
  for (let m = 0; m < modeCount; m++) {
    const label = `mode ${m + 1}`;
    const g = solved.map((p) => p.damping[m] ?? null);
    const w = solved.map((p) => p.frequency[m] ?? null);
    series[`damping_${m}`] = { label, x: V, y: g };
    series[`frequency_${m}`] = { label, x: V, y: w };
    vg.push(line(label, points(V, g), colorOf(m), { pointRadius: 2 }));
    vf.push(line(label, points(V, w), colorOf(m), { pointRadius: 2 }));
  }
  const vlines = [];
  const onset = flutter.flutter;
  if (onset) {
    vlines.push({ x: onset.velocity, label: `flutter ${fmt(onset.velocity, 2)} m/s (mode ${onset.mode + 1})`, color: COLORS.moment });
    const mark = { label: "flutter point", data: [{ x: onset.velocity, y: onset.frequency }], borderColor: COLORS.moment, backgroundColor: COLORS.moment, pointStyle: "crossRot", pointRadius: 8, borderWidth: 2 };
    vf.push(mark);
    vg.push({ ...mark, data: [{ x: onset.velocity, y: 0 }] });
  }
  const divergence = flutter.divergence;
  if (divergence) {
    vlines.push({ x: divergence.velocity, label: `divergence ${fmt(divergence.velocity, 2)} m/s${divergence.within_range ? "" : " (beyond the range)"}`, color: COLORS.fold, dash: [6, 4] });
  }
  const xmax = speedAxisEnd([...flutter.points.map((p) => p.velocity), ...vlines.map((l) => l.x)]);
  const speed = { min: 0, max: xmax };
  draw("chart-vg", {
    title: `V-g${by}: a mode flutters where its damping crosses zero`,
    datasets: vg,
    xTitle: "airspeed V [m/s]",
    yTitle: "damping ratio [-] (negative: grows)",
    x: speed,
    pointLegend: true,
    plugins: { annotations: { vlines, hlines: [{ y: 0, color: "#555" }] } },
  });
  draw("chart-vf", {
    title: `V-f${by}: the modes' frequencies coalesce toward flutter`,
    datasets: vf,
    xTitle: "airspeed V [m/s]",
    yTitle: "frequency ω [rad/s]",
    x: speed,
    y: { min: 0 },
    pointLegend: true,
    plugins: { annotations: { vlines, vlineLabels: false } },
  });
  const shown = flutter.modes.slice(0, shapes);
  const heave = shown.map((mode, m) => line(`mode ${m + 1}, ${fmt(mode.frequency, 1)} rad/s`, points(flutter.y, mode.heave), colorOf(m)));
  const twist = shown.map((mode, m) => line(`mode ${m + 1}`, points(flutter.y, mode.twist), colorOf(m), { borderDash: [6, 3] }));
  shown.forEach((mode, m) => {
    series[`shape_heave_${m}`] = { label: `mode ${m + 1}`, x: flutter.y, y: mode.heave };
    series[`shape_twist_${m}`] = { label: `mode ${m + 1}`, x: flutter.y, y: mode.twist };
  });
  draw("chart-mode-heave", {
    title: "Mode shapes in vacuum: heave (largest edge motion 1 m)",
    datasets: heave,
    xTitle: "spanwise position y [m]",
    yTitle: "heave [m]",
    x: { min: 0 },
    plugins: { annotations: { hlines: [{ y: 0 }] } },
  });
  draw("chart-mode-twist", {
    title: "Mode shapes in vacuum: twist, same scale",
    datasets: twist,
    xTitle: "spanwise position y [m]",
    yTitle: "twist [deg]",
    x: { min: 0 },
    legend: false,
    plugins: { annotations: { hlines: [{ y: 0 }] } },
  });
  record(
    "flutter",
    series,
    {
      status: flutter.status,
      flutter_velocity: onset?.velocity ?? null,
      flutter_frequency: onset?.frequency ?? null,
      flutter_mode: onset?.mode ?? null,
      divergence_velocity: divergence?.velocity ?? null,
    },
    { modes: modeCount, mode_frequencies: flutter.modes.map((m) => m.frequency), aerodynamic_model: flutter.aerodynamic_model ?? null, model: model ?? null },
  );
}
