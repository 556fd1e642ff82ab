// An optional background map under the field: XYZ ("slippy map") web-mercator raster tiles, 256 px
// each, fetched from a URL template such as "https://tile.example.org/{z}/{x}/{y}.png". Off until a
// template is set. The view works in local metres (an equirectangular projection about the field
// centre); each tile is placed by projecting its north-west and south-east corners, which is exact
// at the corners and off by far less than a pixel inside a tile at the size of a farm field.
//
// Tiles are cached as images (the 256 most recently used), a tile that failed to load is never asked
// for again, and a tile not loaded yet is drawn from a loaded ancestor's matching part meanwhile.
// Drawing never throws: a bad template or a degenerate view or projection draws nothing.

const TILE_SIZE = 256;
const MAX_ZOOM = 19;
const MAX_LAT = 85.0511287798066; // web mercator's latitude limit: atan(sinh(pi))
const EQUATOR_RESOLUTION = 156543.03392; // metres per pixel at zoom 0 on the equator (256 px tiles)
const MAX_TILES = 96; // most tiles drawn in one frame
const CACHE_SIZE = 256;
const FAILED_SIZE = 4096; // failed tiles remembered
const ANCESTOR_LEVELS = 4; // how far up a missing tile's stand-in is looked for
const SUBDOMAINS = ["a", "b", "c"];

/**
 * The URL of tile (z, x, y) from a template: `{z}`, `{x}`, `{y}`, `{-y}` (TMS rows, counted from the
 * south) and `{s}` (subdomain a, b or c, by (x + y) % 3) are filled in; other placeholders are left
 * as they are. A template that is not a non-empty string gives "".
 */
export function tileUrl(template, z, x, y) {
  if (typeof template !== "string" || !template) return "";
  const tmsY = 2 ** z - 1 - y;
  const values = { z, x, y, "-y": tmsY, s: SUBDOMAINS[(((x + y) % 3) + 3) % 3] };
  return template.replace(/\{(-?[a-z]+)\}/g, (whole, name) => (name in values ? String(values[name]) : whole));
}

/** Column of the tile at zoom `z` containing longitude `lon` (unclamped, fractional). */
function tileX(lon, z) {
  return ((lon + 180) / 360) * 2 ** z;
}

/** Row of the tile at zoom `z` containing latitude `lat` (row 0 at the north; fractional). */
function tileY(lat, z) {
  const phi = (Math.max(-MAX_LAT, Math.min(MAX_LAT, lat)) * Math.PI) / 180;
  return ((1 - Math.log(Math.tan(phi) + 1 / Math.cos(phi)) / Math.PI) / 2) * 2 ** z;
}

/**
 * The tiles at zoom `z` covering the lon/lat box (degrees) as inclusive indices `{ x0, x1, y0, y1 }`
 * (y0 the northernmost row), clamped to the world (0 .. 2^z - 1). The box's corners may be given in
 * either order. Null if an argument is not a finite number or `z` is not a whole number 0..30.
 */
export function tileRange(west, south, east, north, z) {
  if (![west, south, east, north].every(Number.isFinite) || !Number.isInteger(z) || z < 0 || z > 30) return null;
  const last = 2 ** z - 1;
  const clamp = (v) => Math.max(0, Math.min(last, Math.floor(v)));
  return {
    x0: clamp(tileX(Math.min(west, east), z)),
    x1: clamp(tileX(Math.max(west, east), z)),
    y0: clamp(tileY(Math.max(south, north), z)),
    y1: clamp(tileY(Math.min(south, north), z)),
  };
}

/** Longitude of the west edge of tile column `x` at zoom `z`. */
function tileLon(x, z) {
  return (x / 2 ** z) * 360 - 180;
}

/** Latitude of the north edge of tile row `y` at zoom `z`. */
function tileLat(y, z) {
  return (Math.atan(Math.sinh(Math.PI * (1 - (2 * y) / 2 ** z))) * 180) / Math.PI;
}

/** The lon/lat box of tile (x, y) at zoom `z`: `[west, south, east, north]` in degrees. */
export function tileBounds(x, y, z) {
  return [tileLon(x, z), tileLat(y + 1, z), tileLon(x + 1, z), tileLat(y, z)];
}

