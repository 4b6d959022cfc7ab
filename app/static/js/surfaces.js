// The wing's control surfaces (flaps and ailerons): an editable table, one row per surface, read
// into the request's wing.control_surfaces. Each cell's data-path names the request's value, so a
// 422 about it (wing.control_surfaces[1].hinge) is shown next to that cell.

import { CONTROL_SURFACE_COLUMNS, applyLimits, fillHeader, rowHeader } from "./fields.js";

export class ControlSurfaceTable {
  /** `table`: a <table> with a <thead> and <tbody>; `schema`: ControlSurface from /openapi.json
   * (its descriptions become the headers' titles, its limits the inputs'), or null. */
  constructor(table, { onChange } = {}) {
    this.table = table;
    this.onChange = onChange;
    this.schema = null;
    this.surfaces = [];
    table.addEventListener("input", () => this.onChange?.());
    table.addEventListener("change", () => this.onChange?.());
  }

  setSchema(schema) {
    this.schema = schema;
    this.fill(this.read());
  }

  get rows() {
    return this.table.tBodies[0]?.rows.length ?? 0;
  }

  /** Fill with `surfaces` ([{name, start, end, hinge, deflection, kind}, ...]). */
  fill(surfaces) {
    fillHeader(this.table, CONTROL_SURFACE_COLUMNS, {
      idPrefix: "surface-col-",
      describe: (key) => this.schema?.properties?.[key]?.description,
    });
    const body = this.table.tBodies[0];
    body.replaceChildren();
    surfaces.forEach((surface, i) => {
      const row = body.insertRow();
      rowHeader(row, `surface-row-${i}`, i);
      for (const column of CONTROL_SURFACE_COLUMNS) {
        const cell = row.insertCell();
        let input;
        if (column.kind === "select") {
          input = document.createElement("select");
          for (const [value, text] of column.options) input.add(new Option(text, value));
        } else {
          input = document.createElement("input");
          input.type = column.kind === "text" ? "text" : "number";
          if (input.type === "number") {
            input.step = "any";
            input.inputMode = "decimal";
          }
        }
        input.id = `surface-${column.key}-${i}`;
        input.dataset.path = `wing.control_surfaces[${i}].${column.key}`;
        input.setAttribute("aria-labelledby", `surface-col-${column.key} surface-row-${i}`);
        applyLimits(input, this.schema?.properties?.[column.key]);
        // What a loaded surface leaves out is the API's default (a new row is given whole).
        const value = surface[column.key] ?? this.schema?.properties?.[column.key]?.default ?? column.value;
        input.value = value == null ? "" : String(value);
        cell.append(input);
      }
    });
    this.surfaces = surfaces;
  }

  /** The surfaces as the request carries them (an empty number cell: null, which the service
   * names). */
  read() {
    const surfaces = [];
    for (let i = 0; i < this.rows; i++) {
      const surface = {};
      for (const column of CONTROL_SURFACE_COLUMNS) {
        const input = this.table.querySelector(`#surface-${column.key}-${i}`);
        if (column.kind === "select" || column.kind === "text") surface[column.key] = input.value;
        else {
          const text = input.value.trim();
          const value = text === "" ? null : Number(text);
          surface[column.key] = Number.isFinite(value) ? value : null;
        }
      }
      surfaces.push(surface);
    }
    return surfaces;
  }

  /** Add a surface: the study's aileron first, then a flap inboard of it, then copies. */
  addRow() {
    const surfaces = this.read();
    const defaults = Object.fromEntries(CONTROL_SURFACE_COLUMNS.map((c) => [c.key, c.value]));
    const taken = new Set(surfaces.map((s) => s.name));
    let next = defaults;
    if (taken.has("aileron")) next = { ...defaults, name: "flap", kind: "flap", start: 0, end: 0.45, hinge: 0.5 };
    for (let n = 2; taken.has(next.name); n++) next = { ...next, name: `${next.kind}-${n}` };
    this.fill([...surfaces, next]);
  }

  removeRow(i = this.rows - 1) {
    const surfaces = this.read();
    surfaces.splice(i, 1);
    this.fill(surfaces);
  }
}
