// Figure 14.5: the jig and deformed wing in three views, drawn to scale on equal axes, sections
// placed as the solver places them (geometry.js), control surfaces deflected.

import { sections, surfaceOutlines, wireframe } from "../geometry.js";
import { COLORS, draw, line, record } from "./chart.js";

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
