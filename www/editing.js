// Editing glue: the edit bar and its hint, the edit history's steps planned as they come, a new
// field drawn from nothing, the selected prohibited region's panel, and the states of the
// drive and way-out tools.
//
// Editing (edit-tool.js on the document of editor.js): every change, also each step of a drag,
// re-plans; a finished change is a step of the undo history, and the edited field is kept in this
// browser (localStorage "furrow.session") with the settings ("furrow.settings"), so a reload in the
// cab brings back the field as drawn.
import { $, driver, editHint, formatNumber, history, notes, setPlanState, state, tool, ui, view, way } from "./app.js";
import { BearingDial } from "./dial.js";
import { emptyField, plannerInput, setProperties, toCollection } from "./editor.js";
import { OPENED, openedOption } from "./fields.js";
import { forgetParcels, parcelCount, parcelFile } from "./parcels.js";
import { replan } from "./planning.js";
import { fieldParts, fieldScene, inputFeatures, projectFeature, projectionFor } from "./scene.js";
import { forgetFieldReferences, saveSession, settingsChanged } from "./settings.js";
import { renderWarnings } from "./summary.js";

let dial = null; // the prohibited region's bearing dial, made when first shown

/** A new field is shown: its document starts the edit history (not editable: no document). */
export function startEditing(field, { edited = false } = {}) {
  state.fieldId++;
  state.awaitingBoundary = false;
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
export function applyDoc(doc, { final }) {
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
  if (hasPolygon(doc)) {
    // The boundary is back (redo after undoing it): its corners are edited, not drawn anew.
    if (state.awaitingBoundary && tool.mode === "boundary" && !tool.draft.length) tool.setMode("edit");
    state.awaitingBoundary = false;
    replan({ preview: !final });
  } else awaitBoundary();
  showEditState();
}

/**
 * Nothing to plan yet (a new field, or undo back to before its boundary was closed): no plan,
 * figures, warnings or error are left from before, a plan still on its way is not drawn, and a
 * tap on the map puts down the boundary's first corner.
 */
function awaitBoundary() {
  state.source = null;
  state.plan = null;
  state.error = null;
  state.errorHighlight = [];
  state.drawnSeq = state.replanSeq;
  state.awaitingBoundary = true;
  driver.setPlan(null);
  showDriveState();
  view.extraBounds = null;
  view.setPlan(null);
  view.setHighlights([]);
  notes.hideError();
  notes.clearWarnings({ notify: false });
  ui.summary.replaceChildren();
  renderWarnings([]);
  ui.status.textContent = "Draw the field: tap its corners on the map";
  delete document.body.dataset.swathCount;
  delete document.body.dataset.planMs;
  setPlanState("ready");
  if (tool.mode !== "boundary") tool.setMode("boundary");
}

export function hasPolygon(doc) {
  return doc.features.some((f) => ["Polygon", "MultiPolygon"].includes(f?.geometry?.type));
}

/** Redraws the field from the document, keeping the projection (the map does not shift while
 * a vertex is dragged) and the plan until the next one arrives. */
export function refreshField(doc) {
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
export function newField() {
  state.loadToken++;
  const name = "New field";
  state.entry = { name, opened: true };
  state.opened = null;
  state.field = emptyField();
  state.edited = true;
  openedOption(name);
  ui.field.value = OPENED;
  ui.suggested.disabled = true;
  ui.note.textContent = "Tap the corners of the field on the map; tap the first corner again to close it.";
  if (location.hash) window.history.replaceState(null, "", location.pathname + location.search);
  forgetFieldReferences();
  forgetParcels();
  history.reset(state.field);
  state.fieldId++;
  state.features = [];
  view.setField({ boundary: null, obstacles: [], prohibited: [], bounds: view.field?.bounds ?? null }, { fit: false });
  tool.setMode("boundary");
  awaitBoundary();
}

/** Hooks the edit tool, the driver and the way out to the page, and binds the edit bar. */
export function bindEditing() {
  tool.onChange = (doc, { final }) => applyDoc(doc, { final });
  tool.onState = () => showEditState();
  tool.onPickEdge = (edge) => {
    ui.inputs.referenceEdge.value = String(edge);
    ui.inputs.direction.value = "edge";
    settingsChanged();
  };
  tool.onPickLine = () => {
    ui.inputs.direction.value = "line";
    settingsChanged();
  };
  tool.onWayTap = (world) => way.tap(world);
  driver.onState = () => showDriveState();
  way.onState = () => showWayState();
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
export function setForbidden(from, to, final) {
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
export function showEditState() {
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
  $("export-field").disabled = !editable && !parcelFile();
  $("export-plan").disabled = !state.plan;
  $("export-isoxml").disabled = !state.plan;
  $("export-kml").disabled = !state.plan;
  const hints = {
    edit: "Drag a corner; tap the mark in the middle of an edge to add one; tap a corner or region, then Delete.",
    boundary: `Field: tap its corners${tool.draft.length >= 3 ? "; tap the first again or Finish to close" : ""}.`,
    obstacle: `Obstacle: tap its corners${tool.draft.length >= 3 ? "; tap the first again or Finish to close" : ""}.`,
    prohibited: `Prohibited region: tap its corners${tool.draft.length >= 3 ? "; tap the first again or Finish to close" : ""}.`,
    entrance: "Tap where the machine enters the field.",
    abline: tool.draft.length ? "Now tap B." : "Tap A, then B: the swaths run along the line.",
    edge: "Tap the boundary edge the swaths should run along.",
    way: way.hint((v) => formatNumber(v, 0)),
    parcel: `This file holds ${parcelCount()} parcels. Tap the one to plan, or pick it from the list.`,
  };
  editHint.show(hints[tool.mode], tool.handlePoints());
  showRegionPanel();
}

export function showRegionPanel() {
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

/** The way out's state for tests (`body[data-way]`, `data-way-length`) and its hint. */
export function showWayState() {
  const body = document.body.dataset;
  body.way = way.state;
  if (way.path) body.wayLength = String(way.path.properties.length_m);
  else delete body.wayLength;
  if (tool.mode === "way") editHint.show(way.hint((v) => formatNumber(v, 0)), tool.handlePoints());
}

/** The Drive button and `body[data-drive]`, `data-drive-s`, as the driver's state says. */
export function showDriveState() {
  const button = $("drive");
  button.setAttribute("aria-pressed", String(driver.running));
  button.textContent = driver.running ? "Stop" : "Drive";
  button.disabled = !driver.samples;
  document.body.dataset.drive = driver.running ? "running" : driver.t > 0 ? "paused" : "stopped";
  document.body.dataset.driveS = String(Math.round(driver.t));
}
