// Turns the input field and the plan (GeoJSON, lon/lat) into a scene in local metres that the
// view draws: an equirectangular projection about the field centre,
//   x = (lon - lon0) · cos(lat0) · R,   y = (lat - lat0) · R   (angles in radians),
// which is accurate to well under a pixel over the size of a farm field.

const R = 6371008.8; // mean Earth radius, metres
const RAD = Math.PI / 180;

/** A projection about (lon0, lat0): `forward([lon, lat]) -> [x, y]` in metres, and its inverse. */
export function makeProjection(lon0, lat0) {
  // A latitude beyond the poles (a broken file) would turn x round; draw it as at 89°.
  const kx = Math.cos(Math.min(Math.abs(lat0), 89) * RAD) * R * RAD;
  const ky = R * RAD;
  return {
    lon0,
    lat0,
    forward: (p) => [(p[0] - lon0) * kx, (p[1] - lat0) * ky],
    inverse: (p) => [p[0] / kx + lon0, p[1] / ky + lat0],
  };
}

const isPosition = (p) => Array.isArray(p) && Number.isFinite(p[0]) && Number.isFinite(p[1]);

/** The polygons of a GeoJSON geometry (Polygon or MultiPolygon), each a list of rings. */
function polygonsOf(geometry) {
  if (!geometry || !Array.isArray(geometry.coordinates)) return [];
  if (geometry.type === "Polygon") return [geometry.coordinates];
  if (geometry.type === "MultiPolygon") return geometry.coordinates.filter(Array.isArray);
  return [];
}

/**
 * The parts of an input field: `{ boundary: rings | null, obstacles: [rings], prohibited: [rings] }`
 * in lon/lat. Accepts what the planner accepts (a FeatureCollection with `properties.role`, a
 * Polygon Feature, a bare Polygon whose holes are obstacles) and never throws.
 */
export function fieldParts(geojson) {
  const parts = { boundary: null, obstacles: [], prohibited: [] };
  const fromPolygon = (rings) => {
    parts.boundary = [rings[0]];
    for (const hole of rings.slice(1)) parts.obstacles.push([hole]);
  };
  if (!geojson || typeof geojson !== "object") return parts;
  if (geojson.type === "FeatureCollection" && Array.isArray(geojson.features)) {
    const unnamed = [];
    for (const f of geojson.features) {
      const role = f?.properties?.role;
      const polys = polygonsOf(f?.geometry);
      if (role === "boundary" && polys.length && !parts.boundary) {
        parts.boundary = [polys[0][0]];
        for (const hole of polys[0].slice(1)) parts.obstacles.push([hole]);
      } else if (role === "obstacle") {
        parts.obstacles.push(...polys);
      } else if (role === "prohibited") {
        parts.prohibited.push(...polys);
      } else {
        unnamed.push(...polys);
      }
    }
    if (!parts.boundary && unnamed.length) fromPolygon(unnamed[0]);
  } else if (geojson.type === "Feature") {
    const polys = polygonsOf(geojson.geometry);
    if (polys.length) fromPolygon(polys[0]);
  } else {
    const polys = polygonsOf(geojson);
    if (polys.length) fromPolygon(polys[0]);
  }
  return parts;
}

/**
 * The projection centred on the bounding box of the field boundary (or of all its parts, or when
 * none of them has a usable position, of `fallback`: the paths of inputFeatures()).
 */
export function projectionFor(parts, fallback = []) {
  let rings = parts.boundary ?? [...parts.obstacles, ...parts.prohibited].flat();
  const usable = (ring) => Array.isArray(ring) && ring.some(isPosition);
  if (!rings.some(usable)) rings = fallback.flatMap((f) => f.paths.map((p) => p.points));
  let [x0, y0, x1, y1] = [Infinity, Infinity, -Infinity, -Infinity];
  for (const ring of rings) {
    if (!Array.isArray(ring)) continue;
    for (const p of ring) {
      if (!Number.isFinite(p?.[0]) || !Number.isFinite(p?.[1])) continue;
      x0 = Math.min(x0, p[0]);
      y0 = Math.min(y0, p[1]);
      x1 = Math.max(x1, p[0]);
      y1 = Math.max(y1, p[1]);
    }
  }
  if (!Number.isFinite(x0)) return makeProjection(0, 0);
  return makeProjection((x0 + x1) / 2, (y0 + y1) / 2);
}

