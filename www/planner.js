// The planner behind one small interface. It runs in a Web Worker (worker.js), so that the page
// never freezes while a large field plans; where a worker cannot start, it runs in the page.
//
//   const { version } = await initPlanner();
//   const result = await runPlan(fieldGeoJson, { width, headlandPasses, turnRadius, ... });
//   result.id     increases with every call: draw a result only if it is newer than the last drawn
//   result.plan   (a GeoJSON FeatureCollection with summary, warnings and samples), or
//   result.error  ({ code, message, feature?, ring?, vertex?, coordinate? }), or
//   result.stale  (true: a newer call came before this one started; it never ran)
//
//   const { path, error } = await runPath([lon, lat], headingDeg, [lon, lat], { turning });
//   the shortest way along the last plan's tracks (a GeoJSON Feature), see the package's TrackGraph
//
//   const { text, field, error } = await readFile(file);
//   a field file read off the page's thread, within the planner's limits (reading.js)
//
// The newest call wins: while one plan runs, calls wait in a queue of one, and each new call
// replaces the one waiting (which resolves as stale). Dragging a vertex thus plans the newest
// shape as soon as the planner is free, never a backlog of old ones.
//
// Once a full plan (decomposition "auto") has taken longer than POOL_AFTER_MS in the worker, and
// the device has three cores or more, full plans go to a pool of workers (the package's
// furrow/pool), which plans auto's candidates side by side: the same plan, sooner on fields with
// obstacles and large ones (result.pooled is then true). The worker keeps the previews, the ways
// and the files; the pool's last plan goes to it with the next way asked.
import { plainError } from "./errors.js";
import { readFieldFile } from "./reading.js";
import { MAX_WORKERS, PlannerPool } from "./pkg/pool.js";

/** Full plans slower than this (ms) in the worker send the next ones to a pool of workers. */
const POOL_AFTER_MS = 40;

let ready = null;
let worker = null;
let inPage = null; // the wasm module's plan function, when planning in the page
let nextId = 0;
let running = null; // the call the planner is working on
let waiting = null; // the newest call not yet started
let lastPlan = null; // in the page: the last plan made, for its tracks
let inPageTracks = null; // in the page: furrow/tracks (loaded on the first way asked), and the graph of lastPlan
const calls = new Map(); // id -> resolve, for the ways and files asked of the worker
let pool = null; // furrow/pool's PlannerPool, once full plans have proved slow
let poolFailed = false; // a pool could not start or lost a worker: none is started again
let pooledPlan = null; // the last plan the pool made, until the worker has it for its ways

/** Starts the planner once; resolves to `{ version, worker }` (worker: whether it runs in one). */
export function initPlanner() {
  ready ??= startWorker().catch(startInPage);
  return ready;
}

function startWorker() {
  return new Promise((resolve, reject) => {
    if (typeof Worker !== "function") return reject(new Error("no Web Workers"));
    let w;
    try {
      w = new Worker(new URL("./worker.js", import.meta.url), { type: "module" });
    } catch (e) {
      return reject(e);
    }
    const fail = (e) => {
      w.terminate();
      reject(e instanceof Error ? e : new Error(String(e?.message ?? e)));
    };
    w.onerror = fail;
    w.onmessage = (event) => {
      const data = event.data ?? {};
      if (data.id !== 0) return;
      if (data.failed) return fail(new Error(data.failed));
      worker = w;
      w.onerror = (e) => finish({ id: running?.id, error: { code: "internal", message: String(e?.message ?? e) }, ms: 0 });
      w.onmessage = (e) => {
        const resolve = calls.get(e.data?.id);
        if (!resolve) return finish(e.data);
        calls.delete(e.data.id);
        resolve({ ...e.data });
      };
      resolve({ version: data.version, worker: true });
    };
  });
}

async function startInPage() {
  const module = await import("./pkg/furrow.js");
  await module.default();
  inPage = module.plan;
  inPageTracks = { module: null, graph: null };
  return { version: module.version(), worker: false };
}

/** Plans a field (see the module comment); never rejects. */
export function runPlan(field, options) {
  return new Promise((resolve) => {
    const call = { id: ++nextId, field, options, resolve, t0: performance.now() };
    if (waiting) waiting.resolve({ id: waiting.id, stale: true });
    waiting = call;
    initPlanner().then(pump, (e) => {
      if (waiting === call) waiting = null;
      resolve({ id: call.id, error: plainError(e), ms: 0 });
    });
  });
}

