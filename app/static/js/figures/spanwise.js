// Figure 14.2: the equilibrium along the span: lift per unit span (rigid and flexible), twist
// and heave, the stations beyond the model's validity marked.

import { COLORS, draw, line, points, record } from "./chart.js";

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
