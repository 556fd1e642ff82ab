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

/**
 * Where the field headland runs: all around the field (`"constant"`), or only along the edges
 * where swaths end (`"needed"`).
 */
export type HeadlandMode = "constant" | "needed";

/**
 * When the headland passes are worked: before the swaths, from the field edge in (`"first"`, as
 * in harvesting), or after them, finishing at the field edge (`"last"`, as in seeding).
 */
export type HeadlandOrder = "first" | "last";

/**
 * How the sharp corners of the headland passes are driven: worked into by backing round onto the
 * next side where the machine reverses (`"auto"`; rounded otherwise), rounded at the turning
 * radius (`"round"`), or always worked into, by a manoeuvre outside the field where none fits
 * inside, warned of (`"manoeuvre"`).
 */
export type HeadlandCorners = "auto" | "round" | "manoeuvre";

/**
 * The number of headland passes along one edge of the boundary as drawn: edge `i` runs from
 * point `i` to point `i + 1` of the boundary's outer ring in the input.
 */
export interface EdgePasses {
  /** Index of the edge in the outer ring as drawn, from 0. */
  edge: number;
  /** Number of passes along it, 0 for none (at most 50). */
  passes: number;
}

/**
 * How the driving direction is chosen: `"search"`, the direction of lowest cost by `objective`;
 * `"longest-edge"`, along the longest boundary edge; `"fixed"`, the `bearing` given;
 * `"reference"`, along `referenceLine` or `referenceEdge`, on its grid.
 */
export type DirectionMode = "search" | "longest-edge" | "fixed" | "reference";

/**
 * How the direction search steps: `"coarse-to-fine"` (Oksanen & Visala: six directions, refine
 * around the best three at half the step until under one degree, and the directions of the
 * longest edges; about 30 to 40 evaluations) or `"brute-force"` (every direction at `searchStep`).
 */
export type SearchMethod = "coarse-to-fine" | "brute-force";

/**
 * How the inner field is cut into blocks: `"none"`, one direction, swaths clustered into blocks
 * where obstacles and bays break the lines; `"boustrophedon"`, one direction, Zhou et al.'s
 * boustrophedon cells; `"split-merge"`, Oksanen & Visala's split and merge, each block with its
 * own searched direction (only with the direction searched); `"auto"`, the one of lowest
 * estimated operation time.
 */
export type Decomposition = "none" | "boustrophedon" | "split-merge" | "auto";

/**
 * What the direction search minimises: `"time"`, estimated operation time (swaths, turns by the
 * turn model, and uncovered area); `"swath-count"`; `"swath-length"` (total); `"coverage"` (the
 * uncovered share); `"overlap"` (area worked twice or over the edge); `"turn-count"`;
 * `"oksanen"`, Oksanen & Visala's weighted criterion (efficiency 65 %, area 15 %, distance 20 %).
 */
export type ObjectiveName =
  | "time"
  | "swath-count"
  | "swath-length"
  | "coverage"
  | "overlap"
  | "turn-count"
  | "oksanen";

