//! The planner: field → direction → obstacle classes and headlands → swaths → blocks → route →
//! path → metrics. The direction comes first because obstacle classes and headlands that run
//! only where swaths end depend on it.
//!
//! Each stage is a module of its own with its own types; this module runs them in order and
//! keeps their results together in a [`Plan`]. Up to the headlands there is one plan; from the
//! decomposition on, each decomposition tried is a candidate worked through to its metrics
//! (`candidate`), and `auto` tries the decompositions and chooses among them.

mod auto;
mod candidate;
pub mod contour;
pub mod share;

use crate::decompose::{Blocks, Decomposition};
use crate::direction::{
    choose_bearing, edge_directions, reference_direction, search_field, search_region,
    search_vertices, AreaSearch, DirectionMode, DirectionRule, SearchMethod,
};
use crate::error::{ErrorCode, PlanError, Warning, WarningCode};
use crate::field::projection::OutputAlong;
use crate::field::Field;
use crate::geometry::PlanarHypot;
use crate::headland::complexity::check_offsets;
use crate::headland::edges::{passes_per_edge, EdgeRule};
use crate::headland::{build, EdgePasses, HeadlandSettings, Headlands};
use crate::metrics::{DecompositionReport, StageTimes, Summary};
use crate::numbers::{Decimals, Shortest};
use crate::objective::Objective;
use crate::obstacles::{classify, ClassSettings, ObstacleClasses};
use crate::options::PlanOptions;
use crate::output::budget::{coarsened, sample_spacing};
use crate::path::sample::{sample, Samples};
use crate::path::turn::Area as DrivingArea;
use crate::path::Path;
use crate::route::headland_graph::HeadlandGraph;
use crate::route::{pattern::candidates, Route, RouteSettings};
use crate::swath::{LinePlacement, Swaths};
use candidate::{single_direction, SingleDirection, Worked};
use geo::BoundingRect;
use web_time::Instant;

/// Most swath lines and outline vertices times directions a direction search may sweep (about a
/// third of a second natively): each direction lays every line and sorts the outlines' crossings
/// (1,000 ponds of 96 vertices each took 7 s over 40 directions). Beyond it the direction follows
/// the longest edge.
pub const SEARCH_BUDGET_LINES: f64 = 250_000.0;

/// The decompositions' split tolerance, in working widths: boundary vertices within half a
/// width of a straight line draw no slab line.
const DECOMPOSITION_TOLERANCE: f64 = 0.5;

/// Seed of the block sequence's ant colony: the same field and options give the same route.
const ROUTE_SEED: u64 = 0x5eed_f077;

/// A coverage plan and everything the stages found on the way to it.
#[derive(Debug, Clone)]
pub struct Plan {
    /// The field as planned (local metres).
    pub field: Field,
    /// The options used.
    pub options: PlanOptions,
    /// The class of each obstacle and the holes the headlands run around.
    pub obstacles: ObstacleClasses,
    /// Headland passes and the inner field.
    pub headlands: Headlands,
    /// The swaths.
    pub swaths: Swaths,
    /// The blocks the swaths are grouped in.
    pub blocks: Blocks,
    /// The order of work.
    pub route: Route,
    /// The path driven.
    pub path: Path,
    /// Counts, distances and areas.
    pub summary: Summary,
    /// What was repaired in the input, and what the user should know about the plan.
    pub warnings: Vec<Warning>,
}

impl Plan {
    /// The path sampled every `options.sample_spacing` metres or less ([`sample`]), or, on a
    /// path so long that it would have more samples than
    /// [`MAX_SAMPLES`](crate::output::budget::MAX_SAMPLES), as closely as that
    /// allows ([`sample_spacing`]); positions in the input's coordinates (longitude and
    /// latitude, or local metres).
    pub fn samples(&self) -> Samples {
        let spacing = sample_spacing(&self.path, self.options.sample_spacing);
        let mut s = sample(&self.path, spacing, &self.options.vehicle());
        // The projection is smooth: exact every few hundred metres, quadratic in between
        // (within 0.3 mm of the exact conversion).
        let mut along = OutputAlong::new(&self.field.frame);
        for (x, y) in s.x.iter_mut().zip(s.y.iter_mut()) {
            [*x, *y] = along.convert(geo::Coord { x: *x, y: *y });
        }
        s
    }
}

