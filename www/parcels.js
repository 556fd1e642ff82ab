// Files of many parcels (a parcel register's export, like the corpus's real/ files): every
// parcel is drawn on the map, at least a few pixels wide however far out the map is, and listed
// by name (or id) and area; the list can be searched. A tap on a parcel (on the map, forgiving
// by a finger's width, or in the list) plans it as a field of its own; "All parcels" comes back
// to the list.
//
// The picker is fed a plain list of GeoJSON Features, whatever file they were read from:
// `openParcels(features, name)` (fields.js, also window.furrow.showParcels) opens them as the
// file shown. State for tests: body[data-plan-state=pick] while a parcel is to be picked,
// window.furrow.parcels the picker.
import { $, history, layers, notes, setPlanState, state, tool, ui, view, formatNumber } from "./app.js";
import { roleOf, toCollection } from "./editor.js";
import { loadField, openParcels } from "./fields.js";
import { insidePolygon, labelPoint, makeProjection } from "./scene.js";
import { renderWarnings } from "./summary.js";

const MIN_PX = 10; // a parcel smaller than this on the map is drawn as a dot this wide
const HIT_PX = 22; // a tap this near a parcel (half a 44 px touch target) picks it
const LABEL_PX = 60; // parcels at least this wide on the map carry their name

/** The picker: the file's parcels (and the file as read, to save it again), the search, the
 * parcel picked (an index) or null. */
export const picker = { name: "", source: null, features: [], parcels: [], query: "", picked: null, hover: null };

const el = {
  panel: $("parcels"),
  title: $("parcels-title"),
  back: $("parcels-back"),
  search: $("parcels-search"),
  list: $("parcels-list"),
  none: $("parcels-none"),
};

/** Binds the list, the search and the back button, the map's taps and the drawing. */
export function bindParcels() {
  tool.onParcelTap = (pt) => {
    const i = parcelAt(pt);
    if (i != null) pickParcel(i);
  };
  layers.push(drawParcels);
  el.search.addEventListener("input", () => {
    picker.query = el.search.value;
    renderList();
    view.requestDraw();
  });
  el.search.addEventListener("keydown", (e) => {
    if (e.key !== "Enter") return;
    const first = picker.parcels.find(matches);
    if (first) pickParcel(first.index);
  });
  el.back.addEventListener("click", () => openParcels(picker.features, picker.name, picker.source));
  el.list.addEventListener("click", (e) => {
    const button = e.target.closest("button[data-index]");
    if (button) pickParcel(Number(button.dataset.index));
  });
  const hover = (e) => {
    const button = e.target?.closest?.("button[data-index]");
    picker.hover = button ? Number(button.dataset.index) : null;
    view.requestDraw();
  };
  for (const type of ["pointerover", "focusin"]) el.list.addEventListener(type, hover);
  for (const type of ["pointerleave", "focusout"]) el.list.addEventListener(type, () => hover({ target: null }));
}

/** The parcels of a document if it is a file of them (several polygons, none with a role), or null. */
export function parcelFeatures(doc) {
  const features = Array.isArray(doc?.features) ? doc.features : null;
  if (!features || doc.type !== "FeatureCollection" || features.some((f) => roleOf(f) != null)) return null;
  const parcels = features.filter((f) => outerRings(f).length);
  return parcels.length >= 2 ? parcels : null;
}

/**
 * Shows `features` (GeoJSON Features; those with a polygon are the parcels) on the map and in
 * the list, to pick the one to plan; `name` is the file's, `source` the file as read (what
 * *Save field* writes while no parcel is picked; by default a FeatureCollection of `features`).
 */
