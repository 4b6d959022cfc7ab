// An optimum's figure: the optimal jig twist of the flexible wing against the rigid wing's
// optimum, and the optimal wing's lift per unit span against the elliptic loading of the same
// lift (the least induced drag of a planar wake, Prandtl).

import { COLORS, draw, line, points, record } from "./chart.js";

/** The elliptic lift per span of `lift` [N] (both halves) over semispan `s`, at `y`. */
const elliptic = (lift, s, y) => y.map((yi) => ((4 * lift) / (Math.PI * 2 * s)) * Math.sqrt(Math.max(0, 1 - (yi / s) ** 2)));

/** Jig twist (flexible and rigid optima) and lift per span of a POST /optimize answer. */
export function drawOptimum(optimum) {
  const { stations, panels, totals } = optimum.equilibrium;
  const y = stations.y;
  const semispan = y.at(-1);
  const series = {
    jig_twist: { label: "optimal jig twist, flexible wing", x: y, y: optimum.jig_twist },
    lift: { label: "optimal wing", x: panels.y, y: panels.lift_per_span },
  };
  const twistSets = [line(series.jig_twist.label, points(y, optimum.jig_twist), COLORS.flexible)];
  if (optimum.rigid) {
    series.rigid_jig_twist = { label: "optimal jig twist, rigid wing", x: y, y: optimum.rigid.jig_twist };
    twistSets.unshift(line(series.rigid_jig_twist.label, points(y, optimum.rigid.jig_twist), COLORS.rigid, { borderDash: [6, 4] }));
  }
  const ellipse = Array.from({ length: 101 }, (_, i) => (semispan * i) / 100);
  series.elliptic = { label: "elliptic, same lift", x: ellipse, y: elliptic(totals.lift, semispan, ellipse) };
  draw("chart-optimize-twist", {
    title: "The optimal jig twist",
    datasets: twistSets,
    xTitle: "spanwise position y [m]",
    yTitle: "jig twist [deg]",
    x: { min: 0 },
    plugins: { annotations: { hlines: [{ y: 0 }] } },
  });
  draw("chart-optimize-lift", {
    title: "Its loading against the elliptic",
    datasets: [
      line(series.elliptic.label, points(series.elliptic.x, series.elliptic.y), COLORS.fit, { borderDash: [2, 3] }),
      line(series.lift.label, points(panels.y, panels.lift_per_span), COLORS.flexible),
    ],
    xTitle: "spanwise position y [m]",
    yTitle: "lift per span [N/m]",
    x: { min: 0 },
    y: { beginAtZero: true },
  });
  record(
    "optimize",
    series,
    {
      objective_value: optimum.objective_value,
      induced_drag: optimum.induced_drag,
      span_efficiency: optimum.span_efficiency,
      rigid_induced_drag: optimum.rigid?.induced_drag ?? null,
    },
    { objective: optimum.objective },
  );
}