/// Plans a field.
///
/// ```
/// use furrow::{field::Field, plan, PlanOptions};
///
/// let text = r#"{"type": "Polygon", "coordinates": [[[24.05, 60.25], [24.056, 60.25],
///     [24.056, 60.252], [24.05, 60.252], [24.05, 60.25]]]}"#;
/// let (field, _) = Field::from_geojson_str(text)?;
/// let options = PlanOptions { width: 6.0, headland_passes: 2.into(), bearing_deg: Some(0.0), ..Default::default() };
/// let plan = plan(field, &options)?;
/// // About 333 m east-west, less two 12 m headlands, in 6 m swaths running north; and short
/// // swaths filling the corners the passes round off.
/// assert_eq!(plan.summary.swath_count - plan.summary.fill_swath_count, 52);
/// assert_eq!(plan.summary.turn_count, 51);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn plan(field: Field, options: &PlanOptions) -> Result<Plan, PlanError> {
    let started = Instant::now();
    let mut plan = plan_stages(field, options, Vec::new())?;
    plan.summary.planning_ms = started.elapsed().as_secs_f64() * 1000.0;
    Ok(plan)
}

/// Reads a field from GeoJSON text (in the coordinates `options.coordinates` names) and plans it.
/// The planning time in the summary includes reading the input.
///
/// ```
/// use furrow::{plan_geojson, PlanOptions};
///
/// let text = r#"{"type": "Polygon", "coordinates": [[[24.05, 60.25], [24.056, 60.25],
///     [24.056, 60.252], [24.05, 60.252], [24.05, 60.25]]]}"#;
/// let plan = plan_geojson(text, &PlanOptions::default())?;
/// let geojson = plan.to_geojson_string();
/// assert!(geojson.contains(r#""kind":"swath""#));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn plan_geojson(text: &str, options: &PlanOptions) -> Result<Plan, PlanError> {
    let started = Instant::now();
    options.validate()?;
    let (field, warnings) = Field::from_geojson_str_in(text, options.coordinates)?;
    let read_ms = started.elapsed().as_secs_f64() * 1000.0;
    let mut plan = plan_stages(field, options, warnings)?;
    plan.summary.planning_ms = started.elapsed().as_secs_f64() * 1000.0;
    plan.summary.stages_ms.validation += read_ms;
    Ok(plan)
}

/// Runs the stages on a field read by the caller, keeping the caller's warnings first.
///
/// Where the headland passes asked for leave no inner field for swaths (the field is refused,
/// or planned without a swath), the field is planned again with each smaller number of passes
/// down to none, and the plan that works most of it is kept ([`fewer_passes`]).
pub(crate) fn plan_stages(
    field: Field,
    options: &PlanOptions,
    warnings: Vec<Warning>,
) -> Result<Plan, PlanError> {
    let pending = share::Pending::start(field, options, warnings, share::Share::WHOLE)?;
    let summaries = pending.summaries();
    pending.finish(&summaries).unwrap_or_else(|| {
        Err(PlanError::new(
            ErrorCode::Internal,
            "the plan's one share did not finish it",
        ))
    })
}

/// Whether plan `a` works more of the field than `b`, less what it works outside the field.
fn covers_more(a: &Plan, b: &Plan) -> bool {
    let net = |p: &Plan| p.summary.coverage.covered_area_m2 - p.summary.coverage.outside_area_m2;
    net(a) > net(b) + 1e-6
}

