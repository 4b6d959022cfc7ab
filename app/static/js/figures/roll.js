// Roll: the wing's antisymmetric response to its ailerons, both halves across the span (the left
// wing at negative y): lift per unit span against the rigid wing's, and the twist.

import { COLORS, draw, line, points, record } from "./chart.js";

/** A half wing's values across the span: the left's at -y, root to tip outward. */
const across = (left, right, key) => ({
  x: [...left.y.map((y) => -y).reverse(), ...right.y],
  y: [...[...left[key]].reverse(), ...right[key]],
});

/** Lift per span (flexible and rigid) and twist of both halves of a POST /roll answer. */
export function drawRoll(roll) {
  const lift = across(roll.left_panels, roll.right_panels, "lift_per_span");
  const rigid = across(roll.left_panels, roll.right_panels, "rigid_lift_per_span");
  const twist = across(roll.left, roll.right, "twist");
  draw("chart-roll-lift", {
    title: "The ailerons shift lift from one wing to the other",
    datasets: [
      line("rigid (jig shape)", points(rigid.x, rigid.y), COLORS.rigid),
      line("flexible", points(lift.x, lift.y), COLORS.flexible),
    ],
    xTitle: "spanwise position y [m] (left wing < 0)",
    yTitle: "lift per span [N/m]",
    plugins: { annotations: { hlines: [{ y: 0 }] } },
  });
  draw("chart-roll-twist", {
    title: "Elastic twist of each wing",
    datasets: [line("twist", points(twist.x, twist.y), COLORS.flexible)],
    xTitle: "spanwise position y [m] (left wing < 0)",
    yTitle: "twist θ [deg]",
    legend: false,
    plugins: { annotations: { hlines: [{ y: 0 }] } },
  });
  record(
    "roll",
    {
      lift: { label: "flexible", ...lift },
      rigid_lift: { label: "rigid (jig shape)", ...rigid },
      twist: { label: "twist", ...twist },
    },
    {
      rolling_moment: roll.rolling_moment,
      rigid_rolling_moment: roll.rigid_rolling_moment,
      roll_rate: roll.roll_rate,
      helix_angle: roll.helix_angle,
    },
    { method: roll.method },
  );
}
