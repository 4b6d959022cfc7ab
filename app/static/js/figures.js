// The design study's figures 14.2-14.5, drawn with Chart.js (vendored, loaded before this module
// as window.Chart). Every figure records what it drew in `registry` (series as x/y arrays, marked
// values), which the page exposes as window.__flexwing.figures for tests and for the curious.

import { sections, surfaceOutlines, wireframe } from "./geometry.js";

const { Chart } = window;
if (!Chart) throw new Error("Chart.js did not load (static/vendor/chart.js-*/chart.umd.min.js)");

export const COLORS = {
  flexible: "#1565c0",
  rigid: "#8a8a8a",
  moment: "#c62828",
  torque: "#6a1b9a",
  fold: "#d84315",
  linear: "#2e7d32",
  fit: "#5f6368",
  zero: "#b0b0b0",
  beyond: "#e65100",
  surface: "#ef6c00",
  vonMises: "#c62828",
  bending: "#1565c0",
  allowable: "#2e7d32",
};

/** What the sweep's amplification A is, by the fit's `amplification` kind. */
export const AMPLIFICATION_WORDS = {
  CL: "CL / CL_rigid, CL on the deformed area as the study computes it",
  lift: "L / L_rigid",
  lift_effectiveness: "the trimmed wing's lift effectiveness, its lift-curve slope over the rigid wing's",
};

/** What each code of a response's `validity` is called on the page (the API documents them). */
export const FINDING_TITLES = {
  large_deflection: "Large deflection",
  large_twist: "Large twist",
  section_stall: "Sections past stall",
  near_divergence: "Near divergence",
};

Chart.defaults.animation = false;
Chart.defaults.responsive = true;
Chart.defaults.maintainAspectRatio = false;
Chart.defaults.font.family = "system-ui, -apple-system, 'Segoe UI', Roboto, 'Helvetica Neue', Arial, sans-serif";
Chart.defaults.color = "#333";
Chart.defaults.plugins.legend.labels.boxHeight = 2;

/** What each figure drew: {state, series: {key: {label, x, y}}, marks: {key: value}}. */
export const registry = {};
const charts = new Map();

// ------------------------------------------------------------------------------ chart plugins

// Vertical lines (a speed marked on an airspeed axis), horizontal lines, shaded x-ranges and text
// labels at data coordinates: options.plugins.annotations = {vlines, hlines, regions, labels}.
const annotations = {
  id: "annotations",
  beforeDatasetsDraw(chart, _args, opts) {
    const { ctx, chartArea: area, scales } = chart;
    for (const region of opts.regions ?? []) {
      const left = Math.max(area.left, scales.x.getPixelForValue(region.from));
      const right = Math.min(area.right, scales.x.getPixelForValue(region.to));
      if (right <= left) continue;
      ctx.save();
      ctx.fillStyle = region.color;
      ctx.fillRect(left, area.top, right - left, area.bottom - area.top);
      ctx.restore();
    }
    for (const line of opts.hlines ?? []) {
      const py = scales.y.getPixelForValue(line.y);
      if (py < area.top || py > area.bottom) continue;
      ctx.save();
      ctx.strokeStyle = line.color ?? COLORS.zero;
      ctx.lineWidth = 1;
      ctx.beginPath();
      ctx.moveTo(area.left, py);
      ctx.lineTo(area.right, py);
      ctx.stroke();
      ctx.restore();
    }
  },
  afterDatasetsDraw(chart, _args, opts) {
    const { ctx, chartArea: area, scales } = chart;
    (opts.vlines ?? []).forEach((line, row) => {
      const px = scales.x.getPixelForValue(line.x);
      if (!(px >= area.left - 0.5 && px <= area.right + 0.5)) return;
      ctx.save();
      ctx.strokeStyle = line.color;
      ctx.lineWidth = 1.5;
      ctx.setLineDash(line.dash ?? []);
      ctx.beginPath();
      ctx.moveTo(px, area.top);
      ctx.lineTo(px, area.bottom);
      ctx.stroke();
      ctx.setLineDash([]);
      if (opts.vlineLabels !== false) {
        // One row per line, right-aligned to it, on a white box: labels of close speeds stack.
        ctx.font = "12px " + Chart.defaults.font.family;
        ctx.textAlign = "right";
        ctx.textBaseline = "middle";
        const width = ctx.measureText(line.label).width;
        const x = Math.max(px - 4, area.left + width + 4);
        const y = area.top + 10 + 17 * row;
        ctx.fillStyle = "rgba(255, 255, 255, 0.85)";
        ctx.fillRect(x - width - 3, y - 8, width + 6, 16);
        ctx.fillStyle = line.color;
        ctx.fillText(line.label, x, y);
      }
      ctx.restore();
    });
    for (const label of opts.labels ?? []) {
      const px = scales.x.getPixelForValue(label.x) + (label.dx ?? 0);
      const py = scales.y.getPixelForValue(label.y) + (label.dy ?? 0);
      ctx.save();
      ctx.fillStyle = label.color ?? "#333";
      ctx.font = "bold 12px " + Chart.defaults.font.family;
      ctx.textAlign = label.align ?? "left";
      ctx.textBaseline = "middle";
      ctx.fillText(label.text, Math.min(Math.max(px, area.left + 2), area.right - 2), Math.min(Math.max(py, area.top + 8), area.bottom - 8));
      ctx.restore();
    }
  },
};

