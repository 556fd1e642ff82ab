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
  return function (...args) {
    try {
      return fn(...args);
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
  };
}

/** Plans a field: see furrow.d.ts. */
export const plan = guarded("plan");
/** The default value of every option. */
export const defaultOptions = guarded("defaultOptions");
/** The planner's version. */
export const version = guarded("version");
/** Panics inside the planner on purpose; only for testing the recovery above. */
export const __panicForTests = guarded("__panicForTests");
