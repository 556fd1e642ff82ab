// The background map's tile arithmetic (www/tiles.js), checked against the standard slippy-map
// formulas, and TileLayer.draw with stand-ins for Image, the canvas, the view and the projection
// (no browser needed).
//
//   node --test pkg-tests/tiles.test.mjs
import { test } from "node:test";
import assert from "node:assert/strict";
import { TileLayer, tileBounds, tileRange, tileUrl, zoomFor } from "../www/tiles.js";
import { makeProjection } from "../www/scene.js";

/** The OpenStreetMap wiki's lon/lat -> tile numbers. */
function slippy(lon, lat, z) {
  const n = 2 ** z;
  const rad = (lat * Math.PI) / 180;
  return {
    x: Math.floor(((lon + 180) / 360) * n),
    y: Math.floor(((1 - Math.asinh(Math.tan(rad)) / Math.PI) / 2) * n),
  };
}

const contains = ([w, s, e, n], lon, lat) => lon >= w && lon < e && lat > s && lat <= n;

test("tileRange at zoom 0 is the one tile, whatever the box", () => {
  assert.deepEqual(tileRange(-180, -85, 180, 85, 0), { x0: 0, x1: 0, y0: 0, y1: 0 });
  assert.deepEqual(tileRange(24.9, 60.1, 25.0, 60.2, 0), { x0: 0, x1: 0, y0: 0, y1: 0 });
  assert.deepEqual(tileRange(-400, -90, 400, 90, 0), { x0: 0, x1: 0, y0: 0, y1: 0 });
});

test("tileRange clamps to the world and takes the corners in either order", () => {
  assert.deepEqual(tileRange(-180, -90, 180, 90, 3), { x0: 0, x1: 7, y0: 0, y1: 7 });
  assert.deepEqual(tileRange(180, 90, -180, -90, 3), { x0: 0, x1: 7, y0: 0, y1: 7 });
  assert.deepEqual(tileRange(0.0001, 0.0001, 0.0002, 0.0002, 1), { x0: 1, x1: 1, y0: 0, y1: 0 });
  // A box touching the equator reaches into the southern row (the slippy formula puts lat 0 there).
  assert.deepEqual(tileRange(-0.0001, 0, 0.0001, 0.0001, 1), { x0: 0, x1: 1, y0: 0, y1: 1 });
  assert.equal(tileRange(NaN, 0, 1, 1, 4), null);
  assert.equal(tileRange(0, 0, 1, 1, 2.5), null);
});

test("Helsinki at zoom 10 is tile 582/296, inside the range and the tile's bounds", () => {
  const [lon, lat, z] = [24.94, 60.17, 10];
  assert.deepEqual(slippy(lon, lat, z), { x: 582, y: 296 });
  const r = tileRange(lon - 0.05, lat - 0.02, lon + 0.05, lat + 0.02, z);
  assert.ok(r.x0 <= 582 && 582 <= r.x1 && r.y0 <= 296 && 296 <= r.y1, JSON.stringify(r));
  assert.ok(r.x1 - r.x0 <= 1 && r.y1 - r.y0 <= 1, JSON.stringify(r));
  assert.deepEqual(tileRange(lon, lat, lon, lat, z), { x0: 582, x1: 582, y0: 296, y1: 296 });
  const b = tileBounds(582, 296, z);
  assert.ok(contains(b, lon, lat), JSON.stringify(b));
  assert.ok(!contains(tileBounds(583, 296, z), lon, lat));
  assert.ok(!contains(tileBounds(582, 297, z), lon, lat));
});

test("tileRange agrees with the slippy-map formula at many places and zooms", () => {
  const places = [
    [24.94, 60.17],
    [-0.1276, 51.5072],
    [-58.38, -34.6],
    [151.21, -33.87],
    [-122.42, 37.77],
    [0.0001, -0.0001],
  ];
  for (const [lon, lat] of places) {
    for (const z of [0, 1, 5, 12, 17, 19]) {
      const t = slippy(lon, lat, z);
      assert.deepEqual(tileRange(lon, lat, lon, lat, z), { x0: t.x, x1: t.x, y0: t.y, y1: t.y }, `${lon} ${lat} z${z}`);
      assert.ok(contains(tileBounds(t.x, t.y, z), lon, lat), `${lon} ${lat} z${z}`);
    }
  }
});

