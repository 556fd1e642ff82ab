//! The planner's options: one struct shared by the Rust API, the JavaScript API (camelCase
//! keys) and the command-line planner (kebab-case flags), with a default for every option.

use crate::decompose::Decomposition;
use crate::direction::{DirectionMode, SearchMethod};
use crate::error::{ErrorCode, PlanError};
use crate::field::place::{place_problem, range_problem, MAX_PLACE_DISTANCE_M};
use crate::field::Coordinates;
use crate::geometry::{forbids_every_direction, BearingRange};
use crate::headland::passes::{passes_for_turns, passes_to_fill, HeadlandPasses};
use crate::headland::{EdgePasses, HeadlandCorners, HeadlandMode, HeadlandOrder};
use crate::numbers::{Position, Shortest};
use crate::objective::{Machine, ObjectiveKind};
use crate::route::pattern::SwathPattern;
use crate::sort::SharedSort;
use serde::{Deserialize, Serialize};

/// How the field is to be planned. Every option has a default; JavaScript passes them as an object
/// with camelCase keys (`{ width: 6, headlandPasses: 2 }`), the CLI as kebab-case flags
/// (`--headland-passes 2`).
///
/// ```
/// use furrow::PlanOptions;
///
/// let options: PlanOptions = serde_json::from_str(r#"{"width": 4.5, "bearing": 30}"#)?;
/// assert_eq!(options.width, 4.5);
/// assert_eq!(options.bearing_deg, Some(30.0));
/// assert_eq!(options.headland_passes, PlanOptions::default().headland_passes);
/// options.validate()?;
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase", default, deny_unknown_fields)]
pub struct PlanOptions {
    /// Working width of the implement, metres: the distance between neighbouring swaths and the
    /// width of each headland pass.
    pub width: f64,
    /// Number of headland passes driven around the field boundary and around each obstacle that
    /// gets a headland; `auto`: as many as the machine's turns need
    /// ([`passes_for_turns`](crate::headland::passes::passes_for_turns)); `all`: as many as the
    /// field holds, pass inside pass to the middle (contour work).
    pub headland_passes: HeadlandPasses,
    /// Where the field headland runs: all around (`constant`), or only along edges where swaths
    /// end (`needed`).
    pub headland_mode: HeadlandMode,
    /// In `needed` mode, boundary edges within this many degrees of the swath direction get no
    /// headland.
    #[serde(rename = "headlandTolerance")]
    pub headland_tolerance_deg: f64,
    /// Passes along particular edges of the boundary as drawn (edge `i` runs from point `i` to
    /// point `i + 1` of the outer ring), overriding the mode; 0 for none.
    pub edge_passes: Vec<EdgePasses>,
    /// Whether the headland passes are worked before the swaths (`first`, as in harvesting) or
    /// after them (`last`, as in seeding).
    pub headland_order: HeadlandOrder,
    /// How the sharp corners of the headland passes are driven: worked into by a machine that
    /// reverses where it can (`auto`), rounded (`round`), or always worked into (`manoeuvre`).
    pub headland_corners: HeadlandCorners,
    /// Obstacles narrower than this across the driving direction (metres) do not split the
    /// field: swaths run past them with the implement lifted (class A). `None` means one working
    /// width.
    pub obstacle_threshold: Option<f64>,
    /// Minimum turning radius of the machine, metres.
    pub turn_radius: f64,
    /// How the driving direction is chosen: `search` for the lowest cost by `objective`,
    /// `longest-edge`, `fixed` (`bearing`) or `reference` (`referenceLine` or `referenceEdge`).
    /// `None` follows from the options given: `bearing` means fixed, a reference line or edge
    /// means reference, else search.
    pub direction: Option<DirectionMode>,
    /// The direction search: `coarse-to-fine` (Oksanen & Visala) or `brute-force`.
    pub search: SearchMethod,
    /// Step of the brute-force search, degrees.
    #[serde(rename = "searchStep")]
    pub search_step_deg: f64,
    /// What the direction search minimises.
    pub objective: ObjectiveKind,
    /// Driving direction of the swaths as a compass bearing in degrees (0 = north, clockwise; a
    /// bearing and its reverse are the same direction).
    #[serde(rename = "bearing")]
    pub bearing_deg: Option<f64>,
    /// A reference (AB) line, two points in the input's coordinates: swaths run along it, on a
    /// grid one width apart through it (shifted by `referenceOffset`), so that tracks follow
    /// last year's.
    pub reference_line: Option<[[f64; 2]; 2]>,
    /// A boundary edge as drawn (edge `i` runs from point `i` to point `i + 1` of the outer ring)
    /// to run the swaths along, on a grid one width apart from it.
    pub reference_edge: Option<usize>,
    /// Shift of the swath grid from the reference, metres, to the right looking from the line's
    /// first point to its second. Default: 0 for a reference line (it is a track), half a width
    /// for an edge (the first strip runs along it).
    pub reference_offset: Option<f64>,
    /// Speed while working, km/h: for the estimated operation time.
    #[serde(rename = "workingSpeed")]
    pub working_speed_kmh: f64,
    /// Speed while turning, km/h.
    #[serde(rename = "turningSpeed")]
    pub turning_speed_kmh: f64,
    /// Driving directions that may not be used anywhere in the field (e.g. along drainage
    /// laterals), as compass bearing ranges; a range forbids the reverse directions too.
    #[serde(rename = "forbiddenBearings")]
    pub forbidden_bearings_deg: Vec<BearingRange>,
    /// Swath pieces shorter than this (metres) are not worked as swaths; `None` means one working
    /// width. The headland passes cover what they leave.
    pub min_swath_length: Option<f64>,
    /// The coordinates of the input and of the plan: WGS84 longitude/latitude, or local metres.
    pub coordinates: Coordinates,
    /// How the inner field is cut into blocks: `none` (one direction), `boustrophedon` (one
    /// direction, Zhou et al.'s cells), `split-merge` (Oksanen & Visala: a direction per block)
    /// or `auto` (the one of lowest estimated operation time).
    pub decomposition: Decomposition,
    /// The order of the swaths inside each block: `boustrophedon`, `snake` (skipping
    /// `snakeSkip` swaths at each turn), `spiral` (groups of `spiralSize`), `custom`
    /// (`customOrder`), or `auto` (the pattern whose turns cost least, block by block).
    pub pattern: SwathPattern,
    /// Swaths the snake pattern skips at each turn.
    pub snake_skip: u32,
    /// Swaths in each group of the spiral pattern.
    pub spiral_size: u32,
    /// The custom pattern: a permutation of `0..m`, the order in which each group of `m`
    /// neighbouring swaths is worked (e.g. `[0, 2, 1, 3]`).
    pub custom_order: Vec<u32>,
    /// Where the machine enters the field, in the input's coordinates, within
    /// [`MAX_PLACE_DISTANCE_M`] of the boundary: the route starts there and reaches the first
    /// swath along the headland.
    pub entrance: Option<[f64; 2]>,
    /// Where the machine leaves the field, in the input's coordinates, within
    /// [`MAX_PLACE_DISTANCE_M`] of the boundary: the route ends there.
    /// Without it, the route ends where the work ends.
    pub exit: Option<[f64; 2]>,
    /// Whether the machine may reverse in turns (three-point turns, Reeds-Shepp paths).
    pub reverse: bool,
    /// The machine's largest change of curvature per metre driven (1/m²): how fast it can turn
    /// its steering. Given, turns and corners are continuous-curvature (clothoids into and out
    /// of every arc); `None`: arcs join lines directly (Dubins, Reeds-Shepp).
    pub curvature_rate: Option<f64>,
    /// Distance between the points of the sampled path, metres.
    pub sample_spacing: f64,
}

