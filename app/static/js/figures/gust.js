// Gust loads (POST /gust): the time histories of a 1-cos gust (load factor, tip deflection and
// twist; the tuned gust or any other gradient), the envelopes of total loads along the span
// (1 g plus and minus the incremental extremes: the discrete gusts and continuous turbulence
// side by side), and the tuned-gust search: peak load factor and root bending moment against
// the gust gradient H with the tuned gradients marked and Pratt's load factor for reference.

import { downloadText, toCSV } from "../download.js";
import { COLORS, draw, line, points, record } from "./chart.js";

const LOADS = [
  { key: "shear", label: "shear", unit: "N", canvas: "chart-gust-shear", color: COLORS.flexible },
  { key: "bending_moment", label: "bending moment", unit: "N·m", canvas: "chart-gust-moment", color: COLORS.moment },
  { key: "torque", label: "torque", unit: "N·m", canvas: "chart-gust-torque", color: COLORS.torque },
];

/** Index `i` of the answer's gusts, or its given profile ("profile"). */
export const gustCase = (gust, i) => (i === "profile" ? gust.profile : gust.gusts[Number(i)]);

/** The time histories of gust `i` (an index of `gusts`, or "profile"). */
export function drawHistories(gust, i) {
  const c = gustCase(gust, i);
  const tuned = Number(i) === gust.tuned_load_factor;
  const name = `${c.name}${tuned ? " (tuned)" : ""}`;
  draw("chart-gust-n", {
    title: `Load factor: ${name}`,
    datasets: [
      line("load factor n", points(c.time, c.load_factor), COLORS.flexible),
      line(`Pratt (K_g): ${gust.pratt_load_factor.toFixed(3)}`, points([c.time[0], c.time.at(-1)], [gust.pratt_load_factor, gust.pratt_load_factor]), COLORS.allowable, { borderDash: [2, 3], pointRadius: 0 }),
    ],
    xTitle: "time t [s]",
    yTitle: "load factor n [-]",
    plugins: { annotations: { hlines: [{ y: 1 }] } },
  });
  draw("chart-gust-tip", {
    title: `Tip deflection and twist: ${name}`,
    datasets: [
      line("tip deflection [mm]", points(c.time, c.tip_heave.map((v) => 1000 * v)), COLORS.moment),
      line("tip twist [deg × 10]", points(c.time, c.tip_twist.map((v) => 10 * v)), COLORS.torque, { borderDash: [6, 4] }),
    ],
    xTitle: "time t [s]",
    yTitle: "tip: mm, 0.1 deg",
    plugins: { annotations: { hlines: [{ y: 0 }] } },
  });
  const series = {};
  for (const key of ["load_factor", "tip_heave", "tip_twist", "root_shear", "root_bending_moment", "root_torque"]) {
    series[key] = { label: key.replaceAll("_", " "), x: c.time, y: c[key] };
  }
  record("gust-time", series, { case: i === "profile" ? "profile" : Number(i), gradient: c.gradient, max_load_factor: c.max_load_factor, tuned }, { name: c.name });
}

/** Total loads along the span: 1 g, the 1-cos gusts' envelope and turbulence's design loads. */
export function drawGustEnvelope(gust) {
  const { envelope, turbulence, y } = gust;
  const series = {};
  const marks = {};
  for (const load of LOADS) {
    const oneG = gust[`one_g_${load.key}`];
    series[`one_g_${load.key}`] = { label: "1 g", x: y, y: oneG };
    const datasets = [line("1 g", points(y, oneG), "#555", { borderDash: [2, 3], borderWidth: 1.5 })];
    for (const side of ["max", "min"]) {
      const discrete = envelope[`${side}_${load.key}`];
      series[`discrete_${side}_${load.key}`] = { label: `1-cos ${side}`, x: y, y: discrete };
      datasets.push(line(`1-cos gusts ${side}`, points(y, discrete), load.color, { borderDash: side === "min" ? [6, 4] : [] }));
      marks[`root_discrete_${side}_${load.key}`] = discrete[0];
      if (turbulence) {
        const design = turbulence[`${side}_${load.key}`];
        series[`turbulence_${side}_${load.key}`] = { label: `turbulence ${side}`, x: y, y: design };
        datasets.push(line(`turbulence ${side}`, points(y, design), COLORS.allowable, { borderDash: side === "min" ? [6, 4] : [] }));
        marks[`root_turbulence_${side}_${load.key}`] = design[0];
      }
    }
    draw(load.canvas, {
      title: `Total ${load.label}: root ${marks[`root_discrete_max_${load.key}`].toPrecision(4)} ${load.unit} (1-cos)${turbulence ? `, ${marks[`root_turbulence_max_${load.key}`].toPrecision(4)} (turbulence)` : ""}`,
      datasets,
      xTitle: "spanwise position y [m]",
      yTitle: `${load.label} [${load.unit}]`,
      x: { min: 0 },
      plugins: { annotations: { hlines: [{ y: 0 }] } },
    });
  }
  record("gust-envelope", series, marks, { turbulence: Boolean(turbulence) });
}