test("tileBounds: the world at zoom 0, shared edges between neighbours, children tile their parent", () => {
  const [w, s, e, n] = tileBounds(0, 0, 0);
  assert.equal(w, -180);
  assert.equal(e, 180);
  assert.ok(Math.abs(n - 85.0511287798) < 1e-9, String(n));
  assert.ok(Math.abs(s + 85.0511287798) < 1e-9, String(s));
  const z = 10;
  const a = tileBounds(582, 296, z);
  const right = tileBounds(583, 296, z);
  const below = tileBounds(582, 297, z);
  assert.equal(a[2], right[0]); // east edge = neighbour's west edge
  assert.equal(a[1], below[3]); // south edge = neighbour's north edge
  assert.equal(a[3], right[3]);
  assert.equal(a[0], below[0]);
  assert.ok(a[0] < a[2] && a[1] < a[3]);
  const parent = tileBounds(291, 148, 9);
  const nw = tileBounds(582, 296, 10);
  const se = tileBounds(583, 297, 10);
  assert.equal(nw[0], parent[0]);
  assert.equal(se[2], parent[2]);
  assert.ok(Math.abs(nw[3] - parent[3]) < 1e-12 && Math.abs(se[1] - parent[1]) < 1e-12);
});

test("zoomFor: finer pixels, higher zoom; tiles never coarser than 1.5 screen pixels; within 0..19", () => {
  const lat = 60.17;
  const ground = (z) => (156543.03392 * Math.cos((lat * Math.PI) / 180)) / 2 ** z;
  let last = -1;
  for (const mpp of [100000, 10000, 1000, 100, 10, 1, 0.5, 0.3, 0.1]) {
    const z = zoomFor(mpp, lat);
    assert.ok(Number.isInteger(z) && z >= 0 && z <= 19, `${mpp}: ${z}`);
    assert.ok(z >= last, `${mpp}: ${z} after ${last}`);
    if (z > 0 && z < 19) {
      assert.ok(ground(z) <= 1.5 * mpp + 1e-9, `${mpp}: z${z} is ${ground(z)} m/px`);
      assert.ok(ground(z - 1) > 1.5 * mpp, `${mpp}: z${z - 1} would do`);
    }
    last = z;
  }
  assert.ok(zoomFor(1, lat) > zoomFor(10, lat));
  assert.equal(zoomFor(1, 0), 17); // 156543 / 2^17 = 1.19 m/px, 2^16 would be 2.39
  assert.equal(zoomFor(1e-6, lat), 19);
  assert.equal(zoomFor(1e9, lat), 0);
  assert.equal(zoomFor(0, lat), 0);
  assert.equal(zoomFor(NaN, lat), 0);
  assert.equal(zoomFor(-1, lat), 0);
  assert.equal(zoomFor(1, NaN), 17);
  assert.ok(zoomFor(1, 60) < zoomFor(1, 0)); // pixels at 60° cover half the ground
});

test("tileUrl fills {z} {x} {y} {s} {-y} and leaves other placeholders", () => {
  const plain = "https://tile.example.org/{z}/{x}/{y}.png";
  assert.equal(tileUrl(plain, 10, 582, 296), "https://tile.example.org/10/582/296.png");
  const subdomains = "https://{s}.tile.example.org/{z}/{x}/{y}.png";
  assert.equal(tileUrl(subdomains, 10, 582, 296), "https://c.tile.example.org/10/582/296.png"); // (582 + 296) % 3 = 2
  assert.equal(tileUrl("https://{s}.t/{z}/{x}/{y}", 3, 0, 0), "https://a.t/3/0/0");
  assert.equal(tileUrl("https://{s}.t/{z}/{x}/{y}", 3, 1, 0), "https://b.t/3/1/0");
  assert.equal(tileUrl("https://t/{z}/{x}/{-y}.png", 10, 582, 296), "https://t/10/582/727.png");
  const other = "https://t/{z}/{x}/{y}.png?key={apikey}&r={r}";
  assert.equal(tileUrl(other, 2, 1, 3), "https://t/2/1/3.png?key={apikey}&r={r}");
  assert.equal(tileUrl("https://t/{y}/{y}", 2, 1, 3), "https://t/3/3");
  assert.equal(tileUrl("", 1, 0, 0), "");
  assert.equal(tileUrl(null, 1, 0, 0), "");
});