// Tolerant of broken input (an opened file may have anything where a ring should be).
const projectRing = (ring, f) => (Array.isArray(ring) ? ring.filter(isPosition).map(f) : []);
const projectPolygon = (rings, f) => (Array.isArray(rings) ? rings.map((r) => projectRing(r, f)) : []);

/** Bounds `[x0, y0, x1, y1]` of a list of rings, or null. */
function boundsOf(rings) {
  let b = null;
  for (const ring of rings) {
    for (const [x, y] of ring) {
      if (!b) b = [x, y, x, y];
      else b = [Math.min(b[0], x), Math.min(b[1], y), Math.max(b[2], x), Math.max(b[3], y)];
    }
  }
  return b;
}

/** The field in local metres: `{ boundary, obstacles, prohibited, bounds }`. */
export function fieldScene(parts, projection) {
  const f = projection.forward;
  const boundary = parts.boundary ? projectPolygon(parts.boundary, f) : null;
  const obstacles = parts.obstacles.map((p) => projectPolygon(p, f));
  const prohibited = parts.prohibited.map((p) => projectPolygon(p, f));
  const bounds = boundsOf(boundary ?? [...obstacles, ...prohibited].flat());
  return { boundary, obstacles, prohibited, bounds };
}

/**
 * The plan in local metres: blocks with a label point, obstacles with their class (A-D) and a
 * label point, obstacle groups (the hulls class-C obstacles were merged into), the parts of the
 * field left uncovered (`uncovered`: rings, `area_m2`, `reachable_m2`), the drivable
 * segments by kind (each `{ points, props }`; a swath or pass the implement is lifted on also has
 * `worked` and `lifted`, lists of pieces), and where the route starts and ends.
 */
export function planScene(plan, projection) {
  const f = projection.forward;
  const scene = {
    blocks: [],
    obstacles: [],
    groups: [],
    uncovered: [],
    paths: { headland: [], swath: [], turn: [], connection: [] },
    start: null,
    end: null,
  };
  let first = null;
  let last = null;
  for (const feature of plan?.features ?? []) {
    const props = feature?.properties ?? {};
    const geometry = feature?.geometry;
    if (props.kind === "block" && geometry?.type === "Polygon") {
      const rings = projectPolygon(geometry.coordinates, f);
      scene.blocks.push({ rings, index: props.index, order: props.order, label: labelPoint(rings) });
    } else if (props.kind === "obstacle" && geometry?.type === "Polygon") {
      const rings = projectPolygon(geometry.coordinates, f);
      if (!rings[0]?.length) continue;
      scene.obstacles.push({
        rings,
        index: props.index,
        feature: props.feature,
        name: props.name ?? null,
        class: typeof props.class === "string" ? props.class : null,
        group: props.group ?? null,
        label: labelPoint(rings),
      });
    } else if (props.kind === "obstacle_group" && geometry?.type === "Polygon") {
      const rings = projectPolygon(geometry.coordinates, f);
      if (rings[0]?.length) scene.groups.push({ rings, index: props.index, members: props.members ?? [] });
    } else if (props.kind === "uncovered" && geometry?.type === "Polygon") {
      const rings = projectPolygon(geometry.coordinates, f);
      if (rings[0]?.length) scene.uncovered.push({ rings, area_m2: props.area_m2, reachable_m2: props.reachable_m2 });
    } else if (props.kind in scene.paths && geometry?.type === "LineString") {
      const points = projectRing(geometry.coordinates, f);
      if (points.length < 2) continue;
      const seg = { points, props };
      if ((props.kind === "swath" || props.kind === "headland") && Array.isArray(props.lifted) && props.lifted.length) {
        Object.assign(seg, splitLifted(points, props.lifted, props.length_m));
      }
      scene.paths[props.kind].push(seg);
      const seq = props.sequence ?? 0;
      if (!first || seq < first.props.sequence) first = seg;
      if (!last || seq > last.props.sequence) last = seg;
    }
  }
  if (first) scene.start = first.points[0];
  if (last) scene.end = last.points[last.points.length - 1];
  return scene;
}

/**
 * A line cut into the pieces where the implement works and where it is lifted: `lifted` are
 * `[from, to]` distances from the first point in metres along a line `length` metres long (the
 * planner's own length; the pieces are placed at the same fractions of the drawn line, whose
 * projection differs a little). Returns `{ worked: [points], lifted: [points] }`.
 */