/// The plan with fewer headland passes than `options` asks for that works most of the field
/// less what it works outside (ties to more passes), with a warning of the passes laid; `None`
/// if none plans or covers anything. Two are weighed: the most passes that still leave swaths
/// (found by halving, so that a count asked far beyond the field's room costs a few plans, not
/// one per pass) and none.
fn fewer_passes(field: &Field, options: &PlanOptions, warnings: &[Warning]) -> Option<Plan> {
    let asked = options.headland_pass_count();
    let with = |passes: u32| {
        let fewer = PlanOptions {
            headland_passes: passes.into(),
            edge_passes: options
                .edge_passes
                .iter()
                .map(|e| EdgePasses {
                    passes: e.passes.min(passes),
                    ..*e
                })
                .collect(),
            ..options.clone()
        };
        plan_with_passes(field.clone(), &fewer, warnings.to_vec(), false)
            .ok()
            .filter(|p| {
                p.summary.swath_count > p.summary.fill_swath_count
                    && p.summary.coverage.coverage_ratio > 0.0
            })
    };
    // The most passes below `asked` that leave swaths: in (lo, hi], with the plan at `lo`.
    let (mut lo, mut hi) = (0, asked.saturating_sub(1));
    let mut most: Option<Plan> = None;
    while lo < hi {
        let mid = lo + (hi - lo).div_ceil(2);
        match with(mid) {
            Some(plan) => {
                lo = mid;
                most = Some(plan);
            }
            None => hi = mid - 1,
        }
    }
    let none = with(0);
    let mut plan = match (most, none) {
        (Some(m), Some(n)) => {
            if covers_more(&n, &m) {
                n
            } else {
                m
            }
        }
        (m, n) => m.or(n)?,
    };
    plan.warnings.push(Warning::new(
        WarningCode::HeadlandPassesReduced,
        format!(
            "{asked} headland pass{} of {} m leave no inner field for swaths: {} laid, the number that covers most",
            if asked == 1 { "" } else { "es" },
            Shortest(options.width),
            plan.options.headland_pass_count(),
        ),
    ));
    Some(plan)
}

/// The stages, in order, with the headland passes `options` asks for (to the field's middle,
/// `to_middle`, where `headlandPasses` is `all`): the stages before the decomposition
/// ([`stage`]), each decomposition tried worked into a candidate plan (`auto::work_units`),
/// the fastest chosen (`auto::decide`), and it filled and measured ([`finish`]).
fn plan_with_passes(
    field: Field,
    options: &PlanOptions,
    warnings: Vec<Warning>,
    to_middle: bool,
) -> Result<Plan, PlanError> {
    let mut prepared = stage(field, options, warnings, to_middle)?;
    let mut outcomes = auto::work_units(&mut prepared, share::Share::WHOLE);
    let summaries: Vec<share::UnitSummary> = outcomes.iter().map(|o| o.summary.clone()).collect();
    let decision = auto::decide(&summaries, &prepared.methods)?;
    finish(prepared, decision, &mut outcomes, None)
}

/// The stages before the decomposition: the field cleaned and checked ([`clean_field`]), its
/// direction chosen ([`direction_mode`], [`choose_direction`]), its headlands laid
/// ([`lay_headlands`]), the decompositions to try and what they share.
fn stage(
    mut field: Field,
    options: &PlanOptions,
    mut warnings: Vec<Warning>,
    to_middle: bool,
) -> Result<Prepared, PlanError> {
    let mut times = StageTimes::default();
    let mut clock = Instant::now();
    options.check_places(&field)?;
    let options = options
        .with_field(&field)
        .unwrap_or_else(|| options.clone());
    warnings.extend(clean_field(&mut field, &options)?);
    times.lap(&mut clock, |t| &mut t.validation);
    let objective = options.objective.objective();
    let search = area_search(&options, objective.as_ref());
    let mode = direction_mode(&field, &options, &mut warnings)?;
    let direction = choose_direction(&field, &options, mode, &search)?;
    times.lap(&mut clock, |t| &mut t.direction);
    let (obstacles, headlands, all_around) =
        lay_headlands(&field, &options, direction.bearing, to_middle)?;
    let methods = auto::decompositions(options.decomposition, mode, all_around)?;
    times.lap(&mut clock, |t| &mut t.headlands);
    // The swaths at the field's direction, shared by the single-direction decompositions.
    let single = methods
        .iter()
        .any(|&m| m != Decomposition::SplitMerge)
        .then(|| {
            single_direction(
                &field,
                &options,
                &headlands,
                direction.bearing,
                direction.placement,
                &search,
            )
        })
        .transpose()?;
    times.lap(&mut clock, |t| &mut t.decomposition);
    // The ways along the headland, for every candidate that adds no passes of its own.
    let graph = HeadlandGraph::new(&headlands.passes, options.width).with_crop(&headlands.inner);
    times.lap(&mut clock, |t| &mut t.route);
    let area = driving_area(&field);
    times.lap(&mut clock, |t| &mut t.path);
    let mut prepared = Prepared {
        field,
        options,
        obstacles,
        objective,
        direction,
        headlands,
        graph,
        single,
        area,
        warnings,
        methods: Vec::new(),
        left_out: None,
        times,
    };
    let (methods, left_out) = auto::within_limits(methods, &prepared)?;
    prepared.methods = methods;
    prepared.left_out = left_out;
    Ok(prepared)
}

