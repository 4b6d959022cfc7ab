// Files made in the browser: JSON, CSV and PNG downloads.

export function downloadBlob(name, blob) {
  const url = URL.createObjectURL(blob);
  const link = document.createElement("a");
  link.href = url;
  link.download = name;
  document.body.append(link);
  link.click();
  link.remove();
  setTimeout(() => URL.revokeObjectURL(url), 10_000);
}

export function downloadText(name, type, text) {
  downloadBlob(name, new Blob([text], { type }));
}

export function downloadJSON(name, value) {
  downloadText(name, "application/json", JSON.stringify(value, null, 2) + "\n");
}

function csvCell(value) {
  if (value == null) return "";
  const text = String(value);
  return /[",\n]/.test(text) ? `"${text.replaceAll('"', '""')}"` : text;
}

/** CSV text from `columns` ([header, list of values]); shorter columns are padded with blanks. */
export function toCSV(columns) {
  const rows = Math.max(...columns.map(([, values]) => values.length));
  const lines = [columns.map(([header]) => csvCell(header)).join(",")];
  for (let i = 0; i < rows; i++) lines.push(columns.map(([, values]) => csvCell(values[i])).join(","));
  return lines.join("\n") + "\n";
}
