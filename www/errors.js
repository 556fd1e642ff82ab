// Errors as plain data (structured-clonable): what the planner throws, for the page and the worker.

/** A FurrowError (or anything thrown) as `{ code, message, feature?, ring?, vertex?, coordinate? }`. */
export function plainError(e) {
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