/// The plan of the candidate `decision` chooses among `outcomes` (which must hold it): its
/// leftovers filled, its coverage measured; or `ahead`, where that is the chosen candidate
/// filled before the choice was known.
fn finish(
    mut prepared: Prepared,
    decision: auto::Decision,
    outcomes: &mut [auto::Outcome],
    ahead: Option<share::Ahead>,
) -> Result<Plan, PlanError> {
    let mut times = prepared.times;
    let mut clock = Instant::now();
    let slot = decision.chosen();
    let (chosen, decomposition) = auto::choose(&prepared, decision, outcomes)?;
    times.lap(&mut clock, |t| &mut t.metrics);
    let (chosen, coverage) = match ahead.filter(|a| Some((a.unit, a.k)) == slot) {
        Some(ahead) => {
            times = ahead.times;
            ahead.filled?
        }
        None => candidate::fill_leftovers(&prepared, chosen, &mut times)?,
    };
    let warnings = std::mem::take(&mut prepared.warnings);
    let sample_spacing = prepared.options.sample_spacing;
    let mut plan = assemble(prepared, chosen, decomposition, warnings);
    plan.summary.coverage = coverage;
    plan.summary.stages_ms = times;
    plan.warnings.extend(coarsened(&plan.path, sample_spacing));
    Ok(plan)
}

/// Simplifies the field's dense outlines for the working width (with warnings of what
/// changed), and refuses outlines too jagged for their headland passes.
fn clean_field(field: &mut Field, options: &PlanOptions) -> Result<Vec<Warning>, PlanError> {
    let width = options.width;
    let warnings = field.simplify(width);
    // An outline too jagged for the width would make the headland insets (and the direction
    // search's) take minutes and gigabytes: refused before any is tried.
    // (Obstacles smaller across than the threshold are lifted over, never offset.)
    let threshold = options.obstacle_threshold_m();
    let obstacles: Vec<&geo::Polygon> = field
        .obstacles
        .iter()
        .map(|o| &o.polygon)
        .filter(|p| {
            p.bounding_rect()
                .is_some_and(|r| r.width().planar_hypot(r.height()) >= threshold)
        })
        .collect();
    let most_passes = options
        .edge_passes
        .iter()
        .map(|e| e.passes)
        .fold(options.headland_pass_count(), u32::max);
    check_offsets(
        &field.boundary,
        &obstacles,
        width,
        most_passes,
        options.turn_radius,
    )
    .map_err(|e| e.at_feature(field.feature))?;
    Ok(warnings)
}

/// How the direction of an area is searched, for the field and for the areas that get a
/// direction of their own.
fn area_search<'a>(options: &PlanOptions, objective: &'a dyn Objective) -> AreaSearch<'a> {
    AreaSearch {
        method: options.search,
        step_deg: options.search_step_deg,
        width: options.width,
        min_length: options.min_swath_length_m(),
        machine: options.machine(),
        objective,
    }
}

/// How the field's direction is chosen: as the options say, except that a search too large to
/// be quick follows the longest edge instead, with a warning.
fn direction_mode(
    field: &Field,
    options: &PlanOptions,
    warnings: &mut Vec<Warning>,
) -> Result<DirectionMode, PlanError> {
    let width = options.width;
    let mode = options.direction_mode()?;
    if mode != DirectionMode::Search {
        return Ok(mode);
    }
    // Each evaluation sweeps every swath line over every vertex: beyond a budget the search
    // would keep the user waiting for seconds, so the swaths follow the longest edge instead.
    let lines = field
        .boundary
        .bounding_rect()
        .map_or(0.0, |r| r.width().planar_hypot(r.height()))
        / width;
    let vertices = search_vertices(field, options.obstacle_threshold_m()) as f64;
    let evaluations = match options.search {
        SearchMethod::BruteForce => 180.0 / options.search_step_deg + 8.0,
        SearchMethod::CoarseToFine => 40.0,
    };
    if (lines + vertices) * evaluations <= SEARCH_BUDGET_LINES {
        return Ok(mode);
    }
    warnings.push(Warning::new(
        WarningCode::DirectionNotSearched,
        format!(
            "at {} m the field has up to {} swath lines over outlines of {} vertices, too many to search {} directions quickly; the swaths run along the longest edge",
            Shortest(width),
            Decimals(lines, 0),
            Decimals(vertices, 0),
            Decimals(evaluations, 0)
        ),
    ));
    Ok(DirectionMode::LongestEdge)
}