// Equal scales on both axes (a drawing of the wing, not a graph): options.plugins.equalAspect =
// {xmin, xmax, ymin, ymax}, the box to show. After each layout the axis limits are widened so one
// metre spans as many pixels across as up; the chart is redrawn once when they change.
const equalAspect = {
  id: "equalAspect",
  afterLayout(chart, _args, box) {
    if (box?.xmin === undefined) return;
    const { width, height } = chart.chartArea;
    if (!(width > 0 && height > 0)) return;
    const perPixel = Math.max((box.xmax - box.xmin) / width, (box.ymax - box.ymin) / height);
    const cx = (box.xmin + box.xmax) / 2;
    const cy = (box.ymin + box.ymax) / 2;
    const want = {
      x: [cx - (perPixel * width) / 2, cx + (perPixel * width) / 2],
      y: [cy - (perPixel * height) / 2, cy + (perPixel * height) / 2],
    };
    const scales = chart.config.options.scales;
    const close = (axis) =>
      Math.abs(scales[axis].min - want[axis][0]) < perPixel && Math.abs(scales[axis].max - want[axis][1]) < perPixel;
    if (close("x") && close("y")) return;
    for (const axis of ["x", "y"]) [scales[axis].min, scales[axis].max] = want[axis];
    requestAnimationFrame(() => chart.canvas?.isConnected && chart.update("none"));
  },
};

// ------------------------------------------------------------------------------------ helpers

function points(xs, ys) {
  return xs.map((x, i) => ({ x, y: ys[i] }));
}

function axis(title, extra = {}) {
  return {
    type: "linear",
    title: { display: true, text: title },
    grid: { color: "#e6e6e6" },
    ...extra,
    ticks: { maxTicksLimit: 8, ...extra.ticks },
  };
}

function line(label, data, color, extra = {}) {
  return {
    label,
    data,
    borderColor: color,
    backgroundColor: color,
    showLine: true,
    borderWidth: 2,
    pointRadius: 0,
    pointHitRadius: 6,
    ...extra,
  };
}

function draw(canvasId, { title, datasets, xTitle, yTitle, x = {}, y = {}, plugins = {}, legend = true, pointLegend = false }) {
  charts.get(canvasId)?.destroy();
  const canvas = document.getElementById(canvasId);
  const chart = new Chart(canvas, {
    type: "scatter",
    data: { datasets },
    options: {
      scales: { x: axis(xTitle, x), y: axis(yTitle, y) },
      plugins: {
        title: { display: Boolean(title), text: title, font: { size: 13, weight: "600" } },
        // pointLegend: each legend entry drawn in its dataset's pointStyle ("line" for curves).
        legend: { display: legend, labels: pointLegend ? { usePointStyle: true, boxHeight: 10 } : {} },
        tooltip: { intersect: false, mode: "nearest" },
        ...plugins,
      },
    },
    plugins: [annotations, equalAspect],
  });
  charts.set(canvasId, chart);
  return chart;
}

