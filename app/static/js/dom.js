// Small helpers every module uses: an element by id, a new element, and numbers as words.

export const $ = (id) => document.getElementById(id);

/** A new `tag` element with `attributes` (dataset entries as `data: {...}`, `hidden: true`,
 * anything else as a property or attribute) and `children` (nodes or text). */
export function el(tag, attributes = {}, ...children) {
  const element = document.createElement(tag);
  for (const [name, value] of Object.entries(attributes)) {
    if (value === undefined || value === null || value === false) continue;
    if (name === "data") Object.assign(element.dataset, value);
    else if (name === "className" || name === "id" || name === "type" || name === "textContent") element[name] = value;
    else element.setAttribute(name, value === true ? "" : String(value));
  }
  element.append(...children.filter((child) => child !== null && child !== undefined));
  return element;
}

/** `x` to `digits` decimals, "n/a" when absent. */
export const f = (x, digits) => (x == null ? "n/a" : x.toFixed(digits));

/** `x` to `digits` decimals with its sign, "n/a" when absent. */
export const signed = (x, digits) => (x == null ? "n/a" : `${x >= 0 ? "+" : ""}${x.toFixed(digits)}`);

/** A stress [Pa] in MPa, one decimal. */
export const MPa = (x) => (x == null ? "n/a" : `${(x / 1e6).toFixed(1)} MPa`);

/** "1 surface", "2 surfaces". */
export const plural = (n, word) => `${n} ${word}${n === 1 ? "" : "s"}`;
