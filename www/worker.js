// The planner in a Web Worker: the page stays responsive while a large field plans. Messages in:
// `{ id, field, options }` plans; `{ id, path: { position, heading, target, options, plan? } }`
// asks for the shortest way along the last plan's tracks (its track graph built once per plan;
// `plan`, a FeatureCollection, where the page's pool made the last plan);
// `{ id, read: file }` reads a field file (reading.js: its size and points checked, parsed for
// drawing). Out: `{ id, plan, ms }`, `{ id, path, ms }` or `{ id, error, ms }` (the sampled
// path's typed arrays are transferred, not copied), `{ id, read: { text, field } | { error } }`,
// and `{ id: 0, version }` once the module is ready (or `{ id: 0, failed }` if it cannot load).
// The tracks' module (the package's furrow/tracks) loads on the first way asked.
import init, { plan, version } from "./pkg/furrow.js";
import { plainError } from "./errors.js";
import { readFieldFile } from "./reading.js";

const ready = init().then(
  () => self.postMessage({ id: 0, version: version() }),
  (e) => self.postMessage({ id: 0, failed: String(e?.message ?? e) }),
);

let lastPlan = null; // the last plan made: its features, for its tracks
let tracks = null; // the track graph of lastPlan, made on the first path asked
let tracksModule = null; // furrow/tracks, once loaded

/** The tracks' module, loaded on first use. */
async function loadTracks() {
  tracksModule ??= import("./pkg/tracks.js").then(
    async (module) => {
      await module.default();
      return module;
    },
    (e) => {
      tracksModule = null; // asked again, it tries again
      throw e;
    },
  );
  return tracksModule;
}

self.onmessage = async (event) => {
  const { id, field, options, path, read } = event.data ?? {};
  if (read) {
    // Reading needs no planner: it does not wait for the module.
    self.postMessage({ id, read: await readFieldFile(read) });
    return;
  }
  await ready;
  const t0 = performance.now();
  try {
    if (path) {
      // A plan made elsewhere (the page's pool of workers): the way runs along its tracks.
      if (path.plan) {
        tracks?.free();
        tracks = null;
        lastPlan = path.plan;
      }
      if (!lastPlan) throw Object.assign(new Error("there is no plan to find a way along"), { code: "no_path" });
      const { TrackGraph } = await loadTracks();
      tracks ??= new TrackGraph(lastPlan, path.options);
      const result = tracks.shortestPath(path.position, path.heading, path.target, path.options);
      self.postMessage({ id, path: result, ms: performance.now() - t0 });
      return;
    }
    const result = plan(field, options);
    tracks?.free();
    tracks = null;
    lastPlan = { type: "FeatureCollection", features: result.features };
    const transfer = result.samples ? Object.values(result.samples).map((a) => a.buffer) : [];
    self.postMessage({ id, plan: result, ms: performance.now() - t0 }, transfer);
  } catch (e) {
    self.postMessage({ id, error: plainError(e), ms: performance.now() - t0 });
  }
};