function pump() {
  if (running || !waiting) return;
  running = waiting;
  waiting = null;
  if (worker && pool && isFull(running.options)) return planInPool(running);
  if (worker) {
    try {
      pooledPlan = null; // the worker's own plan is the newer
      worker.postMessage({ id: running.id, field: running.field, options: running.options });
    } catch (e) {
      // Something in the field or options cannot be cloned.
      finish({ id: running.id, error: plainError(e), ms: 0 });
    }
    return;
  }
  // In the page: after the current task, so that the caller's promise chain sees the queue.
  const call = running;
  setTimeout(() => {
    const t0 = performance.now();
    try {
      const plan = inPage(call.field, call.options);
      lastPlan = plan;
      inPageTracks.graph?.free();
      inPageTracks.graph = null;
      finish({ id: call.id, plan, ms: performance.now() - t0 });
    } catch (e) {
      finish({ id: call.id, error: plainError(e), ms: performance.now() - t0 });
    }
  }, 0);
}

/** Whether `options` ask for the full plan: auto's candidates, which the pool shares out. */
function isFull(options) {
  return (options?.decomposition ?? "auto") === "auto";
}

/** Plans `call` in the pool; where the pool cannot start, in the worker from then on. */
function planInPool(call) {
  const t0 = performance.now();
  pool.plan(call.field, call.options).then(
    (plan) => {
      pooledPlan = { type: "FeatureCollection", features: plan.features };
      finish({ id: call.id, plan, ms: performance.now() - t0, pooled: true });
    },
    (e) => {
      const failed = e?.code === "not_initialised" || pool?.broken;
      if (!failed) return finish({ id: call.id, error: plainError(e), ms: performance.now() - t0 });
      // The pool could not start, or a worker of it failed: this call and the next go to the
      // worker.
      pool?.terminate();
      pool = null;
      poolFailed = true;
      running = null;
      if (waiting) call.resolve({ id: call.id, stale: true });
      else waiting = call;
      pump();
    },
  );
}

/**
 * Starts the pool after a full plan slower than POOL_AFTER_MS, where there are cores for it: one
 * is left to the page, which must keep drawing while the pool plans (with every core busy, a
 * drag's frames on the 210 ha field came up to 230 ms apart, against 130 ms with the worker
 * alone), and a pool of one worker would only add the way there.
 */
function maybeStartPool(call, data) {
  const workers = Math.min((globalThis.navigator?.hardwareConcurrency ?? 1) - 1, MAX_WORKERS);
  if (pool || poolFailed || !worker || !data.plan || data.pooled || data.ms <= POOL_AFTER_MS || workers < 2) return;
  if (isFull(call.options)) pool = new PlannerPool({ workers });
}

/**
 * The shortest way along the last plan's tracks (see TrackGraph.shortestPath in the package):
 * resolves to `{ path }` (a GeoJSON Feature) or `{ error }`, with `ms`; never rejects.
 */
export function runPath(position, heading, target, options) {
  return initPlanner().then(
    () =>
      new Promise((resolve) => {
        const id = ++nextId;
        const t0 = performance.now();
        if (worker) {
          calls.set(id, (data) => resolve({ ...data, ms: performance.now() - t0 }));
          // The pool's last plan, where it made the plan shown: the way runs along its tracks.
          worker.postMessage({ id, path: { position, heading, target, options, plan: pooledPlan ?? undefined } });
          pooledPlan = null;
          return;
        }
        const done = (result) => resolve({ id, ...result, ms: performance.now() - t0 });
        pathInPage(position, heading, target, options).then(
          (path) => done({ path }),
          (e) => done({ error: plainError(e) }),
        );
      }),
    (e) => ({ error: plainError(e), ms: 0 }),
  );
}

/** The shortest way along lastPlan's tracks in the page, furrow/tracks loaded on first use. */
async function pathInPage(position, heading, target, options) {
  if (!lastPlan) throw Object.assign(new Error("there is no plan to find a way along"), { code: "no_path" });
  inPageTracks.module ??= import("./pkg/tracks.js").then(
    async (module) => {
      await module.default();
      return module;
    },
    (e) => {
      inPageTracks.module = null; // asked again, it tries again
      throw e;
    },
  );
  const { TrackGraph } = await inPageTracks.module;
  inPageTracks.graph ??= new TrackGraph(lastPlan, options);
  return inPageTracks.graph.shortestPath(position, heading, target, options);
}

/**
 * Reads a field file (a File from the file input or a drop) in the worker, so that a large one
 * never holds up the page: resolves to `{ text, field }` or `{ error }` (reading.js); never
 * rejects. Where there is no worker, it is read in the page.
 */
export function readFile(file) {
  return initPlanner().then(
    () =>
      worker
        ? new Promise((resolve) => {
            const id = ++nextId;
            calls.set(id, (data) => resolve(data.read));
            worker.postMessage({ id, read: file });
          })
        : readFieldFile(file),
    () => readFieldFile(file),
  );
}

function finish(data) {
  const call = running;
  running = null;
  if (call) maybeStartPool(call, data);
  if (call) {
    // `ms` is the whole call as the page sees it: waiting, planning and the copy back.
    call.resolve({ ...data, id: call.id, ms: performance.now() - call.t0, planMs: data.ms });
  }
  pump();
}
