// furrow viewer shell: pick a bundled field or open a GeoJSON file, set the machine, see the
// plan. Every input change re-plans at once (the planner takes a few milliseconds). What the
// planner says (an error, or warnings) is shown in words on the map beside the feature it
// concerns (notes.js), and listed in the panel.
//
// State for tests and debugging: body[data-plan-state] = loading | planning | ready | error | pick
// (planning: the drawn plan is not that of the newest edit yet; pick: a file's parcels wait for
// one to be picked), and after each plan body[data-swath-count], body[data-plan-ms] and
// body[data-plan-seq] (which edit it is of); window.furrow holds the last plan or error, and
// window.furrow.loadField(geojsonTextOrObject, name) plans a field given by the page;
// window.furrow.view.drawn says what the last frame drew (the obstacle class labels among it).
//
// This module starts the page and binds its own controls (files, theme, zoom, background map,
// drive); app.js lists the modules that do the rest.
import { $, driver, history, notes, setPlanState, state, tool, ui, view, way, formatNumber } from "./app.js";
import { emptyField, referenceLineOf } from "./editor.js";
import { bindEditing, newField } from "./editing.js";
import {
  OPENED,
  bindDrop,
  download,
  fetchJson,
  fieldText,
  fileName,
  loadField,
  loadFieldFile,
  openFile,
  openParcels,
  openedOption,
  planText,
  saveKml,
  saveTaskData,
  selectField,
} from "./fields.js";
import { bindParcels, picker } from "./parcels.js";
import { initPlanner } from "./planner.js";
import { replan, showFailure, updateHighlights } from "./planning.js";
import { applySuggested, readOptions, readSession, restoreSettings, saveSettings, settingsChanged, showDependentInputs, showMoreState } from "./settings.js";

const DEFAULT_FIELD = "obstacle-types";
let tiles = null; // the background map, made when a URL is set

notes.onOpenChange = () => updateHighlights();

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
  /** A file's parcels (GeoJSON Features) to pick the one to plan from, and the picker. */
  showParcels: openParcels,
  parcels: picker,
  exportField: fieldText,
  exportPlan: planText,
};

setPlanState("loading");
restoreSettings();
bindControls();
bindEditing();
bindParcels();
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
    const files = [...(ui.file.files ?? [])];
    ui.file.value = ""; // so that opening the same file again (after fixing it) reloads it
    if (files.length) openFile(files.length === 1 ? files[0] : files);
  });
  bindDrop(document.querySelector(".map"));
  // A bearing typed is a fixed direction; cleared, the search again.
  ui.inputs.bearing.addEventListener("input", () => {
    const fixed = ui.inputs.bearing.value.trim() !== "" || ui.inputs.bearing.validity.badInput;
    if (fixed) ui.inputs.direction.value = "fixed";
    else if (ui.inputs.direction.value === "fixed") ui.inputs.direction.value = "search";
    showDependentInputs();
    saveSettings();
  });
  ui.inputs.direction.addEventListener("input", () => {
    if (ui.inputs.direction.value === "edge" && ui.inputs.referenceEdge.value.trim() === "") tool.setMode("edge");
    if (ui.inputs.direction.value === "line" && !referenceLineOf(history.doc ?? emptyField())) tool.setMode("abline");
    showDependentInputs();
  });
  for (const input of Object.values(ui.inputs)) input.addEventListener("input", settingsChanged);
  showDependentInputs();
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
  $("export-isoxml").addEventListener("click", () => saveTaskData(readOptions().options.width));
  $("export-kml").addEventListener("click", saveKml);
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