impl Default for PlanOptions {
    fn default() -> Self {
        PlanOptions {
            width: 6.0,
            headland_passes: HeadlandPasses::Count(2),
            headland_mode: HeadlandMode::Constant,
            headland_tolerance_deg: 5.0,
            edge_passes: Vec::new(),
            headland_order: HeadlandOrder::Last,
            headland_corners: HeadlandCorners::Auto,
            obstacle_threshold: None,
            turn_radius: 8.0,
            direction: None,
            search: SearchMethod::CoarseToFine,
            search_step_deg: 1.0,
            objective: ObjectiveKind::Time,
            bearing_deg: None,
            reference_line: None,
            reference_edge: None,
            reference_offset: None,
            working_speed_kmh: 8.0,
            turning_speed_kmh: 5.0,
            forbidden_bearings_deg: Vec::new(),
            min_swath_length: None,
            coordinates: Coordinates::Wgs84,
            decomposition: Decomposition::Auto,
            pattern: SwathPattern::Auto,
            snake_skip: 1,
            spiral_size: 6,
            custom_order: Vec::new(),
            entrance: None,
            exit: None,
            reverse: false,
            curvature_rate: None,
            sample_spacing: 0.5,
        }
    }
}

/// What an `entrance` or `exit` option must be, for its error message.
fn place_wanted(name: &str, coordinates: Coordinates) -> String {
    let position = match coordinates {
        Coordinates::Wgs84 => "[longitude, latitude]",
        Coordinates::Metric => "[x, y] in the field's metres",
    };
    let act = if name == "exit" { "leaves" } else { "enters" };
    format!(
        "the {position} where the machine {act} the field, within {} km of its boundary",
        Shortest(MAX_PLACE_DISTANCE_M / 1000.0)
    )
}

/// The largest `curvatureRate` accepted, 1/m²: beyond it the clothoids are shorter than a
/// millimetre on any machine, and the turns those of plain arcs.
pub const MAX_CURVATURE_RATE: f64 = 1000.0;

