// furrow: the planner's JavaScript API (the package's main entry). A thin layer over the
// wasm-bindgen module furrow_wasm.js: loading in Node, FurrowError, recovery from a trapped
// instance (load.js). The shortest paths along a plan's tracks are the "furrow/tracks" entry
// (tracks.js), a module of their own that a page that only plans never loads.
import * as core from "./furrow_wasm.js";
import { loader } from "./load.js";

export { FurrowError } from "./load.js";

const planner = loader(core, {
  what: "the planner",
  // Literal, so that bundlers find the .wasm and rewrite the URL to their copy.
  wasmUrl: () => new URL("furrow_wasm_bg.wasm", import.meta.url),
  entry: "furrow",
  initName: "init",
});

/**
 * Loads the planner: in a browser or worker it fetches furrow_wasm_bg.wasm beside this file (or
 * what `input` names); in Node it reads that file (or a `file:` URL given).
 */
export default planner.init;
/**
 * Loads the planner synchronously from the module's bytes or a compiled WebAssembly.Module
 * (`{ module }`); in Node without arguments, from furrow_wasm_bg.wasm beside this file.
 */
export const initSync = planner.initSync;
/** Plans a field: see furrow.d.ts. */
export const plan = planner.guarded("plan");
/** The default value of every option. */
export const defaultOptions = planner.guarded("defaultOptions");
/** The planner's version. */
export const version = planner.guarded("version");
