// The viewer's field document and its history (www/editor.js), in Node: no browser needed.
import { test } from "node:test";
import assert from "node:assert/strict";
import { readFileSync } from "node:fs";
import { join } from "node:path";
import {
  History,
  addPolygon,
  counterClockwise,
  deleteFeature,
  deleteVertex,
  editableRings,
  emptyField,
  entranceOf,
  insertVertex,
  moveRing,
  moveVertex,
  parseRanges,
  plannerInput,
  referenceLineOf,
  setEntrance,
  setProperties,
  setReferenceLine,
  signedArea2,
  toCollection,
} from "../www/editor.js";
import { FIELDS } from "./viewer-support.mjs";

const square = () =>
  toCollection({
    type: "Polygon",
    coordinates: [
      [
        [24, 60],
        [24.01, 60],
        [24.01, 60.01],
        [24, 60.01],
        [24, 60],
      ],
      [
        [24.004, 60.004],
        [24.005, 60.004],
        [24.005, 60.005],
        [24.004, 60.004],
      ],
    ],
  });
const ref = { feature: 0, part: 0, ring: 0 };
const ring = (doc, feature = 0) => doc.features[feature].geometry.coordinates[0];

test("toCollection: a collection as it is; a polygon's holes become obstacles; nothing to edit is null", () => {
  const field = JSON.parse(readFileSync(join(FIELDS, "obstacle-types.geojson"), "utf8"));
  assert.deepEqual(toCollection(field), field);
  assert.notEqual(toCollection(field), field, "a copy, not the input");
  const doc = square();
  assert.deepEqual(
    doc.features.map((f) => f.properties.role),
    ["boundary", "obstacle"],
  );
  assert.equal(toCollection({ type: "Point", coordinates: [1, 2] }), null);
  assert.equal(toCollection("text"), null);
  assert.equal(toCollection({ type: "FeatureCollection", features: [] }), null);
});

test("vertices move, are inserted and deleted; rings stay closed and keep three corners", () => {
  const doc = square();
  const moved = moveVertex(doc, ref, 0, [23.999, 59.999]);
  assert.deepEqual(ring(moved)[0], [23.999, 59.999]);
  assert.deepEqual(ring(moved)[4], [23.999, 59.999], "the closing point follows the first");
  assert.deepEqual(ring(doc)[0], [24, 60], "the old document is unchanged");
  const inserted = insertVertex(doc, ref, 1, [24.011, 60.005]);
  assert.equal(ring(inserted).length, 6);
  assert.deepEqual(ring(inserted)[2], [24.011, 60.005], "between vertices 1 and 2");
  const deleted = deleteVertex(inserted, ref, 2);
  assert.deepEqual(ring(deleted), ring(doc));
  const triangle = deleteVertex(doc, ref, 3);
  assert.equal(ring(triangle).length, 4);
  assert.equal(deleteVertex(triangle, ref, 0), null, "a ring keeps three corners");
  assert.equal(moveVertex(doc, ref, 9, [0, 0]), null, "no such vertex");
  assert.equal(moveVertex(doc, ref, 0, [NaN, 0]), null, "not a position");
  const shifted = moveRing(doc, { feature: 1, part: 0, ring: 0 }, [0.001, 0]);
  assert.deepEqual(ring(shifted, 1)[0], [24.005, 60.004]);
  // The editable rings, open, in lon/lat.
  const rings = editableRings(doc);
  assert.deepEqual(
    rings.map((r) => [r.feature, r.role, r.points.length]),
    [
      [0, "boundary", 4],
      [1, "obstacle", 3],
    ],
  );
});

test("polygons are added before the viewer's extras; a boundary replaces the boundary", () => {
  let doc = setEntrance(square(), [24, 60.005]);
  doc = setReferenceLine(doc, [
    [24, 60],
    [24.01, 60.002],
  ]);
  const tri = [
    [24.002, 60.002],
    [24.003, 60.002],
    [24.0025, 60.003],
  ];
  const added = addPolygon(doc, "prohibited", tri, { forbidden_bearings_deg: [[0, 30]] });
  assert.equal(added.feature, 2);
  assert.deepEqual(
    added.doc.features.map((f) => f.properties.role),
    ["boundary", "obstacle", "prohibited", "entrance", "reference_line"],
  );
  const input = plannerInput(added.doc);
  assert.deepEqual(
    input.field.features.map((f) => f.properties.role),
    ["boundary", "obstacle", "prohibited"],
    "the planner gets the polygons, indices unchanged",
  );
  assert.deepEqual(input.entrance, [24, 60.005]);
  assert.deepEqual(input.referenceLine, [
    [24, 60],
    [24.01, 60.002],
  ]);
  const replaced = addPolygon(added.doc, "boundary", [
    [23.99, 59.99],
    [24.02, 59.99],
    [24.02, 60.02],
  ]);
  assert.equal(replaced.feature, 0);
  assert.equal(replaced.doc.features.length, 5, "the boundary replaced, the rest kept");
  assert.equal(addPolygon(doc, "obstacle", tri.slice(0, 2)), null, "three corners at least");
  // A new field: the boundary is the first feature.
  const fresh = addPolygon(emptyField(), "boundary", tri);
  assert.equal(fresh.feature, 0);
  assert.equal(fresh.doc.features[0].geometry.coordinates[0].length, 4);
  // Removing the extras.
  assert.equal(entranceOf(setEntrance(doc, null)), null);
  assert.equal(referenceLineOf(setReferenceLine(doc, null)), null);
  assert.equal(plannerInput(square()).field.features.length, 2);
  assert.equal(deleteFeature(added.doc, 2).features.length, 4);
  assert.deepEqual(setProperties(added.doc, 2, { forbidden_bearings_deg: [[80, 100]] }).features[2].properties, {
    role: "prohibited",
    forbidden_bearings_deg: [[80, 100]],
  });
});

