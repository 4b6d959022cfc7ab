// A batch's figure: each solve's lift and tip twist, item by item (a batch's solves are any
// wings at any conditions: their order is the only axis they share).

import { COLORS, draw, line, points, record } from "./chart.js";

/** Lift and tip twist of each answered item of a batch's result ({items: [...]}). */
export function drawBatch(result) {
  const answered = result.items.filter((item) => item.status === "ok");
  const number = answered.map((item) => item.index + 1);
  const lift = answered.map((item) => item.result.totals.lift);
  const twist = answered.map((item) => item.result.totals.tip_twist);
  draw("chart-batch", {
    title: "Each solve's lift",
    datasets: [line("lift", points(number, lift), COLORS.flexible, { showLine: false, pointRadius: 4 })],
    xTitle: "solve (item number)",
    yTitle: "lift [N]",
    x: { ticks: { precision: 0 } },
    y: { beginAtZero: true },
    legend: false,
  });
  record(
    "batch",
    { lift: { label: "lift", x: number, y: lift }, tip_twist: { label: "tip twist", x: number, y: twist } },
    { items: result.items.length, problems: result.items.length - answered.length },
  );
}
