// Chart.js (vendored, loaded before the modules as window.Chart) as the figures use it: the
// page's defaults and colours, the annotation and equal-aspect plugins, draw() of one chart, and
// the record of what each figure drew (`registry`, which the page exposes as
// window.__flexwing.figures for tests and for the curious). A figure is the <figure> element
// #fig-<id> ("14.2": #fig-14-2) with its canvases; each figures/*.js module draws one.

const { Chart } = window;
if (!Chart) throw new Error("Chart.js did not load (static/vendor/chart.js-*/chart.umd.min.js)");

export const COLORS = {
  flexible: "#1565c0",
  rigid: "#8a8a8a",
  moment: "#c62828",
  torque: "#6a1b9a",
  fold: "#d84315",
  linear: "#2e7d32",
  fit: "#5f6368",
  zero: "#b0b0b0",
  beyond: "#e65100",
  surface: "#ef6c00",
  vonMises: "#c62828",
  bending: "#1565c0",
  allowable: "#2e7d32",
};

Chart.defaults.animation = false;
Chart.defaults.responsive = true;
Chart.defaults.maintainAspectRatio = false;
Chart.defaults.font.family = "system-ui, -apple-system, 'Segoe UI', Roboto, 'Helvetica Neue', Arial, sans-serif";
Chart.defaults.color = "#333";
Chart.defaults.plugins.legend.labels.boxHeight = 2;

/** What each figure drew: {state, series: {key: {label, x, y}}, marks: {key: value}, drawn:
 * how many answers it has drawn}. */
export const registry = {};
/** canvas id -> its Chart. */
export const charts = new Map();

// ------------------------------------------------------------------------------ chart plugins

// Vertical lines (a speed marked on an airspeed axis), horizontal lines, shaded x-ranges and text
// labels at data coordinates: options.plugins.annotations = {vlines, hlines, regions, labels}.
const annotations = {
  id: "annotations",
  beforeDatasetsDraw(chart, _args, opts) {
    const { ctx, chartArea: area, scales } = chart;
    for (const region of opts.regions ?? []) {
      const left = Math.max(area.left, scales.x.getPixelForValue(region.from));
      const right = Math.min(area.right, scales.x.getPixelForValue(region.to));
      if (right <= left) continue;
      ctx.save();
      ctx.fillStyle = region.color;
      ctx.fillRect(left, area.top, right - left, area.bottom - area.top);
      ctx.restore();
    }
    for (const line of opts.hlines ?? []) {
      const py = scales.y.getPixelForValue(line.y);
      if (py < area.top || py > area.bottom) continue;
      ctx.save();
      ctx.strokeStyle = line.color ?? COLORS.zero;
      ctx.lineWidth = 1;
      ctx.beginPath();
      ctx.moveTo(area.left, py);
      ctx.lineTo(area.right, py);
      ctx.stroke();
      ctx.restore();
    }
  },
  afterDatasetsDraw(chart, _args, opts) {
    const { ctx, chartArea: area, scales } = chart;
    (opts.vlines ?? []).forEach((line, row) => {
      const px = scales.x.getPixelForValue(line.x);
      if (!(px >= area.left - 0.5 && px <= area.right + 0.5)) return;
      ctx.save();
      ctx.strokeStyle = line.color;
      ctx.lineWidth = 1.5;
      ctx.setLineDash(line.dash ?? []);
      ctx.beginPath();
      ctx.moveTo(px, area.top);
      ctx.lineTo(px, area.bottom);
      ctx.stroke();
      ctx.setLineDash([]);
      if (opts.vlineLabels !== false) {
        // One row per line, right-aligned to it, on a white box: labels of close speeds stack.
        ctx.font = "12px " + Chart.defaults.font.family;
        ctx.textAlign = "right";
        ctx.textBaseline = "middle";
        const width = ctx.measureText(line.label).width;
        const x = Math.max(px - 4, area.left + width + 4);
        const y = area.top + 10 + 17 * row;
        ctx.fillStyle = "rgba(255, 255, 255, 0.85)";
        ctx.fillRect(x - width - 3, y - 8, width + 6, 16);
        ctx.fillStyle = line.color;
        ctx.fillText(line.label, x, y);
      }
      ctx.restore();
    });
    for (const label of opts.labels ?? []) {
      const px = scales.x.getPixelForValue(label.x) + (label.dx ?? 0);
      const py = scales.y.getPixelForValue(label.y) + (label.dy ?? 0);
      ctx.save();
      ctx.fillStyle = label.color ?? "#333";
      ctx.font = "bold 12px " + Chart.defaults.font.family;
      ctx.textAlign = label.align ?? "left";
      ctx.textBaseline = "middle";
      ctx.fillText(label.text, Math.min(Math.max(px, area.left + 2), area.right - 2), Math.min(Math.max(py, area.top + 8), area.bottom - 8));
      ctx.restore();
    }
  },
};

