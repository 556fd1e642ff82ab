// Types of the furrow package's main entry: the planner's types and functions from the
// wasm-bindgen module, re-exported by furrow.js, which adds loading in Node, the FurrowError
// class and recovery from a trapped instance. Every type the API uses is exported here; the
// shortest paths along a plan's tracks are the "furrow/tracks" entry (tracks.d.ts).
import type { FurrowErrorDetails, InitInput, InitOutput, SyncInitInput } from "./furrow_wasm.js";

export type {
  GeoJsonObject,
  FieldInput,
  HeadlandMode,
  HeadlandOrder,
  HeadlandCorners,
  EdgePasses,
  DirectionMode,
  SearchMethod,
  Decomposition,
  ObjectiveName,
  PlanOptions,
  SwathPattern,
  PlanFeatureKind,
  ObstacleClass,
  ObstacleClassCounts,
  PlanFeatureProperties,
  Position,
  PlanFeature,
  PlanSummary,
  CoverageSummary,
  StageTimes,
  DirectionReport,
  DecompositionReport,
  RouteReport,
  DecompositionCandidate,
  ObjectiveValues,
  WarningCode,
  PlanWarning,
  Plan,
  PathSamples,
  ErrorCode,
  FurrowErrorDetails,
  InitInput,
  InitOutput,
  SyncInitInput,
} from "./furrow_wasm.js";
export { plan, defaultOptions, version } from "./furrow_wasm.js";

/**
 * What every function of the package throws: an Error with a stable `code` (see `ErrorCode`)
 * and, where the problem has a place in the input, `feature`, `ring`, `vertex` and
 * `coordinate` (`line` and `column` for text that is not JSON).
 *
 * ```ts
 * try {
 *   plan(field, options);
 * } catch (e) {
 *   if (e instanceof FurrowError && e.code === "self_intersection") showAt(e.coordinate);
 * }
 * ```
 */
export declare class FurrowError extends Error {
  constructor(message: string, details: FurrowErrorDetails & { cause?: unknown });
  name: "FurrowError";
}
export interface FurrowError extends FurrowErrorDetails {}

/**
 * Loads the planner, once, before any other call. In a browser or worker it fetches
 * furrow_wasm_bg.wasm beside furrow.js (where a bundler put it), or what `module_or_path` names;
 * in Node it reads that file. Throws a `FurrowError` with code `not_initialised` if it cannot.
 */
export default function init(
  module_or_path?: { module_or_path: InitInput | Promise<InitInput> } | InitInput | Promise<InitInput>,
): Promise<InitOutput>;

/**
 * Loads the planner synchronously from the bytes of furrow_wasm_bg.wasm or a compiled
 * `WebAssembly.Module` (`{ module }`); in Node 20.16 or later it may be left out (the file
 * beside furrow.js is read). Throws a `FurrowError` with code `not_initialised` if it cannot.
 */
export function initSync(module?: { module: SyncInitInput } | SyncInitInput): InitOutput;
