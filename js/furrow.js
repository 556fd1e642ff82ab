// furrow: the planner's JavaScript API.
//
// A thin layer over the wasm-bindgen module (furrow_wasm.js) that keeps the planner alive in the
// user's page: if the WebAssembly instance traps (a panic inside the planner, which input should
// never cause), the call throws a FurrowError with code "internal" and the instance is recreated
// from the already compiled module, so the next call plans again.
import * as core from "./furrow_wasm.js";

/** Loads the planner (fetches furrow_wasm_bg.wasm next to this file unless told otherwise). */
export default core.default;
/** Loads the planner synchronously from bytes or a compiled WebAssembly.Module (Node, workers). */
export const initSync = core.initSync;

function guarded(name) {
  const fn = core[name];
  return (...args) => guardedCall(() => fn(...args));
}

/** Runs `call`; a trap of the instance becomes a FurrowError and a fresh instance. */
function guardedCall(call) {
  try {
    return call();
  } catch (e) {
    if (!(e instanceof WebAssembly.RuntimeError)) throw e;
    // The instance is in an unknown state after a trap: start a fresh one.
    core.__wbg_reset_state();
    const error = new Error(
      `the planner failed inside (${e.message}) and was restarted; please report this with the field and options`,
      { cause: e },
    );
    error.name = "FurrowError";
    error.code = "internal";
    throw error;
  }
}

/** Plans a field: see furrow.d.ts. */
export const plan = guarded("plan");
/** The shortest path along a plan's tracks: see furrow.d.ts. */
export const shortestPath = guarded("shortestPath");

/** The tracks of a plan, for many shortest paths: see furrow.d.ts. */
export class TrackGraph {
  constructor(plan, options) {
    this.inner = guardedCall(() => new core.TrackGraph(plan, options));
  }
  shortestPath(position, heading, target, options) {
    return guardedCall(() => this.inner.shortestPath(position, heading, target, options));
  }
  get trackCount() {
    return this.inner.trackCount;
  }
  get junctionCount() {
    return this.inner.junctionCount;
  }
  free() {
    this.inner.free();
  }
}
/** The default value of every option. */
export const defaultOptions = guarded("defaultOptions");
/** The planner's version. */
export const version = guarded("version");
/** Panics inside the planner on purpose; only for testing the recovery above. */
export const __panicForTests = guarded("__panicForTests");