export function splitLifted(points, lifted, length) {
  const cum = [0];
  for (let i = 1; i < points.length; i++) {
    cum.push(cum[i - 1] + Math.hypot(points[i][0] - points[i - 1][0], points[i][1] - points[i - 1][1]));
  }
  const drawn = cum[cum.length - 1];
  const k = Number.isFinite(length) && length > 0 ? drawn / length : 1;
  const at = (d) => {
    const t = Math.max(0, Math.min(drawn, d));
    let i = 1;
    while (i < cum.length - 1 && cum[i] < t) i++;
    const span = cum[i] - cum[i - 1] || 1;
    const u = (t - cum[i - 1]) / span;
    const [a, b] = [points[i - 1], points[i]];
    return { i, p: [a[0] + (b[0] - a[0]) * u, a[1] + (b[1] - a[1]) * u] };
  };
  /** The points of the line from distance d0 to d1 (d0 <= d1). */
  const piece = (d0, d1) => {
    const s = at(d0);
    const e = at(d1);
    const out = [s.p];
    for (let i = s.i; i < e.i; i++) out.push(points[i]);
    out.push(e.p);
    return out;
  };
  const ranges = lifted
    .filter((r) => Array.isArray(r) && Number.isFinite(r[0]) && Number.isFinite(r[1]))
    .map(([a, b]) => [Math.max(0, Math.min(a, b) * k), Math.min(drawn, Math.max(a, b) * k)])
    .filter(([a, b]) => b > a)
    .sort((p, q) => p[0] - q[0]);
  const worked = [];
  const lift = [];
  let from = 0;
  for (const [a, b] of ranges) {
    if (b <= from) continue; // inside the stretch before
    const start = Math.max(a, from);
    if (start > from) worked.push(piece(from, start));
    lift.push(piece(start, b));
    from = b;
  }
  if (from < drawn) worked.push(piece(from, drawn));
  return { worked, lifted: lift };
}

/** A point inside a polygon to put its label on: the centroid if inside, else the middle of the
 * widest horizontal chord near it. */
export function labelPoint(rings) {
  const outer = rings[0];
  if (!outer || outer.length < 3) return outer?.[0] ?? [0, 0];
  let a = 0;
  let cx = 0;
  let cy = 0;
  for (let i = 0, j = outer.length - 1; i < outer.length; j = i++) {
    const [x0, y0] = outer[j];
    const [x1, y1] = outer[i];
    const c = x0 * y1 - x1 * y0;
    a += c;
    cx += (x0 + x1) * c;
    cy += (y0 + y1) * c;
  }
  const b = boundsOf([outer]);
  const centroid = Math.abs(a) > 1e-9 ? [cx / (3 * a), cy / (3 * a)] : [(b[0] + b[2]) / 2, (b[1] + b[3]) / 2];
  if (insidePolygon(centroid, rings)) return centroid;
  // Scan a few horizontal lines and take the middle of the longest inside stretch.
  let best = null;
  for (let k = 1; k < 12; k++) {
    const y = b[1] + ((b[3] - b[1]) * k) / 12;
    const xs = [];
    for (const ring of rings) {
      for (let i = 0, j = ring.length - 1; i < ring.length; j = i++) {
        const [x0, y0] = ring[j];
        const [x1, y1] = ring[i];
        if ((y0 > y) !== (y1 > y)) xs.push(x0 + ((y - y0) * (x1 - x0)) / (y1 - y0));
      }
    }
    xs.sort((p, q) => p - q);
    for (let i = 0; i + 1 < xs.length; i += 2) {
      const len = xs[i + 1] - xs[i];
      if (!best || len > best.len) best = { len, p: [(xs[i] + xs[i + 1]) / 2, y] };
    }
  }
  return best ? best.p : centroid;
}

/** Even-odd point-in-polygon over all rings (holes included). */
export function insidePolygon([x, y], rings) {
  let inside = false;
  for (const ring of rings) {
    for (let i = 0, j = ring.length - 1; i < ring.length; j = i++) {
      const [xi, yi] = ring[i];
      const [xj, yj] = ring[j];
      if ((yi > y) !== (yj > y) && x < ((xj - xi) * (y - yi)) / (yj - yi) + xi) inside = !inside;
    }
  }
  return inside;
}

// ---- input features, to place errors and warnings ------------------------------------------------

/**
 * Paths of one GeoJSON geometry, `[{ points, closed, ring, part }]` in the input's coordinates:
 * the rings of a (Multi)Polygon (`ring` its index in the polygon, 0 = exterior), the lines of a
 * (Multi)LineString, the points of a (Multi)Point. Positions stay at their index in the input; a
 * position that is not two finite numbers becomes null.
 */
