// Reading a field file within the planner's limits, before anything of it is drawn or planned:
// its size is checked before it is read, its points counted before it is parsed. The page hands
// the file to the planner's worker (worker.js), which reads it there, so that a large file never
// holds up the page; only where there is no worker is it read in the page. A zipped Shapefile
// (or a Shapefile's parts together), KML or KMZ is converted to the field's GeoJSON by the
// package's furrow/formats module, loaded the first time one is opened.

import { parseForDrawing } from "./scene.js";

/** The planner reads at most this many bytes (MAX_INPUT_BYTES in src/field/geojson.rs). */
export const MAX_INPUT_BYTES = 32 * 1024 * 1024;
/** And at most this many points (MAX_VERTICES in src/field/validate.rs). */
export const MAX_VERTICES = 200_000;

/** The largest file of another format read (MAX_FILE_BYTES in src/formats/mod.rs). */
export const MAX_FILE_BYTES = 64 * 1024 * 1024;

/** Whether files are a field file of another format than GeoJSON: a zipped Shapefile, KML,
 * KMZ or ISOXML TaskData (TASKDATA.XML, or its zip), or a Shapefile's parts. */
export function isConverted(files) {
  return files.length > 1 || /\.(zip|kml|kmz|xml|shp|shx|dbf|prj|cpg)$/i.test(files[0]?.name ?? "");
}

/** The most bytes read of these files. */
export function readLimit(files) {
  return isConverted(files) ? MAX_FILE_BYTES : MAX_INPUT_BYTES;
}

/** The planner's error for input of `bytes` bytes when that is more than it reads (`limit`),
 * else null. */
export function sizeError(name, bytes, limit = MAX_INPUT_BYTES) {
  if (!(bytes > limit)) return null;
  const mb = (v) => Math.round(v / (1024 * 1024));
  return {
    code: "input_too_large",
    message: `the file ${name} is ${mb(bytes)} MB; the planner reads at most ${mb(limit)} MB: simplify the outlines`,
  };
}

/**
 * A field file's text read for planning: `{ text, field }` (field: as much of it as parses, for
 * drawing, or undefined), or `{ error }` when it has more points than the planner accepts (found
 * before it is parsed). Text that is not JSON is the planner's to report (with where it fails).
 */
export function readFieldText(text) {
  if (countPositions(text, MAX_VERTICES) > MAX_VERTICES) {
    return {
      error: {
        code: "input_too_large",
        message: `the input has more than ${MAX_VERTICES} points; the planner accepts up to ${MAX_VERTICES}: simplify the outlines`,
      },
    };
  }
  return { text, field: parseForDrawing(text) };
}

/** Reads a File (or Blob), its size checked first, and checks it as readFieldText does; a
 * zipped Shapefile, or a Shapefile's parts (an array of Files), converted to GeoJSON first.
 * Never rejects. */
export async function readFieldFile(file) {
  const files = Array.isArray(file) ? file : [file];
  if (isConverted(files)) return readConverted(files);
  const name = typeof file?.name === "string" && file.name ? file.name : "the file";
  const tooLarge = sizeError(name, file?.size);
  if (tooLarge) return { error: tooLarge };
  let text;
  try {
    text = await file.text();
  } catch (e) {
    return { error: { code: "file_unreadable", message: `the file ${name} could not be read: ${e?.message ?? e}` } };
  }
  return readFieldText(text);
}

/** A Shapefile (zipped, or its parts), KML or KMZ as the field's GeoJSON, checked as
 * readFieldText does. */
async function readConverted(files) {
  const names = files.map((f) => (typeof f?.name === "string" ? f.name : "")).join(", ");
  const tooLarge = sizeError(names, files.reduce((n, f) => n + (f?.size ?? 0), 0), MAX_FILE_BYTES);
  if (tooLarge) return { error: tooLarge };
  let formats;
  try {
    formats = await loadFormats();
  } catch (e) {
    return { error: { code: "not_initialised", message: `the Shapefile reader could not be loaded: ${e?.message ?? e}` } };
  }
  let bytes;
  try {
    bytes = await Promise.all(files.map(async (f) => new Uint8Array(await f.arrayBuffer())));
  } catch (e) {
    return { error: { code: "file_unreadable", message: `the file ${names} could not be read: ${e?.message ?? e}` } };
  }
  try {
    const whole = files.length === 1 && /\.(zip|kml|kmz|xml)$/i.test(files[0].name ?? "");
    const geojson = whole
      ? formats.readFieldFile(bytes[0], files[0].name)
      : formats.readShapefile(files.map((f, i) => ({ name: f.name, bytes: bytes[i] })));
    return readFieldText(JSON.stringify(geojson));
  } catch (e) {
    return { error: { code: e?.code ?? "invalid_file", message: String(e?.message ?? e) } };
  }
}

let formatsModule = null; // furrow/formats, once loaded

/** The package's readers and writers of field files (furrow/formats), loaded on first use. */
export function loadFormats() {
  formatsModule ??= import("./pkg/formats.js").then(
    async (module) => {
      await module.default();
      return module;
    },
    (e) => {
      formatsModule = null; // asked again, it tries again
      throw e;
    },
  );
  return formatsModule;
}

/**
 * How many positions JSON text holds (arrays whose first member is a number: `[` followed by a
 * digit or a minus sign, outside strings), counting no further than just past `limit`. One pass
 * over the characters, without parsing: a file of a million points is refused in milliseconds.
 */
export function countPositions(text, limit = Infinity) {
  let n = 0;
  let inString = false;
  for (let i = 0, len = text.length; i < len && n <= limit; i++) {
    const c = text.charCodeAt(i);
    if (inString) {
      if (c === 92) i++; // a backslash: the next character is escaped
      else if (c === 34) inString = false;
    } else if (c === 34) {
      inString = true;
    } else if (c === 91) {
      let j = i + 1;
      while (j < len && (text.charCodeAt(j) === 32 || text.charCodeAt(j) === 10 || text.charCodeAt(j) === 13 || text.charCodeAt(j) === 9)) j++;
      const d = text.charCodeAt(j);
      if (d === 45 || (d >= 48 && d <= 57)) n++;
    }
  }
  return n;
}
