// An editable table of records, one row per record (the wing's control surfaces, its concentrated
// masses): read into a list of the request. Each cell's data-path names the request's value, so a
// 422 about it (wing.control_surfaces[1].hinge) is shown next to that cell.

import { applyLimits, controlValue, fillHeader, rowHeader } from "../inputs.js";

export class RowTable {
  /** `table`: a <table> with a <thead> and <tbody>; `columns`: [{key, label, unit, kind, value,
   * options}] (kind "text", "select", "integer" or a number); `path`: the request's list
   * ("wing.control_surfaces"); `id`: the prefix of the cells' ids ("surface": surface-hinge-0). */
  constructor(table, { columns, path, id, onChange }) {
    this.table = table;
    this.columns = columns;
    this.path = path;
    this.id = id;
    this.onChange = onChange;
    this.schema = null;
    table.addEventListener("input", () => this.onChange?.());
    table.addEventListener("change", () => this.onChange?.());
  }

  /** The records' JSON schema from /openapi.json: its descriptions become the headers' titles, its
   * limits the inputs', its defaults what a loaded record leaves out. */
  setSchema(schema) {
    this.schema = schema;
    this.fill(this.read());
  }

  get rows() {
    return this.table.tBodies[0]?.rows.length ?? 0;
  }

  /** Fill with `records`; a value a record leaves out is the schema's default, else the column's. */
  fill(records) {
    fillHeader(this.table, this.columns, {
      idPrefix: `${this.id}-col-`,
      describe: (key) => this.schema?.properties?.[key]?.description,
    });
    const body = this.table.tBodies[0];
    body.replaceChildren();
    records.forEach((record, i) => {
      const row = body.insertRow();
      rowHeader(row, `${this.id}-row-${i}`, i);
      for (const column of this.columns) {
        const cell = row.insertCell();
        let input;
        if (column.kind === "select") {
          input = document.createElement("select");
          for (const [value, text] of column.options) input.add(new Option(text, value));
        } else {
          input = document.createElement("input");
          input.type = column.kind === "text" ? "text" : "number";
          if (input.type === "number") {
            input.step = column.kind === "integer" ? "1" : "any";
            input.inputMode = column.kind === "integer" ? "numeric" : "decimal";
          }
        }
        input.id = `${this.id}-${column.key}-${i}`;
        input.dataset.path = `${this.path}[${i}].${column.key}`;
        input.setAttribute("aria-labelledby", `${this.id}-col-${column.key} ${this.id}-row-${i}`);
        applyLimits(input, this.schema?.properties?.[column.key]);
        const value = record[column.key] ?? this.schema?.properties?.[column.key]?.default ?? column.value;
        input.value = value == null ? "" : String(value);
        cell.append(input);
      }
    });
  }

  /** The records as the request carries them (an empty number cell: null, which the service names). */
  read() {
    const records = [];
    for (let i = 0; i < this.rows; i++) {
      const record = {};
      for (const column of this.columns) {
        const input = this.table.querySelector(`#${this.id}-${column.key}-${i}`);
        record[column.key] = controlValue(input, column.kind);
      }
      records.push(record);
    }
    return records;
  }

  /** Append `record` (each column's value where it has none). */
  append(record = {}) {
    const defaults = Object.fromEntries(this.columns.map((c) => [c.key, c.value]));
    this.fill([...this.read(), { ...defaults, ...record }]);
  }

  removeRow(i = this.rows - 1) {
    const records = this.read();
    records.splice(i, 1);
    this.fill(records);
  }
}
