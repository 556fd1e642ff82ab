// furrow/pool: the planner in a pool of workers (Web Workers in a browser, worker threads in
// Node). `auto` weighs up to four pieces of work (the single-direction decompositions, and split
// and merge from each of three seeds); each worker plans the field's stages up to them and a
// share of them, the workers tell each other what their candidates came to, and the one holding
// the candidate chosen finishes the plan. The plan is the one `plan()` gives, in about the time
// of the largest share. See pool.d.ts.
import { FurrowError } from "./load.js";

export { FurrowError } from "./load.js";

/** Most workers a plan can use: `auto` weighs at most four pieces of work. */
export const MAX_WORKERS = 4;

/** The workers a pool starts with by default: the device's cores, at most MAX_WORKERS. */
function defaultWorkers() {
  const cores = globalThis.navigator?.hardwareConcurrency ?? nodeCores() ?? 2;
  return Math.max(1, Math.min(MAX_WORKERS, cores));
}

function nodeCores() {
  const os = globalThis.process?.getBuiltinModule?.("node:os");
  return os ? (os.availableParallelism?.() ?? os.cpus().length) : undefined;
}

function inNode() {
  return typeof globalThis.process?.versions?.node === "string";
}

/** A worker running pool-worker.js, with one `on(handler)` for its messages and errors. */
async function startWorker() {
  const url = new URL("./pool-worker.js", import.meta.url);
  if (inNode()) {
    const name = "node:worker_threads";
    const threads =
      globalThis.process.getBuiltinModule?.(name) ??
      (await import(/* webpackIgnore: true */ /* @vite-ignore */ name));
    const worker = new threads.Worker(url);
    return {
      post: (message, transfer) => worker.postMessage(message, transfer),
      on: (message, error) => {
        worker.on("message", message);
        worker.on("error", error);
      },
      // An idle worker thread does not keep Node running.
      busy: (busy) => (busy ? worker.ref() : worker.unref()),
      terminate: () => worker.terminate(),
    };
  }
  // Literal, so that bundlers find the worker's module.
  const worker = new Worker(new URL("./pool-worker.js", import.meta.url), { type: "module" });
  return {
    post: (message, transfer) => worker.postMessage(message, transfer),
    on: (message, error) => {
      worker.onmessage = (event) => message(event.data);
      worker.onerror = (event) => {
        event.preventDefault?.();
        error(new Error(event.message || "the worker could not start"));
      };
    },
    busy: () => {},
    terminate: () => worker.terminate(),
  };
}

/** The FurrowError a worker's plain error stands for. */
function fromPlain(e) {
  const { message, ...details } = e ?? {};
  return new FurrowError(message ?? "the planner failed in a worker", details);
}

/**
 * A pool of workers that plan together. `workers` (default: the device's cores, at most 4);
 * `wasm`: furrow_pool_wasm_bg.wasm for every worker (what `init()` takes, such as
 * `{ module_or_path }`), by default loaded by each worker from beside this file.
 */
export class PlannerPool {
  constructor({ workers, wasm } = {}) {
    const n = workers ?? defaultWorkers();
    if (!Number.isInteger(n) || n < 1) {
      throw new FurrowError(`a pool needs a whole number of workers, at least 1 (got ${n})`, {
        code: "invalid_option",
      });
    }
    this.size = Math.min(n, MAX_WORKERS);
    this.nextId = 1;
    this.replies = new Map(); // id -> [resolve per worker]
    this.queue = Promise.resolve();
    this.closed = false;
    this.broken = null; // the error of a worker that failed: the pool plans no more
    this.workers = this.#start(wasm);
    // A pool that failed to start rejects each plan; it is not an unhandled rejection itself.
    this.workers.catch(() => {});
  }