function geometryPaths(geometry) {
  const c = geometry?.coordinates;
  if (!Array.isArray(c)) return [];
  const pos = (p) => (isPosition(p) ? [p[0], p[1]] : null);
  const line = (l) => (Array.isArray(l) ? l.map(pos) : []);
  const polygon = (rings, part) =>
    Array.isArray(rings) ? rings.map((r, ring) => ({ points: line(r), closed: true, ring, part })) : [];
  switch (geometry.type) {
    case "Polygon":
      return polygon(c, 0);
    case "MultiPolygon":
      return c.flatMap((rings, part) => polygon(rings, part));
    case "LineString":
      return [{ points: line(c), closed: false, ring: 0, part: 0 }];
    case "MultiLineString":
      return c.map((l, part) => ({ points: line(l), closed: false, ring: 0, part }));
    case "Point":
      return [{ points: [pos(c)], closed: false, ring: 0, part: 0 }];
    case "MultiPoint":
      return c.map((p, part) => ({ points: [pos(p)], closed: false, ring: 0, part }));
    default:
      return [];
  }
}

/**
 * The features of an input as the planner counts them (its errors and warnings carry these
 * indices): the members of a FeatureCollection's `features`, or the one polygon of a lone Feature
 * or bare geometry. Each `{ role, name, paths }` (paths as geometryPaths). Never throws.
 */
export function inputFeatures(geojson) {
  if (!geojson || typeof geojson !== "object") return [];
  const one = (f) => ({
    role: typeof f?.properties?.role === "string" ? f.properties.role : null,
    name: typeof f?.properties?.name === "string" ? f.properties.name : null,
    paths: geometryPaths(f?.geometry),
  });
  if (geojson.type === "FeatureCollection") return Array.isArray(geojson.features) ? geojson.features.map(one) : [];
  if (geojson.type === "Feature") return [one(geojson)];
  return [{ role: null, name: null, paths: geometryPaths(geojson) }];
}

/** A feature's paths in local metres (positions that are not numbers stay null). */
export function projectFeature(feature, projection) {
  return {
    ...feature,
    paths: feature.paths.map((p) => ({ ...p, points: p.points.map((q) => (q ? projection.forward(q) : null)) })),
  };
}

/** Bounds `[x0, y0, x1, y1]` of paths (nulls skipped) and extra points, or null. */
export function pathBounds(paths, points = []) {
  let b = null;
  const add = (q) => {
    if (!q || !Number.isFinite(q[0]) || !Number.isFinite(q[1])) return;
    if (!b) b = [q[0], q[1], q[0], q[1]];
    else b = [Math.min(b[0], q[0]), Math.min(b[1], q[1]), Math.max(b[2], q[0]), Math.max(b[3], q[1])];
  };
  for (const p of paths) p.points.forEach(add);
  points.forEach(add);
  return b;
}

/**
 * A point on the outline of paths (local metres) to pin a note to: the middle of the northmost
 * edge (the top of the feature on the map, where a note covers the least of it), or the one point
 * of a point feature. Null when the paths have no position.
 */
export function outlineAnchor(paths) {
  let best = null;
  for (const path of paths) {
    const pts = path.points.filter(Boolean);
    if (pts.length === 1 && (!best || pts[0][1] > best[1])) best = pts[0];
    const n = path.closed ? pts.length : pts.length - 1;
    for (let i = 0; i < n && pts.length > 1; i++) {
      const a = pts[i];
      const b = pts[(i + 1) % pts.length];
      const m = [(a[0] + b[0]) / 2, (a[1] + b[1]) / 2];
      if (!best || m[1] > best[1] + 1e-9) best = m;
    }
  }
  return best;
}

/**
 * JSON.parse for drawing only: if the text does not parse, NaN and Infinity (which some exporters
 * write, and JSON cannot carry) are read as null so that the rest of the field can still be drawn.
 * Returns the value, or undefined when the text cannot be read at all.
 */
export function parseForDrawing(text) {
  try {
    return JSON.parse(text);
  } catch {
    try {
      return JSON.parse(text.replace(/"(?:[^"\\]|\\.)*"|-?\bInfinity\b|\bNaN\b/g, (m) => (m[0] === '"' ? m : "null")));
    } catch {
      return undefined;
    }
  }
}
