// Plans exported as ISOXML TaskData (the package's furrow/formats) and read back by an independent
// reader, the npm isoxml package (dev4Agriculture): every corpus field with its suggested
// settings, in versions 4 and 3; the boundary and obstacles within a centimetre, one AB guidance
// pattern per block with its heading (within 0.01 degrees of the heading its own A and B points
// give, within 0.05 of the true heading of each of the block's swaths) and the working width, the
// headland passes as curves. And as KML, read back by @tmcw/togeojson (with @xmldom/xmldom).
import { test } from "node:test";
import assert from "node:assert/strict";
import { readFileSync } from "node:fs";
import { ISOXMLManager } from "isoxml";
import { kml as kmlToGeoJson } from "@tmcw/togeojson";
import { DOMParser } from "@xmldom/xmldom";
import { builtEntry } from "./install.mjs";

const fieldsUrl = new URL("../tests/fields/", import.meta.url);
const furrow = await builtEntry("furrow.js", "furrow_wasm_bg.wasm");
const formats = await builtEntry("formats.js", "furrow_formats_wasm_bg.wasm");

/** The corpus README's table: file, width, headland passes, turning radius. */
function corpus() {
  const rows = [];
  for (const line of readFileSync(new URL("README.md", fieldsUrl), "utf8").split("\n")) {
    const c = line.split("|").map((s) => s.trim());
    if (c.length >= 10 && c[1].endsWith(".geojson")) {
      rows.push({ file: c[1], width: +c[6], headlandPasses: +c[7], turnRadius: +c[8] });
    }
  }
  return rows;
}

/** Metres between two [lon, lat] points (flat near them: fine at centimetres). */
function metres(a, b) {
  const k = (Math.PI / 180) * 6_371_000;
  return Math.hypot((a[0] - b[0]) * k * Math.cos((a[1] * Math.PI) / 180), (a[1] - b[1]) * k);
}

/** The farthest a point of `a` lies from the nearest point of `b`, both ways, metres. */
function apart(a, b) {
  const oneWay = (p, q) => Math.max(...p.map((x) => Math.min(...q.map((y) => metres(x, y)))));
  return Math.max(oneWay(a, b), oneWay(b, a));
}

/** The heading from a to b, degrees from north (Vincenty's inverse on WGS84, written here). */
function heading(a, b) {
  const f = 1 / 298.257223563;
  const rad = Math.PI / 180;
  const L = (b[0] - a[0]) * rad;
  const U1 = Math.atan((1 - f) * Math.tan(a[1] * rad));
  const U2 = Math.atan((1 - f) * Math.tan(b[1] * rad));
  let lambda = L;
  for (let i = 0; i < 100; i++) {
    const sinS = Math.hypot(Math.cos(U2) * Math.sin(lambda), Math.cos(U1) * Math.sin(U2) - Math.sin(U1) * Math.cos(U2) * Math.cos(lambda));
    const cosS = Math.sin(U1) * Math.sin(U2) + Math.cos(U1) * Math.cos(U2) * Math.cos(lambda);
    const sigma = Math.atan2(sinS, cosS);
    const sinA = (Math.cos(U1) * Math.cos(U2) * Math.sin(lambda)) / sinS;
    const cos2A = 1 - sinA * sinA;
    const cos2Sm = cos2A === 0 ? 0 : cosS - (2 * Math.sin(U1) * Math.sin(U2)) / cos2A;
    const C = (f / 16) * cos2A * (4 + f * (4 - 3 * cos2A));
    const next = L + (1 - C) * f * sinA * (sigma + C * sinS * (cos2Sm + C * cosS * (-1 + 2 * cos2Sm * cos2Sm)));
    const done = Math.abs(next - lambda) < 1e-13;
    lambda = next;
    if (done) break;
  }
  const y = Math.cos(U2) * Math.sin(lambda);
  const x = Math.cos(U1) * Math.sin(U2) - Math.sin(U1) * Math.cos(U2) * Math.cos(lambda);
  return ((Math.atan2(y, x) / rad) % 360 + 360) % 360;
}

/** The area of a [lon, lat] ring, square metres (flat near its first point). */
function ringArea(ring) {
  const k = (Math.PI / 180) * 6_371_000;
  const c = Math.cos((ring[0][1] * Math.PI) / 180);
  const xy = ring.map(([lon, lat]) => [lon * k * c, lat * k]);
  let twice = 0;
  for (let i = 0; i < xy.length; i++) {
    const [a, b] = [xy[i], xy[(i + 1) % xy.length]];
    twice += a[0] * b[1] - b[0] * a[1];
  }
  return Math.abs(twice / 2);
}

/** The smallest angle between two directions of travel or their reverses, degrees. */
function lineAngle(a, b) {
  const d = (((a - b) % 180) + 180) % 180;
  return Math.min(d, 180 - d);
}

const points = (lsg) => lsg.attributes.Point.map((p) => [p.attributes.PointEast, p.attributes.PointNorth]);

async function readBack(zip) {
  const manager = new ISOXMLManager();
  await manager.parseISOXMLFile(zip, "application/zip");
  return manager;
}

