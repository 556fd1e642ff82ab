// furrow/tracks: shortest paths along a plan's tracks (Plessen & Bemporad), a WebAssembly module
// of its own (furrow_tracks_wasm.js) loaded with its own init, so that a page that only plans
// never loads it. Loading, errors and recovery as the planner's (load.js).
import * as core from "./furrow_tracks_wasm.js";
import { loader } from "./load.js";

export { FurrowError } from "./load.js";

const tracks = loader(core, {
  what: "furrow/tracks",
  // Literal, so that bundlers find the .wasm and rewrite the URL to their copy.
  wasmUrl: () => new URL("furrow_tracks_wasm_bg.wasm", import.meta.url),
  entry: "furrow/tracks",
  initName: "initTracks",
});

/**
 * Loads the tracks' module: in a browser or worker it fetches furrow_tracks_wasm_bg.wasm beside
 * this file (or what `input` names); in Node it reads that file.
 */
export default tracks.init;
/** Loads the tracks' module synchronously (as the planner's initSync). */
export const initSync = tracks.initSync;
/** The shortest path along a plan's tracks: see tracks.d.ts. */
export const shortestPath = tracks.guarded("shortestPath");

/** The tracks of a plan, for many shortest paths: see tracks.d.ts. */
export class TrackGraph {
  constructor(plan, options) {
    this.inner = tracks.guardedCall(() => new core.TrackGraph(plan, options));
  }
  shortestPath(position, heading, target, options) {
    return tracks.guardedCall(() => this.inner.shortestPath(position, heading, target, options));
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
