// Figure 14.5: the jig and deformed shape of any equilibrium a panel has (panel.equilibria():
// the solve's, each of the sweep's), at a chosen exaggeration.

import { $, f, signed } from "../dom.js";
import { drawShape } from "../figures/shape.js";
import { codesOf, titleOf } from "../findings.js";
import { allPanels, definePanel } from "../registry.js";

const choices = () => allPanels().flatMap((panel) => panel.equilibria?.() ?? []);

function draw() {
  const choice = choices().find((c) => c.value === $("shape-of").value);
  if (!choice) return;
  const raw = Number($("shape-scale").value);
  const scale = Number.isFinite(raw) && raw > 0 ? raw : 1;
  drawShape(choice.wing, choice.equilibrium, `${f(choice.velocity, 2)} m/s`, scale);
  const t = choice.equilibrium.totals;
  const beyondModel = codesOf(choice.equilibrium.validity ?? []);
  $("shape-note").textContent =
    `At ${f(choice.velocity, 2)} m/s: tip twist ${signed(t.tip_twist, 2)} deg, tip heave ${f(t.tip_heave, 3)} m` +
    (scale === 1 ? " (true scale)." : `, drawn ${scale} times larger.`) +
    (beyondModel.length ? ` Beyond the model's validity: ${beyondModel.map(titleOf).join(", ").toLowerCase()}.` : "");
}

/** Refresh the choices; `prefer`: the one to show now (after a solve, its answer; after a
 * sweep, its fastest equilibrium, as the study shows it); else the current one is kept. */
export function showShape(prefer) {
  const select = $("shape-of");
  const previous = prefer ?? select.value;
  const all = choices();
  select.replaceChildren(...all.map((choice) => new Option(choice.label, choice.value)));
  if (all.some((c) => c.value === previous)) select.value = previous;
  draw();
}

definePanel({
  name: "shape",
  figures: ["14.5"],
  init() {
    $("shape-of").addEventListener("change", draw);
    $("shape-scale").addEventListener("input", draw);
  },
});
