// Where an answer leaves the model's validity (a response's `validity` findings), in the page's
// words: their titles, short names for a table cell, and a list item for each.

/** What each code of a response's `validity` is called on the page (the API documents them). */
export const FINDING_TITLES = {
  large_deflection: "Large deflection",
  large_twist: "Large twist",
  section_stall: "Sections past stall",
  near_divergence: "Near divergence",
};

/** One word per code, for a table's cell. */
export const SHORT_FINDINGS = { large_deflection: "deflection", large_twist: "twist", section_stall: "stall", near_divergence: "near divergence" };

export const titleOf = (code) => FINDING_TITLES[code] ?? code.replaceAll("_", " ");

/** The distinct codes of `findings`, in order. */
export const codesOf = (findings) => [...new Set(findings.map((f) => f.code))];

/** A list item: the finding's title and its message. */
export function findingItem(finding) {
  const item = document.createElement("li");
  item.dataset.code = finding.code;
  if (finding.measure) item.dataset.measure = finding.measure;
  const title = document.createElement("strong");
  title.textContent = `${titleOf(finding.code)}.`;
  item.append(title, finding.message);
  return item;
}
