// The field being edited, as the GeoJSON the planner reads (lon/lat), and its edit history.
//
// A field document is a FeatureCollection: the boundary, obstacles and prohibited regions as
// Polygon (or MultiPolygon) features with `properties.role`, as in the corpus (tests/fields). The
// viewer's own additions ride at the end of the list, where they shift no planner index: the
// entrance (a Point, role `entrance`) and an AB line (a LineString, role `reference_line`). The
// planner is given the document without them (`plannerInput`), and them as options.
//
// Every edit returns a new document and leaves the old one as it was, so the history keeps
// snapshots and a plan in flight keeps the field it was asked for. Nothing here touches the DOM.

/** Roles the viewer adds and the planner does not read as polygons. */
export const EXTRA_ROLES = new Set(["entrance", "reference_line"]);

const DIGITS = 1e9; // coordinates are kept to 1e-9 degree (0.1 mm), like the corpus files
const round = (v) => Math.round(v * DIGITS) / DIGITS;
const roundPoint = (p) => [round(p[0]), round(p[1])];
const isPosition = (p) => Array.isArray(p) && Number.isFinite(p[0]) && Number.isFinite(p[1]);
const clone = (v) => (v === undefined ? undefined : JSON.parse(JSON.stringify(v)));

/**
 * The input as an editable FeatureCollection, or null when it cannot be edited (not GeoJSON, or
 * no polygon in it). A FeatureCollection is taken as it is (so that exporting an unedited corpus
 * file gives it back equal); a lone Polygon Feature or bare Polygon becomes a collection whose
 * first feature is the boundary and whose holes become obstacles.
 */
export function toCollection(input) {
  if (!input || typeof input !== "object") return null;
  if (input.type === "FeatureCollection" && Array.isArray(input.features)) {
    return input.features.some((f) => polygonsOf(f?.geometry).length) ? clone(input) : null;
  }
  const geometry = input.type === "Feature" ? input.geometry : input;
  const polygon = polygonsOf(geometry)[0];
  if (!polygon) return null;
  const properties = { ...(input.type === "Feature" ? input.properties : {}), role: "boundary" };
  const features = [{ type: "Feature", properties, geometry: { type: "Polygon", coordinates: [clone(polygon[0])] } }];
  for (const hole of polygon.slice(1)) {
    features.push({ type: "Feature", properties: { role: "obstacle" }, geometry: { type: "Polygon", coordinates: [clone(hole)] } });
  }
  // A parcel's AB line (a TaskData partfield's, read by furrow/formats): the field's AB line.
  const line = properties.reference_line;
  const position = (p) => Array.isArray(p) && p.length >= 2 && p.every(Number.isFinite);
  if (Array.isArray(line) && line.length === 2 && line.every(position)) {
    features.push({ type: "Feature", properties: { role: "reference_line" }, geometry: { type: "LineString", coordinates: clone(line) } });
  }
  return { type: "FeatureCollection", features };
}

/** An empty field document, to draw a new field in. */
export function emptyField() {
  return { type: "FeatureCollection", features: [] };
}

function polygonsOf(geometry) {
  if (!geometry || !Array.isArray(geometry.coordinates)) return [];
  if (geometry.type === "Polygon") return [geometry.coordinates];
  if (geometry.type === "MultiPolygon") return geometry.coordinates.filter(Array.isArray);
  return [];
}

/** Role of feature `f` ("boundary", "obstacle", "prohibited", an extra role, or null). */
export function roleOf(f) {
  return typeof f?.properties?.role === "string" ? f.properties.role : null;
}

/**
 * The rings that can be edited: `{ feature, part, ring, role, points }` with the points in lon/lat
 * without the closing repeat of the first. A ring with a position that is not two numbers is left
 * out (it cannot be drawn or dragged).
 */
export function editableRings(doc) {
  const out = [];
  doc?.features?.forEach((f, feature) => {
    const role = roleOf(f);
    if (EXTRA_ROLES.has(role)) return;
    polygonsOf(f?.geometry).forEach((rings, part) => {
      rings.forEach((ringCoords, ring) => {
        if (!Array.isArray(ringCoords) || !ringCoords.every(isPosition)) return;
        const points = openRing(ringCoords);
        if (points.length >= 3) out.push({ feature, part, ring, role, points });
      });
    });
  });
  return out;
}

/** A ring's points without the closing repeat of the first. */
function openRing(coords) {
  const n = coords.length;
  const closed = n > 1 && coords[0][0] === coords[n - 1][0] && coords[0][1] === coords[n - 1][1];
  return coords.slice(0, closed ? n - 1 : n).map((p) => [p[0], p[1]]);
}

/** The ring's points closed again (first repeated at the end), rounded. */
function closeRing(points) {
  const pts = points.map(roundPoint);
  return [...pts, [...pts[0]]];
}

