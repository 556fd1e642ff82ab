// The machine settings: the inputs read as the planner's options (numbers checked, the direction
// mode turned into the options it means), and what this browser keeps between visits (the
// settings in localStorage "furrow.settings", the edited field in "furrow.session").
import { $, history, OPTION_INPUTS, state, ui } from "./app.js";
import { parseRanges, plannerInput, referenceLineOf, toCollection } from "./editor.js";
import { replan } from "./planning.js";

const CHOICES = new Set(["headlandMode", "headlandOrder", "headlandCorners", "objective", "search", "decomposition", "pattern", "reverse", "direction"]); // <select>s: their value is the option
const BOOLEANS = new Set(["reverse"]); // <select>s of "true" and "false"
const OPTIONAL = new Set(["bearing", "obstacleThreshold", "referenceEdge", "curvatureRate"]); // empty: null, the planner's default
const TEXTS = new Set(["forbiddenBearings"]); // read by their own parser
const AUTO = new Set(["headlandPasses"]); // empty: "auto", the planner works the number out
const WORKED_AS = "workedAs"; // not an option: "passes" asks for headlandPasses "all"
const SETTINGS_KEY = "furrow.settings";
const SESSION_KEY = "furrow.session";
const KEPT_INPUTS = [...OPTION_INPUTS, "drive-speed", "tile-url", "way-turning"]; // what persists across visits

/**
 * The planner options from the inputs: `{ options, problems }`, where problems lists inputs
 * that do not hold a number (the planner itself checks the ranges).
 */
export function readOptions() {
  const options = {};
  const problems = [];
  const names = {
    width: "working width",
    headlandPasses: "number of headland passes",
    turnRadius: "turning radius",
    bearing: "bearing",
    obstacleThreshold: "obstacle threshold",
  };
  const passesOnly = ui.inputs[WORKED_AS].value === "passes";
  for (const [id, input] of Object.entries(ui.inputs)) {
    if (TEXTS.has(id) || id === WORKED_AS) continue;
    if (id === "headlandPasses" && passesOnly) {
      options[id] = "all";
      continue;
    }
    if (CHOICES.has(id)) {
      options[id] = BOOLEANS.has(id) ? input.value === "true" : input.value;
      continue;
    }
    const text = input.value.trim();
    const badInput = input.validity.badInput; // text the number input cannot read, e.g. "1e"
    if (OPTIONAL.has(id) && text === "" && !badInput) {
      options[id] = null;
      continue;
    }
    if (AUTO.has(id) && text === "" && !badInput) {
      options[id] = "auto";
      continue;
    }
    const value = Number(text);
    if (text === "" || badInput || !Number.isFinite(value)) {
      problems.push({ id, message: `Enter a number for the ${names[id]}.` });
      continue;
    }
    options[id] = value;
  }
  const forbidden = parseRanges(ui.inputs.forbiddenBearings.value);
  if (forbidden) options.forbiddenBearings = forbidden;
  else problems.push({ id: "forbiddenBearings", message: "Write the forbidden bearings as ranges, e.g. 20-70, 100-120." });
  directionOptions(options, problems);
  const extras = history.doc ? plannerInput(history.doc) : null;
  options.entrance = extras?.entrance ?? null;
  return { options, problems };
}

/** The direction mode as the planner's options (`direction` and the one reference it uses). */
export function directionOptions(options, problems) {
  const mode = options.direction;
  const edge = options.referenceEdge;
  delete options.referenceEdge;
  switch (mode) {
    case "fixed":
      options.direction = "fixed";
      if (options.bearing == null && !problems.some((p) => p.id === "bearing")) {
        problems.push({ id: "bearing", message: "Enter the bearing to drive along." });
      }
      break;
    case "edge":
      options.direction = "reference";
      options.bearing = null;
      if (edge == null) problems.push({ id: "referenceEdge", message: "Tap the boundary edge to drive along (or enter its number)." });
      else options.referenceEdge = edge;
      break;
    case "line": {
      options.direction = "reference";
      options.bearing = null;
      const line = history.doc ? referenceLineOf(history.doc) : null;
      if (!line) problems.push({ id: "direction", message: "Draw the AB line on the map: tap A, then B." });
      else options.referenceLine = line;
      break;
    }
    case "longest-edge":
      options.direction = "longest-edge";
      options.bearing = null;
      break;
    default:
      options.direction = "search";
      options.bearing = null;
  }
}