export function showParcels(features, name, source = picker.features === features ? picker.source : null) {
  picker.source = source ?? { type: "FeatureCollection", features };
  if (features !== picker.features) {
    picker.features = features;
    picker.parcels = parcelsOf(features);
    picker.query = "";
    el.search.value = "";
  }
  picker.name = name;
  picker.picked = null;
  picker.hover = null;
  // The map: every parcel, in one projection about them all; nothing to edit, no plan.
  const all = picker.parcels.map((p) => p.bounds);
  const lonLat = [Math.min(...all.map((b) => b[0])), Math.min(...all.map((b) => b[1])), Math.max(...all.map((b) => b[2])), Math.max(...all.map((b) => b[3]))];
  state.projection = makeProjection((lonLat[0] + lonLat[2]) / 2, (lonLat[1] + lonLat[3]) / 2);
  for (const p of picker.parcels) {
    p.world = p.rings.map((ring) => ring.map(state.projection.forward));
    p.labelAt = labelPoint([p.world[0]]);
  }
  state.features = [];
  state.plan = null;
  state.error = null;
  state.errorHighlight = [];
  state.fitPending = false;
  state.drawnSeq = state.replanSeq; // a plan on its way is not drawn over the list
  history.reset(null);
  view.projection = state.projection;
  const [x0, y0] = state.projection.forward([lonLat[0], lonLat[1]]);
  const [x1, y1] = state.projection.forward([lonLat[2], lonLat[3]]);
  view.setField({ boundary: null, obstacles: [], prohibited: [], bounds: [x0, y0, x1, y1] }, { fit: false });
  view.fit();
  notes.hideError();
  notes.clearWarnings({ notify: false });
  ui.status.textContent = `${picker.parcels.length} parcels in this file: tap the one to plan`;
  ui.summary.replaceChildren();
  renderWarnings([]);
  delete document.body.dataset.swathCount;
  delete document.body.dataset.planMs;
  tool.setMode("parcel");
  renderPanel();
  renderList();
  setPlanState("pick");
}

/** Forgets the file of parcels (another field is shown). */
export function forgetParcels() {
  if (!picker.features.length) return;
  Object.assign(picker, { name: "", source: null, features: [], parcels: [], query: "", picked: null, hover: null });
  el.search.value = "";
  el.list.replaceChildren();
  renderPanel();
}

/** The file of parcels as read while one is to be picked (to save it again), else null. */
export function parcelFile() {
  return picker.features.length && picker.picked == null ? picker.source : null;
}

/** How many parcels the file shown has (0: it is not a file of parcels). */
export function parcelCount() {
  return picker.parcels.length;
}

/** Plans parcel `index` (its place in the list) as a field of its own (its holes are obstacles). */
export async function pickParcel(index) {
  const parcel = picker.parcels[index];
  const field = parcel && toCollection(parcel.feature);
  if (!field) return;
  picker.picked = index;
  picker.hover = null;
  tool.setMode("view");
  renderPanel();
  await loadField(field, parcel.label, { parcel: true });
}

// ---- the list ------------------------------------------------------------------------------------

function renderPanel() {
  const n = picker.parcels.length;
  el.panel.hidden = n === 0;
  if (!n) return;
  const picked = picker.parcels[picker.picked];
  el.title.textContent = picked ? `${picked.label} (parcel ${picked.index + 1} of ${n})` : `${n} parcels in ${picker.name}`;
  el.back.hidden = !picked;
  el.back.textContent = `← All ${n} parcels`;
  el.search.hidden = Boolean(picked);
  el.list.hidden = Boolean(picked);
  el.none.hidden = true;
}

function renderList() {
  const shown = picker.parcels.filter(matches);
  el.list.replaceChildren(
    ...shown.map((p) => {
      const li = document.createElement("li");
      const button = document.createElement("button");
      button.type = "button";
      button.dataset.index = String(p.index);
      const name = document.createElement("span");
      name.className = "parcel-name";
      name.textContent = p.label;
      const area = document.createElement("span");
      area.className = "parcel-area";
      area.textContent = areaText(p.areaM2);
      area.dataset.m2 = String(Math.round(p.areaM2));
      button.append(name, area);
      if (p.detail) button.title = p.detail;
      li.append(button);
      return li;
    }),
  );
  el.none.hidden = shown.length > 0 || picker.picked != null;
}