/// The field's driving direction and how it was found.
struct Direction {
    mode: DirectionMode,
    /// Radians.
    bearing: f64,
    /// Where the swath lines lie across the direction.
    placement: LinePlacement,
    /// Directions the search evaluated (none unless it searched).
    evaluations: usize,
    /// The cost of the direction the search found, when it searched.
    search_cost: Option<f64>,
}

/// Chooses the field's driving direction by `mode`: the bearing given, along the longest edge,
/// along the reference line or edge, or the direction of least cost by `search`.
fn choose_direction(
    field: &Field,
    options: &PlanOptions,
    mode: DirectionMode,
    search: &AreaSearch,
) -> Result<Direction, PlanError> {
    let width = options.width;
    let forbidden = &options.forbidden_bearings_deg;
    let along = |bearing| Direction {
        mode,
        bearing,
        placement: LinePlacement::FromEdge,
        evaluations: 0,
        search_cost: None,
    };
    match mode {
        DirectionMode::Fixed => Ok(along(choose_bearing(
            field,
            DirectionRule::Fixed {
                bearing_deg: options.bearing_deg.unwrap_or(0.0),
            },
            forbidden,
        )?)),
        DirectionMode::LongestEdge => Ok(along(choose_bearing(
            field,
            DirectionRule::LongestEdge {
                tolerance_m: width / 2.0,
            },
            forbidden,
        )?)),
        DirectionMode::Reference => {
            let line = options
                .reference_line
                .map(|[a, b]| [field.frame.to_local(a), field.frame.to_local(b)]);
            let (bearing, placement) = reference_direction(
                line,
                options.reference_edge,
                &field.drawn_boundary,
                options.reference_offset,
                width,
                forbidden,
            )?;
            Ok(Direction {
                placement,
                ..along(bearing)
            })
        }
        DirectionMode::Search => {
            let area = search_region(
                field,
                options.obstacle_threshold_m(),
                options.headland_pass_count() as f64 * width,
                width,
            );
            let seeds = edge_directions(std::iter::once(field.boundary.exterior()), width / 2.0);
            let best = search_field(&area, &field.prohibited, forbidden, &seeds, search)?;
            Ok(Direction {
                evaluations: best.evaluations,
                search_cost: Some(best.cost),
                ..along(best.bearing)
            })
        }
    }
}

/// The obstacle classes and the headland passes at the field's direction: along each edge of
/// the field (all around, or only where the swaths end), round each obstacle that gets a
/// headland, and the inner field they leave (none `to_middle`); and whether the field's
/// headland runs all around.
fn lay_headlands(
    field: &Field,
    options: &PlanOptions,
    bearing: f64,
    to_middle: bool,
) -> Result<(ObstacleClasses, Headlands, bool), PlanError> {
    let width = options.width;
    let edge_passes = passes_per_edge(
        &field.boundary,
        &field.drawn_boundary,
        &EdgeRule {
            mode: options.headland_mode,
            passes: options.headland_pass_count(),
            bearing,
            tolerance: options.headland_tolerance_deg.to_radians(),
        },
        &options.edge_passes,
    )?;
    let obstacles = classify(
        field,
        &ClassSettings {
            bearing,
            width,
            threshold: options.obstacle_threshold_m(),
            obstacle_passes: options.headland_pass_count(),
            edge_passes: &edge_passes,
        },
    );
    let headlands = build(
        &field.boundary,
        &obstacles.hole_polygons(),
        &HeadlandSettings {
            width,
            turn_radius: options.turn_radius,
            exact: options.vehicle().exact_passes(),
            obstacle_passes: options.headland_pass_count(),
            edge_passes: &edge_passes,
            to_middle,
        },
    )
    .map_err(|e| e.at_feature(field.feature))?;
    let all_around = edge_passes
        .iter()
        .all(|&p| p >= options.headland_pass_count());
    Ok((obstacles, headlands, all_around))
}