test("a polygon drawn clockwise is kept counter-clockwise; a drag that turns a ring over leaves it as it ran", () => {
  // Independent check: the shoelace sum over the closed ring as stored.
  const shoelace = (closed) => closed.slice(1).reduce((a, p, i) => a + closed[i][0] * p[1] - p[0] * closed[i][1], 0);
  const clockwise = [
    [24.001, 60.009],
    [24.009, 60.009],
    [24.009, 60.001],
    [24.001, 60.001],
  ]; // top-left, top-right, bottom-right, bottom-left: as tapped on the map
  assert.ok(signedArea2(clockwise) < 0);
  const added = addPolygon(emptyField(), "boundary", clockwise);
  const stored = ring(added.doc);
  assert.ok(shoelace(stored) > 0, "stored counter-clockwise");
  assert.deepEqual(stored[0], clockwise[0], "from the first corner tapped");
  assert.deepEqual(new Set(stored.slice(0, -1).map(String)), new Set(clockwise.map(String)), "the same corners");
  assert.deepEqual(counterClockwise(stored.slice(0, -1)), stored.slice(0, -1), "a counter-clockwise ring as it is");
  for (const role of ["obstacle", "prohibited"]) {
    const more = addPolygon(added.doc, role, clockwise.map(([x, y]) => [x / 2 + 12.002, y / 2 + 30.002]));
    assert.ok(shoelace(ring(more.doc, more.feature)) > 0, `${role} stored counter-clockwise`);
  }
  // A triangle's corner dragged across its far side: the ring would run clockwise; it is mirrored
  // about the dragged corner, which keeps its index and its new place.
  const tri = addPolygon(emptyField(), "boundary", [
    [24, 60],
    [24.01, 60],
    [24.005, 60.01],
  ]).doc;
  assert.ok(shoelace(ring(tri)) > 0);
  const moved = moveVertex(tri, ref, 2, [24.005, 59.99]);
  assert.ok(shoelace(ring(moved)) > 0, "still counter-clockwise");
  assert.deepEqual(ring(moved)[2], [24.005, 59.99], "the dragged corner keeps its index");
  assert.deepEqual(new Set(ring(moved).slice(0, -1).map(String)), new Set(["24,60", "24.01,60", "24.005,59.99"]));
  // A clockwise ring from a file stays clockwise when a corner moves (the file's own order).
  const cw = toCollection({ type: "Polygon", coordinates: [[...clockwise, clockwise[0]]] });
  assert.ok(shoelace(ring(moveVertex(cw, ref, 1, [24.0095, 60.0095]))) < 0);
});

test("History: undo and redo over steps; a drag's previews are one step", () => {
  const a = square();
  const h = new History(a);
  assert.equal(h.canUndo, false);
  const b = moveVertex(a, ref, 0, [23.99, 60]);
  h.push(b);
  // A drag: three previews, one commit.
  const c1 = moveVertex(b, ref, 1, [24.02, 60]);
  const c2 = moveVertex(b, ref, 1, [24.03, 60]);
  h.preview(c1);
  h.preview(c2);
  h.commit();
  assert.equal(h.doc, c2);
  assert.equal(h.undo(), b, "undo skips the previews");
  assert.equal(h.undo(), a);
  assert.equal(h.undo(), null, "nothing more to undo");
  assert.equal(h.redo(), b);
  assert.equal(h.redo(), c2);
  assert.equal(h.redo(), null);
  // A new step after undo drops the redo list.
  h.undo();
  h.push(moveVertex(b, ref, 2, [24.02, 60.02]));
  assert.equal(h.canRedo, false);
  // An uncommitted preview is dropped by undo.
  h.preview(a);
  assert.notEqual(h.undo(), a);
  // The limit.
  const small = new History(a, 3);
  for (let i = 0; i < 10; i++) small.push(moveVertex(a, ref, 0, [24 - i / 1000, 60]));
  let n = 0;
  while (small.undo()) n++;
  assert.equal(n, 3);
});

test("parseRanges reads forbidden bearing ranges as typed", () => {
  assert.deepEqual(parseRanges(""), []);
  assert.deepEqual(parseRanges(" 20-70 "), [[20, 70]]);
  assert.deepEqual(parseRanges("20–70, 200 - 250.5"), [
    [20, 70],
    [200, 250.5],
  ]);
  assert.deepEqual(parseRanges("350 10; 5 to 15"), [
    [350, 10],
    [5, 15],
  ]);
  assert.equal(parseRanges("north"), null);
  assert.equal(parseRanges("20"), null);
});
