// The planner behind one small interface, so that it can move to a Web Worker later: both calls
// take and return plain data (structured-clonable), never DOM objects or wasm handles.
//
//   const { version } = await initPlanner();
//   const result = runPlan(fieldGeoJson, { width, headlandPasses, turnRadius, bearing, headlandMode, ... });
//   result.plan   (a GeoJSON FeatureCollection with summary and warnings), or
//   result.error  ({ code, message, feature?, ring?, vertex?, coordinate? })
import init, { plan, version } from "./pkg/furrow.js";

let ready = null;

/** Loads and instantiates the wasm module once; resolves to `{ version }`. */
export function initPlanner() {
  ready ??= init().then(() => ({ version: version() }));
  return ready;
}

/** Plans a field; never throws. `ms` is the time of the whole call, GeoJSON conversion included. */
export function runPlan(field, options) {
  const t0 = performance.now();
  try {
    const result = plan(field, options);
    return { plan: result, ms: performance.now() - t0 };
  } catch (e) {
    return { error: plainError(e), ms: performance.now() - t0 };
  }
}

/** A FurrowError (or anything thrown) as plain data. */
function plainError(e) {
  const out = {
    code: typeof e?.code === "string" ? e.code : "internal",
    message: typeof e?.message === "string" && e.message ? e.message : String(e),
  };
  for (const key of ["feature", "ring", "vertex"]) {
    if (Number.isInteger(e?.[key])) out[key] = e[key];
  }
  if (Array.isArray(e?.coordinate) && e.coordinate.length >= 2) {
    out.coordinate = [Number(e.coordinate[0]), Number(e.coordinate[1])];
  }
  return out;
}
