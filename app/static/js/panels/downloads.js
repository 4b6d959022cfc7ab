// The results as files: every panel's request and answer as one JSON, and each figure as a PNG
// (any figure's export button, those of panels added later too).

import { downloadBlob, downloadJSON } from "../download.js";
import { $ } from "../dom.js";
import { figurePNG } from "../figures/export.js";
import { allPanels, definePanel } from "../registry.js";

async function exportFigure(button) {
  const blob = await figurePNG($(button.dataset.figure));
  if (blob) downloadBlob(`flexwing-${button.dataset.figure.replace("fig-", "figure-")}.png`, blob);
}

definePanel({
  name: "downloads",
  init() {
    $("download-json").addEventListener("click", () => {
      const results = allPanels().filter((p) => p.results && p.operation);
      downloadJSON("flexwing-results.json", Object.fromEntries(results.map((p) => [p.operation, p.results()])));
    });
    document.addEventListener("click", (event) => {
      const button = event.target.closest?.(".export-png");
      if (button) exportFigure(button);
    });
  },
});