function record(figureId, series, marks = {}, notes = {}) {
  registry[figureId] = {
    state: "drawn",
    series: Object.fromEntries(
      Object.entries(series).map(([key, s]) => [key, { label: s.label, x: [...s.x], y: [...s.y] }]),
    ),
    marks,
    ...notes,
  };
  const figure = document.getElementById(`fig-${figureId.replace(".", "-")}`);
  figure.dataset.state = "drawn";
  figure.dataset.series = Object.keys(series).join(" ");
}

export function clear(figureId) {
  registry[figureId] = { state: "empty", series: {}, marks: {} };
  const figure = document.getElementById(`fig-${figureId.replace(".", "-")}`);
  figure.dataset.state = "empty";
  figure.dataset.series = "";
  for (const canvas of figure.querySelectorAll("canvas")) {
    charts.get(canvas.id)?.destroy();
    charts.delete(canvas.id);
  }
}

const fmt = (value, digits) => (value == null ? "n/a" : value.toFixed(digits));

// ---------------------------------------------------------------------------------- figure 14.2

/** The stations (or strips) the findings of `codes` concern, as a series on (xs, ys). */
function beyond(findings, codes, label, xs, ys) {
  const indices = [...new Set(findings.filter((f) => codes.includes(f.code)).flatMap((f) => f.indices))].sort((a, b) => a - b);
  return { label, x: indices.map((i) => xs[i]), y: indices.map((i) => ys[i]) };
}

function beyondSet(series) {
  return {
    label: series.label,
    data: points(series.x, series.y),
    borderColor: COLORS.beyond,
    backgroundColor: COLORS.beyond,
    pointStyle: "triangle",
    pointRadius: 5,
    showLine: false,
  };
}

/** Lift per span (rigid and flexible), twist and heave along the span. `rigid` may be null.
 * Stations the answer's `validity` findings concern are marked on the chart of their quantity. */
export function drawSpanwise(solution, rigid) {
  const { stations, panels } = solution;
  const findings = solution.validity ?? [];
  const stalled = beyond(findings, ["section_stall"], "past stall (cl > cl_max)", panels.y, panels.lift_per_span);
  const twisted = beyond(findings, ["large_twist"], "twist beyond the limit", stations.y, stations.twist);
  const bent = beyond(findings, ["large_deflection"], "heave or slope beyond the limit", stations.y, stations.heave);
  const series = {
    lift_flexible: { label: "flexible", x: panels.y, y: panels.lift_per_span },
    twist: { label: "twist", x: stations.y, y: stations.twist },
    heave: { label: "heave", x: stations.y, y: stations.heave },
    beyond_lift: stalled,
    beyond_twist: twisted,
    beyond_heave: bent,
  };
  const liftSets = [line("flexible", points(panels.y, panels.lift_per_span), COLORS.flexible)];
  if (stalled.x.length) liftSets.push(beyondSet(stalled));
  if (rigid) {
    series.lift_rigid = { label: "rigid (jig shape)", x: rigid.panels.y, y: rigid.panels.lift_per_span };
    liftSets.unshift(line("rigid (jig shape)", points(rigid.panels.y, rigid.panels.lift_per_span), COLORS.rigid));
  }
  const span = { min: 0 };
  draw("chart-lift", {
    title: "Flexibility shifts the lift distribution outboard",
    datasets: liftSets,
    xTitle: "spanwise position y [m]",
    yTitle: "lift per span [N/m]",
    x: span,
    y: { beginAtZero: true },
  });
  draw("chart-twist", {
    title: "Nose-up twist (wash-in) accumulates toward the tip",
    datasets: [line("twist", points(stations.y, stations.twist), COLORS.flexible), ...(twisted.x.length ? [beyondSet(twisted)] : [])],
    xTitle: "spanwise position y [m]",
    yTitle: "twist θ [deg]",
    x: span,
    legend: twisted.x.length > 0,
    plugins: { annotations: { hlines: [{ y: 0 }] } },
  });
  draw("chart-heave", {
    title: "Bending deflection",
    datasets: [line("heave", points(stations.y, stations.heave), COLORS.flexible), ...(bent.x.length ? [beyondSet(bent)] : [])],
    xTitle: "spanwise position y [m]",
    yTitle: "heave u [m]",
    x: span,
    legend: bent.x.length > 0,
  });
  record(
    "14.2",
    series,
    { tip_twist: solution.totals.tip_twist, tip_heave: solution.totals.tip_heave },
    { findings: findings.map((f) => f.code) },
  );
}