/** Peak load factor and root bending moment against the gust gradient H, the tuned marked. */
export function drawTuning(gust) {
  const H = gust.gusts.map((c) => c.gradient);
  const n = gust.gusts.map((c) => c.max_load_factor);
  const rootM = gust.gusts.map((c) => c.max_bending_moment[0]);
  const tn = gust.gusts[gust.tuned_load_factor];
  const tm = gust.gusts[gust.tuned_bending_moment];
  const mark = { showLine: false, pointRadius: 7, pointStyle: "star", borderWidth: 2 };
  draw("chart-gust-tuned-n", {
    title: `Peak load factor against the gust gradient: tuned H = ${tn.gradient.toPrecision(3)} m`,
    datasets: [
      line("peak load factor", points(H, n), COLORS.flexible, { pointRadius: 3 }),
      line("tuned gust", [{ x: tn.gradient, y: tn.max_load_factor }], "#222", mark),
      line("Pratt (K_g)", points([H[0], H.at(-1)], [gust.pratt_load_factor, gust.pratt_load_factor]), COLORS.allowable, { borderDash: [2, 3], pointRadius: 0 }),
    ],
    xTitle: "gust gradient H [m]",
    yTitle: "peak load factor n [-]",
    pointLegend: true,
  });
  draw("chart-gust-tuned-moment", {
    title: `Incremental root bending moment against the gust gradient: tuned H = ${tm.gradient.toPrecision(3)} m`,
    datasets: [
      line("peak root bending moment", points(H, rootM), COLORS.moment, { pointRadius: 3 }),
      line("tuned gust", [{ x: tm.gradient, y: tm.max_bending_moment[0] }], "#222", mark),
    ],
    xTitle: "gust gradient H [m]",
    yTitle: "root ΔM [N·m]",
    pointLegend: true,
  });
  record(
    "gust-tuned",
    {
      load_factor: { label: "peak load factor", x: H, y: n },
      root_bending_moment: { label: "peak incremental root bending moment", x: H, y: rootM },
    },
    {
      tuned_gradient: tn.gradient,
      tuned_load_factor: tn.max_load_factor,
      tuned_bending_gradient: tm.gradient,
      tuned_root_bending_moment: tm.max_bending_moment[0],
      pratt_load_factor: gust.pratt_load_factor,
    },
  );
}

/** The numbers: [label, value, unit]. */
export function gustNumbers(gust) {
  const tn = gust.gusts[gust.tuned_load_factor];
  const rows = [
    ["true airspeed V", gust.velocity, "m/s"],
    ["equivalent airspeed", gust.equivalent_airspeed, "m/s"],
    ["1 g angle of attack", gust.alpha, "deg"],
    ["F_g (alleviation)", gust.alleviation, "-"],
    ["U_ref (EAS)", gust.reference_velocity, "m/s"],
    ["lift slope a", gust.lift_slope, "1/rad"],
    ["mass ratio mu_g", gust.mass_ratio, "-"],
    ["Pratt's K_g", gust.pratt_alleviation, "-"],
    ["Pratt's load factor", gust.pratt_load_factor, "-"],
    ["tuned gradient H (load factor)", tn.gradient, "m"],
    ["tuned U_ds (TAS)", tn.gust_velocity, "m/s"],
    ["max load factor n", tn.max_load_factor, "-"],
    ["min load factor n", Math.min(...gust.gusts.map((c) => c.min_load_factor)), "-"],
    ["tuned gradient H (root bending)", gust.gusts[gust.tuned_bending_moment].gradient, "m"],
    ["tuned gradient H (root torque)", gust.gusts[gust.tuned_torque].gradient, "m"],
  ];
  if (gust.turbulence) {
    rows.push(["U_sigma (TAS)", gust.turbulence.intensity, "m/s"], ["A-bar of n", gust.turbulence.load_factor, "1/(m/s)"], ["turbulence design n", 1 + gust.turbulence.intensity * gust.turbulence.load_factor, "-"]);
  }
  return rows;
}

/** Per station: 1 g, the 1-cos envelope and turbulence's design loads. */
export function downloadGustEnvelope(gust) {
  const columns = [["y [m]", gust.y]];
  for (const [key, unit] of [
    ["shear", "N"],
    ["bending_moment", "N m"],
    ["torque", "N m"],
  ]) {
    columns.push([`one_g_${key} [${unit}]`, gust[`one_g_${key}`]]);
    for (const side of ["max", "min"]) columns.push([`gust_${side}_${key} [${unit}]`, gust.envelope[`${side}_${key}`]]);
    if (gust.turbulence) for (const side of ["max", "min"]) columns.push([`turbulence_${side}_${key} [${unit}]`, gust.turbulence[`${side}_${key}`]]);
  }
  downloadText("flexwing-gust-envelope.csv", "text/csv", toCSV(columns));
}

/** Per gradient: the gust and its peaks (the tuned-gust search). */
export function downloadGusts(gust) {
  const columns = ["name", "gradient", "gust_velocity", "max_load_factor", "min_load_factor", "max_tip_heave"].map((key) => [key, gust.gusts.map((c) => c[key])]);
  for (const key of ["shear", "bending_moment", "torque"]) columns.push([`root_max_${key}`, gust.gusts.map((c) => c[`max_${key}`][0])], [`root_min_${key}`, gust.gusts.map((c) => c[`min_${key}`][0])]);
  downloadText("flexwing-gusts.csv", "text/csv", toCSV(columns));
}

/** One gust's time histories. */
export function downloadHistories(gust, i) {
  const c = gustCase(gust, i);
  const columns = ["time", "load_factor", "tip_heave", "tip_twist", "root_shear", "root_bending_moment", "root_torque"].map((key) => [key, c[key]]);
  downloadText("flexwing-gust-histories.csv", "text/csv", toCSV(columns));
}