/** Planner options. Every option has a default; see `defaultOptions()`. */
export interface PlanOptions {
  /** Working width of the implement, metres: swath spacing and headland pass width. Default 6. */
  width?: number;
  /**
   * Number of headland passes around the field and around each obstacle that gets a headland;
   * `"auto"`: as many as the machine's turns between neighbouring swaths need to stay inside
   * the field (from `width`, `turnRadius`, `reverse` and `curvatureRate`); `"all"`: as many as
   * the field holds, pass inside pass to its middle, so that the whole field is worked along its
   * outline (contour work: narrow and bent fields). The plan reports the number laid in
   * `summary.headland_passes`. Default 2.
   */
  headlandPasses?: number | "auto" | "all";
  /**
   * Where the field headland runs: `"constant"`, all around the field, or `"needed"`, only along
   * edges where swaths end. Default `"constant"`.
   */
  headlandMode?: HeadlandMode;
  /**
   * In `"needed"` mode, boundary edges within this many degrees of the swath direction get no
   * headland. At least 0 and less than 90. Default 5.
   */
  headlandTolerance?: number;
  /**
   * Passes along particular edges of the boundary as drawn, overriding `headlandMode` and
   * `headlandPasses` there (0 passes for none). Default none.
   */
  edgePasses?: EdgePasses[];
  /**
   * Whether the headland passes are worked before the swaths (`"first"`, harvest) or after them
   * (`"last"`, seeding). Default `"last"`.
   */
  headlandOrder?: HeadlandOrder;
  /**
   * How the sharp corners of the headland passes are driven (see {@link HeadlandCorners}).
   * Default `"auto"`.
   */
  headlandCorners?: HeadlandCorners;
  /**
   * Obstacles narrower than this across the driving direction (metres) do not split the field:
   * swaths run past them with the implement lifted (class A). `null` or absent: one working
   * width.
   */
  obstacleThreshold?: number | null;
  /** Minimum turning radius of the machine, metres. Default 8. */
  turnRadius?: number;
  /**
   * How the driving direction is chosen. `null` or absent: `"fixed"` if `bearing` is given,
   * `"reference"` if `referenceLine` or `referenceEdge` is, else `"search"`.
   */
  direction?: DirectionMode | null;
  /** The direction search. Default `"coarse-to-fine"`. */
  search?: SearchMethod;
  /** Step of the brute-force search, degrees (0.01 to 90). Default 1. */
  searchStep?: number;
  /** What the direction search minimises. Default `"time"`. */
  objective?: ObjectiveName;
  /**
   * Driving direction as a compass bearing in degrees (0 = north, clockwise; a bearing and its
   * reverse are the same direction). `null` or absent: searched.
   */
  bearing?: number | null;
  /**
   * A reference (AB) line: two points in the input's coordinates. Swaths run along it, on a grid
   * one width apart through it (shifted by `referenceOffset`), so that tracks follow last year's.
   */
  referenceLine?: [Position, Position] | null;
  /** A boundary edge as drawn (edge `i` from point `i` to `i + 1`) to run the swaths along. */
  referenceEdge?: number | null;
  /**
   * Shift of the swath grid from the reference, metres, to the right looking from its first point
   * to its second. Default 0 for a line (it is a track), half a width for an edge. The grid
   * repeats every width: only what is left after whole widths counts.
   */
  referenceOffset?: number | null;
  /** Speed while working, km/h (0.1 to 60), for the estimated operation time. Default 8. */
  workingSpeed?: number;
  /** Speed while turning, km/h (0.1 to 60). Default 5. */
  turningSpeed?: number;
  /**
   * Driving directions that may not be used anywhere, as `[from, to]` compass bearings in degrees
   * (clockwise from `from` to `to`; a range forbids the reverse directions too, so one 180
   * degrees wide or more, such as `[0, 360]`, forbids every direction: `no_allowed_direction`).
   * Default none.
   */
  forbiddenBearings?: [number, number][];
  /** Swath pieces shorter than this (metres) are left to the headland. Default: one width. */
  minSwathLength?: number | null;
  /** Coordinates of the input and the plan. Default `"wgs84"` (longitude, latitude). */
  coordinates?: "wgs84" | "metric";
  /**
   * How the inner field is cut into blocks. Default `"auto"`: none, boustrophedon and (when the
   * direction is searched) split and merge are all planned, and the fastest kept.
   */
  decomposition?: Decomposition;
  /**
   * Order of the swaths in each block. Default `"auto"`: for each block, the pattern whose turns
   * cost least (boustrophedon, snake skipping 1, snake skipping enough for plain U-turns, spiral).
   */
  pattern?: SwathPattern;
  /** Swaths the snake pattern skips at each turn, 1 or more. Default 1. */
  snakeSkip?: number;
  /** Swaths in each group of the spiral pattern, 2 or more. Default 6. */
  spiralSize?: number;
  /**
   * The custom pattern: the order in which each group of `m` neighbouring swaths is worked, a
   * permutation of 0..m such as `[0, 2, 1, 3]`. Needed with `pattern: "custom"`.
   */
  customOrder?: number[];
  /**
   * Where the machine enters the field, in the input's coordinates, within 10 km of the
   * boundary: the route starts there.
   */
  entrance?: Position | null;
  /**
   * Where the machine leaves the field, in the input's coordinates, within 10 km of the
   * boundary: the route ends there.
   */
  exit?: Position | null;
  /** Whether the machine may reverse in turns (three-point turns, Reeds-Shepp paths); with
   * `headlandCorners` `"auto"` it then works into the corners of its headland passes. Default
   * false. */
  reverse?: boolean;
  /** Largest change of curvature per metre driven (1/m²): turns get clothoid transitions. At most
   * 1000 and at least 1 / (1000 × turnRadius): steering from straight to the tightest turn takes at
   * most a kilometre. Default none. */
  curvatureRate?: number | null;
  /** Distance between the points of the sampled path, metres. Default 0.5. */
  sampleSpacing?: number;
}

