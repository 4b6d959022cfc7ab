// Figure 14.3 and its continuation: the internal loads along the span (bending moment, torque,
// root values labelled) and a tube spar's stresses against the allowable.

import { COLORS, draw, fmt, line, points, record } from "./chart.js";

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
