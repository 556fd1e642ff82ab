// Fields to plan: the bundled ones (fields/index.json, with their suggested settings), files
// opened or dropped on the map, and the field and plan saved as GeoJSON files.
import { driver, history, notes, setPlanState, state, ui, view } from "./app.js";
import { showDriveState, startEditing } from "./editing.js";
import { sentence } from "./notes.js";
import { initPlanner, readFile } from "./planner.js";
import { forgetParcels, parcelFeatures, parcelFile, showParcels } from "./parcels.js";
import { replan, showFailure } from "./planning.js";
import { loadFormats, readLimit, sizeError } from "./reading.js";
import { fieldParts, fieldScene, inputFeatures, parseForDrawing, projectFeature, projectionFor } from "./scene.js";
import { referenceLineOf } from "./editor.js";
import { applySuggested, forgetFieldReferences, showDependentInputs } from "./settings.js";

/** The value of the field picker's entry for an opened file. */
export const OPENED = ":opened";
const fieldCache = new Map(); // file -> Promise of the field GeoJSON

/** Opening a file by dropping it on the map. Files dropped elsewhere are ignored, not opened by
 * the browser in place of the viewer. */
export function bindDrop(map) {
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
    // One file, or a Shapefile's parts (.shp, .shx, .dbf, .prj) dropped together.
    const files = [...(e.dataTransfer.files ?? [])];
    if (files.length) openFile(files.length === 1 ? files[0] : files);
  });
  for (const type of ["dragover", "drop"]) {
    window.addEventListener(type, (e) => {
      if (!hasFiles(e) || map.contains(e.target)) return;
      e.preventDefault();
      e.dataTransfer.dropEffect = "none";
    });
  }
}

/**
 * Reads a file (or a Shapefile's parts, several files) and plans it as it is. The planner's
 * worker reads it (reading.js: a zipped Shapefile converted to GeoJSON there): a file larger
 * than the planner reads is refused before it is read, and one with more points than it accepts
 * once it is parsed there, so the page never holds up on it.
 */
export async function openFile(input) {
  const files = Array.isArray(input) ? input : [input];
  const first = files.find((f) => /\.shp$/i.test(f.name)) ?? files[0];
  const name = first.name.replace(/\.((geo)?json|zip|shp|kml|kmz|xml)$/i, "") || first.name;
  const token = ++state.loadToken;
  const tooLarge = sizeError(
    files.map((f) => f.name).join(", "),
    files.reduce((n, f) => n + f.size, 0),
    readLimit(files),
  );
  if (tooLarge) {
    showFileFailure(name, tooLarge);
    return;
  }
  setPlanState("loading");
  ui.status.textContent = `Reading ${files.map((f) => f.name).join(", ")}…`;
  const read = await readFile(input);
  if (token !== state.loadToken) return; // another field was chosen meanwhile
  if (read.error) showFileFailure(name, read.error);
  else await loadField(read.text, name, { read });
}

/** A file that could not be opened takes the place of the field shown: its name in the picker,
 * nothing on the map, and why, alone (nothing of the field before is left beside it). */
function showFileFailure(name, error) {
  state.loadToken++;
  forgetParcels();
  state.entry = { name, opened: true };
  state.opened = null;
  state.source = null;
  state.field = undefined;
  state.features = [];
  startEditing(null);
  openedOption(name);
  ui.field.value = OPENED;
  ui.suggested.disabled = true;
  ui.note.textContent = "Opened from a file; not planned.";
  if (location.hash) window.history.replaceState(null, "", location.pathname + location.search);
  view.setField({ boundary: null, obstacles: [], prohibited: [], bounds: null }, { fit: false });
  driver.setPlan(null);
  showDriveState();
  showFailure(sentence(error.message), error.code);
}

/**
 * Shows and plans a field given as GeoJSON text or object, with the current settings. The text
 * goes to the planner as it is, so a broken file gets the planner's own error; for drawing, as
 * much of it as can be read is drawn (`read`: the text as the worker read it, with its parse).
 * Resolves to `{ plan, error }`.
 */