/// The longest clothoid accepted from straight to the tightest turn, metres (`1 / (turnRadius ·
/// curvatureRate)`): no machine takes a kilometre to steer, and the path's turns grow with it
/// (a plan of a 2 ha rectangle took 30 s with a 1,000 km clothoid).
pub const MAX_CLOTHOID_M: f64 = 1000.0;

/// Bounds of `sampleSpacing`, metres: a centimetre (a 200 ha plan is then some ten million
/// points) to 100 m.
pub const MIN_SAMPLE_SPACING_M: f64 = 0.01;
/// See [`MIN_SAMPLE_SPACING_M`].
pub const MAX_SAMPLE_SPACING_M: f64 = 100.0;

/// Each option's key (as in JavaScript), its unit or type, and what it does: the help of the
/// command-line planner. A test checks that it lists exactly the fields of [`PlanOptions`].
pub const OPTION_DOCS: &[(&str, &str, &str)] = &[
    (
        "width",
        "metres",
        "working width of the implement: swath spacing and headland pass width (default 6)",
    ),
    (
        "headlandPasses",
        "count|auto|all",
        "number of headland passes around the field and around each obstacle that gets a headland; auto: as many as the machine's turns between neighbouring swaths need to stay inside the field; all: as many as the field holds, the whole field worked along its outline (default 2)",
    ),
    (
        "headlandMode",
        "constant|needed",
        "headland all around the field, or only along edges where swaths end (default constant)",
    ),
    (
        "headlandTolerance",
        "degrees",
        "in needed mode, edges within this angle of the swath direction get no headland (default 5)",
    ),
    (
        "edgePasses",
        "[{edge,passes},...]",
        "passes along particular boundary edges as drawn (edge i runs from point i to i+1), 0 for none (default none)",
    ),
    (
        "headlandOrder",
        "first|last",
        "work the headland passes before the swaths (harvest) or after them (seeding) (default last)",
    ),
    (
        "headlandCorners",
        "auto|round|manoeuvre",
        "the sharp corners of the headland passes: worked into by backing round where the machine reverses (auto), rounded at the turning radius (round), or always worked into, by a manoeuvre outside the field where none fits inside (manoeuvre) (default auto)",
    ),
    (
        "obstacleThreshold",
        "metres",
        "obstacles narrower than this across the driving direction are passed over with the implement lifted (default: one working width)",
    ),
    (
        "turnRadius",
        "metres",
        "minimum turning radius of the machine (default 8)",
    ),
    (
        "direction",
        "search|longest-edge|fixed|reference",
        "how the driving direction is chosen (default: fixed if bearing is given, reference if a reference line or edge is, else search)",
    ),
    (
        "search",
        "coarse-to-fine|brute-force",
        "direction search: Oksanen's coarse-to-fine (six directions, then around the best three at half the step until under a degree, and the longest edges: about 30 to 40 directions) or every direction at searchStep (default coarse-to-fine)",
    ),
    (
        "searchStep",
        "degrees",
        "step of the brute-force direction search (default 1)",
    ),
    (
        "objective",
        "time|swath-count|swath-length|coverage|overlap|turn-count|oksanen",
        "what the direction search minimises (default time: estimated operation time)",
    ),
    (
        "bearing",
        "degrees",
        "driving direction as a compass bearing, 0 = north (default: searched)",
    ),
    (
        "referenceLine",
        "x,y,x,y",
        "AB line, its two points A and B in the input's coordinates: swaths run along it on a grid one width apart through it (default none)",
    ),
    (
        "referenceEdge",
        "index",
        "boundary edge as drawn (edge i from point i to i+1) to run the swaths along, the first strip beside it (default none)",
    ),
    (
        "referenceOffset",
        "metres",
        "shift of the swath grid to the right of the reference, looking from its first point (default 0 for a line, half a width for an edge)",
    ),
    (
        "workingSpeed",
        "km/h",
        "speed while working, for the estimated operation time (default 8)",
    ),
    (
        "turningSpeed",
        "km/h",
        "speed while turning (default 5)",
    ),
    (
        "forbiddenBearings",
        "[[from,to],...]",
        "driving directions not to use, as compass bearing ranges in degrees; each forbids the reverse too (default none)",
    ),
    (
        "minSwathLength",
        "metres",
        "swath pieces shorter than this are left to the headland (default: one working width)",
    ),
    (
        "coordinates",
        "wgs84|metric",
        "coordinates of the input and the plan: longitude/latitude or local metres (default wgs84)",
    ),
    (
        "decomposition",
        "none|boustrophedon|split-merge|auto",
        "how the field is cut into blocks: one direction, Zhou's boustrophedon cells, Oksanen's split and merge with a direction per block, or whichever is fastest (default auto)",
    ),
    (
        "pattern",
        "boustrophedon|snake|spiral|custom|auto",
        "order of the swaths in each block: one after another, skipping snakeSkip at each turn and coming back, spirals of spiralSize, customOrder, or the one whose turns cost least (default auto)",
    ),
    (
        "snakeSkip",
        "count",
        "swaths the snake pattern skips at each turn (default 1)",
    ),
    (
        "spiralSize",
        "count",
        "swaths in each group of the spiral pattern (default 6)",
    ),
    (
        "customOrder",
        "[i,...]",
        "the custom pattern: the order of each group of neighbouring swaths, a permutation of 0..m such as [0,2,1,3] (default none)",
    ),
    (
        "entrance",
        "x,y",
        "where the machine enters the field, in the input's coordinates, within 10 km of the boundary: the route starts there (default: at the first swath)",
    ),
    (
        "exit",
        "x,y",
        "where the machine leaves the field, in the input's coordinates, within 10 km of the boundary: the route ends there (default: where the work ends)",
    ),
    (
        "reverse",
        "true|false",
        "whether the machine may reverse in turns: three-point turns and Reeds-Shepp paths (default false)",
    ),
    (
        "curvatureRate",
        "1/m2",
        "largest change of curvature per metre driven: turns and corners get clothoid transitions (continuous curvature) (default none: arcs join lines directly)",
    ),
    (
        "sampleSpacing",
        "metres",
        "distance between the points of the sampled path (default 0.5)",
    ),
];