/** A copy of `doc` with the ring at `ref` ({ feature, part, ring }) replaced by `points` (open). */
function withRing(doc, ref, points) {
  const next = { ...doc, features: [...doc.features] };
  const f = doc.features[ref.feature];
  const geometry = clone(f.geometry);
  const rings = geometry.type === "MultiPolygon" ? geometry.coordinates[ref.part] : geometry.coordinates;
  rings[ref.ring] = closeRing(points);
  next.features[ref.feature] = { ...f, geometry };
  return next;
}

function ringPoints(doc, ref) {
  const geometry = doc?.features?.[ref.feature]?.geometry;
  const rings = geometry?.type === "MultiPolygon" ? geometry.coordinates?.[ref.part] : geometry?.coordinates;
  const coords = rings?.[ref.ring];
  return Array.isArray(coords) && coords.every(isPosition) ? openRing(coords) : null;
}

/** Twice the signed area of an open ring in lon/lat: positive when it runs counter-clockwise. */
export function signedArea2(points) {
  let a = 0;
  for (let i = 0, j = points.length - 1; i < points.length; j = i++) {
    a += (points[j][0] - points[0][0]) * (points[i][1] - points[0][1]) - (points[i][0] - points[0][0]) * (points[j][1] - points[0][1]);
  }
  return a;
}

/** An open ring running counter-clockwise, as GeoJSON's outer rings do (RFC 7946): the user
 * taps the corners in whichever order comes naturally. */
export function counterClockwise(points) {
  return signedArea2(points) < 0 ? [points[0], ...points.slice(1).reverse()] : points;
}

/**
 * `doc` with vertex `i` of the ring at `ref` moved to `lonLat`; null if there is no such vertex.
 * A move that turns the ring over (a corner dragged across the far side of a triangle) leaves it
 * running the way it ran: the ring is mirrored about vertex `i`, which keeps its index.
 */
export function moveVertex(doc, ref, i, lonLat) {
  const points = ringPoints(doc, ref);
  if (!points || !points[i] || !isPosition(lonLat)) return null;
  const before = Math.sign(signedArea2(points));
  points[i] = lonLat;
  const after = Math.sign(signedArea2(points));
  if (before !== 0 && after === -before) {
    const n = points.length;
    return withRing(
      doc,
      ref,
      points.map((_, j) => points[(((2 * i - j) % n) + n) % n]),
    );
  }
  return withRing(doc, ref, points);
}

/** `doc` with a vertex at `lonLat` put between vertices `i` and `i + 1` of the ring at `ref`. */
export function insertVertex(doc, ref, i, lonLat) {
  const points = ringPoints(doc, ref);
  if (!points || i < 0 || i >= points.length || !isPosition(lonLat)) return null;
  points.splice(i + 1, 0, lonLat);
  return withRing(doc, ref, points);
}

/** `doc` without vertex `i` of the ring at `ref`; null when the ring would keep fewer than three. */
export function deleteVertex(doc, ref, i) {
  const points = ringPoints(doc, ref);
  if (!points || !points[i] || points.length <= 3) return null;
  points.splice(i, 1);
  return withRing(doc, ref, points);
}

/** `doc` with every point of the ring at `ref` moved by `[dLon, dLat]`. */
export function moveRing(doc, ref, [dLon, dLat]) {
  const points = ringPoints(doc, ref);
  if (!points || !Number.isFinite(dLon) || !Number.isFinite(dLat)) return null;
  return withRing(
    doc,
    ref,
    points.map(([x, y]) => [x + dLon, y + dLat]),
  );
}

/** Index of the first viewer extra (entrance, AB line) at the end of the list: new polygons go before. */
function extrasStart(doc) {
  let i = doc.features.length;
  while (i > 0 && EXTRA_ROLES.has(roleOf(doc.features[i - 1]))) i--;
  return i;
}

/**
 * `doc` with a polygon of `role` drawn through `points` (lon/lat, open ring, at least three),
 * kept counter-clockwise (a drawn polygon is an outer ring: a boundary, or an obstacle's or
 * region's own). A boundary replaces the boundary there is (its obstacles stay); others are added. Returns
 * `{ doc, feature }` (the new feature's index), or null for fewer than three points.
 */
export function addPolygon(doc, role, points, properties = {}) {
  if (!Array.isArray(points) || points.length < 3 || !points.every(isPosition)) return null;
  const feature = {
    type: "Feature",
    properties: { role, ...properties },
    geometry: { type: "Polygon", coordinates: [closeRing(counterClockwise(points))] },
  };
  const next = { ...doc, features: [...doc.features] };
  if (role === "boundary") {
    const at = next.features.findIndex((f) => roleOf(f) === "boundary" || roleOf(f) === "field");
    if (at >= 0) {
      const old = next.features[at];
      feature.properties = { ...old.properties, role: roleOf(old), ...properties };
      next.features[at] = feature;
      return { doc: next, feature: at };
    }
    if (!next.features.some((f) => roleOf(f) != null)) {
      // A field of polygons without roles (a register's parcels): the new boundary is the field.
      next.features = next.features.filter((f) => !polygonsOf(f?.geometry).length);
    }
    next.features.unshift(feature);
    return { doc: next, feature: 0 };
  }
  const at = extrasStart(next);
  next.features.splice(at, 0, feature);
  return { doc: next, feature: at };
}

