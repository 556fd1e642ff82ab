// Turns the input field and the plan (GeoJSON, lon/lat) into a scene in local metres that the
// view draws: an equirectangular projection about the field centre,
//   x = (lon - lon0) · cos(lat0) · R,   y = (lat - lat0) · R   (angles in radians),
// which is accurate to well under a pixel over the size of a farm field.

const R = 6371008.8; // mean Earth radius, metres
const RAD = Math.PI / 180;

/** A projection about (lon0, lat0): `forward([lon, lat]) -> [x, y]` in metres, and its inverse. */
export function makeProjection(lon0, lat0) {
  const kx = Math.cos(lat0 * RAD) * R * RAD;
  const ky = R * RAD;
  return {
    lon0,
    lat0,
    forward: (p) => [(p[0] - lon0) * kx, (p[1] - lat0) * ky],
    inverse: (p) => [p[0] / kx + lon0, p[1] / ky + lat0],
  };
}

/** The polygons of a GeoJSON geometry (Polygon or MultiPolygon), each a list of rings. */
function polygonsOf(geometry) {
  if (!geometry || !Array.isArray(geometry.coordinates)) return [];
  if (geometry.type === "Polygon") return [geometry.coordinates];
  if (geometry.type === "MultiPolygon") return geometry.coordinates;
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

/** The projection centred on the bounding box of the field boundary (or of all its parts). */
export function projectionFor(parts) {
  const rings = parts.boundary ?? [...parts.obstacles, ...parts.prohibited].flat();
  let [x0, y0, x1, y1] = [Infinity, Infinity, -Infinity, -Infinity];
  for (const ring of rings) {
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

const projectRing = (ring, f) => ring.filter((p) => Number.isFinite(p?.[0]) && Number.isFinite(p?.[1])).map(f);
const projectPolygon = (rings, f) => rings.map((r) => projectRing(r, f));

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
 * The plan in local metres: blocks with a label point, the drivable segments by kind (each
 * `{ points, props }`), and where the route starts and ends.
 */
export function planScene(plan, projection) {
  const f = projection.forward;
  const scene = {
    blocks: [],
    obstacles: [],
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
      scene.obstacles.push(projectPolygon(geometry.coordinates, f));
    } else if (props.kind in scene.paths && geometry?.type === "LineString") {
      const points = projectRing(geometry.coordinates, f);
      if (points.length < 2) continue;
      const seg = { points, props };
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
