import type { GeoJsonObject, Plan, Position } from "./furrow_wasm.js";

/**
 * How the machine may turn on its way along the tracks (Plessen & Bemporad 2016):
 * `"heading"` (default) no turning on the spot: the first move follows the heading, and at a
 * junction any way but back (turns up to 135°); `"tracks"` only tracks as driven, changing track
 * only where they meet at the same heading (the repressed-area constraint: on a coverage plan
 * most ways out do not exist then); `"on-the-spot"` any way anywhere (orchard-like areas).
 */
export type Turning = "tracks" | "heading" | "on-the-spot";

export interface TrackPathOptions {
  /** How the machine may turn. Default `"heading"`. */
  turning?: Turning;
  /** The plan's coordinates (as planned): longitude/latitude (default) or local metres. */
  coordinates?: "wgs84" | "metric";
}

/** A shortest path along the tracks, in the plan's coordinates. */
export interface TrackPathFeature {
  type: "Feature";
  geometry: { type: "LineString"; coordinates: Position[] };
  properties: {
    kind: "track_path";
    /** Its length, metres. */
    length_m: number;
    turning: Turning;
    /** Which of the targets it reaches (index; 0 for a single target). */
    target: number;
    /** How far the position was from the nearest track (the path starts there), metres. */
    start_offset_m: number;
    /** Turns on the spot on the way (only with `"on-the-spot"`). */
    turns_on_the_spot: number;
    /** States the search expanded. */
    expanded: number;
    /** The kinds of the tracks driven, in order: `swath`, `headland`, `turn`, `connection`. */
    tracks: string[];
  };
}

/**
 * The tracks of a plan (swaths, headland passes, turns, connections) and where they meet, for
 * many shortest paths. Free it with `free()` when done (or let it be collected).
 */
export class TrackGraph {
  /** The tracks of `plan` (the result of `plan`, or its GeoJSON object or text). */
  constructor(plan: Plan | GeoJsonObject | string, options?: TrackPathOptions);
  /**
   * The shortest way along the tracks from `position` (the machine, within 25 m of a track),
   * facing `heading` (compass degrees), to the nearest point of the boundary lane (the field's
   * outermost headland pass) to `target`, or to the nearest of several targets. Throws a
   * `FurrowError`: `off_tracks`, `no_path`, `invalid_option`.
   */
  shortestPath(position: Position, heading: number, target: Position | Position[], options?: TrackPathOptions): TrackPathFeature;
  readonly trackCount: number;
  readonly junctionCount: number;
  free(): void;
}

/** `new TrackGraph(plan, options).shortestPath(position, heading, target, options)` in one call. */
export function shortestPath(
  plan: Plan | GeoJsonObject | string,
  position: Position,
  heading: number,
  target: Position | Position[],
  options?: TrackPathOptions,
): TrackPathFeature;
