// An operation's airspeeds (`velocities`): a range {start, stop, count}, or a list of airspeeds
// as given, in their order. The list, when it has any, is what is sent; editing the range
// empties it, so the range is sent again.

import { render, resetControl, setControl, value } from "../inputs.js";
import { state } from "../state.js";

/** The fields of airspeeds named `prefix` ("sweep": #f-sweep_start ...), `defaults` the range's. */
export function airspeedFields(prefix, { start, stop, count }) {
  return [
    { key: `${prefix}_start`, path: "velocities.start", label: "From", unit: "m/s", value: start },
    { key: `${prefix}_stop`, path: "velocities.stop", label: "To", unit: "m/s", value: stop },
    { key: `${prefix}_count`, path: "velocities.count", label: "Airspeeds", unit: "-", kind: "integer", value: count },
    {
      key: `${prefix}_list`,
      path: "velocities",
      label: "Or these airspeeds",
      unit: "m/s",
      kind: "text",
      value: "",
      placeholder: "e.g. 6, 10, 12",
      hint: "Comma-separated, in order; replaces the range when given.",
    },
  ];
}

export class Airspeeds {
  /** Render the fields of `prefix` into `parent` (`form`: the form whose Enter runs them). */
  constructor(prefix, parent, defaults, { form } = {}) {
    this.prefix = prefix;
    this.fields = airspeedFields(prefix, defaults);
    render(this.fields, parent, { form });
    for (const end of ["start", "stop", "count"]) {
      this.control(end).addEventListener("input", () => {
        this.control("list").value = "";
      });
    }
  }

  control(part) {
    return state.controls[`${this.prefix}_${part}`].control;
  }

  /** What the request's `velocities` is: the list (numbers as typed; a word that is not one is
   * sent as it is, for the service to name), or the range. */
  read() {
    const text = this.control("list").value.trim();
    if (text) {
      return text
        .split(/[\s,;]+/)
        .filter(Boolean)
        .map((word) => (Number.isFinite(Number(word)) ? Number(word) : word));
    }
    return { start: value(`${this.prefix}_start`), stop: value(`${this.prefix}_stop`), count: value(`${this.prefix}_count`) };
  }

  /** A body's `velocities` into the fields: a list shown as given (its range beside it), a range
   * into the range's fields; none leaves the fields as they are. */
  load(velocities) {
    if (Array.isArray(velocities) && velocities.length) {
      const numbers = velocities.filter((v) => typeof v === "number");
      setControl(`${this.prefix}_start`, numbers.length ? Math.min(...numbers) : undefined);
      setControl(`${this.prefix}_stop`, numbers.length ? Math.max(...numbers) : undefined);
      setControl(`${this.prefix}_count`, velocities.length);
      this.control("list").value = velocities.join(", ");
    } else if (velocities && typeof velocities === "object") {
      for (const end of ["start", "stop", "count"]) resetControl(`${this.prefix}_${end}`, velocities[end]);
      this.control("list").value = "";
    }
  }
}