/** How the swaths of a block are ordered. */
export type SwathPattern = "boustrophedon" | "snake" | "spiral" | "custom" | "auto";

/** What a plan feature is. */
export type PlanFeatureKind =
  | "block"
  | "obstacle"
  | "obstacle_group"
  | "uncovered"
  | "swath"
  | "headland"
  | "turn"
  | "connection";

/**
 * How an obstacle is dealt with (Zhou et al.): `"A"`, small across the driving direction, passed
 * over with the implement lifted; `"B"`, near the boundary, merged into the field headland;
 * `"C"`, closer than a working width to another obstacle, merged with it into an
 * `obstacle_group`; `"D"`, with its own headland.
 */
export type ObstacleClass = "A" | "B" | "C" | "D";

/** Number of obstacles of each class. */
export interface ObstacleClassCounts {
  /** Passed over with the implement lifted. */
  A: number;
  /** Merged into the field headland. */
  B: number;
  /** Merged with neighbouring obstacles into an obstacle group. */
  C: number;
  /** With their own headland. */
  D: number;
}

/** Properties of a plan feature; which are present depends on `kind`. */
export interface PlanFeatureProperties {
  kind: PlanFeatureKind;
  /** Position in driving order, from 0 (swath, headland, turn, connection). */
  sequence?: number;
  /** Index of the block, obstacle, obstacle group or swath. */
  index?: number;
  /** Position of a block in the order blocks are worked. */
  order?: number;
  /** The block a swath, or a turn between two of its swaths, belongs to. */
  block?: number;
  /** The swath line a swath lies on, counted across the field. */
  line?: number;
  /** Area of a part left standing (`uncovered`), square metres. */
  area_m2?: number;
  /** Of a part left standing, what a strip of the implement's width could reach, square metres. */
  reachable_m2?: number;
  /** Which headland pass, 1 = nearest the boundary or obstacle it runs around. */
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
  /** The class of an obstacle; `"C"` for an obstacle group. */
  class?: ObstacleClass;
  /** For a class-C obstacle: the `index` of the obstacle group it was merged into. */
  group?: number;
  /** For an obstacle group: the indices of the obstacles merged into it (its convex hull). */
  members?: number[];
  /**
   * What a headland pass runs around: the field boundary, an obstacle (or obstacle group), or
   * (`"block"`) the border between two blocks where both blocks' swaths end; or (`"fill"`)
   * the outline of crop the other passes and the swaths leave, such as an arm too narrow to
   * turn in.
   */
  around?: "field" | "obstacle" | "block" | "fill";
  /**
   * Whether a headland pass is a closed loop (its last point repeats its first). In `"needed"`
   * mode the passes along the field edges are open lines.
   */
  closed?: boolean;
  /**
   * Where along a swath or headland pass the implement is lifted: `[from, to]` metres from its
   * first point (as driven), in order; over class-A obstacles, and wherever the implement would
   * reach out of the field or over an obstacle (the slanted ends of swaths in a field without
   * headland, a pass across a class-A obstacle). Absent when it is never lifted.
   */
  lifted?: [number, number][];
  /**
   * For a swath on a line placed to work a leftover strip narrower than a width: how far (metres)
   * its strip overlaps its neighbour's. Absent on regular lines, exactly a width apart.
   */
  overlap_m?: number;
  /**
   * For a swath or block in a prohibited region that forbids the field's direction: the index of
   * the region (among the input's prohibited regions), whose own direction it follows.
   */
  region?: number;
  /** Swaths and blocks that work a part the others left standing (corners, strips at swath ends). */
  fill?: true;
  /** Drivable features: distance driven from the start of the path to this feature's start, metres. */
  distance_m?: number;
  /** Drivable features: time from the start of the path to this feature's start, seconds. */
  time_s?: number;
  /** Drivable features: time to drive it, seconds (working speed on swaths and headland passes, else turning speed). */
  duration_s?: number;
  /** Drivable features: whether the implement works along it. */
  working?: boolean;
  /** A turn's form. */
  form?: "u-turn" | "loop" | "three-point" | "reeds-shepp" | "cc-u-turn" | "cc-loop" | "on-the-spot" | "lifted" | "headland" | "none";
  /** A turn's word, e.g. `"LSL"` or `"L+R-L+"`. */
  word?: string;
  /** Turns and connections: `false` where it leaves the field or crosses an obstacle (see the `turn_leaves_field` and `connection_leaves_field` warnings). */
  inside?: boolean;
  /** Connections and turns between swaths: `true` where it drives over crop the plan works later (see the `connection_crosses_crop` and `turn_crosses_crop` warnings); absent elsewhere. */
  crosses_crop?: boolean;
  /** Drivable features: the heading at each point of the line, compass degrees. */
  heading_deg?: number[];
  /** Drivable features: the steering curvature at each point, 1/m, positive to the left. */
  curvature?: number[];
  /** On features where the machine reverses: whether it reverses at each point. */
  reverse?: boolean[];
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
  /** Headland passes (rings) in the plan's headland, a pass split at a neck counting once per part. */
  headland_pass_count: number;
  /**
   * Headland passes laid around the field: the count asked for, the count `"auto"` chose, or
   * fewer where those left no inner field (with a `headland_passes_reduced` warning) or where
   * the field holds no more (as `"all"` lays them).
   */
  headland_passes: number;
  /** Swaths and headland passes. */
  working_distance_m: number;
  swath_distance_m: number;
  headland_distance_m: number;
  /** Turns between swaths of a block and manoeuvres at dead ends and sharp corners of headland and fill passes: the drivable turns of the path. */
  turning_distance_m: number;
  /** The turns between swaths by the turn model the route optimises. */
  turn_model_distance_m: number;
  /** How many turns of each form (`u-turn`, `loop`, `three-point`, `reeds-shepp`, `cc-u-turn`, `cc-loop`). */
  turn_forms: Record<string, number>;
  /** Turns that leave the field or cross an obstacle; each is warned of with its cause. */
  turns_outside_field: number;
  /** Connections that leave the field or cross an obstacle; each is warned of with its cause. */
  connections_outside_field: number;
  /** Changes of gear along the path. */
  cusp_count: number;
  /** Connections between blocks, onto the headland passes, from the entrance and to the exit. */
  connection_distance_m: number;
  /** Of which between blocks. */
  block_connection_distance_m: number;
  total_distance_m: number;
  /** The same route with turns on the spot (Fields2Cover's comparison). */
  on_the_spot_distance_m: number;
  /** Time working, seconds, at working speed. */
  working_time_s: number;
  /** Time turning and connecting (and each cusp's penalty), seconds, at turning speed. */
  non_working_time_s: number;
  field_area_m2: number;
  /** The bands of headland passes along the boundary and around obstacles that have them. */
  headland_area_m2: number;
  /** Where the swaths lie (obstacles left out). */
  inner_field_area_m2: number;
  /**
   * Inner field area over the area of the field less the obstacles that have headlands: the
   * share left for swaths, 0 to 1 (Fields2Cover's remaining-area objective for headlands).
   */
  remaining_area_ratio: number;
  /** Headland area no pass covers: corners rounded to the turning radius, necks too narrow to turn in. */
  uncovered_headland_area_m2: number;
  /**
   * Distance along swaths and headland passes driven with the implement lifted (`lifted` of
   * each).
   */
  lifted_distance_m: number;
  /** Number of obstacles of each class. */
  obstacle_classes: ObstacleClassCounts;
  dropped_swath_count: number;
  /** Of the swaths, those that work parts the others and the headland passes left standing. */
  fill_swath_count: number;
  /** Swath direction, compass degrees in [0, 180): with split and merge, the first block's. */
  bearing_deg: number;
  /** How the direction was chosen. */
  direction: DirectionReport;
  /** Every objective's value for the plan's swaths, turns by the turn model. */
  objectives: ObjectiveValues;
  /** How the inner field was cut into blocks, and the decompositions compared. */
  decomposition: DecompositionReport;
  /** How the swaths and blocks were ordered. */
  route: RouteReport;
  /**
   * Estimated operation time, seconds: swaths and headland passes at working speed; the path's
   * turns and connections (and a penalty per cusp) at turning speed.
   */
  estimated_time_s: number;
  /** The implement's footprint against the field less its obstacles. */
  coverage: CoverageSummary;
  /** Time the planner took, milliseconds. */
  planning_ms: number;
  /** Of which each stage, milliseconds (summed over the decompositions compared). */
  stages_ms: StageTimes;
}

