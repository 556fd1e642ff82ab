// Planning the field shown with the settings, and showing what comes back: the plan (drawn, its
// figures and warnings) or the error (in words beside its place on the map, and in the panel).
//
// The planner runs in a Web Worker (planner.js): the newest edit plans next, older results are
// never drawn over newer ones.
import { driver, notes, setPlanState, state, ui, view, way } from "./app.js";
import { showDriveState, showEditState } from "./editing.js";
import { ERROR_HINTS, featureLabel, sentence } from "./notes.js";
import { runPlan } from "./planner.js";
import { outlineAnchor, pathBounds, planScene } from "./scene.js";
import { inputsNamedIn, markInvalid, readOptions, showMoreState } from "./settings.js";
import { renderSummary, renderWarnings } from "./summary.js";

const PREVIEW_ABOVE_MS = 100; // full plans slower than this are previewed in one direction while dragging

/**
 * Plans the current field with the current inputs (in the planner's worker) and shows the result;
 * resolves to `{ plan, error }` as shown once this call's plan (or a newer one) is drawn. Calls
 * made while one plans replace each other: only the newest runs next, and a result older than
 * the one drawn is never drawn.
 */
export async function replan(how) {
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
  document.body.dataset.pooled = String(result.pooled === true);
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

export function showPlan(plan, options, callMs) {
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
export function warningGroups(warnings) {
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
export function updateHighlights() {
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
export function errorPlace(error) {
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
export function showPlanError(error, { local = false } = {}) {
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
export function jsonExcerpt(source, message) {
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

/** A failure outside planning (loading the package, a field or a file): nothing of the plan or
 * error before it is left beside it. */
export function showFailure(text, code = "load_failed") {
  state.error = { code, message: text };
  state.plan = null;
  state.errorHighlight = [];
  state.drawnSeq = state.replanSeq; // a plan on its way is of what failed to replace it
  view.extraBounds = null;
  view.setPlan(null);
  notes.clearWarnings({ notify: false });
  updateHighlights();
  notes.showError({ code, title: "Not loaded", text, hint: ERROR_HINTS[code], anchor: null });
  ui.status.textContent = "Not loaded";
  ui.summary.replaceChildren();
  renderWarnings([], { text: `Not loaded: ${text}`, code });
  delete document.body.dataset.swathCount;
  delete document.body.dataset.planMs;
  setPlanState("error");
}
