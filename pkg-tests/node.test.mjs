// The built npm package (pkg/) as a Node app uses it: initSync with the wasm bytes, then plan;
// and as installed from npm, in fresh Node processes: the README's Node example as written,
// init() reading the file, calls before init.
import { test } from "node:test";
import assert from "node:assert/strict";
import { execFileSync } from "node:child_process";
import { copyFileSync, existsSync, readFileSync, readdirSync, rmSync, writeFileSync } from "node:fs";
import { join } from "node:path";
import { gzipSync } from "node:zlib";
import { builtEntry, codeBlocks, installPacked, PKG_URL as pkgUrl } from "./install.mjs";

const fieldsUrl = new URL("../tests/fields/", import.meta.url);
const furrow = await builtEntry("furrow.js", "furrow_wasm_bg.wasm");
const tracksEntry = await builtEntry("tracks.js", "furrow_tracks_wasm_bg.wasm");
const formatsEntry = await builtEntry("formats.js", "furrow_formats_wasm_bg.wasm");
const fixturesUrl = new URL("../tests/format-fixtures/", import.meta.url);

const readField = (name) => JSON.parse(readFileSync(new URL(name, fieldsUrl), "utf8"));

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

test("package.json describes the package", () => {
  const pkg = JSON.parse(readFileSync(new URL("package.json", pkgUrl), "utf8"));
  assert.equal(pkg.name, "furrow");
  assert.equal(pkg.type, "module");
  assert.equal(pkg.types, "furrow.d.ts");
  assert.equal(pkg.license, "MIT OR Apache-2.0");
  for (const file of pkg.files) assert.ok(existsSync(new URL(file, pkgUrl)), file);
  for (const licence of ["LICENSE-MIT", "LICENSE-APACHE"]) {
    assert.ok(pkg.files.includes(licence), licence);
    assert.equal(
      readFileSync(new URL(licence, pkgUrl), "utf8"),
      readFileSync(new URL(`../${licence}`, import.meta.url), "utf8"),
    );
  }
  assert.equal(pkg.exports["./package.json"], "./package.json");
  assert.match(pkg.engines.node, /^>=\d+/);
  assert.ok(
    Number(process.versions.node.split(".")[0]) >= Number(pkg.engines.node.match(/\d+/)[0]),
    "this Node is one the package claims",
  );
  // The repository's address, where Cargo.toml gives one.
  const cargo = readFileSync(new URL("../Cargo.toml", import.meta.url), "utf8");
  const repository = cargo.match(/^repository = "(.*)"$/m)?.[1];
  if (repository) assert.equal(pkg.repository.url, `git+${repository}.git`);
});

/** The names an entry's .d.ts exports (re-exported lists and its own declarations). */
function exportedNames(entry) {
  return new Set([
    ...[...entry.matchAll(/^export (?:type )?\{([^}]*)\}/gm)].flatMap((m) => m[1].split(",").map((n) => n.trim())),
    ...[...entry.matchAll(/^export (?:declare )?(?:interface|type|class|function) (\w+)/gm)].map((m) => m[1]),
  ]);
}

/** The API's names in a wasm-bindgen module's .d.ts (its own __wbg functions aside). */
function moduleNames(dts) {
  return [...dts.matchAll(/^export (?:interface|type|class|function) (\w+)/gm)]
    .map((m) => m[1])
    .filter((name) => !name.startsWith("__wbg"));
}

test("the planner's module is within its 400 KB gzipped; the tracks' is apart from it", () => {
  // Gzipped as scripts/build.sh and the bench report measure it (Node's zlib at level 9).
  const gzipped = (file) => gzipSync(readFileSync(new URL(file, pkgUrl)), { level: 9 }).length;
  const planner = gzipped("furrow_wasm_bg.wasm");
  assert.ok(planner < 400_000, `furrow_wasm_bg.wasm is ${planner} bytes gzipped`);
  assert.ok(gzipped("furrow_tracks_wasm_bg.wasm") > 20_000, "the tracks' code is in its own module");
});