/** Whether parcel `p` matches the search: its name, id or any other text of its properties. */
function matches(p) {
  const q = picker.query.trim().toLowerCase();
  return !q || p.search.includes(q);
}

function areaText(m2) {
  return m2 >= 1000 ? `${formatNumber(m2 / 10000, 2)} ha` : `${formatNumber(m2, 0)} m²`;
}

// ---- the parcels, drawn and tapped ---------------------------------------------------------------

/** The parcels of `features`: `{ index, feature, label, search, detail, areaM2, rings, bounds }`
 * (rings: the outer rings in lon/lat; bounds: theirs); showParcels adds `world` (the rings in
 * the view's metres) and `labelAt` (a point inside the first). */
function parcelsOf(features) {
  const out = [];
  for (const feature of features) {
    const rings = outerRings(feature);
    if (!rings.length) continue;
    const index = out.length;
    const props = feature.properties ?? {};
    const label = String(props.name ?? props.id ?? `Parcel ${index + 1}`);
    const texts = Object.values(props).filter((v) => typeof v === "string" || typeof v === "number");
    out.push({
      index,
      feature,
      label,
      search: [label, ...texts].join(" ").toLowerCase(),
      detail: Object.entries(props)
        .filter(([, v]) => typeof v === "string" && v !== label)
        .map(([k, v]) => `${k}: ${v}`)
        .join("\n"),
      areaM2: areaOf(feature),
      rings,
      bounds: lonLatBounds(rings),
    });
  }
  return out;
}

/** The outer rings of a feature's polygons (lon/lat, positions that are numbers only). */
function outerRings(feature) {
  const g = feature?.geometry;
  const polygons = g?.type === "Polygon" ? [g.coordinates] : g?.type === "MultiPolygon" ? g.coordinates : [];
  return (Array.isArray(polygons) ? polygons : [])
    .map((rings) => (Array.isArray(rings?.[0]) ? rings[0].filter((p) => Number.isFinite(p?.[0]) && Number.isFinite(p?.[1])) : []))
    .filter((ring) => ring.length >= 3);
}

/** A feature's area in square metres (its outer rings less their holes), in a projection about
 * the feature itself. */
function areaOf(feature) {
  const g = feature.geometry;
  const polygons = g.type === "Polygon" ? [g.coordinates] : g.coordinates;
  const b = lonLatBounds(outerRings(feature));
  const p = makeProjection((b[0] + b[2]) / 2, (b[1] + b[3]) / 2);
  let area = 0;
  for (const rings of polygons) {
    if (!Array.isArray(rings)) continue;
    rings.forEach((ring, i) => {
      const pts = Array.isArray(ring) ? ring.filter((q) => Number.isFinite(q?.[0]) && Number.isFinite(q?.[1])).map(p.forward) : [];
      const a = Math.abs(shoelace(pts));
      area += i === 0 ? a : -a;
    });
  }
  return Math.max(0, area);
}

function shoelace(pts) {
  let a = 0;
  for (let i = 0, j = pts.length - 1; i < pts.length; j = i++) a += pts[j][0] * pts[i][1] - pts[i][0] * pts[j][1];
  return a / 2;
}

function lonLatBounds(rings) {
  const xs = rings.flat().map((q) => q[0]);
  const ys = rings.flat().map((q) => q[1]);
  return [Math.min(...xs), Math.min(...ys), Math.max(...xs), Math.max(...ys)];
}

/** Where parcel `p` is on the screen: its box, and the point to draw its dot or name at. */
function onScreen(p) {
  let [x0, y0, x1, y1] = [Infinity, Infinity, -Infinity, -Infinity];
  for (const ring of p.world) {
    for (const w of ring) {
      const [x, y] = view.toScreen(w);
      x0 = Math.min(x0, x);
      y0 = Math.min(y0, y);
      x1 = Math.max(x1, x);
      y1 = Math.max(y1, y);
    }
  }
  return { box: [x0, y0, x1, y1], size: Math.max(x1 - x0, y1 - y0), at: view.toScreen(p.labelAt) };
}

