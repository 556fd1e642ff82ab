// furrow viewer shell: pick a bundled field or open a GeoJSON file, set the machine, see the
// plan. Every input change re-plans at once (the planner takes a few milliseconds). What the
// planner says (an error, or warnings) is shown in words on the map beside the feature it
// concerns (notes.js), and listed in the panel.
//
// The planner runs in a Web Worker (planner.js): the newest edit plans next, older results are
// never drawn over newer ones.
//
// State for tests and debugging: body[data-plan-state] = loading | planning | ready | error
// (planning: the drawn plan is not that of the newest edit yet), and after each plan
// body[data-swath-count], body[data-plan-ms] and body[data-plan-seq] (which edit it is of); window.furrow holds the last plan or error,
// and window.furrow.loadField(geojsonTextOrObject, name) plans a field given by the page;
// window.furrow.view.drawn says what the last frame drew (the obstacle class labels among it).
//
// Editing (edit-tool.js on the document of editor.js): every change, also each step of a drag,
// re-plans; a finished change is a step of the undo history, and the edited field is kept in this
// browser (localStorage "furrow.session") with the settings ("furrow.settings"), so a reload in the
// cab brings back the field as drawn.
import { BearingDial } from "./dial.js";
import { Driver } from "./drive.js";
import { EditTool } from "./edit-tool.js";
import {
  History,
  editableRings,
  emptyField,
  parseRanges,
  plannerInput,
  referenceLineOf,
  roleOf,
  setProperties,
  toCollection,
} from "./editor.js";
import { ERROR_HINTS, MapNotes, featureLabel, sentence } from "./notes.js";
import { initPlanner, runPlan } from "./planner.js";
import {
  fieldParts,
  fieldScene,
  inputFeatures,
  outlineAnchor,
  parseForDrawing,
  pathBounds,
  planScene,
  projectFeature,
  projectionFor,
} from "./scene.js";
import { PlanView } from "./view.js";
import { WayOut } from "./way.js";

const DEFAULT_FIELD = "obstacle-types";
const OPTION_INPUTS = [
  "width",
  "headlandPasses",
  "turnRadius",
  "bearing",
  "headlandMode",
  "headlandOrder",
  "obstacleThreshold",
  "objective",
  "search",
  "decomposition",
  "pattern",
  "reverse",
  "direction",
  "referenceEdge",
  "curvatureRate",
  "forbiddenBearings",
];
const CHOICES = new Set(["headlandMode", "headlandOrder", "objective", "search", "decomposition", "pattern", "reverse", "direction"]); // <select>s: their value is the option
const BOOLEANS = new Set(["reverse"]); // <select>s of "true" and "false"
const OPTIONAL = new Set(["bearing", "obstacleThreshold", "referenceEdge", "curvatureRate"]); // empty: null, the planner's default
const TEXTS = new Set(["forbiddenBearings"]); // read by their own parser
const SETTINGS_KEY = "furrow.settings";
const SESSION_KEY = "furrow.session";
const PREVIEW_ABOVE_MS = 100; // full plans slower than this are previewed in one direction while dragging
const KEPT_INPUTS = [...OPTION_INPUTS, "drive-speed", "tile-url", "way-turning"]; // what persists across visits
const OPENED = ":opened"; // value of the field picker's entry for an opened file
const MAX_FILE_BYTES = 64 * 1024 * 1024; // the planner refuses more than 32 MB anyway

const $ = (id) => document.getElementById(id);
const ui = {
  field: $("field"),
  open: $("open-file"),
  file: $("file-input"),
  note: $("field-note"),
  inputs: Object.fromEntries(OPTION_INPUTS.map((id) => [id, $(id)])),
  suggested: $("suggested"),
  more: $("more-options"),
  moreState: $("more-state"),
  status: $("status"),
  summary: $("summary"),
  warnings: $("warnings"),
  message: $("map-message"),
  version: $("version"),
  editBar: $("edit-bar"),
  editHint: $("edit-hint"),
  regionPanel: $("region-panel"),
  regionFrom: $("region-from"),
  regionTo: $("region-to"),
  driveSpeed: $("drive-speed"),
  tileUrl: $("tile-url"),
};

const view = new PlanView($("map"));
const notes = new MapNotes({
  map: document.querySelector(".map"),
  layer: $("map-notes"),
  error: ui.message,
  tools: document.querySelector(".map-tools"),
  view,
});
view.onDraw = () => notes.layout();
const history = new History(null);
const tool = new EditTool({
  view,
  projection: () => state.projection,
  history,
  onChange: (doc, { final }) => applyDoc(doc, { final }),
  onState: () => showEditState(),
  onPickEdge: (edge) => {
    ui.inputs.referenceEdge.value = String(edge);
    ui.inputs.direction.value = "edge";
    settingsChanged();
  },
  onPickLine: () => {
    ui.inputs.direction.value = "line";
    settingsChanged();
  },
  onPickParcel: (feature) => pickParcel(feature),
  onWayTap: (world) => way.tap(world),
});
view.tool = tool;
const driver = new Driver(view, { onState: () => showDriveState() });
// The way out along the tracks: where the machine is and faces, the exit, and the way found.
const way = new WayOut({
  view,
  projection: () => state.projection,
  entrance: () => (history.doc ? plannerInput(history.doc).entrance : null),
  turning: () => $("way-turning").value,
  ready: () => Boolean(state.plan),
  onState: () => showWayState(),
});
view.overlay = (ctx, theme) => {
  driver.draw(ctx, theme);
  way.draw(ctx, theme, tool.mode === "way");
};
let dial = null; // the prohibited region's bearing dial, made when first shown
let tiles = null; // the background map, made when a URL is set
notes.onOpenChange = () => updateHighlights();
const fieldCache = new Map(); // file -> Promise of the field GeoJSON

const state = {
  fields: [], // fields/index.json
  entry: null, // the chosen entry of fields/index.json, or { name, opened: true } for an opened file
  source: null, // what the planner is given: the field's GeoJSON object, or an opened file's text
  field: null, // the field's GeoJSON object as far as it could be read for drawing (or undefined)
  opened: null, // the last opened file: { source, name }
  projection: null,
  features: [], // the input's features (inputFeatures) in the view's metres
  fitPending: false, // fit the view after the next plan (a new field), to its error's place too
  plan: null, // the last good plan
  error: null, // the last error, as { code, message, ... }
  errorHighlight: [], // the outline the error concerns, for the view
  fieldId: 0, // which field is shown: counts fields loaded (edits keep it)
  fullPlanMs: 0, // how long the last full plan took, call to result
  edited: false, // the field was changed in the viewer: the planner gets the edited document
  loadToken: 0,
  replanSeq: 0, // replan calls made
  drawnSeq: 0, // the newest replan call whose result is shown
};