test("furrow/formats reads a zipped Shapefile (RD New) to the register's parcels, in a module of its own", () => {
  const gzipped = (file) => gzipSync(readFileSync(new URL(file, pkgUrl)), { level: 9 }).length;
  assert.ok(gzipped("furrow_formats_wasm_bg.wasm") > 50_000, "the readers are in their own module");
  const zip = readFileSync(new URL("nl_brp_rd_new.zip", fixturesUrl));
  const file = formatsEntry.readFieldFile(zip, "nl_brp_rd_new.zip");
  assert.equal(file.type, "FeatureCollection");
  assert.equal(file.source.crs, "EPSG:28992 (Amersfoort / RD New)");
  // The register's own WGS84 coordinates (written by another program, GDAL, in RD New): every
  // vertex within a centimetre (1e-7 degrees is 1.1 cm of latitude).
  const register = readField("real/nl_brp_2023_sample.geojson");
  assert.equal(file.features.length, register.features.length);
  file.features.forEach((f, i) => {
    const got = f.geometry.coordinates.flat();
    const want = register.features[i].geometry.coordinates.flat();
    assert.equal(got.length, want.length, `parcel ${i}`);
    for (const p of got) {
      const near = want.some((q) => Math.abs(p[0] - q[0]) < 1e-7 && Math.abs(p[1] - q[1]) < 1e-7);
      assert.ok(near, `parcel ${i}: ${p} is not a vertex of the register's`);
    }
  });
  // A parcel plans as a field of its own.
  const result = furrow.plan(file.features[0], { width: 6 });
  assert.ok(result.summary.swath_count > 0);
  // The parts dropped together read as the zip does; a damaged zip is a typed error.
  const parts = ["shp", "shx", "dbf", "prj"].map((ext) => ({
    name: `nl_brp_rd_new.${ext}`,
    bytes: unzipOne(zip, `nl_brp_rd_new.${ext}`),
  }));
  assert.equal(formatsEntry.readShapefile(parts).features.length, register.features.length);
  assert.throws(
    () => formatsEntry.readFieldFile(zip.subarray(0, zip.length >> 1), "cut.zip"),
    (e) => e instanceof furrow.FurrowError && e.code === "invalid_file",
  );
  // TaskData (written by the npm isoxml package): the Dutch parcels, each with its AB line.
  const taskdata = formatsEntry.readFieldFile(readFileSync(new URL("nl_brp_taskdata_v3.zip", fixturesUrl)), "nl.zip");
  assert.equal(taskdata.source.format, "isoxml");
  assert.equal(taskdata.features.length, register.features.length);
  assert.ok(taskdata.features.every((f) => f.properties.reference_line?.length === 2));
  // KMZ (GDAL's KML, zipped): the Danish parcels by their names.
  const kmz = formatsEntry.readFieldFile(readFileSync(new URL("dk_marker.kmz", fixturesUrl)), "dk_marker.kmz");
  assert.equal(kmz.source.format, "kmz");
  const danish = readField("real/dk_marker_2026_sample.geojson");
  assert.deepEqual(kmz.features.map((f) => f.properties.name), danish.features.map((f) => f.properties.id));
  assert.throws(
    () => formatsEntry.readShapefile(parts.filter((p) => !p.name.endsWith(".shp"))),
    (e) => e instanceof furrow.FurrowError && e.code === "invalid_file" && /\.shp/.test(e.message),
  );
});

/** A file of a zip archive, unpacked by Python's zipfile (another reader than the package's). */
function unzipOne(zip, name) {
  const script = "import sys, zipfile, io; sys.stdout.buffer.write(zipfile.ZipFile(io.BytesIO(sys.stdin.buffer.read())).read(sys.argv[1]))";
  return new Uint8Array(execFileSync("python3", ["-c", script, name], { input: zip, maxBuffer: 1 << 26 }));
}