/** `doc` without feature `index` (a polygon or an extra). */
export function deleteFeature(doc, index) {
  if (!doc.features[index]) return null;
  return { ...doc, features: doc.features.filter((_, i) => i !== index) };
}

/** `doc` with the properties of feature `index` merged with `properties`. */
export function setProperties(doc, index, properties) {
  const f = doc.features[index];
  if (!f) return null;
  const next = { ...doc, features: [...doc.features] };
  next.features[index] = { ...f, properties: { ...f.properties, ...properties } };
  return next;
}

/** The extra feature of `role`, or null. */
function extraOf(doc, role) {
  return doc?.features?.find((f) => roleOf(f) === role) ?? null;
}

/** `doc` with the extra of `role` set to `geometry` (or removed when null); extras stay at the end. */
function withExtra(doc, role, geometry) {
  const features = doc.features.filter((f) => roleOf(f) !== role);
  if (geometry) features.push({ type: "Feature", properties: { role }, geometry });
  return { ...doc, features };
}

/** Where the machine enters the field ([lon, lat]), or null. */
export function entranceOf(doc) {
  const c = extraOf(doc, "entrance")?.geometry?.coordinates;
  return isPosition(c) ? [c[0], c[1]] : null;
}

/** `doc` with the entrance at `lonLat` (null: none). */
export function setEntrance(doc, lonLat) {
  return withExtra(doc, "entrance", isPosition(lonLat) ? { type: "Point", coordinates: roundPoint(lonLat) } : null);
}

/** The AB line ([[lon, lat], [lon, lat]]), or null. */
export function referenceLineOf(doc) {
  const c = extraOf(doc, "reference_line")?.geometry?.coordinates;
  return Array.isArray(c) && c.length >= 2 && isPosition(c[0]) && isPosition(c[c.length - 1])
    ? [
        [c[0][0], c[0][1]],
        [c[c.length - 1][0], c[c.length - 1][1]],
      ]
    : null;
}

/** `doc` with the AB line from `a` to `b` (null: none). */
export function setReferenceLine(doc, line) {
  const ok = Array.isArray(line) && isPosition(line[0]) && isPosition(line[1]);
  return withExtra(doc, "reference_line", ok ? { type: "LineString", coordinates: line.map(roundPoint) } : null);
}

/** What the planner is given: the field without the viewer's extras, which become options. */
export function plannerInput(doc) {
  const start = extrasStart(doc);
  const field = start === doc.features.length ? doc : { ...doc, features: doc.features.slice(0, start) };
  // An extra that is not at the end (a hand-edited file) goes too, as an ignored feature would.
  return { field, entrance: entranceOf(doc), referenceLine: referenceLineOf(doc) };
}

/**
 * Undo and redo over field documents. `preview` shows a document without keeping it (a vertex
 * on its way while dragged); `commit` keeps the current one as a step.
 */
export class History {
  constructor(doc, limit = 200) {
    this.limit = limit;
    this.reset(doc);
  }

  /** Starts over at `doc` (a new field): nothing to undo. */
  reset(doc) {
    this.past = [];
    this.future = [];
    this.doc = doc;
    this.kept = doc; // the last committed document
  }

  /** Shows `doc`, not yet a step of its own. */
  preview(doc) {
    this.doc = doc;
  }

  /** Makes the shown document a step (if it changed since the last one). */
  commit() {
    if (this.doc === this.kept) return false;
    this.past.push(this.kept);
    if (this.past.length > this.limit) this.past.shift();
    this.future = [];
    this.kept = this.doc;
    return true;
  }

  /** Shows and keeps `doc` as a step. */
  push(doc) {
    this.preview(doc);
    return this.commit();
  }

  get canUndo() {
    return this.past.length > 0 || this.doc !== this.kept;
  }

  get canRedo() {
    return this.future.length > 0;
  }

  undo() {
    if (this.doc !== this.kept) {
      // A preview not committed (a drag cut short): back to the last step.
      this.doc = this.kept;
      return this.doc;
    }
    if (!this.past.length) return null;
    this.future.push(this.kept);
    this.kept = this.doc = this.past.pop();
    return this.doc;
  }

  redo() {
    if (!this.future.length) return null;
    this.past.push(this.kept);
    this.kept = this.doc = this.future.pop();
    return this.doc;
  }
}

/** "20-70, 100-120" as [[20, 70], [100, 120]] (also "20–70" or "20 70; 100 120"); "" is none;
 * null when the text is not ranges. */
export function parseRanges(text) {
  const t = String(text ?? "").trim();
  if (t === "") return [];
  const out = [];
  for (const part of t.split(/[,;]/)) {
    if (part.trim() === "") continue;
    const m = /^\s*(-?\d+(?:\.\d+)?)\s*(?:-|–|—|\s|to)\s*(-?\d+(?:\.\d+)?)\s*°?\s*$/.exec(part);
    if (!m) return null;
    out.push([Number(m[1]), Number(m[2])]);
  }
  return out;
}