window.furrow = {
  get plan() {
    return state.plan;
  },
  /** Replan calls made, and the newest whose result is drawn. */
  get replans() {
    return { made: state.replanSeq, drawn: state.drawnSeq };
  },
  get error() {
    return state.error;
  },
  get field() {
    return state.field ?? state.source;
  },
  get projection() {
    return state.projection;
  },
  get options() {
    return readOptions().options;
  },
  /** The field as edited (a GeoJSON FeatureCollection), and the edit tool. */
  get document() {
    return history.doc;
  },
  tool,
  driver,
  way,
  view,
  replan,
  selectField,
  loadField,
  exportField: fieldText,
  exportPlan: planText,
};

setPlanState("loading");
restoreSettings();
bindControls();
bindEditing();
start();
registerOffline();

/** The theme the user chose last (kept in this browser), day by default. */
function storedTheme() {
  try {
    return localStorage.getItem("furrow.theme") === "night" ? "night" : "day";
  } catch {
    return "day"; // storage blocked: day
  }
}

/** Day or night: the page's colours (style.css) and the map's, which the view re-reads. */
function setTheme(theme) {
  const night = theme === "night";
  if (night) document.documentElement.dataset.theme = "night";
  else delete document.documentElement.dataset.theme;
  const button = $("theme");
  button.setAttribute("aria-pressed", String(night));
  button.textContent = night ? "Day" : "Night";
  try {
    localStorage.setItem("furrow.theme", night ? "night" : "day");
  } catch {
    // storage blocked: the theme holds for this visit
  }
  view.refreshTheme();
}

/** The service worker (sw.js) that lets the page open and plan with no network. */
function registerOffline() {
  if (!("serviceWorker" in navigator) || !window.isSecureContext) return;
  navigator.serviceWorker
    .register("sw.js")
    .then(() => navigator.serviceWorker.ready)
    .then(() => {
      document.body.dataset.offline = "ready";
    })
    .catch((e) => console.warn("furrow viewer: no offline copy", e));
}

async function start() {
  try {
    const [{ version, worker }, fields] = await Promise.all([initPlanner(), fetchJson("fields/index.json")]);
    document.body.dataset.planner = worker ? "worker" : "page";
    ui.version.textContent = `v${version}`;
    if (!Array.isArray(fields) || fields.length === 0) throw new Error("the list of example fields is empty");
    state.fields = fields;
    ui.field.replaceChildren(
      ...fields.map((f) => {
        const option = document.createElement("option");
        option.value = f.name;
        option.textContent = Number.isFinite(f.areaHa) ? `${f.name} (${formatNumber(f.areaHa, 1)} ha)` : f.name;
        return option;
      }),
    );
    ui.field.disabled = false;
    if (state.opened) openedOption(state.opened.name); // a file was opened meanwhile
    if (state.entry?.opened) {
      ui.field.value = OPENED;
      return;
    }
    const wanted = decodeURIComponent(location.hash.slice(1));
    const session = !wanted && readSession();
    if (session) {
      await loadField(session.doc, session.name, { edited: true });
      setTimeout(() => fields.forEach((f) => loadFieldFile(f.file).catch(() => {})), 500);
      return;
    }
    const first = fields.find((f) => f.name === wanted) ?? fields.find((f) => f.name === DEFAULT_FIELD) ?? fields[0];
    await selectField(first.name);
    // Fetch the other fields in the background so that switching works offline.
    setTimeout(() => fields.forEach((f) => loadFieldFile(f.file).catch(() => {})), 500);
  } catch (e) {
    showFailure(`The viewer could not start: ${e.message ?? e}`);
  }
}

function bindControls() {
  ui.field.addEventListener("change", () => {
    if (ui.field.value === OPENED) {
      if (state.opened && !state.entry?.opened) loadField(state.opened.source, state.opened.name);
    } else selectField(ui.field.value);
  });
  ui.open.addEventListener("click", () => ui.file.click());
  ui.file.addEventListener("change", () => {
    const file = ui.file.files?.[0];
    ui.file.value = ""; // so that opening the same file again (after fixing it) reloads it
    if (file) openFile(file);
  });
  bindDrop(document.querySelector(".map"));
  // A bearing typed is a fixed direction; cleared, the search again.
  ui.inputs.bearing.addEventListener("input", () => {
    const fixed = ui.inputs.bearing.value.trim() !== "" || ui.inputs.bearing.validity.badInput;
    if (fixed) ui.inputs.direction.value = "fixed";
    else if (ui.inputs.direction.value === "fixed") ui.inputs.direction.value = "search";
    showDirectionInputs();
    saveSettings();
  });
  ui.inputs.direction.addEventListener("input", () => {
    if (ui.inputs.direction.value === "edge" && ui.inputs.referenceEdge.value.trim() === "") tool.setMode("edge");
    if (ui.inputs.direction.value === "line" && !referenceLineOf(history.doc ?? emptyField())) tool.setMode("abline");
    showDirectionInputs();
  });
  for (const input of Object.values(ui.inputs)) input.addEventListener("input", settingsChanged);
  showDirectionInputs();
  ui.driveSpeed.addEventListener("input", () => {
    saveSettings();
    if (driver.running) driver.start(Number(ui.driveSpeed.value));
  });
  $("way-turning").addEventListener("input", () => {
    saveSettings();
    way.find();
  });
  ui.tileUrl.addEventListener("input", () => {
    saveSettings();
    setBackground(ui.tileUrl.value.trim());
  });
  setBackground(ui.tileUrl.value.trim());
  $("drive").addEventListener("click", () => {
    if (driver.running) driver.stop();
    else if (!driver.start(Number(ui.driveSpeed.value))) ui.status.textContent = "No plan to drive";
  });
  $("new-field").addEventListener("click", newField);
  $("export-field").addEventListener("click", () => download(`${fileName()}.geojson`, fieldText()));
  $("export-plan").addEventListener("click", () => {
    if (state.plan) download(`${fileName()}-plan.geojson`, planText());
  });
  // On a phone (or a short screen) the headland and obstacle options start folded, so that the
  // map (or the plan's figures) are in view; their values show beside the title.
  if (matchMedia("(max-width: 760px), (max-height: 860px)").matches) ui.more.open = false;
  showMoreState();
  ui.suggested.addEventListener("click", () => {
    if (!state.entry || state.entry.opened) return;
    applySuggested(state.entry);
    replan();
  });
  $("fit").addEventListener("click", () => view.fit());
  $("theme").addEventListener("click", () => setTheme(document.documentElement.dataset.theme === "night" ? "day" : "night"));
  setTheme(storedTheme());
  $("zoom-in").addEventListener("click", () => view.zoomAt(1.5));
  $("zoom-out").addEventListener("click", () => view.zoomAt(1 / 1.5));
  window.addEventListener("hashchange", () => {
    const name = decodeURIComponent(location.hash.slice(1));
    if (name && name !== state.entry?.name && state.fields.some((f) => f.name === name)) selectField(name);
  });
}