// Equal scales on both axes (a drawing of the wing, not a graph): options.plugins.equalAspect =
// {xmin, xmax, ymin, ymax}, the box to show. After each layout the axis limits are widened so one
// metre spans as many pixels across as up; the chart is redrawn once when they change.
const equalAspect = {
  id: "equalAspect",
  afterLayout(chart, _args, box) {
    if (box?.xmin === undefined) return;
    const { width, height } = chart.chartArea;
    if (!(width > 0 && height > 0)) return;
    const perPixel = Math.max((box.xmax - box.xmin) / width, (box.ymax - box.ymin) / height);
    const cx = (box.xmin + box.xmax) / 2;
    const cy = (box.ymin + box.ymax) / 2;
    const want = {
      x: [cx - (perPixel * width) / 2, cx + (perPixel * width) / 2],
      y: [cy - (perPixel * height) / 2, cy + (perPixel * height) / 2],
    };
    const scales = chart.config.options.scales;
    const close = (axis) =>
      Math.abs(scales[axis].min - want[axis][0]) < perPixel && Math.abs(scales[axis].max - want[axis][1]) < perPixel;
    if (close("x") && close("y")) return;
    for (const axis of ["x", "y"]) [scales[axis].min, scales[axis].max] = want[axis];
    requestAnimationFrame(() => chart.canvas?.isConnected && chart.update("none"));
  },
};

// ------------------------------------------------------------------------------------ helpers

export function points(xs, ys) {
  return xs.map((x, i) => ({ x, y: ys[i] }));
}

function axis(title, extra = {}) {
  return {
    type: "linear",
    title: { display: true, text: title },
    grid: { color: "#e6e6e6" },
    ...extra,
    ticks: { maxTicksLimit: 8, ...extra.ticks },
  };
}

export function line(label, data, color, extra = {}) {
  return {
    label,
    data,
    borderColor: color,
    backgroundColor: color,
    showLine: true,
    borderWidth: 2,
    pointRadius: 0,
    pointHitRadius: 6,
    ...extra,
  };
}

export function draw(canvasId, { title, datasets, xTitle, yTitle, x = {}, y = {}, plugins = {}, legend = true, pointLegend = false }) {
  charts.get(canvasId)?.destroy();
  const canvas = document.getElementById(canvasId);
  const chart = new Chart(canvas, {
    type: "scatter",
    data: { datasets },
    options: {
      scales: { x: axis(xTitle, x), y: axis(yTitle, y) },
      plugins: {
        title: { display: Boolean(title), text: title, font: { size: 13, weight: "600" } },
        // pointLegend: each legend entry drawn in its dataset's pointStyle ("line" for curves).
        legend: { display: legend, labels: pointLegend ? { usePointStyle: true, boxHeight: 10 } : {} },
        tooltip: { intersect: false, mode: "nearest" },
        ...plugins,
      },
    },
    plugins: [annotations, equalAspect],
  });
  charts.set(canvasId, chart);
  return chart;
}

/** The figure element of `figureId` ("14.2" is #fig-14-2). */
export const figureElement = (figureId) => document.getElementById(`fig-${figureId.replace(".", "-")}`);

/** Record what figure `figureId` drew (its series as x/y arrays, its marked values, notes). */
export function record(figureId, series, marks = {}, notes = {}) {
  registry[figureId] = {
    state: "drawn",
    drawn: (registry[figureId]?.drawn ?? 0) + 1,
    series: Object.fromEntries(
      Object.entries(series).map(([key, s]) => [key, { label: s.label, x: [...s.x], y: [...s.y] }]),
    ),
    marks,
    ...notes,
  };
  const figure = figureElement(figureId);
  figure.dataset.state = "drawn";
  figure.dataset.series = Object.keys(series).join(" ");
}

/** Figure `figureId` empty again: its charts destroyed, its record emptied. */
export function clear(figureId) {
  registry[figureId] = { state: "empty", series: {}, marks: {}, drawn: registry[figureId]?.drawn ?? 0 };
  const figure = figureElement(figureId);
  figure.dataset.state = "empty";
  figure.dataset.series = "";
  for (const canvas of figure.querySelectorAll("canvas")) {
    charts.get(canvas.id)?.destroy();
    charts.delete(canvas.id);
  }
}

export const fmt = (value, digits) => (value == null ? "n/a" : value.toFixed(digits));

/** One colour per control surface or mode, in order. */
export const PALETTE = ["#1565c0", "#c62828", "#2e7d32", "#6a1b9a", "#ef6c00", "#00838f", "#5d4037", "#ad1457"];
export const colorOf = (i) => PALETTE[i % PALETTE.length];

/** The nicest axis end above the largest of `speeds` (5 m/s steps up to 100, 10 beyond). */
export function speedAxisEnd(speeds) {
  const top = 1.03 * Math.max(...speeds.filter((v) => v != null && Number.isFinite(v)));
  const step = top > 100 ? 10 : 5;
  return step * Math.ceil(top / step);
}