/** The field's boundary ring and its obstacles' rings, as the plan has them (the field's own
 * boundary: the feature with role boundary, or the single polygon). */
function boundaryOf(field) {
  const features = field.type === "FeatureCollection" ? field.features : [field.type === "Feature" ? field : { geometry: field, properties: {} }];
  const b = features.find((f) => f.properties?.role === "boundary") ?? features.find((f) => f.geometry?.type === "Polygon");
  return b.geometry.coordinates[0];
}

test("every corpus plan exported as ISOXML v4 reads back with the isoxml package: boundary, obstacles, a pattern per block", async () => {
  for (const row of corpus()) {
    const field = JSON.parse(readFileSync(new URL(row.file, fieldsUrl), "utf8"));
    const options = { width: row.width, headlandPasses: row.headlandPasses, turnRadius: row.turnRadius };
    const plan = furrow.plan(field, options);
    const zip = formats.exportTaskData(field, plan, { width: row.width });
    const manager = await readBack(zip);
    assert.deepEqual(manager.getWarnings(), [], `${row.file}: the reader's warnings`);
    assert.equal(manager.options.version, 4);
    const partfields = manager.rootElement.attributes.Partfield;
    assert.equal(partfields.length, 1, row.file);
    const pfd = partfields[0].attributes;
    const polygons = pfd.PolygonnonTreatmentZoneonly;
    const boundary = polygons.filter((p) => p.attributes.PolygonType === "1");
    assert.equal(boundary.length, 1, `${row.file}: one boundary`);
    const ring = points(boundary[0].attributes.LineString[0]);
    assert.ok(apart(ring, boundaryOf(field)) < 0.01, `${row.file}: boundary ${apart(ring, boundaryOf(field))} m off`);
    // Obstacles: those of the plan, each within a centimetre.
    const planObstacles = plan.features.filter((f) => f.properties.kind === "obstacle");
    const obstacles = polygons.filter((p) => p.attributes.PolygonType === "6");
    assert.equal(obstacles.length, planObstacles.length, `${row.file}: obstacles`);
    obstacles.forEach((o, i) => {
      const d = apart(points(o.attributes.LineString[0]), planObstacles[i].geometry.coordinates[0]);
      assert.ok(d < 0.01, `${row.file}: obstacle ${i} ${d} m off`);
    });
    // The headland's inner edge (type 10): the inner field's area within 3 % (the passes are
    // rounded at the turning radius where the inner field keeps its corners).
    const headland = polygons.filter((p) => p.attributes.PolygonType === "10");
    const passesRound = plan.features.some((f) => f.properties.kind === "headland" && f.properties.around === "field" && f.properties.closed);
    if (passesRound) {
      const area = headland.reduce((sum, p) => sum + p.attributes.LineString.reduce((s, l) => s + (l.attributes.LineStringType === "1" ? 1 : -1) * ringArea(points(l)), 0), 0);
      const inner = plan.summary.inner_field_area_m2;
      if (inner > 0) {
        assert.ok(Math.abs(area - inner) <= 0.03 * inner, `${row.file}: headland edge holds ${area} m², the inner field ${inner} m²`);
      } else {
        // Worked by passes to its middle (no inner field): the edge is the innermost pass's,
        // round what the passes leave to the fill, inside the field.
        const field = ringArea(points(boundary[0].attributes.LineString[0]));
        assert.ok(area > 0 && area < field, `${row.file}: headland edge holds ${area} m² of the field's ${field} m²`);
      }
    } else {
      assert.equal(headland.length, 0, `${row.file}: no headland polygon without passes round the field`);
    }
    // One guidance group per block with swaths, an AB line each.
    const blocks = plan.features.filter((f) => f.properties.kind === "block");
    const withSwaths = new Set(plan.features.filter((f) => f.properties.kind === "swath").map((f) => f.properties.block));
    const groups = pfd.GuidanceGroup;
    const blockGroups = groups.filter((g) => g.attributes.GuidanceGroupDesignator.startsWith("Block "));
    assert.equal(blockGroups.length, withSwaths.size, `${row.file}: guidance groups`);
    for (const g of blockGroups) {
      const [pattern] = g.attributes.GuidancePattern;
      assert.equal(g.attributes.GuidancePattern.length, 1);
      assert.equal(pattern.attributes.GuidancePatternType, "1", "AB");
      const [lsg] = pattern.attributes.LineString;
      assert.equal(lsg.attributes.LineStringWidth, Math.round(row.width * 1000));
      const [a, b] = points(lsg);
      const g4 = pattern.attributes.GuidancePatternHeading;
      assert.ok(Math.abs(g4 - heading(a, b)) < 0.01, `${row.file}: heading ${g4} against ${heading(a, b)} from A and B`);
      // Along the block's swaths: within 0.05 degrees of the true heading of every one of them
      // (from the plan's coordinates), and of the block's direction. The swaths are parallel in
      // the field's own map frame, whose north turns from true north by about a hundredth of a
      // degree a kilometre east or west at these latitudes: their true headings differ by that
      // much across a wide block.
      const order = Number(g.attributes.GuidanceGroupDesignator.match(/\d+/)[0]) - 1;
      const block = blocks.find((f) => f.properties.order === order);
      const swaths = plan.features.filter((f) => f.properties.kind === "swath" && f.properties.block === block.properties.index);
      for (const s of swaths) {
        const c = s.geometry.coordinates;
        const along = heading(c[0], c[c.length - 1]);
        assert.ok(lineAngle(g4, along) < 0.05, `${row.file}: block ${order} heading ${g4}, a swath's ${along}`);
      }
      assert.ok(lineAngle(g4, block.properties.bearing_deg) < 0.05, `${row.file}: block ${order} heading ${g4}, direction ${block.properties.bearing_deg}`);
    }
    // The headland passes as curves.
    const passes = plan.features.filter((f) => f.properties.kind === "headland" && f.geometry.coordinates.length >= 2);
    const curves = groups.filter((g) => g.attributes.GuidanceGroupDesignator === "Headland passes").flatMap((g) => g.attributes.GuidancePattern);
    assert.equal(curves.length, passes.length, `${row.file}: headland curves`);
    assert.ok(curves.every((c) => c.attributes.GuidancePatternType === "3"));
  }
});

