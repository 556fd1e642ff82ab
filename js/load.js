// What the package's two entry points share (furrow.js, the planner; tracks.js, the shortest
// paths along a plan's tracks): the FurrowError class, and loading a wasm-bindgen module so that
// - it loads in Node without fetch (which cannot read files there): `init()` reads the module's
//   .wasm beside the entry with the fs module;
// - every error is thrown as a FurrowError, also a call before the module is loaded
//   (`not_initialised`);
// - it stays alive in the user's page: if the WebAssembly instance traps (a panic inside, which
//   input should never cause), the call throws a FurrowError with code "internal" and the
//   instance is recreated from the already compiled module, so the next call works again.

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

function notInitialised(what, cause) {
  return new FurrowError(what, { code: "not_initialised", cause });
}

/**
 * The loading of one wasm-bindgen module `core` (its JS module's namespace). `what` names it in
 * messages ("the planner"); `wasmUrl()` is where its .wasm is: the entry's own
 * `new URL("..._bg.wasm", import.meta.url)`, which bundlers find and rewrite to their copy.
 * `entry` is the entry's file name and `initName` what its init function is imported as, for
 * messages. Returns `{ init, initSync, guarded, guardedCall }`.
 */
export function loader(core, { what, wasmUrl, entry, initName }) {
  let loaded = false;
  const wasmFile = () => wasmUrl().pathname.split("/").pop();

  async function init(input) {
    if (loaded) return core.default(input);
    const url = fileUrl(input, wasmUrl);
    let load = input;
    if (url) {
      try {
        load = { module_or_path: await readFile(url) };
      } catch (e) {
        throw notInitialised(
          `could not read ${what}'s WebAssembly, ${url.href}: ${e.message}; or pass its bytes: initSync({ module: bytes })`,
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
        `could not load ${what}'s WebAssembly${where}: ${e.message}` +
          (input === undefined
            ? `. A bundler must put ${wasmFile()} beside the bundle (see the package README), or pass its URL: ${initName}({ module_or_path: url })`
            : ""),
        e,
      );
    }
    loaded = true;
    return exports;
  }

  function initSync(input) {
    if (loaded) return core.initSync(input);
    const fs = input === undefined ? nodeFs() : undefined;
    if (input === undefined && !fs) {
      throw notInitialised(
        `initSync() needs ${what}'s WebAssembly: initSync({ module: bytes }), with the bytes of ${wasmFile()} (or call await ${initName}())`,
      );
    }
    let exports;
    try {
      exports = core.initSync(fs ? { module: fs.readFileSync(wasmUrl()) } : input);
    } catch (e) {
      throw notInitialised(`could not load ${what}'s WebAssembly: ${e.message}`, e);
    }
    loaded = true;
    return exports;
  }

  /** Runs `call`; errors become FurrowErrors, and a trap of the instance a fresh instance. */
  function guardedCall(call) {
    if (!loaded) {
      throw notInitialised(
        `${what} is not loaded yet: call await ${initName}() (or initSync(...)) from "${entry}" once first`,
      );
    }
    try {
      return call();
    } catch (e) {
      if (!(e instanceof WebAssembly.RuntimeError)) throw asFurrowError(e);
      // The instance is in an unknown state after a trap: start a fresh one.
      core.__wbg_reset_state();
      throw new FurrowError(
        `${what} failed inside (${e.message}) and was restarted; please report this with the field and options`,
        { code: "internal", cause: e },
      );
    }
  }

  function guarded(name) {
    const fn = core[name];
    return (...args) => guardedCall(() => fn(...args));
  }

  return { init, initSync, guarded, guardedCall };
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
function fileUrl(input, wasmUrl) {
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
