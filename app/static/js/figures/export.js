// A figure's charts as one PNG, laid out as on screen, and every chart redrawn at its size.

import { charts } from "./chart.js";

const { Chart } = window;

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