test("version 3 for older terminals: the same lines as guidance line strings of the partfield; curves as AB segments on request", async () => {
  const field = JSON.parse(readFileSync(new URL("l-shape.geojson", fieldsUrl), "utf8"));
  const plan = furrow.plan(field, { width: 6 });
  const blocks = new Set(plan.features.filter((f) => f.properties.kind === "swath").map((f) => f.properties.block)).size;
  const passes = plan.features.filter((f) => f.properties.kind === "headland");
  const v3 = await readBack(formats.exportTaskData(field, plan, { width: 6, version: 3 }));
  assert.equal(v3.options.version, 3);
  const pfd = v3.rootElement.attributes.Partfield[0].attributes;
  assert.equal(pfd.GuidanceGroup, undefined);
  const lines = pfd.LineString.filter((l) => l.attributes.LineStringType === "5");
  assert.equal(lines.length, blocks + passes.length);
  // Curves as AB segments: every pattern an AB line.
  const ab = await readBack(formats.exportTaskData(field, plan, { width: 6, curvesAsAb: true }));
  const patterns = ab.rootElement.attributes.Partfield[0].attributes.GuidanceGroup.flatMap((g) => g.attributes.GuidancePattern);
  const segments = passes.reduce((n, p) => n + p.geometry.coordinates.length - 1, 0);
  assert.equal(patterns.length, blocks + segments);
  assert.ok(patterns.every((p) => p.attributes.GuidancePatternType === "1"));
  // Names: at most 32 plain characters; the text form is the zip's file.
  const xml = formats.taskDataXml(field, plan, { width: 6, name: "Nørre mark — <the long one by the river bend>" });
  assert.match(xml, /<PFD A="PFD1" C="N_rre mark _ _the long one by th" /);
  assert.throws(() => formats.exportTaskData(field, plan, {}), (e) => e.code === "option_out_of_range");
  assert.throws(() => formats.exportTaskData(field, plan, { width: 6, version: 2 }), (e) => e.code === "invalid_option");
});

test("every corpus plan exported as KML reads back with @tmcw/togeojson: boundary, obstacles, blocks, swaths and passes", () => {
  for (const row of corpus()) {
    const field = JSON.parse(readFileSync(new URL(row.file, fieldsUrl), "utf8"));
    const plan = furrow.plan(field, { width: row.width, headlandPasses: row.headlandPasses, turnRadius: row.turnRadius });
    const text = formats.exportKml(field, plan);
    const read = kmlToGeoJson(new DOMParser().parseFromString(text, "text/xml"));
    const named = (prefix) => read.features.filter((f) => String(f.properties.name).startsWith(prefix));
    const [boundary] = named("Boundary");
    assert.ok(apart(boundary.geometry.coordinates[0], boundaryOf(field)) < 0.01, `${row.file}: boundary`);
    const planObstacles = plan.features.filter((f) => f.properties.kind === "obstacle");
    assert.equal(named("Obstacle ").length, planObstacles.length, `${row.file}: obstacles`);
    for (const [prefix, kind] of [["Block ", "block"], ["Swath ", "swath"], ["Headland pass ", "headland"], ["Turn ", "turn"], ["Connection ", "connection"]]) {
      const mine = plan.features.filter((f) => f.properties.kind === kind);
      const theirs = named(prefix);
      assert.equal(theirs.length, mine.length, `${row.file}: ${kind}`);
    }
    // Every swath where the plan has it, by its number in driving order.
    for (const s of plan.features.filter((f) => f.properties.kind === "swath")) {
      const [k] = named(`Swath ${s.properties.sequence}`).filter((f) => f.properties.name === `Swath ${s.properties.sequence}`);
      assert.ok(apart(k.geometry.coordinates, s.geometry.coordinates) < 0.001, `${row.file}: swath ${s.properties.sequence}`);
    }
  }
});
