// Generates src/field/landmask.bin: a coarse map of where land is, used to spot fields whose
// longitude and latitude were swapped (such a field usually lands in the sea).
//
//   node scripts/landmask.mjs     (a development tool; the output is committed)
//
// Source: Natural Earth 1:50m land (public domain), as TopoJSON in the npm package world-atlas
// (ISC). Grid: 0.5 degree cells, 720 columns from longitude -180 and 360 rows from latitude -90.
// A cell is land when any of 3 x 3 sample points in it is on land, so coasts count as land.
// Format: "FLM1", u16 columns, u16 rows (little endian); then per row, LEB128 varints: the
// number of runs, then run lengths alternating sea, land, sea, ... starting with sea.
import { readFileSync, writeFileSync } from "node:fs";
import { feature } from "topojson-client";

const CELL = 0.5;
const COLS = 360 / CELL;
const ROWS = 180 / CELL;
const SUB = [1 / 6, 1 / 2, 5 / 6];

const topology = JSON.parse(readFileSync(new URL("../node_modules/world-atlas/land-50m.json", import.meta.url)));
const land = feature(topology, topology.objects.land);
const rings = [];
for (const f of land.features ?? [land]) {
  const g = f.geometry;
  const polygons = g.type === "Polygon" ? [g.coordinates] : g.coordinates;
  for (const polygon of polygons) for (const ring of polygon) rings.push(ring);
}
const edges = [];
for (const ring of rings) {
  for (let i = 0; i + 1 < ring.length; i++) edges.push([ring[i], ring[i + 1]]);
}

/** Longitude intervals on land along a latitude (even-odd over all rings). */
function landAlong(lat) {
  const xs = [];
  for (const [[x0, y0], [x1, y1]] of edges) {
    if (y0 <= lat !== y1 <= lat) xs.push(x0 + ((lat - y0) / (y1 - y0)) * (x1 - x0));
  }
  xs.sort((a, b) => a - b);
  const out = [];
  for (let i = 0; i + 1 < xs.length; i += 2) out.push([xs[i], xs[i + 1]]);
  return out;
}

const bytes = [0x46, 0x4c, 0x4d, 0x31, COLS & 255, COLS >> 8, ROWS & 255, ROWS >> 8];
const varint = (n) => {
  do {
    let b = n & 127;
    n >>>= 7;
    if (n) b |= 128;
    bytes.push(b);
  } while (n);
};
let landCells = 0;
for (let r = 0; r < ROWS; r++) {
  const row = new Uint8Array(COLS);
  for (const s of SUB) {
    const intervals = landAlong(-90 + (r + s) * CELL);
    for (let c = 0; c < COLS; c++) {
      if (row[c]) continue;
      for (const t of SUB) {
        const lon = -180 + (c + t) * CELL;
        if (intervals.some(([a, b]) => lon >= a && lon <= b)) {
          row[c] = 1;
          break;
        }
      }
    }
  }
  const runs = [];
  let value = 0;
  let length = 0;
  for (let c = 0; c < COLS; c++) {
    if (row[c] !== value) {
      runs.push(length);
      value = row[c];
      length = 0;
    }
    length++;
    landCells += row[c];
  }
  runs.push(length);
  varint(runs.length);
  runs.forEach(varint);
}
writeFileSync(new URL("../src/field/landmask.bin", import.meta.url), Buffer.from(bytes));
console.log(`landmask: ${bytes.length} bytes, ${landCells} of ${COLS * ROWS} cells land`);
