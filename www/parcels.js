// Files of many parcels (a parcel register's export): every parcel is shown, and the one tapped
// is planned.
import { history, notes, setPlanState, state, tool, ui, view } from "./app.js";
import { editableRings, roleOf, toCollection } from "./editor.js";
import { loadField } from "./fields.js";
import { renderWarnings } from "./summary.js";

/** A file of several polygons and no roles (a parcel register's export, like the corpus's real/
 * files): every parcel is shown, and the one tapped is planned. False if the file is not that. */
export function offerParcels() {
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
export function editableParcels(doc) {
  return new Set(editableRings(doc).map((r) => r.feature)).size;
}

/** Plans parcel `feature` of the file shown, as a field of its own (its holes are obstacles). */
export function pickParcel(feature) {
  const f = history.doc?.features?.[feature];
  const field = f && toCollection(f);
  if (!field) return;
  const p = f.properties ?? {};
  const name = String(p.name ?? p.id ?? `${state.entry?.name ?? "parcel"} ${feature}`);
  view.extraBounds = null;
  tool.setMode("view");
  loadField(field, name);
}