/// [`PlanOptions::default`] as JSON text, as `serde_json` writes it (a test checks): the npm
/// package's `defaultOptions` parses it rather than carrying the options' writer.
pub const DEFAULT_OPTIONS_JSON: &str = r#"{"width":6.0,"headlandPasses":2,"headlandMode":"constant","headlandTolerance":5.0,"edgePasses":[],"headlandOrder":"last","headlandCorners":"auto","obstacleThreshold":null,"turnRadius":8.0,"direction":null,"search":"coarse-to-fine","searchStep":1.0,"objective":"time","bearing":null,"referenceLine":null,"referenceEdge":null,"referenceOffset":null,"workingSpeed":8.0,"turningSpeed":5.0,"forbiddenBearings":[],"minSwathLength":null,"coordinates":"wgs84","decomposition":"auto","pattern":"auto","snakeSkip":1,"spiralSize":6,"customOrder":[],"entrance":null,"exit":null,"reverse":false,"curvatureRate":null,"sampleSpacing":0.5}"#;

/// Most swaths the snake pattern may skip, and most in a spiral or custom group.
pub const MAX_PATTERN_SWATHS: u32 = 1000;

/// Largest working width accepted, metres.
pub const MAX_WIDTH_M: f64 = 200.0;
/// Smallest working width accepted, metres.
pub const MIN_WIDTH_M: f64 = 0.1;
/// Most headland passes accepted.
pub const MAX_HEADLAND_PASSES: u32 = 50;
/// Largest turning radius accepted, metres.
pub const MAX_TURN_RADIUS_M: f64 = 200.0;
/// Smallest working or turning speed accepted, km/h: slower, the times of a plan run to years.
pub const MIN_SPEED_KMH: f64 = 0.1;
/// Largest working or turning speed accepted, km/h.
pub const MAX_SPEED_KMH: f64 = 60.0;

/// The error of an option outside its range. (Out of line: one copy of the message's writing
/// for every option checked.)
#[inline(never)]
fn out_of_range(name: &str, value: &dyn std::fmt::Display, range: &str) -> PlanError {
    PlanError::new(
        ErrorCode::OptionOutOfRange,
        format!("option `{name}` is {value}; it must be {range}"),
    )
}

