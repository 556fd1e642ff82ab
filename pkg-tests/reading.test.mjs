// The viewer's reading of field files (www/reading.js), in Node: the planner's limits checked
// before a file is read (its size) and before it is parsed (its points).
import { test } from "node:test";
import assert from "node:assert/strict";
import { readdirSync, readFileSync } from "node:fs";
import { join } from "node:path";
import { countPositions, MAX_INPUT_BYTES, MAX_VERTICES, readFieldFile, readFieldText, sizeError } from "../www/reading.js";
import { FIELDS } from "./viewer-support.mjs";

/** Independent count: arrays whose first member is a number, in the parsed value. */
function parsedPositions(value) {
  if (Array.isArray(value)) return typeof value[0] === "number" ? 1 : value.reduce((n, v) => n + parsedPositions(v), 0);
  if (value && typeof value === "object") return Object.values(value).reduce((n, v) => n + parsedPositions(v), 0);
  return 0;
}

test("countPositions counts as the parsed value has them, whitespace and strings notwithstanding", () => {
  const files = readdirSync(FIELDS).filter((f) => f.endsWith(".geojson")).map((f) => join(FIELDS, f));
  files.push(join(FIELDS, "real/dk_marker_2026_sample.geojson"));
  for (const file of files) {
    const text = readFileSync(file, "utf8");
    assert.equal(countPositions(text), parsedPositions(JSON.parse(text)), file);
    const pretty = JSON.stringify(JSON.parse(text), null, "\t");
    assert.equal(countPositions(pretty), parsedPositions(JSON.parse(pretty)), `${file}, indented`);
  }
  const tricky = JSON.stringify({ name: 'a "[1, 2]" \\[3', list: [-1.5, 2], nested: [[[1e3, 2]], [["x"]]] });
  assert.equal(countPositions(tricky), parsedPositions(JSON.parse(tricky)));
  assert.equal(countPositions(`[${"[1,2],".repeat(99)}[1,2]]`, 10), 11, "stops just past the limit");
});

test("the planner's limits: 32 MB read, 200,000 points", async () => {
  assert.equal(MAX_INPUT_BYTES, 32 * 1024 * 1024);
  assert.equal(MAX_VERTICES, 200_000);
  assert.equal(sizeError("a.geojson", MAX_INPUT_BYTES), null);
  assert.equal(sizeError("a.geojson", MAX_INPUT_BYTES + 1).code, "input_too_large");
  assert.match(sizeError("a.geojson", 36e6).message, /a\.geojson is 34 MB; the planner reads at most 32 MB/);
  // A file over the size is refused without being read.
  let read = false;
  const huge = { name: "huge.geojson", size: 40 * 1024 * 1024, text: () => ((read = true), Promise.resolve("")) };
  assert.equal((await readFieldFile(huge)).error.code, "input_too_large");
  assert.equal(read, false, "not read");
  const ring = (n) => `{"type":"Polygon","coordinates":[[${Array.from({ length: n }, (_, i) => `[${i % 7},${i % 5}]`).join(",")}]]}`;
  assert.equal(readFieldText(ring(MAX_VERTICES)).field.type, "Polygon", "at the limit: parsed for drawing");
  const over = readFieldText(ring(MAX_VERTICES + 1));
  assert.equal(over.error.code, "input_too_large");
  assert.match(over.error.message, /more than 200000 points/);
  // Text that is not JSON goes to the planner as it is, to say where it breaks.
  const broken = await readFieldFile(new Blob(['{"type": "Polygon", "coordinates": [[[1, 2], [3']));
  assert.equal(broken.field, undefined);
  assert.match(broken.text, /^\{"type"/);
});