/**
 * Coverage: the strip of the implement's width along every stretch worked (swaths, headland
 * passes; not turns, connections or stretches lifted over an obstacle), against the field less
 * its obstacles. Measured on a grid of cells `resolution_m` across (a sixth of the working width,
 * at most 1 m; coarser on large fields). The crop left standing is in the features of kind `uncovered`.
 */
export interface CoverageSummary {
  /** The field less its obstacles, square metres. */
  field_area_m2: number;
  /** Of it, worked at least once. */
  covered_area_m2: number;
  /** `covered_area_m2` over `field_area_m2`. */
  coverage_ratio: number;
  /**
   * The share of the field a strip of the implement's width can reach at all (the field opened
   * by a disc of the working width across): the limit of `coverage_ratio`.
   */
  reachable_ratio: number;
  /** Area worked twice or more, over the field area. */
  overlap_ratio: number;
  /** Area left standing, square metres. */
  uncovered_area_m2: number;
  /**
   * Area worked outside the field or over an obstacle, square metres: the implement's strip past
   * the boundary (outer swaths of a field worked without headland, along a side not parallel to
   * them), or over an obstacle it is not lifted over.
   */
  outside_area_m2: number;
  /** The side of the grid's cells, metres. */
  resolution_m: number;
}

/** Time spent in each stage of planning, milliseconds. */
export interface StageTimes {
  /** Reading the input and checking it, simplifying the boundary. */
  validation: number;
  /** Choosing the swath direction. */
  direction: number;
  /** Obstacle classes and headland passes. */
  headlands: number;
  /** Cutting the inner field into blocks and laying the swaths. */
  decomposition: number;
  /** The order of work. */
  route: number;
  /** The drivable path. */
  path: number;
  /** The figures of the plan. */
  metrics: number;
}