/** The parcel under screen point `pt` ({x, y}): the smallest one it is inside, else the nearest
 * within a finger's width of its outline or dot; its index, or null. */
export function parcelAt(pt) {
  let best = null;
  const world = view.toWorld(pt.x, pt.y);
  for (const p of picker.parcels) {
    if (!matches(p)) continue;
    const s = onScreen(p);
    let d;
    if (p.world.some((ring) => insidePolygon(world, [ring]))) d = -1 / (1 + p.areaM2); // inside: the smallest wins
    else if (s.size < MIN_PX) d = Math.max(0, Math.hypot(pt.x - s.at[0], pt.y - s.at[1]) - MIN_PX / 2);
    else d = Math.min(...p.world.map((ring) => ringDistance(ring, [pt.x, pt.y])));
    if (d <= HIT_PX && (!best || d < best.d)) best = { index: p.index, d };
  }
  return best?.index ?? null;
}

/** Distance in screen px from `pt` to the outline of a ring (world metres). */
function ringDistance(ring, pt) {
  let d = Infinity;
  for (let i = 0; i < ring.length; i++) {
    const a = view.toScreen(ring[i]);
    const b = view.toScreen(ring[(i + 1) % ring.length]);
    d = Math.min(d, segmentDistance(pt, a, b));
  }
  return d;
}

function segmentDistance([px, py], [ax, ay], [bx, by]) {
  const dx = bx - ax;
  const dy = by - ay;
  const l2 = dx * dx + dy * dy;
  const u = l2 > 0 ? Math.max(0, Math.min(1, ((px - ax) * dx + (py - ay) * dy) / l2)) : 0;
  return Math.hypot(px - (ax + u * dx), py - (ay + u * dy));
}

/** Every parcel, outlined (a dot where it would be smaller than MIN_PX), those the search leaves
 * out faint, the one the list points at thick; names where they fit. */
function drawParcels(ctx, t) {
  if (tool.mode !== "parcel" || !picker.parcels.length) return;
  const labels = [];
  for (const p of picker.parcels) {
    const s = onScreen(p);
    const hot = p.index === picker.hover;
    ctx.globalAlpha = matches(p) ? 1 : 0.25;
    ctx.beginPath();
    if (s.size < MIN_PX) {
      ctx.arc(s.at[0], s.at[1], MIN_PX / 2, 0, 2 * Math.PI);
      ctx.fillStyle = t.select;
      ctx.fill();
      ctx.lineWidth = 1.5;
      ctx.strokeStyle = t.labelFill;
      ctx.stroke();
    } else {
      for (const ring of p.world) {
        ring.forEach((w, i) => {
          const [x, y] = view.toScreen(w);
          if (i === 0) ctx.moveTo(x, y);
          else ctx.lineTo(x, y);
        });
        ctx.closePath();
      }
      ctx.fillStyle = t.field;
      ctx.globalAlpha *= 0.8;
      ctx.fill("evenodd");
      ctx.globalAlpha = matches(p) ? 1 : 0.25;
      ctx.lineWidth = 2;
      ctx.strokeStyle = t.select;
      ctx.stroke();
      if (s.size >= LABEL_PX && matches(p)) labels.push([p.label, s.at]);
    }
    if (hot) {
      ctx.beginPath();
      ctx.arc(s.at[0], s.at[1], Math.max(MIN_PX, Math.min(s.size / 2, 40)), 0, 2 * Math.PI);
      ctx.lineWidth = 4;
      ctx.strokeStyle = t.select;
      ctx.stroke();
    }
  }
  ctx.globalAlpha = 1;
  ctx.font = `600 12px system-ui, sans-serif`;
  ctx.textAlign = "center";
  ctx.textBaseline = "middle";
  ctx.lineJoin = "round";
  for (const [text, [x, y]] of labels) {
    ctx.lineWidth = 3;
    ctx.strokeStyle = t.labelFill;
    ctx.strokeText(text, x, y);
    ctx.fillStyle = t.label;
    ctx.fillText(text, x, y);
  }
}