// ---- TileLayer.draw with stand-ins -------------------------------------------------------------

/** A stand-in for HTMLImageElement: records what was asked for; the test loads or fails it. */
class FakeImage {
  static made = [];
  constructor() {
    this.naturalWidth = 0;
    this.onload = null;
    this.onerror = null;
    FakeImage.made.push(this);
  }
  set src(v) {
    this._src = v;
  }
  get src() {
    return this._src;
  }
  load() {
    this.naturalWidth = 256;
    this.onload?.();
  }
  fail() {
    this.onerror?.();
  }
}

/** A view like view.js's: centre (cx, cy) metres, `scale` CSS px per metre. */
function fakeView(cssW, cssH, scale, cx = 0, cy = 0) {
  return {
    cssW,
    cssH,
    scale,
    toWorld: (sx, sy) => [cx + (sx - cssW / 2) / scale, cy - (sy - cssH / 2) / scale],
    toScreen: ([x, y]) => [(x - cx) * scale + cssW / 2, cssH / 2 - (y - cy) * scale],
  };
}

function fakeCtx() {
  const calls = [];
  return { calls, drawImage: (...args) => calls.push(args), getTransform: () => ({ a: 1 }) };
}

function withFakes(body) {
  const saved = { Image: globalThis.Image, raf: globalThis.requestAnimationFrame };
  const frames = [];
  globalThis.Image = FakeImage;
  globalThis.requestAnimationFrame = (fn) => frames.push(fn);
  FakeImage.made = [];
  try {
    body(frames);
  } finally {
    globalThis.Image = saved.Image;
    globalThis.requestAnimationFrame = saved.raf;
  }
}

test("TileLayer: off by default, and nothing fetched", () => {
  withFakes(() => {
    const layer = new TileLayer();
    assert.equal(layer.url, "");
    const ctx = fakeCtx();
    assert.equal(layer.draw(ctx, fakeView(800, 600, 2), makeProjection(24.94, 60.17)), 0);
    layer.setUrl(null);
    assert.equal(layer.draw(ctx, fakeView(800, 600, 2), makeProjection(24.94, 60.17)), 0);
    assert.equal(FakeImage.made.length, 0);
    assert.equal(ctx.calls.length, 0);
  });
});

test("TileLayer: fetches the covering tiles, draws them where they lie, redraws once per frame", () => {
  withFakes((frames) => {
    let loads = 0;
    const layer = new TileLayer({ onLoad: () => loads++ });
    layer.setUrl("https://{s}.tile.example.org/{z}/{x}/{y}.png");
    assert.equal(layer.url, "https://{s}.tile.example.org/{z}/{x}/{y}.png");
    const projection = makeProjection(24.94, 60.17);
    const view = fakeView(800, 600, 4); // 0.25 m per pixel
    const ctx = fakeCtx();
    assert.equal(layer.draw(ctx, view, projection), 0); // nothing loaded yet
    const z = zoomFor(0.25, 60.17);
    assert.equal(z, 18);
    const centre = slippy(24.94, 60.17, z);
    assert.ok(FakeImage.made.length > 0 && FakeImage.made.length <= 96);
    const urls = FakeImage.made.map((img) => img.src);
    assert.ok(urls.some((u) => u.endsWith(`/${z}/${centre.x}/${centre.y}.png`)), urls.join("\n"));
    assert.ok(FakeImage.made.every((img) => img.crossOrigin === "anonymous" && img.decoding === "async"));

    for (const img of FakeImage.made) img.load();
    assert.equal(frames.length, 1); // coalesced
    frames.shift()();
    assert.equal(loads, 1);

    const made = FakeImage.made.length;
    const drawn = layer.draw(ctx, view, projection);
    assert.equal(drawn, made);
    assert.equal(FakeImage.made.length, made); // cached: nothing fetched again
    // The centre tile is drawn over the screen centre, with its NW corner where projection puts it.
    const img = FakeImage.made.find((i) => i.src.endsWith(`/${z}/${centre.x}/${centre.y}.png`));
    const call = ctx.calls.find((c) => c[0] === img);
    const [, x, y, w, h] = call;
    assert.ok(x <= 400 && 400 <= x + w && y <= 300 && 300 <= y + h, JSON.stringify(call.slice(1)));
    const [west, , , north] = tileBounds(centre.x, centre.y, z);
    const nw = view.toScreen(projection.forward([west, north]));
    assert.ok(Math.abs(nw[0] - x) <= 0.5 && Math.abs(nw[1] - y) <= 0.5);
    // A tile at zoom 18 at 60° N is about 76 m, 304 px at 4 px per metre.
    assert.ok(Math.abs(w - 304) < 4 && Math.abs(h - 304) < 8, `${w} x ${h}`);
  });
});

