// Types of furrow/pool: the planner in a pool of workers (Web Workers in a browser, worker
// threads in Node), giving the plan `plan()` gives in about the time of the largest share of
// `auto`'s work.
import type { FieldInput, InitInput, Plan, PlanOptions } from "./furrow.js";

export { FurrowError } from "./furrow.js";

/** Most workers a plan can use: `auto` weighs at most four pieces of work. */
export declare const MAX_WORKERS: 4;

export interface PoolOptions {
  /** Workers to start: default the device's cores, at most {@link MAX_WORKERS} (more are not started). */
  workers?: number;
  /**
   * The planner's WebAssembly for every worker, as `init()` of "furrow" takes it (for example
   * `{ module_or_path: compiledModule }` of furrow_pool_wasm_bg.wasm); by default each worker
   * loads furrow_pool_wasm_bg.wasm from beside the package.
   */
  wasm?: InitInput | { module_or_path: InitInput };
}

/**
 * A pool of workers that plan together. Start it once and plan many times (each worker keeps
 * its planner loaded):
 *
 * ```js
 * import { PlannerPool } from "furrow/pool";
 * const pool = new PlannerPool({ workers: 4 });
 * const plan = await pool.plan(field, { width: 6, headlandPasses: 2 });
 * pool.terminate();
 * ```
 *
 * Errors are FurrowErrors with the codes `plan()` throws; a pool whose workers cannot load the
 * planner rejects each plan with code `not_initialised`.
 */
export declare class PlannerPool {
  constructor(options?: PoolOptions);
  /** The workers in the pool. */
  readonly size: number;
  /**
   * Plans `field` with `options`: the same plan as `plan(field, options)`. Plans asked while
   * one is planning wait their turn.
   */
  plan(field: FieldInput, options?: PlanOptions): Promise<Plan>;
  /** Stops the workers; plans asked after are refused. */
  terminate(): void;
}

/**
 * Plans `field` with `options` in a pool of `workers` workers (default the device's cores, at
 * most 4) kept for the next call: the same plan as `plan(field, options)`.
 */
export declare function planInWorkers(
  field: FieldInput,
  options?: PlanOptions,
  settings?: { workers?: number },
): Promise<Plan>;
