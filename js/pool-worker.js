// The worker of furrow/pool (pool.js): a Web Worker in a browser, a worker thread in Node. It
// loads the planner (furrow_pool_wasm: the planner with planning in shares), plans one share of
// each plan the pool asks for (planShare), fills its own best candidate while the others work
// (fillAhead), then finishes the plan if it holds the candidate chosen (finishShare).
//
// Messages in: `{ init: input }` first (furrow_pool_wasm_bg.wasm: undefined to load it from
// beside this file, or a compiled WebAssembly.Module); then `{ id, start: { field, options,
// index, of } }` and `{ id, finish: Float64Array }`. Out: `{ ready: true }` or `{ failed: error }`
// once loaded; `{ id, summaries: Float64Array }`, `{ id, plan }` (the plan with its GeoJSON as text
// in `json` beside `samples`, or null where another share finishes it) or `{ id, error: { message, code, ... } }`. The samples' and summaries'
// buffers are transferred, not copied.
import * as core from "./furrow_pool_wasm.js";
import { loader } from "./load.js";

const planner = loader(core, {
  what: "the planner",
  // Literal, so that bundlers find the .wasm and rewrite the URL to their copy.
  wasmUrl: () => new URL("furrow_pool_wasm_bg.wasm", import.meta.url),
  entry: "furrow/pool",
  initName: "init",
});
const planShare = planner.guarded("planShare");
const finishShare = planner.guarded("finishShare");
const fillAhead = planner.guarded("fillAhead");

/** An error as plain values: its message, code and place. */
function plainError(e) {
  const out = { message: String(e?.message ?? e), code: e?.code ?? "internal" };
  for (const key of ["feature", "ring", "vertex", "coordinate", "line", "column"]) {
    if (e?.[key] !== undefined) out[key] = e[key];
  }
  return out;
}

function handle(data) {
  const { id, init, start, finish } = data ?? {};
  if ("init" in (data ?? {})) {
    planner
      .init(init)
      .then(() => post({ ready: true }))
      .catch((e) => post({ failed: plainError(e) }));
    return;
  }
  try {
    if (start) {
      const summaries = planShare(start.field, start.options, start.index, start.of);
      post({ id, summaries }, [summaries.buffer]);
      // While the other workers finish their shares: this share's best candidate filled, which
      // is the plan's where it is the one chosen. A failure here is the choice's to meet again.
      try {
        fillAhead();
      } catch {
        // finishShare fills the chosen candidate itself.
      }
    } else if (finish) {
      const plan = finishShare(finish);
      const transfer = plan?.samples ? Object.values(plan.samples).map((a) => a.buffer) : [];
      post({ id, plan }, transfer);
    }
  } catch (e) {
    post({ id, error: plainError(e) });
  }
}

// In a browser the handler is set at once (messages that come before it would be lost); in
// Node the port keeps them until it is.
let post;
if (typeof globalThis.process?.versions?.node !== "string") {
  post = (message, transfer) => self.postMessage(message, transfer);
  self.onmessage = (event) => handle(event.data);
} else {
  const name = "node:worker_threads";
  const threads =
    globalThis.process.getBuiltinModule?.(name) ??
    (await import(/* webpackIgnore: true */ /* @vite-ignore */ name));
  const port = threads.parentPort;
  post = (message, transfer) => port.postMessage(message, transfer);
  port.on("message", handle);
}