test("TypeScript definitions declare the API and export every type", () => {
  const entry = readFileSync(new URL("furrow.d.ts", pkgUrl), "utf8");
  for (const name of ["plan", "defaultOptions", "version", "initSync", "default", "Plan", "PlanOptions", "FurrowError"]) {
    assert.match(entry, new RegExp(`\\b${name}\\b`), `furrow.d.ts re-exports ${name}`);
  }
  assert.match(entry, /export declare class FurrowError extends Error/);
  const dts = readFileSync(new URL("furrow_wasm.d.ts", pkgUrl), "utf8");
  assert.match(dts, /export function plan\(field: FieldInput, options\?: PlanOptions\): Plan;/);
  // Every type, class and function of each wasm module's API is exported by its entry.
  const names = moduleNames(dts);
  assert.ok(names.length > 30, names.join());
  const exported = exportedNames(entry);
  for (const name of names) assert.ok(exported.has(name), `furrow.d.ts exports ${name}`);
  const tracksEntry = readFileSync(new URL("tracks.d.ts", pkgUrl), "utf8");
  const tracksNames = moduleNames(readFileSync(new URL("furrow_tracks_wasm.d.ts", pkgUrl), "utf8"));
  for (const name of ["TrackGraph", "shortestPath", "TrackPathFeature", "TrackPathOptions", "Turning"]) {
    assert.ok(tracksNames.includes(name), `furrow_tracks_wasm.d.ts declares ${name}`);
  }
  const tracksExported = exportedNames(tracksEntry);
  for (const name of [...tracksNames, "initSync", "FurrowError"]) {
    assert.ok(tracksExported.has(name), `tracks.d.ts exports ${name}`);
  }
  assert.match(tracksEntry, /^export default function initTracks\(/m);
  const formatsDts = readFileSync(new URL("formats.d.ts", pkgUrl), "utf8");
  assert.match(formatsDts, /^export default function initFormats\(/m);
  for (const name of ["readFieldFile", "readShapefile", "initSync", "FurrowError", "FieldFileGeoJson"]) {
    assert.ok(exportedNames(formatsDts).has(name), `formats.d.ts exports ${name}`);
  }
  assert.doesNotMatch(entry + readFileSync(new URL("furrow.js", pkgUrl), "utf8"), /__panic|ForTests/);
  // Every option the planner knows is typed.
  for (const key of Object.keys(furrow.defaultOptions())) {
    assert.match(dts, new RegExp(`\\b${key}\\?:`), `option ${key}`);
  }
});

test("every corpus field plans with its suggested settings", () => {
  const rows = corpus();
  assert.ok(rows.length >= 20);
  for (const row of rows) {
    const field = readField(row.file);
    const { file, ...options } = row;
    const plan = furrow.plan(field, options);
    assert.equal(plan.type, "FeatureCollection", file);
    assert.ok(plan.summary.swath_count > 0, file);
    // Drivable features follow each other in driving order, each starting where the last ended.
    const drivable = plan.features.filter((f) =>
      ["swath", "headland", "turn", "connection"].includes(f.properties.kind),
    );
    drivable.forEach((f, i) => assert.equal(f.properties.sequence, i, file));
    for (let i = 1; i < drivable.length; i++) {
      const end = drivable[i - 1].geometry.coordinates.at(-1);
      const start = drivable[i].geometry.coordinates[0];
      assert.ok(Math.abs(end[0] - start[0]) < 1e-8 && Math.abs(end[1] - start[1]) < 1e-8, file);
    }
    // The plan is in the input's coordinates: near the field's own longitude and latitude.
    const [lon, lat] = field.features[0].geometry.coordinates[0][0];
    const [x, y] = drivable[0].geometry.coordinates[0];
    assert.ok(Math.abs(x - lon) < 0.05 && Math.abs(y - lat) < 0.05, file);
  }
});

test("options change the plan", () => {
  const field = readField("rectangle.geojson");
  const a = furrow.plan(field, { width: 6, headlandPasses: 2 });
  const b = furrow.plan(field, { width: 3, headlandPasses: 2 });
  const c = furrow.plan(field, { width: 6, headlandPasses: 2, bearing: 0 });
  // 22 swaths across the inner field, and any that fill the corners the passes round off.
  assert.equal(a.summary.swath_count - a.summary.fill_swath_count, 22);
  assert.ok(b.summary.swath_count > 40);
  assert.ok(Math.abs(c.summary.bearing_deg) < 1e-6);
  assert.notEqual(c.summary.swath_count, a.summary.swath_count);
});

test("the path comes as drivable turns and as typed arrays of samples", () => {
  const field = readField("rectangle.geojson");
  const plan = furrow.plan(field, { width: 6, headlandPasses: 2, turnRadius: 8, reverse: true });
  const s = plan.samples;
  assert.ok(s.x instanceof Float64Array && s.heading_deg instanceof Float64Array);
  assert.ok(s.kind instanceof Uint8Array && s.segment instanceof Uint32Array);
  assert.ok(s.x.length > 10000);
  for (const key of ["y", "heading_deg", "curvature", "distance_m", "time_s", "kind", "reverse", "working", "segment"]) {
    assert.equal(s[key].length, s.x.length, key);
  }
  // Half a metre apart at most, curvature within 1/r, the path's length at the end.
  for (let i = 1; i < s.x.length; i++) {
    assert.ok(s.distance_m[i] - s.distance_m[i - 1] <= 0.5 + 1e-9);
    assert.ok(Math.abs(s.curvature[i]) <= 1 / 8 + 1e-6);
  }
  assert.ok(Math.abs(s.distance_m[s.x.length - 1] - plan.summary.total_distance_m) < 1);
  const turns = plan.features.filter((f) => f.properties.kind === "turn");
  assert.ok(turns.length > 10);
  for (const t of turns) {
    assert.ok(t.properties.form, "a turn has its form");
    assert.equal(t.properties.heading_deg.length, t.geometry.coordinates.length);
  }
  assert.equal(plan.summary.turns_outside_field, 0);
});

test("invalid inputs throw a FurrowError with a code", () => {
  const expected = {
    "hole-crossing-boundary.geojson": "hole_crossing_boundary",
    "latitude-out-of-range.geojson": "coordinate_out_of_range",
    "obstacle-outside-field.geojson": "obstacle_outside_field",
    "self-intersecting-bowtie.geojson": "self_intersection",
    "too-few-points.geojson": "too_few_points",
    "zero-area.geojson": "zero_area",
    "not-geojson.geojson": "invalid_json",
    "nan-coordinates.geojson": "invalid_json",
  };
  for (const file of readdirSync(new URL("invalid/", fieldsUrl))) {
    if (!(file in expected)) continue;
    // Text in both cases: two of the files are not JSON at all.
    const text = readFileSync(new URL(`invalid/${file}`, fieldsUrl), "utf8");
    assert.throws(
      () => furrow.plan(text),
      (e) => e instanceof furrow.FurrowError && e.name === "FurrowError" && e.code === expected[file],
      file,
    );
  }
  // The place in the input comes along, and the stack leads to the caller.
  const bowtie = { type: "Polygon", coordinates: [[[0, 0], [1, 1], [1, 0], [0, 1], [0, 0]]] };
  assert.throws(
    () => furrow.plan(bowtie),
    (e) =>
      e instanceof furrow.FurrowError &&
      e instanceof Error &&
      e.code === "self_intersection" &&
      e.coordinate.length === 2 &&
      e.message.length > 0 &&
      String(e).startsWith("FurrowError: ") &&
      e.stack.includes("node.test.mjs"),
  );
  const made = new furrow.FurrowError("a message", { code: "no_path", feature: 2 });
  assert.deepEqual([made.name, made.code, made.feature, made.ring, made.message], ["FurrowError", "no_path", 2, undefined, "a message"]);
  assert.throws(() => furrow.plan(readField("rectangle.geojson"), { width: -1 }), { code: "option_out_of_range" });
  assert.throws(() => furrow.plan(readField("rectangle.geojson"), { widht: 3 }), { code: "invalid_option" });
});

test("the planner's memory stays flat over 1,000 re-plans of a field whose corner is dragged", () => {
  // As the viewer re-plans while a vertex is dragged: a corner moved a centimetre a plan, out
  // over 50 places and back, ten times. The wasm memory only grows: once every place has been
  // planned, a leak that keeps part of each plan (its text, its samples) shows as pages added
  // over the 900 plans after.
  const field = readField("square-1ha.geojson");
  const options = { width: 2.5, headlandPasses: 3, turnRadius: 2.1 };
  const bytes = readFileSync(new URL("furrow_wasm_bg.wasm", pkgUrl));
  const memory = () => furrow.initSync({ module: bytes }).memory.buffer.byteLength;
  const planned = (k) => {
    const step = k % 100 < 50 ? k % 100 : 100 - (k % 100);
    const moved = structuredClone(field);
    const ring = moved.features[0].geometry.coordinates[0];
    ring[2] = [ring[2][0] + step * 1.8e-7, ring[2][1] + step * 0.9e-7];
    return furrow.plan(moved, options).summary.swath_count;
  };
  for (let k = 0; k < 100; k++) assert.ok(planned(k) > 0);
  const warm = memory();
  for (let k = 100; k < 1000; k++) assert.ok(planned(k) > 0);
  assert.equal(memory(), warm, `wasm memory ${warm} -> ${memory()} bytes over 900 plans`);
});

test("the instance keeps planning after errors", () => {
  for (let i = 0; i < 50; i++) {
    assert.throws(() => furrow.plan("{"), { code: "invalid_json" });
  }
  assert.equal(furrow.plan(readField("square-1ha.geojson")).type, "FeatureCollection");
});

test("a trap inside the planner is reported and the planner recovers", () => {
  const field = readField("square-1ha.geojson");
  const before = furrow.plan(field);
  // No input makes the planner trap. To see the recovery, the clock the planner reads (through
  // performance.now) throws a RuntimeError, as a trap does, part-way through a plan: the
  // instance is left mid-call, as after a trap.
  // (An own property over the prototype's, which is read-only in Node 18.)
  const now = performance.now;
  let calls = 0;
  Object.defineProperty(performance, "now", {
    configurable: true,
    value() {
      if (++calls === 2) throw new WebAssembly.RuntimeError("unreachable");
      return now.call(this);
    },
  });
  try {
    assert.throws(
      () => furrow.plan(field),
      (e) => e instanceof furrow.FurrowError && e.code === "internal" && e.cause instanceof WebAssembly.RuntimeError,
    );
  } finally {
    delete performance.now;
  }
  assert.equal(performance.now, now);
  assert.equal(calls, 2, "the planner read the clock");
  // A fresh instance plans the same field to the same plan.
  const after = furrow.plan(field);
  assert.equal(after.summary.swath_count, before.summary.swath_count);
  assert.equal(after.features.length, before.features.length);
  for (let i = 0; i < 20; i++) furrow.plan(field);
});

test("shortest paths along the tracks: TrackGraph and shortestPath of furrow/tracks", () => {
  const field = readField("large-250ha-10-obstacles.geojson");
  const result = furrow.plan(field, { width: 24, headlandPasses: 2, turnRadius: 9 });
  // The planner's module has none of the tracks' code.
  assert.equal(furrow.TrackGraph, undefined);
  assert.equal(furrow.shortestPath, undefined);
  const tracks = new tracksEntry.TrackGraph(result);
  assert.ok(tracks.trackCount > 100 && tracks.junctionCount > 100, `${tracks.trackCount} tracks`);
  // From the middle of a swath facing its way, to the field's first vertex.
  const swath = result.features.find((f) => f.properties.kind === "swath" && f.properties.length_m > 200);
  const [a, b] = [swath.geometry.coordinates[0], swath.geometry.coordinates.at(-1)];
  const middle = [(a[0] + b[0]) / 2, (a[1] + b[1]) / 2];
  const exit = field.features[0].geometry.coordinates[0][0];
  const lengths = {};
  // Without options: no turning on the spot.
  const plain = tracks.shortestPath(middle, swath.properties.bearing_deg, exit);
  assert.equal(plain.properties.turning, "heading");
  for (const turning of ["on-the-spot", "heading", "tracks"]) {
    let path;
    try {
      path = tracks.shortestPath(middle, swath.properties.bearing_deg, exit, { turning });
    } catch (e) {
      assert.equal(e.code, "no_path", `${turning}: ${e.message}`);
      continue;
    }
    assert.equal(path.type, "Feature");
    assert.equal(path.properties.turning, turning);
    assert.ok(path.geometry.coordinates.length >= 2);
    // The middle of the ends' longitudes and latitudes lies a few centimetres off a long swath
    // in the plan's projection (2.4 cm for this one of 679 m).
    assert.ok(path.properties.start_offset_m < 0.05, `the start is on a track: ${path.properties.start_offset_m} m off`);
    lengths[turning] = path.properties.length_m;
  }
  assert.ok(lengths["on-the-spot"] > 0 && lengths["on-the-spot"] <= lengths.heading, JSON.stringify(lengths));
  if (lengths.tracks) assert.ok(lengths.heading <= lengths.tracks);
  // The one-call form, and several exits: the nearest wins.
  const one = tracksEntry.shortestPath(result, middle, swath.properties.bearing_deg, [exit, middle], { turning: "on-the-spot" });
  assert.ok(one.properties.length_m <= lengths["on-the-spot"]);
  // Errors are FurrowErrors with codes.
  const code = (f) => {
    try {
      f();
    } catch (e) {
      // One FurrowError class for both entries.
      assert.ok(e instanceof furrow.FurrowError && e instanceof tracksEntry.FurrowError, String(e));
      return e.code;
    }
    return null;
  };
  assert.equal(code(() => tracks.shortestPath([middle[0] + 0.1, middle[1]], 0, exit)), "off_tracks");
  assert.equal(code(() => tracks.shortestPath(middle, 0, exit, { turning: "sideways" })), "invalid_option");
  assert.equal(code(() => tracks.shortestPath("here", 0, exit)), "invalid_option");
  assert.equal(code(() => new tracksEntry.TrackGraph({ type: "FeatureCollection" })), "invalid_geojson");
  tracks.free();
});

/** Runs `script` (an ES module) with Node in `dir`; its standard output. */
function node(dir, script, file = "main.mjs") {
  writeFileSync(join(dir, file), script);
  return execFileSync(process.execPath, [file], { cwd: dir, encoding: "utf8", stdio: ["ignore", "pipe", "pipe"] });
}

test("the package as installed: the README's Node example as written, and calls before init", () => {
  const { dir, files } = installPacked("node");
  for (const file of ["furrow.js", "furrow_wasm.js", "furrow_wasm_bg.wasm", "furrow.d.ts", "load.js", "pool.js", "pool-worker.js", "furrow_pool_wasm.js", "furrow_pool_wasm_bg.wasm", "tracks.js", "tracks.d.ts", "furrow_tracks_wasm.js", "furrow_tracks_wasm_bg.wasm", "LICENSE-MIT", "LICENSE-APACHE"]) {
    assert.ok(files.includes(file), `the package holds ${file}`);
  }
  // The README's example that reads field.geojson, run as it is written.
  const readme = readFileSync(new URL("../js/README.md", import.meta.url), "utf8");
  const example = codeBlocks(readme, "js").find((block) => block.includes('from "node:fs"'));
  assert.ok(example, "js/README.md has a Node example");
  copyFileSync(new URL("rectangle.geojson", fieldsUrl), join(dir, "field.geojson"));
  // The rectangle's 22 swaths across the inner field and those that fill its corners, as the
  // package planned here gives them.
  const own = furrow.plan(readField("rectangle.geojson"), { width: 6, headlandPasses: 2, turnRadius: 8 }).summary;
  assert.equal(own.swath_count - own.fill_swath_count, 22);
  assert.match(node(dir, example), new RegExp(`^${own.swath_count} swaths, \\d+ m\n$`));
  // Before init: a FurrowError that says what to do. initSync() without arguments reads the file
  // where Node has process.getBuiltinModule (20.16 on), and says what it needs elsewhere.
  const before = node(
    dir,
    `import init, { plan, version, initSync, FurrowError } from "furrow";
    for (const call of [() => plan("{}"), () => version(), () => initSync()]) {
      try {
        call();
      } catch (e) {
        console.log(e instanceof FurrowError, e.code, e.message);
      }
    }
    if (typeof process.getBuiltinModule !== "function") await init();
    console.log(version());`,
  );
  const lines = before.trim().split("\n");
  const sync = typeof process.getBuiltinModule === "function";
  assert.equal(lines.length, sync ? 3 : 4, before);
  for (const line of lines.slice(0, 2)) assert.match(line, /^true not_initialised .*init\(\).*initSync/);
  if (!sync) assert.match(lines[2], /^true not_initialised initSync\(\) needs .*bytes/);
  assert.match(lines.at(-1), /^\d+\.\d+\.\d+/);
  // furrow/tracks as installed: its own init (init() reading its file), the same FurrowError.
  const tracks = node(
    dir,
    `import init, { plan, FurrowError } from "furrow";
    import initTracks, { shortestPath, FurrowError as TracksError } from "furrow/tracks";
    import { readFileSync } from "node:fs";
    await init();
    const result = plan(readFileSync("field.geojson", "utf8"));
    const swath = result.features.find((f) => f.properties.kind === "swath").geometry.coordinates;
    try {
      shortestPath(result, swath[0], 0, swath.at(-1));
    } catch (e) {
      console.log(e instanceof FurrowError, e.code, e.message);
    }
    await initTracks();
    const way = shortestPath(result, swath[0], 0, swath.at(-1), { turning: "on-the-spot" });
    console.log(TracksError === FurrowError, way.properties.kind, way.properties.length_m > 0);`,
    "tracks.mjs",
  );
  assert.match(tracks, /^true not_initialised .*initTracks\(\).*"furrow\/tracks"/);
  assert.match(tracks, /\ntrue track_path true\n$/);
  // furrow/pool as installed: its workers load their module from the package.
  const pooled = node(
    dir,
    `import { PlannerPool, FurrowError } from "furrow/pool";
    import { readFileSync } from "node:fs";
    const pool = new PlannerPool({ workers: 2 });
    const result = await pool.plan(readFileSync("field.geojson", "utf8"));
    await pool.plan("{", {}).catch((e) => console.log(e instanceof FurrowError, e.code));
    pool.terminate();
    console.log(result.summary.swath_count, result.samples.x.length > 0);`,
    "pool.mjs",
  );
  const alone = furrow.plan(readFileSync(join(dir, "field.geojson"), "utf8")).summary.swath_count;
  assert.equal(pooled, `true invalid_json\n${alone} true\n`);
  // Without the .wasm file, init() says which file it could not read.
  rmSync(join(dir, "node_modules/furrow/furrow_wasm_bg.wasm"));
  const missing = node(
    dir,
    `import init, { FurrowError } from "furrow";
    await init().catch((e) => console.log(e instanceof FurrowError, e.code, e.message));`,
  );
  assert.match(missing, /^true not_initialised could not read .*furrow_wasm_bg\.wasm/);
});