/// Where turns must stay: the field less its obstacles, the same for every candidate.
fn driving_area(field: &Field) -> DrivingArea {
    let obstacles: Vec<&geo::Polygon> = field.obstacles.iter().map(|o| &o.polygon).collect();
    DrivingArea::new(&field.boundary, &obstacles)
}

/// What every decomposition tried is worked from: the field and the options, and what the
/// stages before the decomposition found.
struct Prepared {
    field: Field,
    /// The options with what the field gives (its entrance, its reference line).
    options: PlanOptions,
    obstacles: ObstacleClasses,
    objective: Box<dyn Objective>,
    direction: Direction,
    headlands: Headlands,
    /// The headland graph of the passes in `headlands`.
    graph: HeadlandGraph,
    /// The swaths at the field's direction, when a single-direction decomposition is planned.
    single: Option<SingleDirection>,
    /// Where turns must stay (the field less its obstacles): the same for every candidate.
    area: DrivingArea,
    /// What was repaired in the input and what the stages so far found.
    warnings: Vec<Warning>,
    /// The decompositions to try, within their limits.
    methods: Vec<Decomposition>,
    /// Why split and merge was not tried, where it was left out.
    left_out: Option<String>,
    /// The stages' times so far.
    times: StageTimes,
}

/// The plan of the chosen candidate: its summary with the decomposition report and the pattern
/// asked for, its warnings after those of the stages before it.
fn assemble(
    prepared: Prepared,
    chosen: Worked,
    decomposition: DecompositionReport,
    mut warnings: Vec<Warning>,
) -> Plan {
    let Prepared {
        field,
        options,
        obstacles,
        ..
    } = prepared;
    let Worked {
        headlands,
        swaths,
        blocks,
        route,
        path,
        mut summary,
        warnings: own_warnings,
        ..
    } = chosen;
    summary.decomposition = decomposition;
    summary.route.pattern = options.pattern;
    // The passes laid: as many as asked, or as many as found room.
    let laid = headlands.passes.iter().map(|p| p.index).max().unwrap_or(0);
    summary.headland_passes = options.headland_pass_count().min(laid as u32);
    warnings.extend(own_warnings);
    Plan {
        field,
        options,
        obstacles,
        headlands,
        swaths,
        blocks,
        route,
        path,
        summary,
        warnings,
    }
}

/// How deep a headland the turns between swaths must keep to, metres: the passes' depth for a
/// machine that reverses (its three-point turns fit a pass or two where the ends are level or
/// staggered along an oblique edge, U-turns between swaths further apart often do not).
/// Infinite for a machine that only drives forward: its loops fit few such headlands, and
/// weighing the turns that do not fit chose other patterns with as many turns over crop (121
/// of the drill's 135 register parcel plans either way); and for a field without passes.
fn headland_for_turns(options: &PlanOptions) -> f64 {
    match options.headland_pass_count() {
        n if options.reverse && n > 0 => f64::from(n) * options.width,
        _ => f64::INFINITY,
    }
}

/// The route stage's settings for these options: the patterns to choose from, the headland
/// order, the machine, and the entrance and exit in the field's local metres. The crop is for
/// the caller to give: a plan gives its inner field (`RouteSettings { crop:
/// Some(plan.headlands.inner.clone()), ..route_settings(..) }` routes as the plan did).
pub fn route_settings(options: &PlanOptions, field: &Field) -> RouteSettings {
    let custom: Vec<usize> = options.custom_order.iter().map(|&p| p as usize).collect();
    RouteSettings {
        orders: candidates(
            options.pattern,
            options.snake_skip as usize,
            options.spiral_size as usize,
            &custom,
            options.width,
            options.turn_radius,
        ),
        headland_order: options.headland_order,
        width: options.width,
        turn_radius: options.turn_radius,
        reverse: options.reverse,
        headland_m: headland_for_turns(options),
        entrance: options.entrance.map(|p| field.frame.to_local(p)),
        exit: options.exit.map(|p| field.frame.to_local(p)),
        seed: ROUTE_SEED,
        crop: None,
    }
}