impl PlanOptions {
    /// Checks that every option is within the range the planner accepts.
    pub fn validate(&self) -> Result<(), PlanError> {
        let out_of_range = |name: &str, value: &dyn std::fmt::Display, range: &str| {
            Err(out_of_range(name, value, range))
        };
        if !(self.width.is_finite() && (MIN_WIDTH_M..=MAX_WIDTH_M).contains(&self.width)) {
            return out_of_range(
                "width",
                &Shortest(self.width),
                &format!(
                    "between {} and {} metres",
                    Shortest(MIN_WIDTH_M),
                    Shortest(MAX_WIDTH_M)
                ),
            );
        }
        if let Some(n) = self
            .headland_passes
            .count()
            .filter(|&n| n > MAX_HEADLAND_PASSES)
        {
            return out_of_range(
                "headlandPasses",
                &n,
                &format!("at most {MAX_HEADLAND_PASSES}"),
            );
        }
        if !(self.turn_radius.is_finite() && (0.0..=MAX_TURN_RADIUS_M).contains(&self.turn_radius))
        {
            return out_of_range(
                "turnRadius",
                &Shortest(self.turn_radius),
                &format!("between 0 and {} metres", Shortest(MAX_TURN_RADIUS_M)),
            );
        }
        if let Some(b) = self.bearing_deg {
            if !b.is_finite() {
                return out_of_range("bearing", &Shortest(b), "a finite number of degrees");
            }
        }
        if let Some(r) = self.forbidden_bearings_deg.iter().find(|r| !r.is_finite()) {
            return out_of_range(
                "forbiddenBearings",
                &format!("[{}, {}]", Shortest(r.from_deg), Shortest(r.to_deg)),
                "pairs of finite compass bearings",
            );
        }
        if forbids_every_direction(&self.forbidden_bearings_deg) {
            return Err(PlanError::new(
                ErrorCode::NoAllowedDirection,
                "option `forbiddenBearings` forbids every driving direction; leave at least one range of directions open",
            ));
        }
        if !(self.headland_tolerance_deg.is_finite()
            && (0.0..90.0).contains(&self.headland_tolerance_deg))
        {
            return out_of_range(
                "headlandTolerance",
                &Shortest(self.headland_tolerance_deg),
                "at least 0 and less than 90 degrees",
            );
        }
        if let Some(e) = self
            .edge_passes
            .iter()
            .find(|e| e.passes > MAX_HEADLAND_PASSES)
        {
            return out_of_range(
                "edgePasses",
                &format!("{} passes for edge {}", e.passes, e.edge),
                &format!("at most {MAX_HEADLAND_PASSES} passes"),
            );
        }
        if let Some(t) = self.obstacle_threshold {
            if !(t.is_finite() && t >= 0.0) {
                return out_of_range("obstacleThreshold", &Shortest(t), "0 or more metres");
            }
        }
        if !(self.search_step_deg.is_finite() && (0.01..=90.0).contains(&self.search_step_deg)) {
            return out_of_range(
                "searchStep",
                &Shortest(self.search_step_deg),
                "between 0.01 and 90 degrees",
            );
        }
        for (name, v) in [
            ("workingSpeed", self.working_speed_kmh),
            ("turningSpeed", self.turning_speed_kmh),
        ] {
            if !(v.is_finite() && (MIN_SPEED_KMH..=MAX_SPEED_KMH).contains(&v)) {
                return out_of_range(
                    name,
                    &Shortest(v),
                    &format!(
                        "between {} and {} km/h",
                        Shortest(MIN_SPEED_KMH),
                        Shortest(MAX_SPEED_KMH)
                    ),
                );
            }
        }
        if let Some(line) = self.reference_line {
            if line.iter().flatten().any(|v| !v.is_finite()) {
                return out_of_range(
                    "referenceLine",
                    &format!("[{}, {}]", Position(line[0]), Position(line[1])),
                    "two points of finite coordinates",
                );
            }
            if line[0] == line[1] {
                return Err(PlanError::new(
                    ErrorCode::InvalidOption,
                    "option `referenceLine` has two equal points; it needs two different points to give a direction",
                ));
            }
        }
        if let Some(o) = self.reference_offset {
            if !o.is_finite() {
                return out_of_range("referenceOffset", &Shortest(o), "a finite number of metres");
            }
        }
        let mode = self.direction_mode()?;
        if self.decomposition == Decomposition::SplitMerge && mode != DirectionMode::Search {
            return Err(PlanError::new(
                ErrorCode::InvalidOption,
                "option `decomposition` is `split-merge`, which searches a direction for each block; it cannot follow a fixed `bearing`, a reference or the longest edge (use `auto` or `boustrophedon`, or leave the direction to the search)",
            ));
        }
        if let Some(m) = self.min_swath_length {
            if !(m.is_finite() && m >= 0.0) {
                return out_of_range("minSwathLength", &Shortest(m), "0 or more metres");
            }
        }
        if let Some(c) = self.curvature_rate {
            if !(c.is_finite() && c > 0.0 && c <= MAX_CURVATURE_RATE) {
                return out_of_range(
                    "curvatureRate",
                    &Shortest(c),
                    &format!(
                        "more than 0 and at most {} per square metre",
                        Shortest(MAX_CURVATURE_RATE)
                    ),
                );
            }
            let least = 1.0 / (MAX_CLOTHOID_M * self.turn_radius);
            if self.turn_radius > 0.0 && c < least {
                return out_of_range(
                    "curvatureRate",
                    &Shortest(c),
                    &format!(
                        "at least {} per square metre with a turning radius of {} m (a clothoid from straight to the tightest turn at most {} km long)",
                        Shortest(least),
                        Shortest(self.turn_radius),
                        Shortest(MAX_CLOTHOID_M / 1000.0)
                    ),
                );
            }
        }
        if !(self.sample_spacing.is_finite()
            && (MIN_SAMPLE_SPACING_M..=MAX_SAMPLE_SPACING_M).contains(&self.sample_spacing))
        {
            return out_of_range(
                "sampleSpacing",
                &Shortest(self.sample_spacing),
                &format!(
                    "between {} and {} metres",
                    Shortest(MIN_SAMPLE_SPACING_M),
                    Shortest(MAX_SAMPLE_SPACING_M)
                ),
            );
        }
        if !(1..=MAX_PATTERN_SWATHS).contains(&self.snake_skip) {
            return out_of_range(
                "snakeSkip",
                &self.snake_skip,
                &format!("between 1 and {MAX_PATTERN_SWATHS}"),
            );
        }
        if !(2..=MAX_PATTERN_SWATHS).contains(&self.spiral_size) {
            return out_of_range(
                "spiralSize",
                &self.spiral_size,
                &format!("between 2 and {MAX_PATTERN_SWATHS}"),
            );
        }
        if self.custom_order.len() > MAX_PATTERN_SWATHS as usize {
            return out_of_range(
                "customOrder",
                &format!("{} positions long", self.custom_order.len()),
                &format!("at most {MAX_PATTERN_SWATHS} positions"),
            );
        }
        let mut sorted = self.custom_order.clone();
        sorted.shared_sort_unstable_by(Ord::cmp);
        if sorted.iter().enumerate().any(|(i, &p)| p as usize != i) {
            return Err(PlanError::new(
                ErrorCode::InvalidOption,
                format!(
                    "option `customOrder` is [{}]; it must hold each of 0 to {} once",
                    self.custom_order
                        .iter()
                        .map(u32::to_string)
                        .collect::<Vec<_>>()
                        .join(", "),
                    self.custom_order.len().saturating_sub(1)
                ),
            ));
        }
        if self.pattern == SwathPattern::Custom && self.custom_order.is_empty() {
            return Err(PlanError::new(
                ErrorCode::InvalidOption,
                "option `pattern` is `custom` but `customOrder` is empty; give the order of a group of swaths, such as [0, 2, 1, 3]",
            ));
        }
        for (name, point) in self.places() {
            if let Some(problem) = range_problem(point, self.coordinates) {
                return Err(PlanError::new(
                    ErrorCode::OptionOutOfRange,
                    format!(
                        "option `{name}` is {}: {problem}; give {}",
                        Position(point),
                        place_wanted(name, self.coordinates)
                    ),
                ));
            }
        }
        Ok(())
    }