/**
 * The zoom level (a whole number 0..19) to draw at `metresPerPixel` on screen near latitude `latDeg`:
 * the coarsest whose tile pixels are at most 1.5 screen pixels (web mercator's ground resolution is
 * 156543.03392 · cos(lat) / 2^z metres per pixel). 0 for a resolution that is not a positive number
 * (Infinity included), 19 for one finer than zoom 19 gives.
 */
export function zoomFor(metresPerPixel, latDeg) {
  if (!(metresPerPixel > 0) || !Number.isFinite(metresPerPixel)) return 0;
  const lat = Number.isFinite(latDeg) ? Math.max(-MAX_LAT, Math.min(MAX_LAT, latDeg)) : 0;
  const ground = EQUATOR_RESOLUTION * Math.cos((lat * Math.PI) / 180);
  const z = Math.ceil(Math.log2(ground / (1.5 * metresPerPixel)) - 1e-9);
  return Math.max(0, Math.min(MAX_ZOOM, z));
}

/** Calls `fn` at the next animation frame (or soon, where there are no frames). */
function nextFrame(fn) {
  if (typeof requestAnimationFrame === "function") requestAnimationFrame(fn);
  else setTimeout(fn, 16);
}

/**
 * A background map of XYZ tiles. `onLoad()` is called (at most once per animation frame) when tile
 * images have arrived, so that the map is drawn again.
 */
export class TileLayer {
  /** `onLoad`: called after tile images arrive; the owner redraws, calling `draw` again. */
  constructor({ onLoad } = {}) {
    this.onLoad = typeof onLoad === "function" ? onLoad : null;
    this.template = "";
    this.cache = new Map(); // "z/x/y" -> { img, loaded }, least recently used first
    this.failed = new Set(); // "z/x/y" of tiles that failed, oldest first
    this.loadPending = false;
  }

  /** Sets the URL template (see `tileUrl`); "" or null turns the map off. A new template empties the cache. */
  setUrl(template) {
    const next = typeof template === "string" ? template.trim() : "";
    if (next === this.template) return;
    for (const entry of this.cache.values()) forget(entry);
    this.cache.clear();
    this.failed.clear();
    this.template = next;
  }

  /** The URL template in use ("" when the map is off). */
  get url() {
    return this.template;
  }

  /**
   * Draws the tiles covering the view (call it first, under everything else). `view` gives `cssW`,
   * `cssH`, `scale` (CSS px per metre), `toWorld(sx, sy)` and `toScreen([x, y])`; `projection` gives
   * `forward([lon, lat])` and `inverse([x, y])`. Returns the number of tiles drawn (stand-ins
   * included); never throws (any failure draws nothing, or fewer tiles).
   */
  draw(ctx, view, projection) {
    if (!this.template || typeof Image === "undefined") return 0;
    try {
      return this.drawTiles(ctx, view, projection);
    } catch {
      return 0;
    }
  }

