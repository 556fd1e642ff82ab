// The planner in a Web Worker: the page stays responsive while a large field plans. Messages in:
// `{ id, field, options }`; out: `{ id, plan, ms }` or `{ id, error, ms }` (the sampled path's
// typed arrays are transferred, not copied), and `{ id: 0, version }` once the module is ready
// (or `{ id: 0, failed }` if it cannot load).
import init, { plan, version } from "./pkg/furrow.js";
import { plainError } from "./errors.js";

const ready = init().then(
  () => self.postMessage({ id: 0, version: version() }),
  (e) => self.postMessage({ id: 0, failed: String(e?.message ?? e) }),
);

self.onmessage = async (event) => {
  const { id, field, options } = event.data ?? {};
  await ready;
  const t0 = performance.now();
  try {
    const result = plan(field, options);
    const transfer = result.samples ? Object.values(result.samples).map((a) => a.buffer) : [];
    self.postMessage({ id, plan: result, ms: performance.now() - t0 }, transfer);
  } catch (e) {
    self.postMessage({ id, error: plainError(e), ms: performance.now() - t0 });
  }
};
