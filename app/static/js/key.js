// The API key the page sends when the service has keys (FLEXWING_API_KEYS_FILE). It is typed
// once per tab, kept in this tab's sessionStorage only (gone when the tab closes, never in a URL
// or a cookie) and sent as `Authorization: Bearer <key>`. The key box stays hidden until the
// service asks for a key (a 401 problem) or one is kept.

const STORAGE = "flexwing.apiKey";
const $ = (id) => document.getElementById(id);

/** The kept key, or "". */
export function apiKey() {
  try {
    return sessionStorage.getItem(STORAGE) ?? "";
  } catch {
    return ""; // storage refused (e.g. a sandboxed frame): no key
  }
}

function keep(key) {
  try {
    if (key) sessionStorage.setItem(STORAGE, key);
    else sessionStorage.removeItem(STORAGE);
  } catch {
    // storage refused: the key lasts as long as nothing else asks
  }
}

/** The request headers that carry the kept key (none without one). */
export function authorization() {
  const key = apiKey();
  return key ? { authorization: `Bearer ${key}` } : {};
}

function showState() {
  $("api-key-state").textContent = apiKey()
    ? "A key is kept for this tab."
    : "No key yet: ask the service's operator for one.";
  $("api-key-forget").disabled = !apiKey();
}

/** Show the key box, open, its input focused: the service wants a (different) key. */
export function askForKey() {
  const box = $("api-key-box");
  box.hidden = false;
  box.open = true;
  showState();
  $("api-key").focus({ preventScroll: true });
}

/** Wire the key box; `onKey()` runs after a key is entered. */
export function installKeyBox(onKey) {
  $("api-key-box").hidden = !apiKey();
  showState();
  $("api-key-form").addEventListener("submit", (event) => {
    event.preventDefault();
    keep($("api-key").value.trim());
    $("api-key").value = "";
    $("api-key-box").open = false;
    showState();
    onKey();
  });
  $("api-key-forget").addEventListener("click", () => {
    keep("");
    showState();
  });
}