  /** `draw` without its guard. */
  drawTiles(ctx, view, projection) {
    const w = view.cssW;
    const h = view.cssH;
    if (!(w > 0 && h > 0 && view.scale > 0 && Number.isFinite(view.scale))) return 0;
    const corners = [
      [0, 0],
      [w, 0],
      [0, h],
      [w, h],
    ].map(([sx, sy]) => projection.inverse(view.toWorld(sx, sy)));
    const lons = corners.map((c) => c[0]);
    const lats = corners.map((c) => c[1]);
    if (![...lons, ...lats].every(Number.isFinite)) return 0;
    const centre = projection.inverse(view.toWorld(w / 2, h / 2));
    const west = Math.max(-180, Math.min(...lons));
    const east = Math.min(180, Math.max(...lons));
    const south = Math.max(-MAX_LAT, Math.min(...lats));
    const north = Math.min(MAX_LAT, Math.max(...lats));
    if (!(west < east && south < north)) return 0;

    let z = zoomFor(1 / view.scale, centre[1]);
    let range = tileRange(west, south, east, north, z);
    while (range && z > 0 && (range.x1 - range.x0 + 1) * (range.y1 - range.y0 + 1) > MAX_TILES) {
      z -= 1;
      range = tileRange(west, south, east, north, z);
    }
    if (!range) return 0;

    // Device-pixel rounding of the tile edges, so that neighbouring tiles meet without seams.
    const m = typeof ctx.getTransform === "function" ? ctx.getTransform() : null;
    const dpr = m && m.a > 0 && Number.isFinite(m.a) ? m.a : 1;
    const snap = (v) => Math.round(v * dpr) / dpr;
    const screen = (lon, lat) => view.toScreen(projection.forward([lon, lat]));

    let drawn = 0;
    for (let y = range.y0; y <= range.y1; y++) {
      for (let x = range.x0; x <= range.x1; x++) {
        const [tw, ts, te, tn] = tileBounds(x, y, z);
        const nw = screen(tw, tn);
        const se = screen(te, ts);
        const left = snap(nw[0]);
        const top = snap(nw[1]);
        const dw = snap(se[0]) - left;
        const dh = snap(se[1]) - top;
        if (![left, top, dw, dh].every(Number.isFinite) || dw <= 0 || dh <= 0) continue;
        try {
          if (this.drawTile(ctx, z, x, y, left, top, dw, dh)) drawn += 1;
        } catch {
          // A broken image: skip the tile.
        }
      }
    }
    return drawn;
  }

  /** Draws tile (z, x, y) into the screen rectangle, or a loaded ancestor's part of it; whether it drew. */
  drawTile(ctx, z, x, y, left, top, dw, dh) {
    const entry = this.tile(z, x, y);
    if (entry?.loaded) {
      ctx.drawImage(entry.img, left, top, dw, dh);
      return true;
    }
    for (let k = 1; k <= ANCESTOR_LEVELS && k <= z; k++) {
      const up = this.cache.get(`${z - k}/${x >> k}/${y >> k}`);
      if (!up?.loaded) continue;
      this.touch(`${z - k}/${x >> k}/${y >> k}`, up);
      const side = (up.img.naturalWidth || TILE_SIZE) / 2 ** k;
      const sx = (x - ((x >> k) << k)) * side;
      const sy = (y - ((y >> k) << k)) * side;
      ctx.drawImage(up.img, sx, sy, side, side, left, top, dw, dh);
      return true;
    }
    return false;
  }

  /** The cache entry of tile (z, x, y), its image requested if it is not cached; null if it failed. */
  tile(z, x, y) {
    const key = `${z}/${x}/${y}`;
    if (this.failed.has(key)) return null;
    const cached = this.cache.get(key);
    if (cached) {
      this.touch(key, cached);
      return cached;
    }
    const src = tileUrl(this.template, z, x, y);
    if (!src) return null;
    const img = new Image();
    const entry = { img, loaded: false };
    img.crossOrigin = "anonymous";
    img.decoding = "async";
    img.onload = () => {
      img.onload = img.onerror = null;
      entry.loaded = img.naturalWidth > 0;
      this.loaded();
    };
    img.onerror = () => {
      img.onload = img.onerror = null;
      if (this.cache.get(key) === entry) this.cache.delete(key);
      this.failed.add(key);
      if (this.failed.size > FAILED_SIZE) this.failed.delete(this.failed.values().next().value);
    };
    this.cache.set(key, entry);
    while (this.cache.size > CACHE_SIZE) {
      const [oldKey, old] = this.cache.entries().next().value;
      forget(old);
      this.cache.delete(oldKey);
    }
    img.src = src;
    return entry;
  }

  /** Marks a cache entry as the most recently used. */
  touch(key, entry) {
    this.cache.delete(key);
    this.cache.set(key, entry);
  }

  /** A tile arrived: tell the owner, once per frame. */
  loaded() {
    if (this.loadPending || !this.onLoad) return;
    this.loadPending = true;
    nextFrame(() => {
      this.loadPending = false;
      this.onLoad?.();
    });
  }
}

/** Detaches a dropped cache entry's image, so that a late load or error does nothing. */
function forget(entry) {
  entry.img.onload = null;
  entry.img.onerror = null;
}
