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
];
const CHOICES = new Set(["headlandMode", "headlandOrder", "objective", "search", "decomposition", "pattern", "reverse"]); // <select>s: their value is the option
const BOOLEANS = new Set(["reverse"]); // <select>s of "true" and "false"
const OPTIONAL = new Set(["bearing", "obstacleThreshold"]); // empty: null, the planner's default
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
  view,
  replan,
  selectField,
  loadField,
};

setPlanState("loading");
bindControls();
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
  for (const input of Object.values(ui.inputs)) input.addEventListener("input", replan);
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
async function loadField(input, name = "Opened field") {
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
  openedOption(name);
  ui.field.value = OPENED;
  ui.field.disabled = false;
  ui.suggested.disabled = true;
  ui.note.textContent = "Opened from a file; planned with the settings below.";
  if (location.hash) history.replaceState(null, "", location.pathname + location.search);
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
  option.textContent = `${name} (opened file)`;
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
  ui.suggested.disabled = false;
  ui.note.textContent = entry.note ?? "";
  if (location.hash.slice(1) !== encodeURIComponent(entry.name)) {
    history.replaceState(null, "", `#${encodeURIComponent(entry.name)}`);
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
  return { options, problems };
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
  ui.moreState.textContent = [
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
async function replan() {
  showMoreState();
  if (state.source == null) return { plan: null, error: null };
  const seq = ++state.replanSeq;
  const { options, problems } = readOptions();
  markInvalid(problems.map((p) => p.id));
  if (problems.length) {
    state.drawnSeq = seq;
    showPlanError({ code: "invalid_option", message: problems.map((p) => p.message).join(" ") }, { local: true });
    return { plan: state.plan, error: state.error };
  }
  setPlanState("planning");
  const source = state.source;
  const result = await runPlan(source, options);
  if (result.stale || seq <= state.drawnSeq || source !== state.source) {
    // A newer edit (or another field) came first: its plan is drawn instead.
    return { plan: state.plan, error: state.error };
  }
  state.drawnSeq = seq;
  const fit = state.fitPending;
  state.fitPending = false;
  if (result.error) showPlanError(result.error);
  else showPlan(result.plan, options, result.ms);
  if (fit) view.fit();
  // Newer edits are on their way: not ready until the newest is drawn.
  if (seq !== state.replanSeq) setPlanState("planning");
  document.body.dataset.planSeq = String(seq);
  return { plan: state.plan, error: state.error };
}

function showPlan(plan, options, callMs) {
  state.plan = plan;
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
  const place = local ? { anchor: null, marker: null, paths: [] } : errorPlace(error);
  state.errorHighlight = place.paths.length ? [{ paths: place.paths, kind: "error" }] : [];
  view.extraBounds = place.anchor ? pathBounds(place.paths, [place.anchor, place.marker]) : null;
  notes.clearWarnings({ notify: false });
  view.setPlan(null, { marker: place.marker });
  updateHighlights();
  if (!local) markInvalid(inputsNamedIn(error));
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
