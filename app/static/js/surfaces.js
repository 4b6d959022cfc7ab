// The wing's control surfaces (flaps and ailerons), one row each: wing.control_surfaces.

import { CONTROL_SURFACE_COLUMNS } from "./fields.js";
import { RowTable } from "./rows.js";

export class ControlSurfaceTable extends RowTable {
  constructor(table, { onChange } = {}) {
    super(table, { columns: CONTROL_SURFACE_COLUMNS, path: "wing.control_surfaces", id: "surface", onChange });
  }

  /** Add a surface: the study's aileron first, then a flap inboard of it, then copies. */
  addRow() {
    const surfaces = this.read();
    const defaults = Object.fromEntries(CONTROL_SURFACE_COLUMNS.map((c) => [c.key, c.value]));
    const taken = new Set(surfaces.map((s) => s.name));
    let next = defaults;
    if (taken.has("aileron")) next = { ...defaults, name: "flap", kind: "flap", start: 0, end: 0.45, hinge: 0.5 };
    for (let n = 2; taken.has(next.name); n++) next = { ...next, name: `${next.kind}-${n}` };
    this.append(next);
  }
}
