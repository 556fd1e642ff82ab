// The bearing dial's geometry (www/dial.js): compass bearings of screen points, degrees brought into
// [0, 360), and the SVG sector paths. The dial itself needs a DOM and is not tested here.
//
//   node --test pkg-tests/dial.test.mjs
import { test } from "node:test";
import assert from "node:assert/strict";
import { bearingFromPoint, normaliseDeg, sectorPath } from "../www/dial.js";

const near = (a, b, eps = 1e-9) => Math.abs(a - b) <= eps;

/** The numbers of an "M cx cy L x1 y1 A r r rot large sweep x2 y2 Z" path. */
function parseSector(d) {
  const m = d.match(/^M (\S+) (\S+) L (\S+) (\S+) A (\S+) (\S+) (\S+) ([01]) ([01]) (\S+) (\S+) Z$/);
  assert.ok(m, `not a sector path: ${d}`);
  const n = m.slice(1).map(Number);
  assert.ok(n.every(Number.isFinite), d);
  const [cx, cy, x1, y1, rx, ry, rot, large, sweep, x2, y2] = n;
  return { cx, cy, x1, y1, rx, ry, rot, large, sweep, x2, y2 };
}

test("bearingFromPoint: up 0, right 90, down 180, left 270 (screen y grows downwards)", () => {
  assert.equal(bearingFromPoint(100, 100, 100, 50), 0);
  assert.equal(bearingFromPoint(100, 100, 150, 100), 90);
  assert.equal(bearingFromPoint(100, 100, 100, 150), 180);
  assert.equal(bearingFromPoint(100, 100, 50, 100), 270);
  assert.ok(near(bearingFromPoint(0, 0, 10, -10), 45));
  assert.ok(near(bearingFromPoint(0, 0, 10, 10), 135));
  assert.ok(near(bearingFromPoint(0, 0, -10, 10), 225));
  assert.ok(near(bearingFromPoint(0, 0, -10, -10), 315));
  assert.ok(near(bearingFromPoint(0, 0, -0.001, -100), 360 - 0.000572957795, 1e-8));
  assert.equal(bearingFromPoint(5, 5, 5, 5), 0);
  for (let i = 0; i < 100; i++) {
    const b = bearingFromPoint(0, 0, Math.cos(i) * 37, Math.sin(i * 1.7) * 23);
    assert.ok(b >= 0 && b < 360, String(b));
  }
});

test("normaliseDeg brings angles into [0, 360)", () => {
  assert.equal(normaliseDeg(-10), 350);
  assert.equal(normaliseDeg(725), 5);
  assert.equal(normaliseDeg(360), 0);
  assert.equal(normaliseDeg(0), 0);
  assert.ok(Object.is(normaliseDeg(-0), 0));
  assert.equal(normaliseDeg(-360), 0);
  assert.equal(normaliseDeg(-720.5), 359.5);
  assert.equal(normaliseDeg(359.5), 359.5);
  assert.equal(normaliseDeg(-1e-15), 0);
  assert.equal(normaliseDeg(NaN), 0);
  assert.equal(normaliseDeg(Infinity), 0);
});

test("sectorPath: empty for a span of 0 or a bad radius", () => {
  assert.equal(sectorPath(84, 84, 60, 20, 20), "");
  assert.equal(sectorPath(84, 84, 60, 0, 360 - 360), "");
  assert.equal(sectorPath(84, 84, 60, 350, -10), "");
  assert.equal(sectorPath(84, 84, 0, 20, 70), "");
  assert.equal(sectorPath(84, 84, -5, 20, 70), "");
  assert.equal(sectorPath(84, 84, 60, NaN, 70), "");
});

test("sectorPath: from the centre to the rim at `from`, clockwise to `to`", () => {
  // 0 -> 90: from the top of the circle to its right, a quarter, clockwise.
  const q = parseSector(sectorPath(100, 100, 50, 0, 90));
  assert.deepEqual([q.cx, q.cy, q.x1, q.y1, q.x2, q.y2], [100, 100, 100, 50, 150, 100]);
  assert.deepEqual([q.rx, q.ry, q.rot, q.large, q.sweep], [50, 50, 0, 0, 1]);
  // 20 -> 70: both ends on the rim at their compass bearings.
  const p = parseSector(sectorPath(84, 84, 60, 20, 70));
  assert.equal(p.large, 0);
  assert.ok(near(Math.hypot(p.x1 - 84, p.y1 - 84), 60, 0.01));
  assert.ok(near(Math.hypot(p.x2 - 84, p.y2 - 84), 60, 0.01));
  assert.ok(near(bearingFromPoint(84, 84, p.x1, p.y1), 20, 0.05));
  assert.ok(near(bearingFromPoint(84, 84, p.x2, p.y2), 70, 0.05));
  // Across north: 350 -> 10 is a span of 20, not 340.
  const n = parseSector(sectorPath(0, 0, 10, 350, 10));
  assert.equal(n.large, 0);
  assert.ok(n.x1 < 0 && n.x2 > 0 && n.y1 < 0 && n.y2 < 0);
  // The reverse sector of 20 -> 70 (200 -> 250) lies down and left.
  const r = parseSector(sectorPath(84, 84, 60, 200, 250));
  assert.ok(r.x1 < 84 && r.y1 > 84 && r.x2 < 84 && r.y2 > 84);
});

test("sectorPath: large-arc flag 1 for a span over 180", () => {
  assert.equal(parseSector(sectorPath(84, 84, 60, 0, 180)).large, 0);
  assert.equal(parseSector(sectorPath(84, 84, 60, 0, 181)).large, 1);
  assert.equal(parseSector(sectorPath(84, 84, 60, 10, 300)).large, 1);
  assert.equal(parseSector(sectorPath(84, 84, 60, 300, 10)).large, 0); // span 70
  assert.equal(parseSector(sectorPath(84, 84, 60, 90, 0)).large, 1); // span 270
});

test("sectorPath: the full disc when to - from is 360 or more", () => {
  const d = sectorPath(84, 84, 60, 0, 360);
  assert.match(d, /^M 84 24 A 60 60 0 1 1 84 144 A 60 60 0 1 1 84 24 Z$/);
  assert.equal(sectorPath(84, 84, 60, 10, 400), d);
});
