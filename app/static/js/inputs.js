// Inputs rendered from descriptors (editor/fields.js says what a descriptor has): a labelled
// field, a table's header cells, and the value a control gives a request. Every field rendered
// with render() is kept by its key in state.controls, so any module reads or sets a field it
// knows by name (value, setControl).

import { state } from "./state.js";

let uid = 0;

/** A labelled input (or select, or checkbox) for `field`, appended to `parent`; returns the
 * control. kind: "number" (default), "integer", "select", "text" or "flag" (a checkbox). */
export function renderField(field, parent, { form } = {}) {
  const id = `f-${field.key}`;
  const wrap = document.createElement("div");
  wrap.className = "field";
  const label = document.createElement("label");
  label.htmlFor = id;
  label.textContent = field.label;
  if (field.unit) {
    const unit = document.createElement("span");
    unit.className = "unit";
    unit.textContent = ` [${field.unit}]`;
    label.append(unit);
  }
  let control;
  if (field.kind === "select") {
    control = document.createElement("select");
    for (const [value, text] of field.options) {
      const option = document.createElement("option");
      option.value = value;
      option.textContent = text;
      control.append(option);
    }
  } else {
    control = document.createElement("input");
    if (field.kind === "text") {
      control.type = "text";
    } else if (field.kind === "flag") {
      control.type = "checkbox";
    } else {
      control.type = "number";
      control.step = field.kind === "integer" ? "1" : "any";
      control.inputMode = field.kind === "integer" ? "numeric" : "decimal";
    }
  }
  control.id = id;
  control.name = field.key;
  if (field.kind === "flag") control.checked = Boolean(field.value);
  else control.value = field.value == null ? "" : String(field.value);
  if (field.placeholder) control.placeholder = field.placeholder;
  if (field.path) control.dataset.path = field.path;
  if (form) control.setAttribute("form", form);
  wrap.append(label, control);
  if (field.flightMode) wrap.dataset.flightMode = field.flightMode;
  if (field.hint) {
    const hint = document.createElement("p");
    hint.className = "hint";
    hint.id = `${id}-hint-${uid++}`;
    hint.textContent = field.hint;
    control.setAttribute("aria-describedby", hint.id);
    wrap.append(hint);
  }
  parent.append(wrap);
  return control;
}

/** Render `fields` into `parent`, each kept in state.controls by its key. */
export function render(fields, parent, options = {}) {
  for (const field of fields) {
    const control = renderField(field, parent, options);
    state.controls[field.key] = { field, control };
  }
}

/** The value the field `key` gives a request (controlValue). */
export function value(key) {
  const { field, control } = state.controls[key];
  return controlValue(control, field.kind);
}

/** Set the field `key` to `v`; undefined or null leaves it as it is. */
export function setControl(key, v) {
  const entry = state.controls[key];
  if (v === undefined || v === null || !entry) return;
  if (entry.field.kind === "flag") entry.control.checked = Boolean(v);
  else entry.control.value = String(v);
}

/** Set the field `key` to `v`, or back to its descriptor's default when `v` is absent. */
export function resetControl(key, v) {
  const entry = state.controls[key];
  if (!entry) return;
  const given = v === undefined || v === null ? entry.field.value : v;
  if (entry.field.kind === "flag") entry.control.checked = Boolean(given);
  else entry.control.value = given == null ? "" : String(given);
}

/** Replace `table`'s header with a "#" corner and one column header per column ({key, label,
 * unit}), each with the id `${idPrefix}${key}` and, where `describe(key)` gives one, a title. */
export function fillHeader(table, columns, { idPrefix, describe = () => undefined }) {
  const head = table.tHead ?? table.createTHead();
  head.replaceChildren();
  const headRow = head.insertRow();
  const corner = document.createElement("th");
  corner.scope = "col";
  corner.textContent = "#";
  headRow.append(corner);
  for (const column of columns) {
    const th = document.createElement("th");
    th.scope = "col";
    th.id = `${idPrefix}${column.key}`;
    th.textContent = column.label;
    if (column.unit) {
      const unit = document.createElement("span");
      unit.className = "unit";
      unit.textContent = ` [${column.unit}]`;
      th.append(unit);
    }
    const description = describe(column.key);
    if (description) th.title = description;
    headRow.append(th);
  }
}

/** A body row's index cell: a row header `i`, its id `id`. */
export function rowHeader(row, id, i) {
  const index = document.createElement("th");
  index.scope = "row";
  index.id = id;
  index.textContent = String(i);
  row.append(index);
}

/** The value of a control as the request should carry it: a number, or null when empty or not a
 * number (the service then names the field and says why), the text of a text/select field, or
 * whether a checkbox is ticked. */
export function controlValue(control, kind) {
  if (kind === "select" || kind === "text") return control.value;
  if (kind === "flag") return control.checked;
  const text = control.value.trim();
  if (text === "") return null;
  const value = Number(text);
  return Number.isFinite(value) ? value : null;
}

/** obj with `value` set at a dotted path ("flight.velocity"), creating objects on the way. */
export function setPath(obj, path, value) {
  const parts = path.split(".");
  let node = obj;
  for (const part of parts.slice(0, -1)) {
    node[part] ??= {};
    node = node[part];
  }
  node[parts.at(-1)] = value;
  return obj;
}

export function getPath(obj, path) {
  return path.split(".").reduce((node, part) => (node == null ? undefined : node[part]), obj);
}

/** An input's limits (min, max) from a JSON-schema property (its `anyOf`/`oneOf` numbers too). */
export function applyLimits(control, property) {
  const number = [property, ...(property?.anyOf ?? []), ...(property?.oneOf ?? [])].find(
    (p) => p && (p.minimum !== undefined || p.maximum !== undefined || p.exclusiveMinimum !== undefined),
  );
  if (!number || control.type !== "number") return;
  const min = number.minimum ?? number.exclusiveMinimum;
  const max = number.maximum ?? number.exclusiveMaximum;
  if (min !== undefined) control.min = String(min);
  if (max !== undefined) control.max = String(max);
}