export async function loadField(input, name = "Opened field", { edited = false, read = null, parcel = false } = {}) {
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
  // A file read in the worker comes parsed for drawing already (read.field).
  state.field = read ? read.field : typeof input === "string" ? parseForDrawing(input) : input;
  // A file of many parcels: the one to plan is picked first (a parcel picked is planned here).
  if (!parcel) forgetParcels();
  const parcels = !edited && !parcel && parcelFeatures(state.field);
  if (!edited) forgetFieldReferences();
  // A parcel picked with its own AB line (a TaskData partfield's, the terminal's line) is
  // planned along it.
  if (parcel && state.field?.type === "FeatureCollection" && referenceLineOf(state.field)) {
    ui.inputs.direction.value = "line";
    showDependentInputs();
  }
  state.edited = edited;
  openedOption(name);
  ui.field.value = OPENED;
  ui.field.disabled = false;
  ui.suggested.disabled = true;
  ui.note.textContent = edited ? "Drawn or edited here; planned with the settings below." : "Opened from a file; planned with the settings below.";
  if (location.hash) window.history.replaceState(null, "", location.pathname + location.search);
  if (parcels) {
    openParcels(parcels, name, state.field);
    return { plan: null, error: null };
  }
  startEditing(state.field, { edited });
  showField(state.field);
  return replan();
}

/**
 * Shows a file's parcels (GeoJSON Features) to pick the one to plan (parcels.js): the file is the
 * one opened (`source`: as read, to save it again), nothing is planned until a parcel is picked.
 */
export function openParcels(features, name, source = null) {
  state.loadToken++; // a parcel still loading is not shown over the list
  state.opened = { source: source ?? { type: "FeatureCollection", features }, name };
  state.entry = { name, opened: true };
  state.edited = false;
  openedOption(name);
  ui.field.value = OPENED;
  ui.suggested.disabled = true;
  ui.note.textContent = "A file of parcels: pick the one to plan, on the map or in the list.";
  if (location.hash) window.history.replaceState(null, "", location.pathname + location.search);
  startEditing(null);
  state.source = null;
  showParcels(features, name, source);
}

/** The field picker's entry for the opened file, first in the list. */
export function openedOption(name) {
  let option = ui.field.querySelector(`option[value="${OPENED}"]`);
  if (!option) {
    option = document.createElement("option");
    option.value = OPENED;
    ui.field.prepend(option);
  }
  option.textContent = state.edited ? `${name} (drawn here)` : `${name} (opened file)`;
}

/** Draws a field (whatever of it can be drawn) without a plan; the next plan fits the view. */
export function showField(geojson) {
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
export async function selectField(name) {
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
  forgetParcels();
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

export function loadFieldFile(file) {
  if (!fieldCache.has(file)) {
    const p = fetchJson(file);
    p.catch(() => fieldCache.delete(file));
    fieldCache.set(file, p);
  }
  return fieldCache.get(file);
}

export async function fetchJson(url) {
  const res = await fetch(url);
  if (!res.ok) throw new Error(`${url}: ${res.status} ${res.statusText}`);
  return res.json();
}

export function fileName() {
  return (state.entry?.name ?? "field").replace(/ \(edited\)$/, "-edited").replace(/[^\w.-]+/g, "-") || "field";
}

/** The field as GeoJSON text: the document as edited (a file opened and not edited comes back
 * as it was read, a file of parcels too while none is picked). */
export function fieldText() {
  const doc = history.doc ?? parcelFile();
  return doc ? `${JSON.stringify(doc, null, 1)}\n` : "";
}

/** The plan as GeoJSON text (without the sampled path, which is not GeoJSON). */
export function planText() {
  if (!state.plan) return "";
  const { samples, ...plan } = state.plan;
  void samples;
  return `${JSON.stringify(plan)}\n`;
}

/**
 * Saves the plan as ISOXML TaskData for an ISOBUS terminal (a zip holding TASKDATA/TASKDATA.XML),
 * written by the package's furrow/formats module (loaded the first time).
 */
export async function saveTaskData(width) {
  if (!state.plan) return;
  const plan = state.plan;
  try {
    const formats = await loadFormats();
    const zip = formats.exportTaskData(fieldText(), plan, { width, name: state.entry?.name });
    download(`${fileName()}-TASKDATA.zip`, zip, "application/zip");
  } catch (e) {
    ui.status.textContent = `The plan could not be saved as ISOXML: ${sentence(e?.message ?? String(e))}`;
  }
}

/** Saves the plan as KML for Google Earth, written by furrow/formats. */
export async function saveKml() {
  if (!state.plan) return;
  const plan = state.plan;
  try {
    const formats = await loadFormats();
    download(`${fileName()}-plan.kml`, formats.exportKml(fieldText(), plan), "application/vnd.google-earth.kml+xml");
  } catch (e) {
    ui.status.textContent = `The plan could not be saved as KML: ${sentence(e?.message ?? String(e))}`;
  }
}

export function download(name, text, type = "application/geo+json") {
  if (!text || !text.length) return;
  const url = URL.createObjectURL(new Blob([text], { type }));
  const a = document.createElement("a");
  a.href = url;
  a.download = name;
  document.body.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 10_000);
}
