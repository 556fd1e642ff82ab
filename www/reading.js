// Reading a field file within the planner's limits, before anything of it is drawn or planned:
// its size is checked before it is read, its points counted before it is parsed. The page hands
// the file to the planner's worker (worker.js), which reads it there, so that a large file never
// holds up the page; only where there is no worker is it read in the page.

import { parseForDrawing } from "./scene.js";

/** The planner reads at most this many bytes (MAX_INPUT_BYTES in src/field/geojson.rs). */
export const MAX_INPUT_BYTES = 32 * 1024 * 1024;
/** And at most this many points (MAX_VERTICES in src/field/validate.rs). */
export const MAX_VERTICES = 200_000;

/** The planner's error for input of `bytes` bytes when that is more than it reads, else null. */
export function sizeError(name, bytes) {
  if (!(bytes > MAX_INPUT_BYTES)) return null;
  const mb = (v) => Math.round(v / (1024 * 1024));
  return {
    code: "input_too_large",
    message: `the file ${name} is ${mb(bytes)} MB; the planner reads at most ${mb(MAX_INPUT_BYTES)} MB: simplify the outlines`,
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

/** Reads a File (or Blob), its size checked first, and checks it as readFieldText does; never
 * rejects. */
export async function readFieldFile(file) {
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