  async #start(wasm) {
    const workers = await Promise.all(Array.from({ length: this.size }, startWorker));
    await Promise.all(
      workers.map(
        (w, i) =>
          new Promise((resolve, reject) => {
            let ready = false;
            w.on(
              (data) => {
                if (data?.ready) {
                  ready = true;
                  resolve();
                } else if (data?.failed) reject(fromPlain(data.failed));
                else this.#reply(i, data);
              },
              (e) => {
                // Before it is ready, the worker could not start (its script did not load).
                const error = new FurrowError(`a planner worker failed: ${e.message}`, {
                  code: ready ? "internal" : "not_initialised",
                  cause: e,
                });
                reject(error);
                this.#fail(i, error);
              },
            );
            w.post({ init: wasm });
          }),
      ),
    ).catch((e) => {
      for (const w of workers) w.terminate();
      throw e instanceof FurrowError
        ? e
        : new FurrowError(`the planner's workers could not start: ${e.message}`, {
            code: "not_initialised",
            cause: e,
          });
    });
    for (const w of workers) w.busy(false);
    return workers;
  }

  #reply(i, data) {
    const waiting = this.replies.get(data?.id);
    waiting?.[i]?.(data);
  }

  #fail(i, error) {
    // A worker that failed outside the planner (which recovers from its own traps) is gone:
    // this plan and every later one fail.
    this.broken = error;
    for (const waiting of this.replies.values()) {
      waiting[i]?.({ error: { message: error.message, code: "internal" } });
    }
  }

  /**
   * Sends each worker its message (`message(i)`) and waits for every reply, or with `until`
   * only until a reply it accepts (then that reply alone, or null if none).
   */
  async #round(workers, message, { transfer = () => [], until } = {}) {
    const id = this.nextId++;
    const replies = workers.map(
      (_, i) =>
        new Promise((resolve) => {
          const waiting = this.replies.get(id) ?? [];
          waiting[i] = resolve;
          this.replies.set(id, waiting);
        }),
    );
    try {
      workers.forEach((w, i) => w.post({ id, ...message(i) }, transfer(i)));
      if (!until) return await Promise.all(replies);
      return await new Promise((resolve) => {
        let left = replies.length;
        for (const reply of replies) {
          reply.then((r) => (until(r) ? resolve(r) : --left === 0 && resolve(null)));
        }
      });
    } finally {
      this.replies.delete(id);
    }
  }

  /**
   * Plans `field` with `options` in the pool's workers: the same plan as `plan(field,
   * options)`. Plans asked while one is planning wait their turn.
   */
  plan(field, options) {
    const planned = this.queue.then(() => this.#plan(field, options));
    this.queue = planned.catch(() => {});
    return planned;
  }

  async #plan(field, options) {
    if (this.closed) {
      throw new FurrowError("the pool was terminated", { code: "not_initialised" });
    }
    const workers = await this.workers;
    if (this.broken) throw this.broken;
    const of = workers.length;
    for (const w of workers) w.busy(true);
    try {
      let started;
      try {
        started = await this.#round(workers, (index) => ({ start: { field, options, index, of } }));
      } catch (e) {
        // postMessage could not copy the field or the options.
        const what = e?.name === "DataCloneError" ? "plain values" : "values a worker can receive";
        throw new FurrowError(`the field and options must be ${what}: ${e.message}`, {
          code: "invalid_geojson",
          cause: e,
        });
      }
      const failed = started.find((r) => r.error);
      if (failed) throw fromPlain(failed.error);
      const length = started.reduce((sum, r) => sum + r.summaries.length, 0);
      const all = new Float64Array(length);
      let at = 0;
      for (const r of started) {
        all.set(r.summaries, at);
        at += r.summaries.length;
      }
      // The worker that holds the plan answers with it; the others (which may still be filling a
      // candidate of their own) are not waited for.
      const finished = await this.#round(workers, () => ({ finish: all }), { until: (r) => r.plan || r.error });
      if (finished?.error) throw fromPlain(finished.error);
      const done = finished?.plan;
      if (!done) throw new FurrowError("no worker finished the plan", { code: "internal" });
      // The worker sends the GeoJSON as text: a string crosses threads far cheaper than the
      // object it parses to.
      const plan = JSON.parse(done.json);
      plan.samples = done.samples;
      return plan;
    } finally {
      for (const w of workers) w.busy(false);
    }
  }

  /** Stops the workers. Plans asked after are refused. */
  terminate() {
    this.closed = true;
    this.workers.then((ws) => ws.forEach((w) => w.terminate())).catch(() => {});
  }
}

let shared = null; // the pool planInWorkers keeps between calls

/**
 * Plans `field` with `options` in a pool of `workers` workers kept for the next call (a call
 * with another count starts a new pool): the same plan as `plan(field, options)`.
 */
export async function planInWorkers(field, options, { workers } = {}) {
  const size = Math.min(workers ?? defaultWorkers(), MAX_WORKERS);
  if (shared?.size !== size) {
    shared?.terminate();
    shared = new PlannerPool({ workers: size });
  }
  return shared.plan(field, options);
}
