// Types of the package's "furrow/tracks" entry: shortest paths along a plan's tracks, from the
// wasm-bindgen module furrow_tracks_wasm.js, re-exported by tracks.js (which adds loading in
// Node, FurrowError and recovery from a trapped instance, as the planner's entry).
import type { InitInput, InitOutput, SyncInitInput } from "./furrow_tracks_wasm.js";

export type {
  Turning,
  TrackPathOptions,
  TrackPathFeature,
  InitInput,
  InitOutput,
  SyncInitInput,
} from "./furrow_tracks_wasm.js";
export { shortestPath, TrackGraph } from "./furrow_tracks_wasm.js";
/** The same class as the planner's: `instanceof` holds for errors of either entry. */
export { FurrowError } from "./furrow.js";

/**
 * Loads the tracks' module, once, before any other call of this entry (the planner's `init`
 * does not load it). In a browser or worker it fetches furrow_tracks_wasm_bg.wasm beside
 * tracks.js (where a bundler put it), or what `module_or_path` names; in Node it reads that
 * file. Throws a `FurrowError` with code `not_initialised` if it cannot.
 */
export default function initTracks(
  module_or_path?: { module_or_path: InitInput | Promise<InitInput> } | InitInput | Promise<InitInput>,
): Promise<InitOutput>;

/**
 * Loads the tracks' module synchronously from the bytes of furrow_tracks_wasm_bg.wasm or a
 * compiled `WebAssembly.Module` (`{ module }`); in Node 20.16 or later it may be left out.
 */
export function initSync(module?: { module: SyncInitInput } | SyncInitInput): InitOutput;