/** Opening a file by dropping it on the map. Files dropped elsewhere are ignored, not opened by
 * the browser in place of the viewer. */
function bindDrop(map) {
  const hasFiles = (e) => [...(e.dataTransfer?.types ?? [])].includes("Files");
  for (const type of ["dragenter", "dragover"]) {
    map.addEventListener(type, (e) => {
      if (!hasFiles(e)) return;
      e.preventDefault();
      e.dataTransfer.dropEffect = "copy";
      map.classList.add("drop-target");
    });
  }
  map.addEventListener("dragleave", (e) => {
    if (!map.contains(e.relatedTarget)) map.classList.remove("drop-target");
  });
  map.addEventListener("drop", (e) => {
    map.classList.remove("drop-target");
    if (!hasFiles(e)) return;
    e.preventDefault();
    const file = e.dataTransfer.files?.[0];
    if (file) openFile(file);
  });
  for (const type of ["dragover", "drop"]) {
    window.addEventListener(type, (e) => {
      if (!hasFiles(e) || map.contains(e.target)) return;
      e.preventDefault();
      e.dataTransfer.dropEffect = "none";
    });
  }
}

/** Reads a file and plans it as it is. */
async function openFile(file) {
  const name = file.name.replace(/\.(geo)?json$/i, "") || file.name;
  if (file.size > MAX_FILE_BYTES) {
    const mb = Math.round(file.size / 1e6);
    showFailure(`${file.name} is ${mb} MB: too large for a field (at most 32 MB).`, "file_too_large");
    return;
  }
  let text;
  try {
    text = await file.text();
  } catch (e) {
    showFailure(`${file.name} could not be read: ${e.message ?? e}`, "file_unreadable");
    return;
  }
  await loadField(text, name);
}

/**
 * Shows and plans a field given as GeoJSON text or object, with the current settings. The text
 * goes to the planner as it is, so a broken file gets the planner's own error; for drawing, as
 * much of it as can be read is drawn. Resolves to `{ plan, error }`.
 */
async function loadField(input, name = "Opened field", { edited = false } = {}) {
  const token = ++state.loadToken;
  setPlanState("loading");
  try {
    await initPlanner();
  } catch (e) {
    if (token === state.loadToken) showFailure(`The planner could not be loaded: ${e.message ?? e}`);
    return { plan: null, error: state.error };
  }
  if (token !== state.loadToken) return { plan: null, error: null };
  name = String(name || "Opened field");
  state.opened = { source: input, name };
  state.entry = { name, opened: true };
  state.source = input;
  state.field = typeof input === "string" ? parseForDrawing(input) : input;
  if (!edited) forgetFieldReferences();
  state.edited = edited;
  openedOption(name);
  ui.field.value = OPENED;
  ui.field.disabled = false;
  ui.suggested.disabled = true;
  ui.note.textContent = edited ? "Drawn or edited here; planned with the settings below." : "Opened from a file; planned with the settings below.";
  if (location.hash) window.history.replaceState(null, "", location.pathname + location.search);
  startEditing(state.field, { edited });
  showField(state.field);
  return replan();
}

/** The field picker's entry for the opened file, first in the list. */
function openedOption(name) {
  let option = ui.field.querySelector(`option[value="${OPENED}"]`);
  if (!option) {
    option = document.createElement("option");
    option.value = OPENED;
    ui.field.prepend(option);
  }
  option.textContent = state.edited ? `${name} (drawn here)` : `${name} (opened file)`;
}

/** Draws a field (whatever of it can be drawn) without a plan; the next plan fits the view. */
function showField(geojson) {
  notes.hideError();
  notes.clearWarnings();
  state.errorHighlight = [];
  let scene;
  try {
    const parts = fieldParts(geojson);
    const features = inputFeatures(geojson);
    state.projection = projectionFor(parts, features);
    state.features = features.map((f) => projectFeature(f, state.projection));
    scene = fieldScene(parts, state.projection);
  } catch (e) {
    // Drawing never stops the planner from saying what is wrong with the field.
    console.warn("furrow viewer: the field could not be drawn", e);
    state.projection = projectionFor({ boundary: null, obstacles: [], prohibited: [] });
    state.features = [];
    scene = { boundary: null, obstacles: [], prohibited: [], bounds: null };
  }
  view.projection = state.projection;
  view.setField(scene, { fit: false });
  state.fitPending = true;
}

/** Loads a field of the index by name, applies its suggested machine settings, fits and plans. */
async function selectField(name) {
  const entry = state.fields.find((f) => f.name === name);
  if (!entry) return;
  const token = ++state.loadToken;
  setPlanState("loading");
  ui.field.value = entry.name;
  ui.status.textContent = `Loading ${entry.name}…`;
  let field;
  try {
    field = await loadFieldFile(entry.file);
  } catch (e) {
    if (token === state.loadToken) showFailure(`The field ${entry.name} could not be loaded: ${e.message ?? e}`);
    return;
  }
  if (token !== state.loadToken) return; // another field was picked meanwhile
  state.entry = entry;
  state.field = field;
  state.source = field;
  startEditing(field);
  ui.suggested.disabled = false;
  ui.note.textContent = entry.note ?? "";
  if (location.hash.slice(1) !== encodeURIComponent(entry.name)) {
    window.history.replaceState(null, "", `#${encodeURIComponent(entry.name)}`);
  }
  applySuggested(entry);
  showField(field);
  replan();
}

function loadFieldFile(file) {
  if (!fieldCache.has(file)) {
    const p = fetchJson(file);
    p.catch(() => fieldCache.delete(file));
    fieldCache.set(file, p);
  }
  return fieldCache.get(file);
}

