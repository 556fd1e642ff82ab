/** Any GeoJSON object the planner reads. */
export interface GeoJsonObject {
  type: string;
  [member: string]: unknown;
}

/**
 * A field: a GeoJSON FeatureCollection whose features have `properties.role` of `"boundary"`
 * (one Polygon), `"obstacle"` or `"prohibited"` (with `forbidden_bearings_deg`); or a single
 * Polygon Feature or bare Polygon geometry (its holes are obstacles); or the GeoJSON as text.
 */
export type FieldInput = GeoJsonObject | string;

/** Planner options. Every option has a default; see `defaultOptions()`. */
export interface PlanOptions {
  /** Working width of the implement, metres: swath spacing and headland pass width. Default 6. */
  width?: number;
  /** Number of headland passes around the field. Default 2. */
  headlandPasses?: number;
  /** Minimum turning radius of the machine, metres. Default 8. */
  turnRadius?: number;
  /**
   * Driving direction as a compass bearing in degrees (0 = north, clockwise; a bearing and its
   * reverse are the same direction). `null` or absent: along the longest boundary edge.
   */
  bearing?: number | null;
  /**
   * Driving directions that may not be used anywhere, as `[from, to]` compass bearings in degrees
   * (clockwise from `from` to `to`; a range forbids the reverse directions too). Default none.
   */
  forbiddenBearings?: [number, number][];
  /** Swath pieces shorter than this (metres) are left to the headland. Default: one width. */
  minSwathLength?: number | null;
  /** Coordinates of the input and the plan. Default `"wgs84"` (longitude, latitude). */
  coordinates?: "wgs84" | "metric";
}

/** What a plan feature is. */
export type PlanFeatureKind = "block" | "obstacle" | "swath" | "headland" | "turn" | "connection";

/** Properties of a plan feature; which are present depends on `kind`. */
export interface PlanFeatureProperties {
  kind: PlanFeatureKind;
  /** Position in driving order, from 0 (swath, headland, turn, connection). */
  sequence?: number;
  /** Index of the block, obstacle or swath. */
  index?: number;
  /** Position of a block in the order blocks are worked. */
  order?: number;
  /** The block a swath or turn belongs to. */
  block?: number;
  /** The swath line a swath lies on, counted across the field. */
  line?: number;
  /** Which headland pass, 1 = outermost. */
  pass?: number;
  /** Number of swaths of a block. */
  swath_count?: number;
  /** Index of the input feature an obstacle came from. */
  feature?: number;
  /** The input feature's name, for obstacles that had one. */
  name?: string;
  /** Length in metres. */
  length_m?: number;
  /** Compass bearing in degrees: driving direction of a swath, swath direction of a block. */
  bearing_deg?: number;
}

export type Position = [number, number];

export interface PlanFeature {
  type: "Feature";
  properties: PlanFeatureProperties;
  geometry:
    | { type: "LineString"; coordinates: Position[] }
    | { type: "Polygon"; coordinates: Position[][] };
}

/** The figures of a plan. Distances in metres, areas in square metres. */
export interface PlanSummary {
  swath_count: number;
  turn_count: number;
  block_count: number;
  headland_pass_count: number;
  /** Swaths and headland passes. */
  working_distance_m: number;
  swath_distance_m: number;
  headland_distance_m: number;
  turning_distance_m: number;
  connection_distance_m: number;
  total_distance_m: number;
  field_area_m2: number;
  headland_area_m2: number;
  inner_field_area_m2: number;
  dropped_swath_count: number;
  /** Swath direction, compass degrees in [0, 180). */
  bearing_deg: number;
  /** Time the planner took, milliseconds. */
  planning_ms: number;
}

export interface PlanWarning {
  code: string;
  message: string;
  /** Index of the input feature concerned. */
  feature?: number;
}

/** A plan: GeoJSON in the input's coordinates, drivable features in driving order. */
export interface Plan {
  type: "FeatureCollection";
  features: PlanFeature[];
  summary: PlanSummary;
  warnings: PlanWarning[];
}

/** The stable codes of errors thrown by `plan`. */
export type ErrorCode =
  | "invalid_json"
  | "invalid_geojson"
  | "no_boundary"
  | "ambiguous_boundary"
  | "unsupported_geometry"
  | "non_finite_coordinate"
  | "coordinate_out_of_range"
  | "too_few_points"
  | "zero_area"
  | "self_intersection"
  | "obstacle_outside_field"
  | "hole_crossing_boundary"
  | "invalid_option"
  | "option_out_of_range"
  | "input_too_large"
  | "field_too_large"
  | "headland_consumes_field"
  | "no_allowed_direction"
  | "bearing_forbidden"
  | "coordinates_swapped"
  | "internal";

/** What `plan` throws: an Error named "FurrowError" with a stable code and the place in the input. */
export interface FurrowError extends Error {
  name: "FurrowError";
  code: ErrorCode;
  /** Index of the offending feature in the input's `features`. */
  feature?: number;
  /** Index of the offending ring (0 = exterior). */
  ring?: number;
  /** Index of the offending vertex. */
  vertex?: number;
  /** The offending position, in the input's coordinates. */
  coordinate?: Position;
  /** For input that is not JSON: the line (from 1) where reading stopped. */
  line?: number;
  /** For input that is not JSON: the column (from 1) where reading stopped. */
  column?: number;
}

/**
 * Plans a field. `field` is GeoJSON (an object, or its text) in the coordinates
 * `options.coordinates` names; `options` may be left out. Returns the plan as a GeoJSON
 * FeatureCollection with `summary` and `warnings`. Throws a `FurrowError` when the field or an
 * option cannot be planned.
 */
export function plan(field: FieldInput, options?: PlanOptions): Plan;
