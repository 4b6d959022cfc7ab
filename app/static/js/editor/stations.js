// The wing: planform numbers -> stations, and the editable station table (the request's wing is
// always read from the table; the planform numbers only fill it).

import { fillHeader, rowHeader } from "../inputs.js";
import { STATION_COLUMNS } from "./fields.js";

export function linspace(start, stop, n) {
  if (n === 1) return [start];
  return Array.from({ length: n }, (_, i) => start + ((stop - start) * i) / (n - 1));
}

/** 10 significant digits, as the service's own example of the study's wing. */
export function significant(x) {
  return Number.isFinite(x) ? Number(x.toPrecision(10)) : x;
}

// The study's law c = sqrt(linspace(c_root^2, c_tip^2, N)), written with signed squares so that a
// negative chord typed in stays negative (and the service says which station is wrong) instead of
// being squared away.
function sqrtTaper(root, tip, n) {
  const signedSquare = (c) => Math.sign(c) * c * c;
  return linspace(signedSquare(root), signedSquare(tip), n).map(
    (s) => Math.sign(s) * Math.sqrt(Math.abs(s)),
  );
}

/** Station lists from planform numbers ({span, n, root_chord, ...}); null values pass through as
 * NaN so the service reports them. */
export function stationsFromPlanform(p) {
  const n = Math.max(0, Math.min(1000, Math.round(p.n ?? 0)));
  const y = linspace(0, (p.span ?? NaN) / 2, n);
  const chord =
    p.taper === "linear"
      ? linspace(p.root_chord ?? NaN, p.tip_chord ?? NaN, n)
      : sqrtTaper(p.root_chord ?? NaN, p.tip_chord ?? NaN, n);
  const law = (kind, k) => chord.map((c) => (kind === "constant" ? k : k * c ** 3));
  return {
    y: y.map(significant),
    chord: chord.map(significant),
    elastic_axis: chord.map(() => p.elastic_axis ?? NaN),
    bending_stiffness: law(p.ei_law, p.ei_k ?? NaN).map(significant),
    torsional_stiffness: law(p.gj_law, p.gj_k ?? NaN).map(significant),
  };
}

/** The station table in `table` (a <table> with an empty <tbody>), for `columns`. */
export class StationTable {
  constructor(table, { onEdit } = {}) {
    this.table = table;
    this.columns = [...STATION_COLUMNS];
    this.onEdit = onEdit;
    this.rows = 0;
    table.addEventListener("input", (event) => {
      if (event.target.matches("input")) this.onEdit?.(event.target);
    });
  }

  /** Add a column (a field a later API adds, e.g. jig twist) before filling the table. */
  addColumn(column) {
    if (!this.columns.some((c) => c.key === column.key)) this.columns.push(column);
  }

  /** Fill the table with `stations` ({y: [...], chord: [...], ...}); a number fills a column. */
  fill(stations) {
    const n = Math.max(...this.columns.map((c) => (Array.isArray(stations[c.key]) ? stations[c.key].length : 0)), 0);
    fillHeader(this.table, this.columns, { idPrefix: "col-" });
    const body = this.table.tBodies[0] ?? this.table.createTBody();
    body.replaceChildren();
    for (let i = 0; i < n; i++) {
      const row = body.insertRow();
      rowHeader(row, `row-${i}`, i);
      for (const column of this.columns) {
        const cell = row.insertCell();
        const input = document.createElement("input");
        input.type = "number";
        input.step = "any";
        input.inputMode = "decimal";
        input.id = `cell-${column.key}-${i}`;
        input.dataset.path = `wing.${column.key}[${i}]`;
        input.dataset.column = column.key;
        input.setAttribute("aria-labelledby", `col-${column.key} row-${i}`);
        const values = stations[column.key];
        const value = Array.isArray(values) ? values[i] : (values ?? column.value ?? "");
        input.value = value == null || Number.isNaN(value) ? "" : String(value);
        cell.append(input);
      }
    }
    this.rows = n;
  }

  /** The table's lists; a column marked scalarWhenUniform becomes one number when uniform. */
  read() {
    const wing = {};
    for (const column of this.columns) {
      const values = [];
      for (let i = 0; i < this.rows; i++) {
        // A column just added (addColumn) has no cells yet: its default stands in.
        const cell = this.table.querySelector(`#cell-${column.key}-${i}`);
        const text = cell ? cell.value.trim() : String(column.value ?? "");
        const value = text === "" ? null : Number(text);
        values.push(Number.isFinite(value) ? value : null);
      }
      const uniform = values.length > 0 && values.every((v) => v !== null && v === values[0]);
      wing[column.key] = column.scalarWhenUniform && uniform ? values[0] : values;
    }
    return wing;
  }

  addRow() {
    const wing = this.read();
    for (const column of this.columns) {
      const values = Array.isArray(wing[column.key]) ? wing[column.key] : Array(this.rows).fill(wing[column.key]);
      const last = values.at(-1) ?? 0;
      const step = column.key === "y" && values.length > 1 ? last - values.at(-2) : 0;
      wing[column.key] = [...values, significant(last + step)];
    }
    this.fill(wing);
  }

  removeRow() {
    if (this.rows <= 1) return;
    const wing = this.read();
    for (const column of this.columns) {
      if (Array.isArray(wing[column.key])) wing[column.key] = wing[column.key].slice(0, -1);
    }
    this.fill(wing);
  }
}