    /// Checks that the entrance and exit the options give lie near `field`: within
    /// [`MAX_PLACE_DISTANCE_M`] of its boundary ([`validate`](Self::validate) checks the rest).
    ///
    /// ```
    /// use furrow::{field::Field, ErrorCode, PlanOptions};
    ///
    /// let (field, _) = Field::from_geojson_str(r#"{"type": "Polygon", "coordinates": [[[24.05, 60.25],
    ///     [24.056, 60.25], [24.056, 60.252], [24.05, 60.252], [24.05, 60.25]]]}"#)?;
    /// let at_the_gate = PlanOptions { entrance: Some([24.056, 60.2505]), ..Default::default() };
    /// at_the_gate.check_places(&field)?;
    /// let in_town = PlanOptions { entrance: Some([24.94, 60.17]), ..Default::default() };
    /// assert_eq!(in_town.check_places(&field).unwrap_err().code, ErrorCode::OptionOutOfRange);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn check_places(&self, field: &crate::field::Field) -> Result<(), PlanError> {
        for (name, point) in self.places() {
            if let Some(problem) =
                place_problem(point, self.coordinates, &field.boundary, &field.frame)
            {
                return Err(PlanError::new(
                    ErrorCode::OptionOutOfRange,
                    format!(
                        "option `{name}` is {}: {problem}; give {}",
                        Position(point),
                        place_wanted(name, self.coordinates)
                    ),
                ));
            }
        }
        Ok(())
    }

    /// The entrance and exit given, with their options' names.
    fn places(&self) -> impl Iterator<Item = (&'static str, [f64; 2])> {
        [("entrance", self.entrance), ("exit", self.exit)]
            .into_iter()
            .filter_map(|(name, p)| p.map(|p| (name, p)))
    }

    /// Reads options from JSON text (camelCase keys), e.g. from a command line or a file.
    pub fn from_json_str(text: &str) -> Result<Self, PlanError> {
        let options: PlanOptions = serde_json::from_str(text).map_err(|e| {
            PlanError::new(ErrorCode::InvalidOption, format!("invalid options: {e}"))
        })?;
        options.validate()?;
        Ok(options)
    }

    /// The number of headland passes: as given, or for `auto` the fewest whose depth holds the
    /// machine's turns between neighbouring swaths. `all` depends on the field: it is counted
    /// when planning ([`PlanOptions::with_pass_count`]; the plan's `summary.headland_passes` has
    /// the passes laid), 0 here.
    ///
    /// ```
    /// use furrow::headland::passes::HeadlandPasses;
    /// use furrow::PlanOptions;
    ///
    /// let mower = PlanOptions { width: 3.0, turn_radius: 5.0, headland_passes: HeadlandPasses::Auto, ..Default::default() };
    /// assert_eq!(mower.headland_pass_count(), 5);
    /// let reversing = PlanOptions { reverse: true, ..mower.clone() };
    /// assert!(reversing.headland_pass_count() < 5);
    /// ```
    pub fn headland_pass_count(&self) -> u32 {
        match self.headland_passes {
            HeadlandPasses::Count(n) => n,
            HeadlandPasses::Auto => passes_for_turns(&self.vehicle(), MAX_HEADLAND_PASSES),
            HeadlandPasses::All => 0,
        }
    }

    /// These options with `auto` headland passes replaced by their count, and `all` by the most
    /// the field's boundary can hold ([`passes_to_fill`]: the headland stage lays them until
    /// one finds no room); `None` when they are a count already.
    pub fn with_pass_count(&self, boundary: &geo::Polygon) -> Option<PlanOptions> {
        let count = match self.headland_passes {
            HeadlandPasses::Count(_) => return None,
            HeadlandPasses::Auto => self.headland_pass_count(),
            HeadlandPasses::All => passes_to_fill(boundary, self.width),
        };
        Some(PlanOptions {
            headland_passes: HeadlandPasses::Count(count),
            ..self.clone()
        })
    }

    /// These options with what the field itself gives and the options leave out: its entrance,
    /// and its AB line when no bearing, reference or other direction is asked for. `None` when
    /// the field adds nothing.
    pub fn with_field(&self, field: &crate::field::Field) -> Option<PlanOptions> {
        let entrance = self.entrance.is_none() && field.entrance.is_some();
        let line = field.reference_line.is_some()
            && self.reference_line.is_none()
            && self.reference_edge.is_none()
            && self.bearing_deg.is_none()
            && matches!(self.direction, None | Some(DirectionMode::Reference));
        if !entrance && !line {
            return None;
        }
        let mut out = self.clone();
        if entrance {
            out.entrance = field.entrance;
        }
        if line {
            out.reference_line = field.reference_line;
        }
        Some(out)
    }

    /// The direction mode, given or following from the options given.
    pub fn direction_mode(&self) -> Result<DirectionMode, PlanError> {
        let invalid = |m: String| Err(PlanError::new(ErrorCode::InvalidOption, m));
        let has_reference = self.reference_line.is_some() || self.reference_edge.is_some();
        if self.reference_line.is_some() && self.reference_edge.is_some() {
            return invalid(
                "options `referenceLine` and `referenceEdge` both given; give one reference".into(),
            );
        }
        match self.direction {
            None => match (self.bearing_deg, has_reference) {
                (Some(_), true) => invalid(
                    "options `bearing` and a reference line or edge both given; give one of them, or set `direction`".into(),
                ),
                (Some(_), false) => Ok(DirectionMode::Fixed),
                (None, true) => Ok(DirectionMode::Reference),
                (None, false) => Ok(DirectionMode::Search),
            },
            Some(DirectionMode::Fixed) if self.bearing_deg.is_none() => {
                invalid("option `direction` is `fixed` but no `bearing` is given".into())
            }
            Some(DirectionMode::Reference) if !has_reference => invalid(
                "option `direction` is `reference` but neither `referenceLine` nor `referenceEdge` is given".into(),
            ),
            Some(mode) => Ok(mode),
        }
    }

    /// The machine as the objectives see it (speeds in metres per second).
    pub fn machine(&self) -> Machine {
        Machine {
            width: self.width,
            turn_radius: self.turn_radius,
            working_speed: self.working_speed_kmh / 3.6,
            turning_speed: self.turning_speed_kmh / 3.6,
        }
    }

    /// The vehicle as the path sees it (speeds in metres per second).
    pub fn vehicle(&self) -> crate::path::turn::Vehicle {
        crate::path::turn::Vehicle {
            width: self.width,
            turn_radius: self.turn_radius,
            reverse: self.reverse,
            corners: self.headland_corners,
            curvature_rate: self.curvature_rate,
            working_speed: self.working_speed_kmh / 3.6,
            turning_speed: self.turning_speed_kmh / 3.6,
        }
    }

    /// The class-A obstacle threshold in metres, with its default applied.
    pub fn obstacle_threshold_m(&self) -> f64 {
        self.obstacle_threshold.unwrap_or(self.width)
    }

    /// The minimum swath length in metres, with its default applied.
    pub fn min_swath_length_m(&self) -> f64 {
        self.min_swath_length.unwrap_or(self.width)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_default_options_text_is_the_defaults_written() {
        let written = serde_json::to_string(&PlanOptions::default()).unwrap();
        assert_eq!(DEFAULT_OPTIONS_JSON, written);
    }

    #[test]
    fn docs_list_exactly_the_options() {
        let v = serde_json::to_value(PlanOptions::default()).unwrap();
        let mut keys: Vec<&str> = v.as_object().unwrap().keys().map(|k| k.as_str()).collect();
        let mut documented: Vec<&str> = OPTION_DOCS.iter().map(|(k, _, _)| *k).collect();
        keys.sort_unstable();
        documented.sort_unstable();
        assert_eq!(keys, documented);
    }

    #[test]
    fn unknown_option_is_refused() {
        let e = PlanOptions::from_json_str(r#"{"widht": 3}"#).unwrap_err();
        assert_eq!(e.code, ErrorCode::InvalidOption);
        assert!(e.message.contains("widht"), "{}", e.message);
    }

    #[test]
    fn out_of_range_options_are_refused() {
        for text in [
            r#"{"width": 0}"#,
            r#"{"width": -3}"#,
            r#"{"width": 1000}"#,
            r#"{"headlandPasses": 51}"#,
            r#"{"turnRadius": -1}"#,
            r#"{"minSwathLength": -1}"#,
            r#"{"headlandTolerance": 90}"#,
            r#"{"obstacleThreshold": -2}"#,
            r#"{"edgePasses": [{"edge": 0, "passes": 99}]}"#,
            r#"{"searchStep": 0}"#,
            r#"{"workingSpeed": 0}"#,
            r#"{"workingSpeed": 1e-320}"#,
            r#"{"workingSpeed": 0.09}"#,
            r#"{"turningSpeed": 1e-300}"#,
            r#"{"turningSpeed": 100}"#,
            r#"{"turnRadius": 2, "curvatureRate": 5e-7}"#,
        ] {
            let e = PlanOptions::from_json_str(text).unwrap_err();
            assert_eq!(e.code, ErrorCode::OptionOutOfRange, "{text}");
        }
        let e = PlanOptions::from_json_str(r#"{"headlandPasses": -1}"#).unwrap_err();
        assert_eq!(e.code, ErrorCode::InvalidOption);
    }

    #[test]
    fn forbidden_bearings_that_leave_no_direction_are_refused() {
        let ok =
            PlanOptions::from_json_str(r#"{"forbiddenBearings": [[20, 70], [200, 250]]}"#).unwrap();
        assert_eq!(ok.forbidden_bearings_deg.len(), 2);
        let e = PlanOptions::from_json_str(r#"{"forbiddenBearings": [[0, 90], [80, 185]]}"#)
            .unwrap_err();
        assert_eq!(e.code, ErrorCode::NoAllowedDirection);
        // A range all the way round forbids every direction too.
        for full in ["[[0, 360]]", "[[-90, 270]]", "[[45, 405]]"] {
            let e = PlanOptions::from_json_str(&format!(r#"{{"forbiddenBearings": {full}}}"#))
                .unwrap_err();
            assert_eq!(e.code, ErrorCode::NoAllowedDirection, "{full}");
        }
        let e = PlanOptions::from_json_str(r#"{"forbiddenBearings": [[0, 90, 4]]}"#).unwrap_err();
        assert_eq!(e.code, ErrorCode::InvalidOption);
    }

    #[test]
    fn direction_mode_follows_from_the_options_given() {
        let mode = |t: &str| PlanOptions::from_json_str(t).map(|o| o.direction_mode().unwrap());
        assert_eq!(mode("{}").unwrap(), DirectionMode::Search);
        assert_eq!(mode(r#"{"bearing": 10}"#).unwrap(), DirectionMode::Fixed);
        assert_eq!(
            mode(r#"{"referenceEdge": 2}"#).unwrap(),
            DirectionMode::Reference
        );
        assert_eq!(
            mode(r#"{"direction": "longest-edge", "bearing": 10}"#).unwrap(),
            DirectionMode::LongestEdge
        );
        for bad in [
            r#"{"bearing": 10, "referenceEdge": 1}"#,
            r#"{"direction": "fixed"}"#,
            r#"{"direction": "reference"}"#,
            r#"{"referenceLine": [[1, 2], [1, 2]]}"#,
            r#"{"referenceLine": [[1, 2], [3, 4]], "referenceEdge": 0}"#,
            r#"{"direction": "sideways"}"#,
        ] {
            assert_eq!(
                PlanOptions::from_json_str(bad).unwrap_err().code,
                ErrorCode::InvalidOption,
                "{bad}"
            );
        }
    }

    #[test]
    fn speeds_at_the_ends_of_their_range_are_accepted() {
        for text in [
            r#"{"workingSpeed": 0.1, "turningSpeed": 0.1}"#,
            r#"{"workingSpeed": 60, "turningSpeed": 60}"#,
        ] {
            PlanOptions::from_json_str(text).unwrap();
        }
        let e = PlanOptions::from_json_str(r#"{"turningSpeed": 0.01}"#).unwrap_err();
        assert!(e.message.contains("turningSpeed"), "{}", e.message);
        assert!(e.message.contains("between 0.1 and 60"), "{}", e.message);
    }

    #[test]
    fn defaults_are_valid() {
        PlanOptions::default().validate().unwrap();
    }
}