/** The folded options' values, beside their title: "All around, last, 6 m, shortest time". */
export function showMoreState() {
  const text = (id) => ui.inputs[id].selectedOptions?.[0]?.textContent ?? "";
  const threshold = ui.inputs.obstacleThreshold.value.trim();
  const direction = ui.inputs.direction.value;
  ui.moreState.textContent = [
    ...(direction === "search" || direction === "fixed" ? [] : [text("direction").toLowerCase()]),
    text("headlandMode"),
    text("headlandOrder").replace(/ \(.*\)$/, "").toLowerCase(),
    threshold === "" ? "1 width" : `${threshold} m`,
    text("objective").toLowerCase(),
  ].join(", ");
}

export function settingsChanged() {
  showDependentInputs();
  saveSettings();
  replan();
}

/** The inputs that depend on others: the edge number on the direction, the number of passes
 * on how the field is worked (passes to the middle: as many as it holds). */
export function showDependentInputs() {
  $("edge-input").hidden = ui.inputs.direction.value !== "edge";
  ui.inputs.headlandPasses.disabled = ui.inputs[WORKED_AS].value === "passes";
}

/** A bearing, an edge number or an AB line belong to one field: another starts from the search. */
export function forgetFieldReferences() {
  ui.inputs.bearing.value = "";
  ui.inputs.referenceEdge.value = "";
  if (ui.inputs.direction.value !== "longest-edge") ui.inputs.direction.value = "search";
  showDependentInputs();
}

/** The field's suggested machine settings; the headland mode, order and obstacle threshold are
 * the user's, and stay. */
export function applySuggested(entry) {
  const set = (id, v) => {
    ui.inputs[id].value = Number.isFinite(v) ? String(v) : "";
  };
  set("width", entry.width);
  set("headlandPasses", entry.headlandPasses);
  set("turnRadius", entry.turnRadius);
  set("bearing", null);
  forgetFieldReferences();
}

/** The inputs an error message names, e.g. "option `width` is -1". */
export function inputsNamedIn(error) {
  const ids = new Set();
  for (const m of String(error.message).matchAll(/`(\w+)`/g)) if (m[1] in ui.inputs) ids.add(m[1]);
  if (error.code === "headland_consumes_field") ids.add("width");
  return [...ids];
}

export function markInvalid(ids) {
  for (const [id, input] of Object.entries(ui.inputs)) {
    if (ids.includes(id)) input.setAttribute("aria-invalid", "true");
    else input.removeAttribute("aria-invalid");
  }
}

export function storage() {
  try {
    return window.localStorage;
  } catch {
    return null; // blocked: nothing is kept
  }
}

export function saveSettings() {
  const values = {};
  for (const id of KEPT_INPUTS) values[id] = $(id).value;
  try {
    storage()?.setItem(SETTINGS_KEY, JSON.stringify(values));
  } catch {
    // full or blocked: the settings hold for this visit
  }
}

export function restoreSettings() {
  let values;
  try {
    values = JSON.parse(storage()?.getItem(SETTINGS_KEY) ?? "null");
  } catch {
    values = null;
  }
  if (!values || typeof values !== "object") return;
  for (const id of KEPT_INPUTS) {
    const el = $(id);
    const v = values[id];
    if (typeof v !== "string") continue;
    if (el instanceof HTMLSelectElement && ![...el.options].some((o) => o.value === v)) continue;
    el.value = v;
  }
}

export function saveSession() {
  const doc = history.doc;
  if (!doc) return;
  try {
    storage()?.setItem(SESSION_KEY, JSON.stringify({ name: state.entry?.name ?? "Field", doc }));
  } catch {
    // too large for the browser's storage: the field holds for this visit
  }
}

export function readSession() {
  try {
    const s = JSON.parse(storage()?.getItem(SESSION_KEY) ?? "null");
    return s && typeof s.name === "string" && toCollection(s.doc) ? s : null;
  } catch {
    return null;
  }
}
