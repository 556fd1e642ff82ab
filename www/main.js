// furrow viewer shell: pick a bundled field, set the machine, see the plan. Every input change
// re-plans at once (the planner takes a few milliseconds).
//
// State for tests and debugging: body[data-plan-state] = loading | ready | error, and after each
// plan body[data-swath-count] and body[data-plan-ms]; window.furrow holds the last plan.
import { initPlanner, runPlan } from "./planner.js";
import { fieldParts, fieldScene, planScene, projectionFor } from "./scene.js";
import { PlanView } from "./view.js";

const DEFAULT_FIELD = "obstacle-types";
const OPTION_INPUTS = ["width", "headlandPasses", "turnRadius", "bearing"];

const $ = (id) => document.getElementById(id);
const ui = {
  field: $("field"),
  note: $("field-note"),
  inputs: Object.fromEntries(OPTION_INPUTS.map((id) => [id, $(id)])),
  suggested: $("suggested"),
  status: $("status"),
  summary: $("summary"),
  warnings: $("warnings"),
  message: $("map-message"),
  version: $("version"),
};

const view = new PlanView($("map"));
const fieldCache = new Map(); // file -> Promise of the field GeoJSON

const state = {
  fields: [], // fields/index.json
  entry: null, // the chosen entry of fields/index.json
  field: null, // its GeoJSON
  projection: null,
  plan: null, // the last good plan
  error: null, // the last error, as { code, message, ... }
  loadToken: 0,
};

window.furrow = {
  get plan() {
    return state.plan;
  },
  get error() {
    return state.error;
  },
  get field() {
    return state.field;
  },
  get options() {
    return readOptions().options;
  },
  view,
  replan,
  selectField,
};

setPlanState("loading");
bindControls();
start();