/** How the direction of a plan was chosen. */
export interface DirectionReport {
  mode: DirectionMode;
  /** The search method, when the direction was searched. */
  method: SearchMethod | null;
  /** The objective minimised, by which `cost` is measured. */
  objective: ObjectiveName;
  /** Directions evaluated: the field's, its prohibited regions', and with split and merge its blocks'. */
  evaluations: number;
  /** The objective's cost of the plan's swaths (seconds for `"time"`). */
  cost: number;
  /**
   * The lowest cost the search found, on the area it measures (the field less a constant
   * headland); `null` when the direction was not searched.
   */
  search_cost: number | null;
}

/** How the inner field was cut into blocks. */
export interface DecompositionReport {
  /** What the `decomposition` option asked for. */
  requested: Decomposition;
  /** What the plan uses: for `"auto"`, the candidate of lowest estimated operation time. */
  method: Exclude<Decomposition, "auto">;
  /** Why, in words, with the time of each candidate. */
  reason: string;
  /** Every decomposition planned. */
  candidates: DecompositionCandidate[];
}

/** How the swaths and blocks were ordered. */
export interface RouteReport {
  /** The pattern the options asked for. */
  pattern: SwathPattern;
  /** The swath order of each block in working order: `boustrophedon`, `snake-1`, `spiral-6`, `custom`. */
  block_patterns: string[];
  /** How the block order was found: exactly (dynamic programming), by ant colony and local search, or (for more than 256 blocks, or where the ways between them would take too long to search) nearest block first. */
  sequence: "exact" | "ant-colony" | "nearest-neighbour";
  /** Connections that found no way along the headland and run straight. */
  straight_connections: number;
}