// ---------------------------------------------------------------------------------- figure 14.3

/** Bending moment and torque along the span, root values labelled. */
export function drawLoads(solution) {
  const { stations, totals } = solution;
  const rootM = totals.root_bending_moment;
  const rootT = totals.root_torque;
  const labelM = `root: ${fmt(rootM, 0)} N·m`;
  const labelT = `root: ${fmt(rootT, 1)} N·m`;
  draw("chart-moment", {
    title: "Bending moment, flexible wing",
    datasets: [line("bending moment", points(stations.y, stations.bending_moment), COLORS.moment)],
    xTitle: "spanwise position y [m]",
    yTitle: "bending moment M [N·m]",
    x: { min: 0 },
    legend: false,
    plugins: { annotations: { labels: [{ x: stations.y[0], y: rootM, text: labelM, color: COLORS.moment, dx: 10 }] } },
  });
  draw("chart-torque", {
    title: "Elastic-axis torque, flexible wing",
    datasets: [line("torque", points(stations.y, stations.torque), COLORS.torque)],
    xTitle: "spanwise position y [m]",
    yTitle: "torque T [N·m]",
    x: { min: 0 },
    legend: false,
    plugins: { annotations: { labels: [{ x: stations.y[0], y: rootT, text: labelT, color: COLORS.torque, dx: 10 }], hlines: [{ y: 0 }] } },
  });
  record(
    "14.3",
    {
      bending_moment: { label: "bending moment", x: stations.y, y: stations.bending_moment },
      torque: { label: "torque", x: stations.y, y: stations.torque },
    },
    { root_bending_moment: rootM, root_torque: rootT },
    { labels: [labelM, labelT] },
  );
}

// ------------------------------------------------------------------------- spar stresses (14.3)

/** Von Mises and bending stress in the tube spar along the span [MPa], with the allowable
 * yield / safety factor; the registry records the drawn values (MPa). */
export function drawStress(solution, yieldStress, safetyFactor) {
  const { stations, totals } = solution;
  const mpa = (values) => values.map((v) => v / 1e6);
  const allowable = yieldStress / safetyFactor / 1e6;
  const series = {
    von_mises: { label: "von Mises", x: stations.y, y: mpa(stations.von_mises_stress) },
    bending: { label: "bending (outer fibre)", x: stations.y, y: mpa(stations.bending_stress) },
  };
  const allowableLabel =
    safetyFactor === 1 ? `yield ${fmt(allowable, 0)} MPa` : `allowable: yield / ${safetyFactor} = ${fmt(allowable, 0)} MPa`;
  const top = Math.max(allowable, ...series.von_mises.y);
  draw("chart-stress", {
    title: "Spar stresses against the allowable",
    datasets: [
      line("von Mises", points(series.von_mises.x, series.von_mises.y), COLORS.vonMises),
      line("bending (outer fibre)", points(series.bending.x, series.bending.y), COLORS.bending, { borderDash: [6, 4] }),
      line(allowableLabel, points([0, stations.y.at(-1)], [allowable, allowable]), COLORS.allowable, { borderDash: [2, 3], borderWidth: 1.5 }),
    ],
    xTitle: "spanwise position y [m]",
    yTitle: "stress [MPa]",
    x: { min: 0 },
    y: { beginAtZero: true, suggestedMax: 1.12 * top },
    plugins: {
      annotations: {
        hlines: [{ y: 0 }],
      },
    },
  });
  record(
    "stress",
    series,
    {
      allowable,
      max_von_mises: totals.max_von_mises_stress / 1e6,
      failure_margin: totals.failure_margin,
      spar_mass: totals.spar_mass,
    },
    { unit: "MPa", allowable_label: allowableLabel },
  );
}