async function start() {
  try {
    const [{ version }, fields] = await Promise.all([initPlanner(), fetchJson("fields/index.json")]);
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
  ui.field.addEventListener("change", () => selectField(ui.field.value));
  for (const input of Object.values(ui.inputs)) input.addEventListener("input", replan);
  ui.suggested.addEventListener("click", () => {
    if (!state.entry) return;
    applySuggested(state.entry);
    replan();
  });
  $("fit").addEventListener("click", () => view.fit());
  $("zoom-in").addEventListener("click", () => view.zoomAt(1.5));
  $("zoom-out").addEventListener("click", () => view.zoomAt(1 / 1.5));
  window.addEventListener("hashchange", () => {
    const name = decodeURIComponent(location.hash.slice(1));
    if (name && name !== state.entry?.name && state.fields.some((f) => f.name === name)) selectField(name);
  });
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
  ui.note.textContent = entry.note ?? "";
  if (location.hash.slice(1) !== encodeURIComponent(entry.name)) {
    history.replaceState(null, "", `#${encodeURIComponent(entry.name)}`);
  }
  applySuggested(entry);
  const parts = fieldParts(field);
  state.projection = projectionFor(parts);
  view.setField(fieldScene(parts, state.projection), { fit: true });
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
  };
  for (const [id, input] of Object.entries(ui.inputs)) {
    const text = input.value.trim();
    const badInput = input.validity.badInput; // text the number input cannot read, e.g. "1e"
    if (id === "bearing" && text === "" && !badInput) {
      options.bearing = null;
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

/** Plans the current field with the current inputs and shows the result. */
function replan() {
  if (!state.field) return;
  const { options, problems } = readOptions();
  markInvalid(problems.map((p) => p.id));
  if (problems.length) {
    showPlanError({ code: "invalid_option", message: problems.map((p) => p.message).join(" ") }, { local: true });
    return;
  }
  const result = runPlan(state.field, options);
  if (result.error) {
    showPlanError(result.error);
    return;
  }
  showPlan(result.plan, options, result.ms);
}

function showPlan(plan, options, callMs) {
  state.plan = plan;
  state.error = null;
  view.setPlan(planScene(plan, state.projection), { machineWidth: options.width });
  ui.message.hidden = true;
  ui.message.textContent = "";
  const s = plan.summary ?? {};
  ui.status.textContent = `Plan of ${state.entry.name}`;
  renderSummary(s, options, callMs);
  renderWarnings(plan.warnings ?? []);
  document.body.dataset.swathCount = String(s.swath_count ?? 0);
  document.body.dataset.planMs = String(s.planning_ms ?? callMs);
  setPlanState("ready");
}

/** Shows why there is no plan; the field stays drawn and the inputs stay usable. */
function showPlanError(error, { local = false } = {}) {
  state.error = error;
  state.plan = null;
  const marker = error.coordinate && state.projection ? state.projection.forward(error.coordinate) : null;
  view.setPlan(null, { marker });
  if (!local) markInvalid(inputsNamedIn(error));
  const text = local ? error.message : `Cannot plan this field: ${sentence(error.message)}`;
  ui.message.textContent = text;
  ui.message.hidden = false;
  ui.status.textContent = "No plan";
  ui.summary.replaceChildren();
  const where = [];
  if (Number.isInteger(error.feature)) where.push(`input feature ${error.feature}`);
  if (error.coordinate) where.push(`near ${error.coordinate.map((v) => v.toFixed(6)).join(", ")}`);
  renderWarnings([], where.length ? `${text} (${where.join(", ")})` : text);
  delete document.body.dataset.swathCount;
  delete document.body.dataset.planMs;
  setPlanState("error");
}

/** A failure outside planning (loading the package or a field). */
function showFailure(text) {
  state.error = { code: "load_failed", message: text };
  ui.message.textContent = text;
  ui.message.hidden = false;
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

function renderSummary(s, options, callMs) {
  const km = (m) => `${formatNumber((m ?? 0) / 1000, 2)} km`;
  const ha = (m2) => `${formatNumber((m2 ?? 0) / 10000, 2)} ha`;
  const swaths =
    s.dropped_swath_count > 0 ? `${s.swath_count} (${s.dropped_swath_count} too short, left out)` : `${s.swath_count}`;
  const bearing = `${formatNumber(s.bearing_deg ?? 0, 1)}°${options.bearing == null ? " (auto)" : ""}`;
  const rows = [
    ["Swaths", swaths],
    ["Turns", s.turn_count],
    ["Blocks", s.block_count],
    ["Headland passes", s.headland_pass_count],
    ["Working distance", km(s.working_distance_m)],
    ["Turning distance", km(s.turning_distance_m)],
    ["Connections", km(s.connection_distance_m)],
    ["Total distance", km(s.total_distance_m), "total"],
    ["Field area", ha(s.field_area_m2)],
    ["Headland area", ha(s.headland_area_m2)],
    ["Inner field", ha(s.inner_field_area_m2)],
    ["Swath bearing", bearing],
    ["Planning time", `${formatNumber(s.planning_ms ?? 0, 2)} ms`],
  ];
  ui.summary.replaceChildren(
    ...rows.flatMap(([label, value, cls]) => {
      const dt = document.createElement("dt");
      const dd = document.createElement("dd");
      dt.textContent = label;
      dd.textContent = String(value ?? "–");
      if (cls) dt.className = dd.className = cls;
      if (label === "Planning time") dd.title = `${formatNumber(callMs, 2)} ms with the GeoJSON conversion`;
      return [dt, dd];
    }),
  );
}

function renderWarnings(warnings, errorText) {
  const items = warnings.map((w) => {
    const li = document.createElement("li");
    li.textContent = sentence(w.message ?? w.code);
    li.title = w.code;
    return li;
  });
  if (errorText) {
    const li = document.createElement("li");
    li.className = "error";
    li.textContent = errorText;
    items.push(li);
  }
  ui.warnings.replaceChildren(...items);
}

function setPlanState(s) {
  document.body.dataset.planState = s;
}

/** "the field falls…" -> "The field falls….": messages from the planner start lower case. */
function sentence(text) {
  const t = String(text ?? "").trim();
  if (!t) return t;
  const s = t[0].toUpperCase() + t.slice(1);
  return /[.!?]$/.test(s) ? s : `${s}.`;
}

function formatNumber(v, digits) {
  return Number(v).toLocaleString(undefined, { minimumFractionDigits: digits, maximumFractionDigits: digits });
}