test("TileLayer: a failed tile is never asked for again; a missing one is drawn from its parent", () => {
  withFakes(() => {
    const layer = new TileLayer();
    layer.setUrl("https://t/{z}/{x}/{y}.png");
    const projection = makeProjection(24.94, 60.17);
    const ctx = fakeCtx();
    const coarse = fakeView(800, 600, 2); // zoom 17
    layer.draw(ctx, coarse, projection);
    for (const img of FakeImage.made) img.load();
    const fine = fakeView(800, 600, 4); // zoom 18: the same place, tiles of half the size
    const before = FakeImage.made.length;
    const drawnFromParents = layer.draw(ctx, fine, projection);
    const fresh = FakeImage.made.slice(before);
    assert.ok(fresh.length > 0 && fresh.every((i) => i.src.startsWith("https://t/18/")));
    assert.equal(drawnFromParents, fresh.length);
    const quarter = ctx.calls.at(-1);
    assert.equal(quarter.length, 9); // drawImage(img, sx, sy, sw, sh, dx, dy, dw, dh)
    assert.equal(quarter[3], 128);
    assert.ok(quarter[0].src.startsWith("https://t/17/"));

    fresh[0].fail();
    const failedUrl = fresh[0].src;
    const count = FakeImage.made.length;
    layer.draw(ctx, fine, projection);
    layer.draw(ctx, fine, projection);
    assert.equal(FakeImage.made.length, count);
    assert.ok(!FakeImage.made.slice(count).some((i) => i.src === failedUrl));
  });
});

test("TileLayer: never throws, and keeps at most 256 images", () => {
  withFakes(() => {
    const layer = new TileLayer();
    layer.setUrl("https://t/{z}/{x}/{y}.png");
    const ctx = fakeCtx();
    const good = makeProjection(24.94, 60.17);
    const nan = { forward: () => [NaN, NaN], inverse: () => [NaN, NaN] };
    const zero = { forward: () => [0, 0], inverse: () => [0, 0] };
    const throws = { forward: () => { throw new Error("no"); }, inverse: () => { throw new Error("no"); } };
    for (const projection of [nan, zero, throws, {}, null]) {
      assert.equal(layer.draw(ctx, fakeView(800, 600, 2), projection), 0);
    }
    for (const view of [fakeView(0, 0, 2), fakeView(800, 600, 0), fakeView(800, 600, NaN), {}, null]) {
      assert.equal(layer.draw(ctx, view, good), 0);
    }
    assert.equal(layer.draw(null, fakeView(800, 600, 2), good), 0);
    // Zoomed far out: no more than 96 tiles a frame.
    const before = FakeImage.made.length;
    layer.draw(ctx, fakeView(4000, 3000, 1e-4), good);
    assert.ok(FakeImage.made.length - before <= 96 && FakeImage.made.length > before);
    // Pan across many tiles: the cache stays bounded, the oldest images are let go.
    for (let i = 0; i < 30; i++) layer.draw(ctx, fakeView(800, 600, 2, i * 2000, 0), good);
    assert.ok(FakeImage.made.length > 256);
    assert.ok(layer.cache.size <= 256);
    assert.equal(FakeImage.made[0].onload, null);
    // A new template starts afresh.
    layer.setUrl("https://other/{z}/{x}/{y}.png");
    assert.equal(layer.cache.size, 0);
  });
});
