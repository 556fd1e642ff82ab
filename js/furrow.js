// furrow: the planner's JavaScript API.
//
// A thin layer over the wasm-bindgen module (furrow_wasm.js) that:
// - loads the planner in Node without fetch (which cannot read files there): `init()` reads
//   furrow_wasm_bg.wasm beside this file with the fs module;
// - throws every error as a FurrowError (the class below), also a call before the planner is
//   loaded (`not_initialised`);
// - keeps the planner alive in the user's page: if the WebAssembly instance traps (a panic inside
//   the planner, which input should never cause), the call throws a FurrowError with code
//   "internal" and the instance is recreated from the already compiled module, so the next call
//   plans again.
import * as core from "./furrow_wasm.js";

/** The members of a FurrowError that say where in the input the problem is. */
const PLACE = ["feature", "ring", "vertex", "coordinate", "line", "column"];

/** What the package throws: an Error with a stable `code` and, where it has one, the place. */
export class FurrowError extends Error {
  constructor(message, { code, cause, ...place } = {}) {
    super(message, cause === undefined ? undefined : { cause });
    this.code = code ?? "internal";
    for (const key of PLACE) {
      if (place[key] !== undefined) this[key] = place[key];
    }
  }
}
Object.defineProperty(FurrowError.prototype, "name", {
  value: "FurrowError",
  writable: true,
  configurable: true,
});

/** An error the wasm module threw (an Error named "FurrowError") as a FurrowError. */
function asFurrowError(e) {
  if (e instanceof FurrowError || !(e instanceof Error) || e.name !== "FurrowError") return e;
  const details = { code: e.code };
  for (const key of PLACE) details[key] = e[key];
  return new FurrowError(e.message, details);
}

let loaded = false;

function notInitialised(what, cause) {
  return new FurrowError(what, { code: "not_initialised", cause });
}

/**
 * Loads the planner: in a browser or worker it fetches furrow_wasm_bg.wasm beside this file (or
 * what `input` names); in Node it reads that file (or a `file:` URL given).
 */
export default async function init(input) {
  if (loaded) return core.default(input);
  const url = fileUrl(input);
  let load = input;
  if (url) {
    try {
      load = { module_or_path: await readFile(url) };
    } catch (e) {
      throw notInitialised(
        `could not read the planner's WebAssembly, ${url.href}: ${e.message}; or pass its bytes: initSync({ module: bytes })`,
        e,
      );
    }
  }
  let exports;
  try {
    exports = await core.default(load);
  } catch (e) {
    const where = input === undefined ? ` from ${wasmUrl().href}` : "";
    throw notInitialised(
      `could not load the planner's WebAssembly${where}: ${e.message}` +
        (input === undefined
          ? ". A bundler must put furrow_wasm_bg.wasm beside the bundle (see the package README), or pass its URL: init({ module_or_path: url })"
          : ""),
      e,
    );
  }
  loaded = true;
  return exports;
}

/**
 * Loads the planner synchronously from the module's bytes or a compiled WebAssembly.Module
 * (`{ module }`); in Node without arguments, from furrow_wasm_bg.wasm beside this file.
 */
export function initSync(input) {
  if (loaded) return core.initSync(input);
  const fs = input === undefined ? nodeFs() : undefined;
  if (input === undefined && !fs) {
    throw notInitialised(
      "initSync() needs the planner's WebAssembly: initSync({ module: bytes }), with the bytes of furrow_wasm_bg.wasm (or call await init())",
    );
  }
  let exports;
  try {
    exports = core.initSync(fs ? { module: fs.readFileSync(wasmUrl()) } : input);
  } catch (e) {
    throw notInitialised(`could not load the planner's WebAssembly: ${e.message}`, e);
  }
  loaded = true;
  return exports;
}

/** Where the planner's WebAssembly is: beside this file (bundlers rewrite this to their copy). */
function wasmUrl() {
  return new URL("furrow_wasm_bg.wasm", import.meta.url);
}

/** Whether this runs in Node (or a runtime like it), whose fetch cannot read files. */
function inNode() {
  return typeof globalThis.process?.versions?.node === "string";
}

/** Node's fs module where it can be had synchronously (Node 20.16 and 22.3 on). */
function nodeFs() {
  return inNode() ? globalThis.process.getBuiltinModule?.("node:fs") : undefined;
}

/** The `file:` URL `init` must read itself rather than fetch: only in Node. */
function fileUrl(input) {
  if (!inNode()) return undefined;
  let target = input;
  if (target !== null && typeof target === "object" && Object.getPrototypeOf(target) === Object.prototype) {
    target = target.module_or_path;
  }
  if (target === undefined) target = wasmUrl();
  if (typeof target === "string" && target.startsWith("file:")) target = new URL(target);
  return target instanceof URL && target.protocol === "file:" ? target : undefined;
}

/** The bytes of a file, in Node. */
async function readFile(url) {
  // The specifier is in a variable, and marked, so that bundlers leave it alone: this line runs
  // only in Node, where fs is there (on Node before 20.16, which lacks getBuiltinModule).
  const name = "node:fs";
  const fs = nodeFs() ?? (await import(/* webpackIgnore: true */ /* @vite-ignore */ name));
  return fs.promises.readFile(url);
}

function guarded(name) {
  const fn = core[name];
  return (...args) => guardedCall(() => fn(...args));
}

/** Runs `call`; errors become FurrowErrors, and a trap of the instance a fresh instance. */
function guardedCall(call) {
  if (!loaded) {
    throw notInitialised(
      "the planner is not loaded yet: call await init() (or initSync(...)) once first",
    );
  }
  try {
    return call();
  } catch (e) {
    if (!(e instanceof WebAssembly.RuntimeError)) throw asFurrowError(e);
    // The instance is in an unknown state after a trap: start a fresh one.
    core.__wbg_reset_state();
    throw new FurrowError(
      `the planner failed inside (${e.message}) and was restarted; please report this with the field and options`,
      { code: "internal", cause: e },
    );
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