/** The figures of one decomposition planned. */
export interface DecompositionCandidate {
  method: Exclude<Decomposition, "auto">;
  block_count: number;
  /** The blocks' swath directions, compass degrees in [0, 180), each once. */
  bearings_deg: number[];
  swath_count: number;
  /** Turns within blocks. */
  turn_count: number;
  /** Headland passes along borders between blocks. */
  block_headland_passes: number;
  /** Estimated operation time, seconds. */
  estimated_time_s: number;
  /**
   * Inner field area its swaths leave uncovered, square metres; counted as if worked at working
   * speed when the decompositions are compared.
   */
  uncovered_area_m2: number;
  /** Directions split and merge evaluated for its blocks (0 for the others). */
  evaluations: number;
}

/** The objectives' values for a plan's swaths. */
export interface ObjectiveValues {
  swath_count: number;
  /** Total swath length, metres. */
  swath_length_m: number;
  /** Share of the inner field covered by the swaths' strips, 0 to 1. */
  coverage: number;
  covered_area_m2: number;
  /** Area worked twice, or over the inner field's edge into the headland, by the strips. */
  overlap_m2: number;
  turn_count: number;
  /** Length of the turns between swaths by the turn model (U-turn, or loop turn under 2 radii). */
  turning_distance_m: number;
  /** Swaths at working speed and turns at turning speed, seconds. */
  time_s: number;
  /** Oksanen & Visala's weighted score, 0 to 1, higher is better. */
  oksanen_score: number;
}

/** The codes of warnings in a plan. */
export type WarningCode =
  | "ring_closed"
  | "repeated_vertices"
  | "collinear_vertices"
  | "spikes_removed"
  | "ring_reoriented"
  | "obstacle_clipped"
  | "obstacles_merged"
  | "outline_simplified"
  | "field_at_sea"
  | "prohibited_clipped"
  | "ignored_feature"
  | "short_swaths_dropped"
  | "straight_connections"
  | "implement_lifted"
  | "implement_lifted_at_edges"
  | "region_own_direction"
  | "region_not_worked"
  | "direction_not_searched"
  | "turn_leaves_field"
  | "connection_leaves_field"
  | "connection_crosses_crop"
  | "turn_crosses_crop"
  | "output_coarsened"
  | "headland_passes_reduced";

export interface PlanWarning {
  /** What the warning is about; see the README's warning reference. */
  code: WarningCode;
  message: string;
  /** Index of the input feature concerned (for `implement_lifted`, the class-A obstacle). */
  feature?: number;
}

/** A plan: GeoJSON in the input's coordinates, drivable features in driving order. */
export interface Plan {
  type: "FeatureCollection";
  features: PlanFeature[];
  summary: PlanSummary;
  warnings: PlanWarning[];
  /** The path sampled every `sampleSpacing` metres or less, as flat typed arrays (not in the GeoJSON text). */
  samples: PathSamples;
}

/**
 * The sampled path, one entry per point in every array. Positions in the input's coordinates.
 * Kinds: 0 swath, 1 headland pass, 2 turn, 3 connection.
 */
export interface PathSamples {
  x: Float64Array;
  y: Float64Array;
  /** Heading, compass degrees (where the machine faces, also when reversing). */
  heading_deg: Float64Array;
  /** Steering curvature, 1/m, positive to the left. */
  curvature: Float64Array;
  /** Distance from the start of the path, metres. */
  distance_m: Float64Array;
  /** Time from the start of the path, seconds. */
  time_s: Float64Array;
  kind: Uint8Array;
  /** 1 where the machine reverses. */
  reverse: Uint8Array;
  /** 1 where the implement works. */
  working: Uint8Array;
  /** Index (`sequence`) of the drivable feature the point lies on. */
  segment: Uint32Array;
}

/** The stable codes of the errors the package throws. */
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
  | "field_too_complex"
  | "headland_consumes_field"
  | "no_allowed_direction"
  | "bearing_forbidden"
  | "invalid_file"
  | "unknown_crs"
  | "coordinates_swapped"
  | "off_tracks"
  | "no_path"
  | "not_initialised"
  | "internal";

/**
 * What a `FurrowError` (the class of every error the package throws) carries besides its message:
 * a stable code and, where the problem has one, the place in the input.
 */
export interface FurrowErrorDetails {
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
