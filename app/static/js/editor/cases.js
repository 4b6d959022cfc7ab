// The load cases of a sizing run (POST /loads `cases`), one row each: a name, the trimmed
// flight's airspeed, weight, load factor or lift, and a rolling pull-out's aileron and roll rate.
// An empty cell is not sent (the API's default: a load factor of 1, no aileron); what a loaded
// case has that no column shows (its flight's density, altitude or equivalent airspeed) is kept
// with its row and sent as given.

import { RowTable } from "./rows.js";

// `flight`: the column is a key of the case's flight, else of the case itself.
export const CASE_COLUMNS = [
  { key: "name", label: "name", unit: "", kind: "text", value: "" },
  { key: "velocity", label: "airspeed", unit: "m/s", value: null, flight: true },
  { key: "weight", label: "weight", unit: "N", value: null, flight: true },
  { key: "load_factor", label: "load factor", unit: "-", value: null, flight: true },
  { key: "lift", label: "or lift", unit: "N", value: null, flight: true },
  { key: "aileron", label: "aileron", unit: "deg", value: null },
  { key: "roll_rate", label: "roll rate", unit: "rad/s", value: null },
];

/** The page's cases before any is loaded: a pull-up, cruise and a push-over of the study's wing
 * at its 300 N. */
export const DEFAULT_CASES = [
  { name: "pull-up", flight: { velocity: 12, weight: 300, load_factor: 2.5 } },
  { name: "cruise", flight: { velocity: 14, weight: 300 } },
  { name: "push-over", flight: { velocity: 12, weight: 300, load_factor: -1 } },
];

const SHOWN = new Set(CASE_COLUMNS.map((c) => c.key));

/** The columns' descriptions and limits from the running API's schemas (FlightCase, its
 * flights), without their defaults: an empty cell stays empty, and is not sent. */
export function caseSchema(schemas) {
  const sources = [schemas.FlightCase, schemas.FlightAtWeight, schemas.FlightAtLift];
  const properties = {};
  for (const { key } of CASE_COLUMNS) {
    const found = sources.map((schema) => schema?.properties?.[key]).find(Boolean);
    if (found) {
      const { default: _, ...described } = found;
      properties[key] = described;
    }
  }
  return { properties };
}

export class CaseTable extends RowTable {
  constructor(table) {
    super(table, { columns: CASE_COLUMNS, path: "cases", id: "case" });
    this.kept = []; // per row: {flight: {...}, case: {...}} what no column shows
  }

  /** Fill with `cases` (FlightCase bodies), each row keeping what no column shows. */
  load(cases) {
    this.kept = cases.map((c) => ({
      flight: Object.fromEntries(Object.entries(c.flight ?? {}).filter(([k]) => !SHOWN.has(k))),
      case: Object.fromEntries(Object.entries(c).filter(([k]) => k !== "flight" && !SHOWN.has(k))),
    }));
    this.fill(cases.map((c) => ({ ...c.flight, ...c, flight: undefined })));
  }

  fill(records) {
    super.fill(records);
    // A 422 names the case's flight key (cases[0].flight.velocity): shown next to its cell.
    for (const column of CASE_COLUMNS.filter((c) => c.flight)) {
      for (let i = 0; i < this.rows; i++) {
        this.table.querySelector(`#${this.id}-${column.key}-${i}`).dataset.path = `cases[${i}].flight.${column.key}`;
      }
    }
  }

  /** The cases as the request carries them: the cells given, and each row's kept keys. */
  cases() {
    return this.read().map((record, i) => {
      const kept = this.kept[i] ?? { flight: {}, case: {} };
      const flight = { ...kept.flight };
      const body = { ...kept.case, name: record.name, flight };
      for (const column of CASE_COLUMNS.slice(1)) {
        const v = record[column.key];
        if (v === null) continue;
        if (column.flight) flight[column.key] = v;
        else body[column.key] = v;
      }
      return body;
    });
  }

  /** Append a case: a copy of the last one's flight (or the first default), named anew. */
  addCase() {
    const cases = this.cases();
    const last = cases.at(-1) ?? DEFAULT_CASES[0];
    this.load([...cases, { ...last, name: `case ${cases.length + 1}` }]);
  }

  removeCase() {
    this.load(this.cases().slice(0, -1));
  }
}
