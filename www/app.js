// The viewer's shared parts, made once when the page loads: the page's elements (`ui`), what is
// shown (`state`), the map view and the notes over it, the edit history and tool, the driver and
// the way out. The concern modules import them from here:
//
//   main.js      start-up, the page's own controls, theme, background map, offline copy
//   fields.js    bundled fields, opened files and dropped ones, saving the field and the plan
//   planning.js  planning the field and showing the plan or the error
//   summary.js   the plan's figures and the list of warnings, in words
//   settings.js  the machine settings as planner options; what this browser keeps
//   editing.js   the edit bar, the edit history and drawing a new field
//   parcels.js   files of many parcels: the list to pick one from
//
// Nothing here calls into those modules; they hook themselves onto the tool, the driver and the
// way out when main.js binds them (their top level only defines functions).
import { Driver } from "./drive.js";
import { EditTool } from "./edit-tool.js";
import { History, plannerInput } from "./editor.js";
import { EditHint } from "./hint.js";
import { MapNotes } from "./notes.js";
import { PlanView } from "./view.js";
import { WayOut } from "./way.js";

/** The planner options' inputs, by id. */
export const OPTION_INPUTS = [
  "width",
  "headlandPasses",
  "turnRadius",
  "bearing",
  "headlandMode",
  "headlandOrder",
  "headlandCorners",
  "workedAs",
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

export const $ = (id) => document.getElementById(id);

export const ui = {
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

export const state = {
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
  awaitingBoundary: false, // the field drawn has no boundary yet: taps draw it
  loadToken: 0,
  replanSeq: 0, // replan calls made
  drawnSeq: 0, // the newest replan call whose result is shown
};

export const view = new PlanView($("map"));

export const notes = new MapNotes({
  map: document.querySelector(".map"),
  layer: $("map-notes"),
  error: ui.message,
  tools: document.querySelector(".map-tools"),
  view,
});

export const history = new History(null);

/** The edit tool; editing.js gives it its callbacks. */
export const tool = new EditTool({ view, projection: () => state.projection, history });
view.tool = tool;

export const driver = new Driver(view);

/** The way out along the tracks: where the machine is and faces, the exit, and the way found. */
export const way = new WayOut({
  view,
  projection: () => state.projection,
  entrance: () => (history.doc ? plannerInput(history.doc).entrance : null),
  turning: () => $("way-turning").value,
  ready: () => Boolean(state.plan),
});

/** The edit hint, kept clear of the marks on the map, the map's buttons and the error callout. */
export const editHint = new EditHint(ui.editHint, { view, avoid: [document.querySelector(".map-tools"), ui.message] });

view.onDraw = () => {
  notes.layout();
  if (!ui.editHint.hidden) editHint.layout(tool.handlePoints());
};
/** More to draw over the map, first: `(ctx, theme) => void` (the parcels of a file, parcels.js). */
export const layers = [];

view.overlay = (ctx, theme) => {
  for (const draw of layers) draw(ctx, theme);
  driver.draw(ctx, theme);
  way.draw(ctx, theme, tool.mode === "way");
};

/** Numbers as the user's locale writes them, with `digits` decimals. */
export function formatNumber(v, digits) {
  return Number(v).toLocaleString(undefined, { minimumFractionDigits: digits, maximumFractionDigits: digits });
}

/** The plan's state for tests and the page's style: loading | planning | ready | error | pick. */
export function setPlanState(s) {
  document.body.dataset.planState = s;
}