// ---------------------------------------------------------------------------------- figure 14.4

/** The study's amplification A of a sweep point, as the fit defines it (fit.amplification). */
export function amplification(equilibrium, kind) {
  const { totals } = equilibrium;
  if (kind === "lift_effectiveness") return totals.lift_effectiveness ?? null;
  if (!totals.rigid_lift) return null;
  const ratio = totals.lift / totals.rigid_lift;
  return kind === "CL" ? (ratio * totals.reference_area) / totals.deformed_area : ratio;
}

/** Tip twist and lift amplification against airspeed, the fitted 1/A law, and the speeds. */
export function drawSweep(sweep, density) {
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
  if (fit.slope != null && fit.intercept != null && fit.velocity != null) {
    // The study draws the fit from 0 to 92 % of its divergence speed.
    const fitV = Array.from({ length: 300 }, (_, i) => (0.92 * fit.velocity * i) / 299);
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

// ---------------------------------------------------------------------------------- figure 14.5

function bounds(pointLists) {
  const all = pointLists.flat().filter((p) => p.x !== null);
  const xs = all.map((p) => p.x);
  const ys = all.map((p) => p.y);
  const box = { xmin: Math.min(...xs), xmax: Math.max(...xs), ymin: Math.min(...ys), ymax: Math.max(...ys) };
  const pad = 0.04 * Math.max(box.xmax - box.xmin, box.ymax - box.ymin);
  return { xmin: box.xmin - pad, xmax: box.xmax + pad, ymin: box.ymin - pad, ymax: box.ymax + pad };
}

/** Jig and deformed shape in three views; `scale` exaggerates the deformation (1: true). */
export function drawShape(wing, equilibrium, label, scale = 1) {
  const { stations } = equilibrium;
  const base = { y: wing.y, chord: wing.chord, elasticAxis: wing.elastic_axis };
  const zeros = wing.y.map(() => 0);
  const jig = sections({ ...base, heave: zeros, twist: zeros });
  const deformed = sections({ ...base, heave: stations.heave, twist: stations.twist, scale });
  const deformedLabel = scale === 1 ? `deformed, ${label}` : `deformed ×${scale}, ${label}`;
  const views = [
    ["top", "chart-top", "Top view", "y [m]", "x [m], aft down"],
    ["front", "chart-front", "Front view (bending)", "y [m]", "z [m]"],
    ["side", "chart-side", "Side view from the right tip (twist)", "x [m]", "z [m]"],
  ];
  const series = {};
  for (const [view, canvasId, title, xTitle, yTitle] of views) {
    const jigPoints = wireframe(jig, view);
    const deformedPoints = wireframe(deformed, view);
    series[`${view}_jig`] = { label: "jig", x: jigPoints.map((p) => p.x), y: jigPoints.map((p) => p.y) };
    series[`${view}_deformed`] = { label: deformedLabel, x: deformedPoints.map((p) => p.x), y: deformedPoints.map((p) => p.y) };
    const datasets = [
      line("jig (undeformed)", jigPoints, COLORS.rigid, { borderWidth: 1 }),
      line(deformedLabel, deformedPoints, COLORS.flexible, { borderWidth: 1.2 }),
    ];
    // The control surfaces, deflected, on the deformed wing (drawn at their true deflection).
    const surfacePoints = surfaceOutlines(deformed, wing.control_surfaces, view);
    if (surfacePoints.length) {
      series[`${view}_surfaces`] = { label: "control surfaces", x: surfacePoints.map((p) => p.x), y: surfacePoints.map((p) => p.y) };
      datasets.push(line("control surfaces, deflected", surfacePoints, COLORS.surface, { borderWidth: 1.5 }));
    }
    draw(canvasId, {
      title,
      datasets,
      xTitle,
      yTitle,
      x: { ticks: { includeBounds: false } },
      y: view === "top" ? { reverse: true, ticks: { includeBounds: false } } : { ticks: { includeBounds: false } },
      plugins: { equalAspect: bounds([jigPoints, deformedPoints, surfacePoints]) },
      legend: view === "top",
    });
  }
  record("14.5", series, { scale, tip_heave: stations.heave.at(-1), tip_twist: stations.twist.at(-1) }, { label });
}

// -------------------------------------------------------------------- control effectiveness

/** One colour per control surface or mode, in order. */
export const PALETTE = ["#1565c0", "#c62828", "#2e7d32", "#6a1b9a", "#ef6c00", "#00838f", "#5d4037", "#ad1457"];
const colorOf = (i) => PALETTE[i % PALETTE.length];

/** The nicest axis end above the largest of `speeds` (5 m/s steps up to 100, 10 beyond). */
function speedAxisEnd(speeds) {
  const top = 1.03 * Math.max(...speeds.filter((v) => v != null && Number.isFinite(v)));
  const step = top > 100 ? 10 : 5;
  return step * Math.ceil(top / step);
}

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

// --------------------------------------------------------------------------------- flutter

/** V-g and V-f: every mode's damping ratio and frequency against airspeed, the flutter and
 * divergence speeds marked; and the first modes' shapes (heave, twist) along the span. */
export function drawFlutter(flutter, { shapes = 3 } = {}) {
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
    title: "V-g: a mode flutters where its damping crosses zero",
    datasets: vg,
    xTitle: "airspeed V [m/s]",
    yTitle: "damping ratio [-] (negative: grows)",
    x: speed,
    pointLegend: true,
    plugins: { annotations: { vlines, hlines: [{ y: 0, color: "#555" }] } },
  });
  draw("chart-vf", {
    title: "V-f: the modes' frequencies coalesce toward flutter",
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
    { modes: modeCount, mode_frequencies: flutter.modes.map((m) => m.frequency) },
  );
}

// ----------------------------------------------------------------------------------- exporting

/** The figure's charts as one PNG (laid out as on screen, white background), as a Blob. */
export function figurePNG(figure) {
  const canvases = [...figure.querySelectorAll("canvas")].filter((c) => charts.has(c.id));
  if (!canvases.length) return Promise.resolve(null);
  const ratio = canvases[0].width / canvases[0].getBoundingClientRect().width || 1;
  const rects = canvases.map((c) => c.getBoundingClientRect());
  const left = Math.min(...rects.map((r) => r.left));
  const top = Math.min(...rects.map((r) => r.top));
  const width = Math.max(...rects.map((r) => r.right)) - left;
  const height = Math.max(...rects.map((r) => r.bottom)) - top;
  const band = 28;
  const out = document.createElement("canvas");
  out.width = Math.round(width * ratio);
  out.height = Math.round((height + band) * ratio);
  const ctx = out.getContext("2d");
  ctx.scale(ratio, ratio);
  ctx.fillStyle = "#fff";
  ctx.fillRect(0, 0, width, height + band);
  ctx.fillStyle = "#222";
  ctx.font = "bold 14px " + Chart.defaults.font.family;
  ctx.textBaseline = "middle";
  ctx.fillText(figure.dataset.title ?? "", 8, band / 2);
  canvases.forEach((canvas, i) => {
    ctx.drawImage(canvas, rects[i].left - left, rects[i].top - top + band, rects[i].width, rects[i].height);
  });
  return new Promise((resolve) => out.toBlob(resolve, "image/png"));
}

/** Redraw every chart at its container's size (after the layout changed). */
export function resizeAll() {
  for (const chart of charts.values()) chart.resize();
}