async function fetchJson(url) {
  const res = await fetch(url);
  if (!res.ok) throw new Error(`${url}: ${res.status} ${res.statusText}`);
  return res.json();
}

/** The field's suggested machine settings; the headland mode, order and obstacle threshold are
 * the user's, and stay. */
function applySuggested(entry) {
  const set = (id, v) => {
    ui.inputs[id].value = Number.isFinite(v) ? String(v) : "";
  };
  set("width", entry.width);
  set("headlandPasses", entry.headlandPasses);
  set("turnRadius", entry.turnRadius);
  set("bearing", null);
  forgetFieldReferences();
}

/** A bearing, an edge number or an AB line belong to one field: another starts from the search. */
function forgetFieldReferences() {
  ui.inputs.bearing.value = "";
  ui.inputs.referenceEdge.value = "";
  if (ui.inputs.direction.value !== "longest-edge") ui.inputs.direction.value = "search";
  showDirectionInputs();
}

/**
 * The planner options from the inputs: `{ options, problems }`, where problems lists inputs
 * that do not hold a number (the planner itself checks the ranges).
 */
function readOptions() {
  const options = {};
  const problems = [];
  const names = {
    width: "working width",
    headlandPasses: "number of headland passes",
    turnRadius: "turning radius",
    bearing: "bearing",
    obstacleThreshold: "obstacle threshold",
  };
  for (const [id, input] of Object.entries(ui.inputs)) {
    if (TEXTS.has(id)) continue;
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
function directionOptions(options, problems) {
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

/** "Direction per block, 3 directions" with the candidates' times for auto. */
function decompositionText(d) {
  if (!d) return "–";
  const names = {
    none: "One direction",
    boustrophedon: "Cells, one direction",
    "split-merge": "Direction per block",
  };
  const chosen = d.candidates?.find((c) => c.method === d.method);
  const directions = chosen ? chosen.bearings_deg.length : 1;
  let text = `${names[d.method] ?? d.method}${directions > 1 ? `, ${directions} directions` : ""}`;
  if (d.requested === "auto" && d.candidates?.length > 1) {
    const others = d.candidates
      .filter((c) => c.method !== d.method)
      .map((c) => `${names[c.method] ?? c.method} ${duration(c.estimated_time_s)}`);
    text += ` (fastest; ${others.join(", ")})`;
  }
  return text;
}

/** The folded options' values, beside their title: "All around, last, 6 m, shortest time". */
function showMoreState() {
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

/**
 * Plans the current field with the current inputs (in the planner's worker) and shows the result;
 * resolves to `{ plan, error }` as shown once this call's plan (or a newer one) is drawn. Calls
 * made while one plans replace each other: only the newest runs next, and a result older than
 * the one drawn is never drawn.
 */
async function replan(how) {
  showMoreState();
  if (state.source == null) return { plan: null, error: null };
  const seq = ++state.replanSeq;
  const { options, problems } = readOptions();
  // While a vertex is dragged on a field whose plan takes more than a few frames, each step is
  // planned in one direction (a fraction of the time of comparing decompositions); the release
  // plans it in full.
  const preview = how?.preview === true && state.fullPlanMs > PREVIEW_ABOVE_MS && options.decomposition !== "none";
  if (preview) options.decomposition = "none";
  markInvalid(problems.map((p) => p.id));
  if (problems.length) {
    state.drawnSeq = seq;
    showPlanError({ code: "invalid_option", message: problems.map((p) => p.message).join(" ") }, { local: true });
    return { plan: state.plan, error: state.error };
  }
  setPlanState("planning");
  const fieldId = state.fieldId;
  const result = await runPlan(state.source, options);
  if (result.stale || seq <= state.drawnSeq || fieldId !== state.fieldId) {
    // A newer edit (or another field) came first: its plan is drawn instead. (An older edit's
    // plan of the same field is drawn while the newest plans: a drag shows the plan follow.)
    return { plan: state.plan, error: state.error };
  }
  state.drawnSeq = seq;
  const fit = state.fitPending;
  state.fitPending = false;
  if (!preview && !result.error) state.fullPlanMs = result.ms;
  document.body.dataset.planPreview = String(preview);
  if (result.error) showPlanError(result.error);
  else showPlan(result.plan, options, result.ms);
  if (preview && !result.error) ui.status.textContent = "Preview while dragging (one direction); the full plan on release";
  // The way out follows the plan (not its previews: each would build the tracks' graph again).
  if (!preview && !result.error && way.asked) way.find();
  if (fit) view.fit();
  // Newer edits are on their way: not ready until the newest is drawn.
  if (seq !== state.replanSeq) setPlanState("planning");
  document.body.dataset.planSeq = String(seq);
  return { plan: state.plan, error: state.error };
}

function showPlan(plan, options, callMs) {
  state.plan = plan;
  driver.setPlan(plan.samples, state.projection, options.width);
  showDriveState();
  state.error = null;
  state.errorHighlight = [];
  view.extraBounds = null;
  notes.hideError();
  const warnings = plan.warnings ?? [];
  const noteGroups = warningGroups(warnings);
  // The obstacle class labels keep clear of the warning badges.
  view.setPlan(planScene(plan, state.projection), {
    machineWidth: options.width,
    keepClear: noteGroups.map((g) => g.anchor),
  });
  const s = plan.summary ?? {};
  ui.status.textContent = `Plan of ${state.entry.name}`;
  renderSummary(s, options, callMs);
  renderWarnings(warnings);
  notes.showWarnings(noteGroups);
  updateHighlights();
  document.body.dataset.swathCount = String(s.swath_count ?? 0);
  document.body.dataset.planMs = String(s.planning_ms ?? callMs);
  showEditState();
  setPlanState("ready");
}

/** The warning notes: a badge on the outline of each feature that warnings name; several on one
 * feature share it. */
function warningGroups(warnings) {
  const byFeature = new Map();
  for (const w of warnings) {
    if (!Number.isInteger(w.feature)) continue;
    if (!byFeature.has(w.feature)) byFeature.set(w.feature, []);
    byFeature.get(w.feature).push(w);
  }
  const groups = [];
  for (const [feature, list] of byFeature) {
    const f = state.features[feature];
    const anchor = f ? outlineAnchor(f.paths) : null;
    if (!anchor) continue; // nothing to pin it to: the panel lists it
    groups.push({ feature, label: featureLabel(f, feature), anchor, warnings: list });
  }
  return groups;
}

/** The outlines the view highlights: the error's feature, and the features of open warnings. */
function updateHighlights() {
  const open = notes.groups.filter((g) => notes.isOpen(g));
  view.setHighlights([
    ...state.errorHighlight,
    ...open.map((g) => ({ paths: state.features[g.feature]?.paths ?? [], kind: "warning" })),
  ]);
}

/**
 * Where an error is, in the view's metres: `{ anchor, marker, paths }`: the point the callout
 * points at (the error's coordinate, else the vertex it names, else a point on the outline of its
 * feature or ring), the point to mark (the coordinate), and the outline to highlight.
 */
function errorPlace(error) {
  const forward = state.projection?.forward;
  const c = error.coordinate;
  const marker = forward && Array.isArray(c) && Number.isFinite(c[0]) && Number.isFinite(c[1]) ? forward(c) : null;
  let paths = Number.isInteger(error.feature) ? (state.features[error.feature]?.paths ?? []) : [];
  if (Number.isInteger(error.ring)) {
    const ring = paths.filter((p) => p.ring === error.ring);
    if (ring.length) paths = [ring[0]];
  }
  let anchor = marker;
  if (!anchor && Number.isInteger(error.vertex) && paths.length === 1) {
    // The vertex itself, or (when it is not a number) the nearest one that is.
    const pts = paths[0].points;
    for (let d = 0; d < pts.length && !anchor; d++) anchor = pts[error.vertex - d] ?? pts[error.vertex + d] ?? null;
  }
  anchor ??= outlineAnchor(paths);
  return { anchor, marker, paths: paths.some((p) => p.points.some(Boolean)) ? paths : [] };
}

/** Shows why there is no plan; the field stays drawn and the inputs stay usable. */
function showPlanError(error, { local = false } = {}) {
  state.error = error;
  state.plan = null;
  driver.setPlan(null);
  showDriveState();
  const place = local ? { anchor: null, marker: null, paths: [] } : errorPlace(error);
  state.errorHighlight = place.paths.length ? [{ paths: place.paths, kind: "error" }] : [];
  view.extraBounds = place.anchor ? pathBounds(place.paths, [place.anchor, place.marker]) : null;
  notes.clearWarnings({ notify: false });
  view.setPlan(null, { marker: place.marker });
  updateHighlights();
  if (!local) markInvalid(inputsNamedIn(error));
  if (!local && error.code === "ambiguous_boundary" && offerParcels()) return;
  const title = local ? "Check the settings" : "Cannot plan this field";
  const text = sentence(error.message);
  const where = [];
  if (Number.isInteger(error.feature)) where.push(`feature ${error.feature}`);
  if (Number.isInteger(error.ring)) where.push(`ring ${error.ring}`);
  if (Number.isInteger(error.vertex)) where.push(`vertex ${error.vertex}`);
  notes.showError({
    code: error.code,
    feature: error.feature,
    title,
    text,
    hint: local ? null : ERROR_HINTS[error.code],
    excerpt: local ? null : jsonExcerpt(state.source, error.message),
    detail: local ? null : `Error code ${error.code}${where.length ? `, ${where.join(", ")}` : ""}`,
    anchor: place.anchor,
  });
  ui.status.textContent = "No plan";
  ui.summary.replaceChildren();
  const at = error.coordinate ? ` (near ${error.coordinate.map((v) => v.toFixed(6)).join(", ")})` : "";
  renderWarnings([], { text: `${title}: ${text}${at}`, code: error.code, feature: error.feature });
  delete document.body.dataset.swathCount;
  delete document.body.dataset.planMs;
  showEditState();
  setPlanState("error");
}

/** The text around the line and column an invalid_json message names, to find it in the file. */
function jsonExcerpt(source, message) {
  const m = /line (\d+) column (\d+)/.exec(String(message));
  if (typeof source !== "string" || !m) return null;
  const lines = source.split("\n");
  const line = lines[Number(m[1]) - 1];
  if (line == null) return null;
  const col = Math.max(0, Math.min(line.length, Number(m[2]) - 1));
  const cut = (t) => t.replace(/\s+/g, " ");
  return {
    before: (col > 24 ? "…" : "") + cut(line.slice(Math.max(0, col - 24), col)),
    at: cut(line.slice(col, col + 1)),
    after: cut(line.slice(col + 1, col + 16)) + (col + 16 < line.length ? "…" : ""),
  };
}

/** A failure outside planning (loading the package, a field or a file). */
function showFailure(text, code = "load_failed") {
  state.error = { code, message: text };
  notes.clearWarnings({ notify: false });
  notes.showError({ code, title: "Not loaded", text, anchor: null });
  ui.status.textContent = "Not loaded";
  setPlanState("error");
}

/** The inputs an error message names, e.g. "option `width` is -1". */
function inputsNamedIn(error) {
  const ids = new Set();
  for (const m of String(error.message).matchAll(/`(\w+)`/g)) if (m[1] in ui.inputs) ids.add(m[1]);
  if (error.code === "headland_consumes_field") ids.add("headlandPasses");
  return [...ids];
}

function markInvalid(ids) {
  for (const [id, input] of Object.entries(ui.inputs)) {
    if (ids.includes(id)) input.setAttribute("aria-invalid", "true");
    else input.removeAttribute("aria-invalid");
  }
}

/**
 * The figures of the plan. Each row's `dd` carries `data-key`, the summary member it shows, and
 * `data-value`, its number as the planner gave it (for tests and for copying).
 */
function renderSummary(s, options, callMs) {
  const num = (v) => (!Number.isFinite(v) || Math.abs(v) < 1e-9 ? 0 : v); // no "-0"
  const km = (m) => `${formatNumber(num(m) / 1000, 2)} km`;
  const ha = (m2) => `${formatNumber(num(m2) / 10000, 2)} ha`;
  // Small areas (corners a pass cannot reach) in square metres, where 0.00 ha would hide them.
  const area = (m2) => (num(m2) >= 1000 ? ha(m2) : `${formatNumber(num(m2), 0)} m²`);
  const swaths =
    s.dropped_swath_count > 0 ? `${s.swath_count} (${s.dropped_swath_count} too short, left out)` : `${s.swath_count}`;
  const bearing = `${formatNumber(s.bearing_deg ?? 0, 1)}°${options.bearing == null ? " (auto)" : ""}`;
  const classes = s.obstacle_classes ?? {};
  const classCount = ["A", "B", "C", "D"].reduce((n, c) => n + (classes[c] ?? 0), 0);
  const rows = [
    ["Swaths", swaths, { key: "swath_count" }],
    ["Turns", s.turn_count, { key: "turn_count" }],
    ["Blocks", s.block_count, { key: "block_count" }],
    [
      "Decomposition",
      decompositionText(s.decomposition),
      { key: "decomposition", title: s.decomposition?.reason ?? "" },
    ],
    ["Headland passes", s.headland_pass_count, { key: "headland_pass_count" }],
    ["Working distance", km(s.working_distance_m), { key: "working_distance_m" }],
    ["Turning distance", km(s.turning_distance_m), { key: "turning_distance_m" }],
    [
      "Turn forms",
      Object.entries(s.turn_forms ?? {})
        .map(([form, n]) => `${n} ${form}`)
        .join(", ") || "none",
      { key: "turn_forms", title: "The drivable turns between swaths, by form" },
    ],
    ...(num(s.turns_outside_field) > 0
      ? [
          [
            "Turns outside the field",
            s.turns_outside_field,
            { key: "turns_outside_field", title: "No turn the machine can drive fits the headland there (see the warnings)" },
          ],
        ]
      : []),
    ["Connections", km(s.connection_distance_m), { key: "connection_distance_m" }],
    ["Total distance", km(s.total_distance_m), { key: "total_distance_m", cls: "total" }],
    ["Field area", ha(s.field_area_m2), { key: "field_area_m2" }],
    ["Headland area", ha(s.headland_area_m2), { key: "headland_area_m2" }],
    [
      "Uncovered headland",
      area(s.uncovered_headland_area_m2),
      { key: "uncovered_headland_area_m2", title: "Headland no pass covers: rounded corners, necks too narrow to turn in" },
    ],
    ["Inner field", ha(s.inner_field_area_m2), { key: "inner_field_area_m2" }],
    [
      "Remaining area",
      `${formatNumber(num(s.remaining_area_ratio) * 100, 1)} %`,
      { key: "remaining_area_ratio", title: "Inner field over field area: the share left for swaths" },
    ],
    ["Obstacle classes", classCount ? classTags(classes) : "none", { key: "obstacle_classes" }],
    ...(num(s.lifted_distance_m) > 0 || classes.A > 0
      ? [["Implement lifted", `${formatNumber(num(s.lifted_distance_m), 0)} m`, { key: "lifted_distance_m" }]]
      : []),
    ["Swath bearing", bearing, { key: "bearing_deg" }],
    [
      "Direction",
      directionText(s.direction),
      { key: "direction", title: "How the direction was chosen, and the cost of the plan's swaths" },
    ],
    [
      "Coverage",
      `${formatNumber(num(s.objectives?.coverage) * 100, 2)} %`,
      { key: "objectives", title: "Share of the inner field the swaths' strips cover" },
    ],
    [
      "Estimated time",
      duration(s.estimated_time_s),
      { key: "estimated_time_s", title: "Swaths and headland at working speed, turns and connections at turning speed" },
    ],
    [
      "Planning time",
      `${formatNumber(s.planning_ms ?? 0, 2)} ms`,
      { key: "planning_ms", title: `${formatNumber(callMs, 2)} ms with the GeoJSON conversion` },
    ],
  ];
  ui.summary.replaceChildren(
    ...rows.flatMap(([label, value, { key, cls, title }]) => {
      const dt = document.createElement("dt");
      const dd = document.createElement("dd");
      dt.textContent = label;
      if (value instanceof Node) dd.append(value);
      else dd.textContent = String(value ?? "–");
      dd.dataset.key = key;
      const raw = s[key];
      dd.dataset.value = typeof raw === "object" && raw !== null ? JSON.stringify(raw) : String(raw ?? "");
      if (cls) dt.className = dd.className = cls;
      if (title) dt.title = dd.title = title;
      return [dt, dd];
    }),
  );
}

/** How the direction was chosen, in words: "searched, 36 directions (coarse to fine)". */
function directionText(d) {
  if (!d) return "–";
  switch (d.mode) {
    case "search":
      return `searched, ${d.evaluations} directions (${d.method === "brute-force" ? "every degree" : "coarse to fine"})`;
    case "fixed":
      return "as given";
    case "reference":
      return "along the reference";
    default:
      return "along the longest edge";
  }
}

/** Seconds as "1 h 05 min" or "12 min". */
function duration(seconds) {
  const min = Math.round((Number.isFinite(seconds) ? seconds : 0) / 60);
  return min >= 60 ? `${Math.floor(min / 60)} h ${String(min % 60).padStart(2, "0")} min` : `${min} min`;
}

/** "A1 B1 C2 D1", each class in the tag the map labels obstacles with. */
function classTags(classes) {
  const out = document.createDocumentFragment();
  for (const c of ["A", "B", "C", "D"]) {
    const tag = document.createElement("span");
    tag.className = "class-tag";
    tag.dataset.class = c;
    tag.textContent = c;
    out.append(tag, String(classes[c] ?? 0));
  }
  return out;
}

/** The panel's list: every warning (those on a feature are on the map too), and the error. */
function renderWarnings(warnings, error) {
  const item = (text, code, feature, cls) => {
    const li = document.createElement("li");
    li.textContent = text;
    li.title = code;
    li.dataset.code = code;
    if (Number.isInteger(feature)) li.dataset.feature = String(feature);
    if (cls) li.className = cls;
    return li;
  };
  const items = warnings.map((w) => item(sentence(w.message ?? w.code), w.code, w.feature));
  if (error) items.push(item(error.text, error.code, error.feature, "error"));
  ui.warnings.replaceChildren(...items);
}

function setPlanState(s) {
  document.body.dataset.planState = s;
}

function formatNumber(v, digits) {
  return Number(v).toLocaleString(undefined, { minimumFractionDigits: digits, maximumFractionDigits: digits });
}

// ---- editing -------------------------------------------------------------------------------------

/** A new field is shown: its document starts the edit history (not editable: no document). */
function startEditing(field, { edited = false } = {}) {
  state.fieldId++;
  way.reset();
  showWayState();
  const doc = toCollection(field);
  history.reset(doc);
  tool.setMode(doc ? (tool.mode === "view" ? "view" : "edit") : "view");
  // A field saved here carries its entrance and AB line: the planner gets them as options.
  const input = doc ? plannerInput(doc) : null;
  state.edited = edited || Boolean(input && input.field !== doc);
  if (state.edited && input) state.source = input.field;
  showEditState();
}

/** An edit: draw the field as it is now and plan it; a finished edit is kept for the next visit. */
function applyDoc(doc, { final }) {
  state.edited = true;
  state.field = doc;
  const input = plannerInput(doc);
  state.source = input.field;
  if (!state.entry?.opened) {
    // A bundled field, once edited, is the user's own: the picker shows it as opened.
    const name = `${state.entry?.name ?? "Field"} (edited)`;
    state.entry = { name, opened: true };
    openedOption(name);
    ui.field.value = OPENED;
    ui.suggested.disabled = true;
    if (location.hash) window.history.replaceState(null, "", location.pathname + location.search);
  }
  ui.note.textContent = "Drawn or edited here; planned with the settings below.";
  if (final) {
    state.opened = { source: doc, name: state.entry.name };
    saveSession();
  }
  refreshField(doc);
  if (hasPolygon(doc)) replan({ preview: !final });
  else {
    driver.setPlan(null);
    view.setPlan(null);
    ui.status.textContent = "Draw the field: tap its corners on the map";
  }
  showEditState();
}

function hasPolygon(doc) {
  return doc.features.some((f) => ["Polygon", "MultiPolygon"].includes(f?.geometry?.type));
}

/** Redraws the field from the document, keeping the projection (the map does not shift while
 * a vertex is dragged) and the plan until the next one arrives. */
function refreshField(doc) {
  try {
    const parts = fieldParts(doc);
    const features = inputFeatures(doc);
    if (!state.projection) state.projection = projectionFor(parts, features);
    view.projection = state.projection;
    state.features = features.map((f) => projectFeature(f, state.projection));
    view.setField(fieldScene(parts, state.projection), { fit: false, keepPlan: true });
  } catch (e) {
    console.warn("furrow viewer: the field could not be drawn", e);
  }
}

/** Starts a new, empty field where the map is: the boundary tool is on. */
function newField() {
  state.loadToken++;
  const name = "New field";
  state.entry = { name, opened: true };
  state.opened = null;
  state.source = null;
  state.field = emptyField();
  state.plan = null;
  state.error = null;
  state.edited = true;
  openedOption(name);
  ui.field.value = OPENED;
  ui.suggested.disabled = true;
  ui.note.textContent = "Tap the corners of the field on the map; tap the first corner again to close it.";
  if (location.hash) window.history.replaceState(null, "", location.pathname + location.search);
  forgetFieldReferences();
  notes.hideError();
  notes.clearWarnings({ notify: false });
  history.reset(state.field);
  state.fieldId++;
  state.features = [];
  view.setField({ boundary: null, obstacles: [], prohibited: [], bounds: view.field?.bounds ?? null }, { fit: false });
  driver.setPlan(null);
  ui.summary.replaceChildren();
  renderWarnings([]);
  ui.status.textContent = "Draw the field: tap its corners on the map";
  delete document.body.dataset.swathCount;
  setPlanState("ready");
  tool.setMode("boundary");
}

function bindEditing() {
  for (const button of ui.editBar.querySelectorAll("button[data-mode]")) {
    button.addEventListener("click", () => {
      if (!history.doc) return;
      tool.setMode(button.dataset.mode);
      view.canvas.focus({ preventScroll: true });
    });
  }
  $("finish").addEventListener("click", () => tool.finish());
  $("delete").addEventListener("click", () => tool.deleteSelection());
  $("undo").addEventListener("click", () => tool.undo());
  $("redo").addEventListener("click", () => tool.redo());
  // Undo and redo from anywhere but a text box.
  window.addEventListener("keydown", (e) => {
    if (e.target instanceof HTMLInputElement || e.target instanceof HTMLSelectElement || e.target === view.canvas) return;
    const key = e.key.toLowerCase();
    if ((e.ctrlKey || e.metaKey) && (key === "z" || key === "y")) {
      if (key === "y" || e.shiftKey) tool.redo();
      else tool.undo();
      e.preventDefault();
    }
  });
  const region = () => {
    const from = Number(ui.regionFrom.value);
    const to = Number(ui.regionTo.value);
    if (ui.regionFrom.value.trim() === "" || ui.regionTo.value.trim() === "" || !Number.isFinite(from) || !Number.isFinite(to)) return;
    setForbidden(from, to, true);
  };
  ui.regionFrom.addEventListener("input", region);
  ui.regionTo.addEventListener("input", region);
  // The scale bar keeps above the edit bar.
  const tools = document.querySelector(".map-tools");
  new ResizeObserver(() => {
    view.bottomInset = ui.editBar.offsetHeight + 8;
    view.fitInsets = { right: tools.offsetWidth + 10, bottom: ui.editBar.offsetHeight + 10 };
    if (view.fitted) view.fit();
    else view.draw();
  }).observe(ui.editBar);
  showEditState();
  showDriveState();
}

/** Sets the selected prohibited region's first forbidden range (others it has stay). */
function setForbidden(from, to, final) {
  const selected = tool.selectedFeature;
  if (!selected || selected.role !== "prohibited") return;
  const ranges = Array.isArray(selected.feature.properties?.forbidden_bearings_deg)
    ? selected.feature.properties.forbidden_bearings_deg.slice(1)
    : [];
  const doc = setProperties(history.doc, selected.index, { forbidden_bearings_deg: [[from, to], ...ranges] });
  if (!doc) return;
  tool.change(doc, final);
}

/** The edit bar, the hint beside it and the region panel, as the tool's state says. */
function showEditState() {
  const editable = Boolean(history.doc);
  ui.editBar.dataset.mode = tool.mode;
  document.body.dataset.editMode = tool.mode;
  for (const button of ui.editBar.querySelectorAll("button")) {
    if (button.dataset.mode) {
      button.setAttribute("aria-pressed", String(button.dataset.mode === tool.mode));
      button.disabled = !editable;
    }
  }
  $("finish").hidden = !tool.drawing || tool.mode === "abline";
  $("finish").disabled = tool.draft.length < 3;
  $("delete").disabled = !tool.selection;
  $("undo").disabled = !history.canUndo;
  $("redo").disabled = !history.canRedo;
  $("export-field").disabled = !editable;
  $("export-plan").disabled = !state.plan;
  const hints = {
    edit: "Drag a corner; tap the mark in the middle of an edge to add one; tap a corner or region, then Delete.",
    boundary: `Field: tap its corners${tool.draft.length >= 3 ? "; tap the first again or Finish to close" : ""}.`,
    obstacle: `Obstacle: tap its corners${tool.draft.length >= 3 ? "; tap the first again or Finish to close" : ""}.`,
    prohibited: `Prohibited region: tap its corners${tool.draft.length >= 3 ? "; tap the first again or Finish to close" : ""}.`,
    entrance: "Tap where the machine enters the field.",
    abline: tool.draft.length ? "Now tap B." : "Tap A, then B: the swaths run along the line.",
    edge: "Tap the boundary edge the swaths should run along.",
    way: way.hint((v) => formatNumber(v, 0)),
    parcel: `This file holds ${editableParcels(history.doc ?? emptyField())} parcels. Tap the one to plan.`,
  };
  const hint = hints[tool.mode];
  ui.editHint.hidden = !hint;
  ui.editHint.textContent = hint ?? "";
  showRegionPanel();
}

function showRegionPanel() {
  const selected = tool.selectedFeature;
  const show = selected?.role === "prohibited";
  ui.regionPanel.hidden = !show;
  if (!show) return;
  const range = selected.feature.properties?.forbidden_bearings_deg?.[0] ?? [0, 0];
  $("region-name").textContent = selected.feature.properties?.name ? `“${selected.feature.properties.name}”` : `(feature ${selected.index})`;
  // Typing stays as typed; the numbers follow the dial and the undo history.
  if (document.activeElement !== ui.regionFrom) ui.regionFrom.value = String(range[0]);
  if (document.activeElement !== ui.regionTo) ui.regionTo.value = String(range[1]);
  dial ??= new BearingDial($("region-dial"), {
    label: "Forbidden bearings of the region",
    onChange: ({ from, to, final }) => setForbidden(from, to, final),
  });
  dial.set(range[0], range[1]);
}

// ---- files -------------------------------------------------------------------------------------

function fileName() {
  return (state.entry?.name ?? "field").replace(/ \(edited\)$/, "-edited").replace(/[^\w.-]+/g, "-") || "field";
}

/** The field as GeoJSON text: the document as edited (a file opened and not edited comes back
 * as it was read). */
function fieldText() {
  const doc = history.doc;
  return doc ? `${JSON.stringify(doc, null, 1)}\n` : "";
}

/** The plan as GeoJSON text (without the sampled path, which is not GeoJSON). */
function planText() {
  if (!state.plan) return "";
  const { samples, ...plan } = state.plan;
  void samples;
  return `${JSON.stringify(plan)}\n`;
}

function download(name, text) {
  if (!text) return;
  const url = URL.createObjectURL(new Blob([text], { type: "application/geo+json" }));
  const a = document.createElement("a");
  a.href = url;
  a.download = name;
  document.body.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 10_000);
}

// ---- settings and session, kept in this browser ----------------------------------------------------

function settingsChanged() {
  showDirectionInputs();
  saveSettings();
  replan();
}

function showDirectionInputs() {
  $("edge-input").hidden = ui.inputs.direction.value !== "edge";
}

function storage() {
  try {
    return window.localStorage;
  } catch {
    return null; // blocked: nothing is kept
  }
}

function saveSettings() {
  const values = {};
  for (const id of KEPT_INPUTS) values[id] = $(id).value;
  try {
    storage()?.setItem(SETTINGS_KEY, JSON.stringify(values));
  } catch {
    // full or blocked: the settings hold for this visit
  }
}

function restoreSettings() {
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

function saveSession() {
  const doc = history.doc;
  if (!doc) return;
  try {
    storage()?.setItem(SESSION_KEY, JSON.stringify({ name: state.entry?.name ?? "Field", doc }));
  } catch {
    // too large for the browser's storage: the field holds for this visit
  }
}

function readSession() {
  try {
    const s = JSON.parse(storage()?.getItem(SESSION_KEY) ?? "null");
    return s && typeof s.name === "string" && toCollection(s.doc) ? s : null;
  } catch {
    return null;
  }
}

// ---- background map and driving ---------------------------------------------------------------------

/** The optional background map: off (nothing fetched) unless a tile URL is set. */
async function setBackground(url) {
  if (!url) {
    tiles?.setUrl("");
    view.background = null;
    view.draw();
    return;
  }
  if (!tiles) {
    const { TileLayer } = await import("./tiles.js");
    tiles ??= new TileLayer({ onLoad: () => view.requestDraw() });
  }
  if (ui.tileUrl.value.trim() !== url) return; // changed again meanwhile
  tiles.setUrl(url);
  view.background = tiles;
  view.draw();
}

function showDriveState() {
  const button = $("drive");
  button.setAttribute("aria-pressed", String(driver.running));
  button.textContent = driver.running ? "Stop" : "Drive";
  button.disabled = !driver.samples;
  document.body.dataset.drive = driver.running ? "running" : driver.t > 0 ? "paused" : "stopped";
  document.body.dataset.driveS = String(Math.round(driver.t));
}

// ---- files of many parcels ----------------------------------------------------------------------

/** A file of several polygons and no roles (a parcel register's export, like the corpus's real/
 * files): every parcel is shown, and the one tapped is planned. False if the file is not that. */
function offerParcels() {
  const doc = history.doc;
  if (!doc || doc.features.some((f) => roleOf(f) != null)) return false;
  const parcels = editableParcels(doc);
  if (parcels < 2) return false;
  tool.setMode("parcel");
  view.extraBounds = tool.bounds();
  state.fitPending = false;
  view.fit();
  notes.hideError();
  ui.status.textContent = `${parcels} parcels in this file: tap the one to plan`;
  ui.summary.replaceChildren();
  renderWarnings([]);
  delete document.body.dataset.swathCount;
  setPlanState("pick");
  return true;
}

/** How many polygon features with rings to edit `doc` has. */
function editableParcels(doc) {
  return new Set(editableRings(doc).map((r) => r.feature)).size;
}

/** Plans parcel `feature` of the file shown, as a field of its own (its holes are obstacles). */
function pickParcel(feature) {
  const f = history.doc?.features?.[feature];
  const field = f && toCollection(f);
  if (!field) return;
  const p = f.properties ?? {};
  const name = String(p.name ?? p.id ?? `${state.entry?.name ?? "parcel"} ${feature}`);
  view.extraBounds = null;
  tool.setMode("view");
  loadField(field, name);
}

/** The way out's state for tests (`body[data-way]`, `data-way-length`) and its hint. */
function showWayState() {
  const body = document.body.dataset;
  body.way = way.state;
  if (way.path) body.wayLength = String(way.path.properties.length_m);
  else delete body.wayLength;
  if (tool.mode === "way") {
    ui.editHint.hidden = false;
    ui.editHint.textContent = way.hint((v) => formatNumber(v, 0));
  }
}
