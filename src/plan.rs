//! The planner: field → direction → obstacle classes and headlands → swaths → blocks → route →
//! path → metrics. The direction comes first because obstacle classes and headlands that run
//! only where swaths end depend on it.
//!
//! Each stage is a module of its own with its own types; this module runs them in order and
//! keeps their results together in a [`Plan`].

use crate::decompose::block_headlands::cut_block_headlands;
use crate::decompose::boustrophedon::{self, cluster_into_cells};
use crate::decompose::cells::MergeRule;
use crate::decompose::split_merge::{
    cells_at, improve, split_merge, within_limits, Criterion, SplitMerge, SplitMergeSettings,
};
use crate::decompose::{cluster_swaths, BlockArea, Blocks, Decomposition};
use crate::direction::{
    choose_bearing, edge_directions, reference_direction, search_area, search_field, search_region,
    search_vertices, AreaSearch, DirectionMode, DirectionRule, SearchMethod,
};
use crate::error::{ErrorCode, PlanError, Warning, WarningCode};
use crate::field::projection::OutputAlong;
use crate::field::{Field, ProhibitedRegion};
use crate::geometry::forbids_every_direction;
use crate::geometry::PlanarHypot;
use crate::geometry::SweepFrame;
use crate::headland::complexity::check_offsets;
use crate::headland::edges::{passes_per_edge, EdgeRule};
use crate::headland::{build, HeadlandSettings, Headlands};
use crate::metrics::{
    summarise, DecompositionCandidate, DecompositionReport, DirectionFigures, DirectionReport,
    StageTimes, Summary,
};
use crate::objective::{measure_all, Machine, Objective, ObjectiveValues};
use crate::obstacles::{classify, ClassSettings, ObstacleClass, ObstacleClasses};
use crate::options::PlanOptions;
use crate::output::budget::{coarsened, sample_spacing};
use crate::path::sample::{sample, Samples};
use crate::path::turn::Area as DrivingArea;
use crate::path::{build_path, Path};
use crate::prohibited::{forbidding, split};
use crate::route::headland_graph::HeadlandGraph;
use crate::route::{pattern::candidates, plan_route, plan_route_on, Route, RouteSettings};
use crate::swath::{generate_with, lifts, LinePlacement, Swath, SwathArea, SwathSettings, Swaths};
use geo::{Area, BooleanOps, BoundingRect, Centroid};
use web_time::Instant;

/// Most swath lines and outline vertices times directions a direction search may sweep (about a
/// third of a second natively): each direction lays every line and sorts the outlines' crossings
/// (1,000 ponds of 96 vertices each took 7 s over 40 directions). Beyond it the direction follows
/// the longest edge.
pub const SEARCH_BUDGET_LINES: f64 = 250_000.0;

/// The decompositions' split tolerance, in working widths: boundary vertices within half a
/// width of a straight line draw no slab line.
const DECOMPOSITION_TOLERANCE: f64 = 0.5;

/// Split and merge joins trapezoids whose ends are at least this steep to the direction
/// (Oksanen & Visala 2.4).
const MIN_END_ANGLE_DEG: f64 = 20.0;

/// Where split and merge starts: Oksanen & Visala's greedy selection, and the boustrophedon
/// cells of the field's direction; each is improved, and the faster kept. (The greedy selection
/// with blocks counting as substantial from half or a quarter of the area left, see
/// [`Criterion::substantial_share`], won on 2 of the 21 corpus fields, by under 2 %, at the
/// cost of a greedy run each.)
const SPLIT_MERGE_SEEDS: [Seed; 3] = [Seed::Greedy(1.0), Seed::Cells, Seed::OksanenCells];

/// Where a split-and-merge decomposition starts.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Seed {
    /// Oksanen & Visala's greedy selection, with this substantial share.
    Greedy(f64),
    /// The boustrophedon cells of the field's direction.
    Cells,
    /// The cells of the field's direction merged by Oksanen & Visala's rule (ends at least 20
    /// degrees to the direction), so that bays with oblique sides are cells of their own.
    OksanenCells,
}

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
/// let options = PlanOptions { width: 6.0, headland_passes: 2, bearing_deg: Some(0.0), ..Default::default() };
/// let plan = plan(field, &options)?;
/// // About 333 m east-west, less two 12 m headlands, in 6 m swaths running north.
/// assert_eq!(plan.summary.swath_count, 52);
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
pub(crate) fn plan_stages(
    mut field: Field,
    options: &PlanOptions,
    mut warnings: Vec<Warning>,
) -> Result<Plan, PlanError> {
    let mut times = StageTimes::default();
    let mut clock = Instant::now();
    options.validate()?;
    options.check_places(&field)?;
    let with_field = options.with_field(&field);
    let options = with_field.as_ref().unwrap_or(options);
    let width = options.width;
    warnings.extend(field.simplify(width));
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
        .fold(options.headland_passes, u32::max);
    check_offsets(
        &field.boundary,
        &obstacles,
        width,
        most_passes,
        options.turn_radius,
    )
    .map_err(|e| e.at_feature(field.feature))?;
    times.lap(&mut clock, |t| &mut t.validation);
    let forbidden = &options.forbidden_bearings_deg;
    let objective = options.objective.objective();
    let search = AreaSearch {
        method: options.search,
        step_deg: options.search_step_deg,
        width,
        min_length: options.min_swath_length_m(),
        machine: options.machine(),
        objective: objective.as_ref(),
    };
    let mut mode = options.direction_mode()?;
    if mode == DirectionMode::Search {
        // Each evaluation sweeps every swath line over every vertex: beyond a budget the search
        // would keep the user waiting for seconds, so the swaths follow the longest edge instead.
        let lines = field
            .boundary
            .bounding_rect()
            .map_or(0.0, |r| r.width().planar_hypot(r.height()))
            / width;
        let vertices = search_vertices(&field, options.obstacle_threshold_m()) as f64;
        let evaluations = match options.search {
            SearchMethod::BruteForce => 180.0 / options.search_step_deg + 8.0,
            SearchMethod::CoarseToFine => 40.0,
        };
        if (lines + vertices) * evaluations > SEARCH_BUDGET_LINES {
            mode = DirectionMode::LongestEdge;
            warnings.push(Warning::new(
                WarningCode::DirectionNotSearched,
                format!(
                    "at {width} m the field has up to {lines:.0} swath lines over outlines of {vertices:.0} vertices, too many to search {evaluations:.0} directions quickly; the swaths run along the longest edge"
                ),
            ));
        }
    }
    let mut evaluations = 0;
    let mut search_cost = None;
    let mut placement = LinePlacement::FromEdge;
    let bearing = match mode {
        DirectionMode::Fixed => choose_bearing(
            &field,
            DirectionRule::Fixed {
                bearing_deg: options.bearing_deg.unwrap_or(0.0),
            },
            forbidden,
        )?,
        DirectionMode::LongestEdge => choose_bearing(
            &field,
            DirectionRule::LongestEdge {
                tolerance_m: width / 2.0,
            },
            forbidden,
        )?,
        DirectionMode::Reference => {
            let line = options
                .reference_line
                .map(|[a, b]| [field.frame.to_local(a), field.frame.to_local(b)]);
            let (b, p) = reference_direction(
                line,
                options.reference_edge,
                &field.drawn_boundary,
                options.reference_offset,
                width,
                forbidden,
            )?;
            placement = p;
            b
        }
        DirectionMode::Search => {
            let area = search_region(
                &field,
                options.obstacle_threshold_m(),
                options.headland_passes as f64 * width,
                width,
            );
            let seeds = edge_directions(std::iter::once(field.boundary.exterior()), width / 2.0);
            let best = search_field(&area, &field.prohibited, forbidden, &seeds, &search)?;
            evaluations += best.evaluations;
            search_cost = Some(best.cost);
            best.bearing
        }
    };
    times.lap(&mut clock, |t| &mut t.direction);
    let edge_passes = passes_per_edge(
        &field.boundary,
        &field.drawn_boundary,
        &EdgeRule {
            mode: options.headland_mode,
            passes: options.headland_passes,
            bearing,
            tolerance: options.headland_tolerance_deg.to_radians(),
        },
        &options.edge_passes,
    )?;
    let obstacles = classify(
        &field,
        &ClassSettings {
            bearing,
            width,
            threshold: options.obstacle_threshold_m(),
            obstacle_passes: options.headland_passes,
            edge_passes: &edge_passes,
        },
    );
    let headlands = build(
        &field.boundary,
        &obstacles.hole_polygons(),
        &HeadlandSettings {
            width,
            turn_radius: options.turn_radius,
            obstacle_passes: options.headland_passes,
            edge_passes: &edge_passes,
        },
    )
    .map_err(|e| e.at_feature(field.feature))?;
    // Split and merge gives blocks their own directions, so their swaths may end on any edge:
    // it needs the field headland all around. (Only where needed, the headland follows the
    // field's one direction.)
    let all_around = edge_passes.iter().all(|&p| p >= options.headland_passes);
    if options.decomposition == Decomposition::SplitMerge && !all_around {
        return Err(PlanError::new(
            ErrorCode::InvalidOption,
            "option `decomposition` is `split-merge`, whose blocks each have their own direction and may end on any edge; it needs the headland all around the field (`headlandMode: constant`, no `edgePasses` with fewer passes)",
        ));
    }
    times.lap(&mut clock, |t| &mut t.headlands);
    let methods: Vec<Decomposition> = match options.decomposition {
        Decomposition::Auto if mode == DirectionMode::Search && all_around => vec![
            Decomposition::None,
            Decomposition::Boustrophedon,
            Decomposition::SplitMerge,
        ],
        Decomposition::Auto => vec![Decomposition::None, Decomposition::Boustrophedon],
        m => vec![m],
    };
    let single = if methods.iter().any(|&m| m != Decomposition::SplitMerge) {
        Some(single_direction(
            &field,
            options,
            &headlands.inner,
            bearing,
            placement,
            &search,
        )?)
    } else {
        None
    };
    times.lap(&mut clock, |t| &mut t.decomposition);
    // The ways along the headland, for every candidate that adds no passes of its own.
    let graph = HeadlandGraph::new(&headlands.passes, width).with_crop(&headlands.inner);
    times.lap(&mut clock, |t| &mut t.route);
    let prepared = Prepared {
        mode,
        bearing,
        evaluations,
        search_cost,
        objective: objective.as_ref(),
        headlands,
        graph,
        single,
        area: {
            let obstacles: Vec<&geo::Polygon> =
                field.obstacles.iter().map(|o| &o.polygon).collect();
            DrivingArea::new(&field.boundary, &obstacles)
        },
    };
    times.lap(&mut clock, |t| &mut t.path);
    // Split and merge's work grows with the cells and vertices of the inner field: beyond its
    // limits auto leaves it out, and asking for it is refused.
    let mut left_out = None;
    let methods: Vec<Decomposition> = if methods.contains(&Decomposition::SplitMerge) {
        let tolerance = width * DECOMPOSITION_TOLERANCE;
        match within_limits(&prepared.headlands.inner, bearing, tolerance) {
            Ok(()) => methods,
            Err(why) if options.decomposition == Decomposition::Auto => {
                left_out = Some(why);
                methods
                    .into_iter()
                    .filter(|&m| m != Decomposition::SplitMerge)
                    .collect()
            }
            Err(why) => {
                return Err(PlanError::new(
                    ErrorCode::FieldTooComplex,
                    format!("the field is too complex for split and merge at {width} m: {why}; use decomposition boustrophedon or none, or a wider working width"),
                ))
            }
        }
    } else {
        methods
    };
    let mut candidates: Vec<Worked> = Vec::with_capacity(methods.len());
    for &m in &methods {
        if m == Decomposition::SplitMerge {
            // The greedy selection cannot see what a block leaves behind: start it several
            // ways and keep the plan of lowest estimated time. A start (or a result) equal to
            // an earlier seed's would plan the same again: it is skipped.
            let mut best: Option<Worked> = None;
            let mut evaluations = 0;
            let mut starts: Vec<Vec<BlockSignature>> = Vec::new();
            let mut results: Vec<Vec<BlockSignature>> = Vec::new();
            for seed in SPLIT_MERGE_SEEDS {
                let mut clock = Instant::now();
                let sm = decompose_seed(&field, options, &prepared, seed, &mut starts)?;
                times.lap(&mut clock, |t| &mut t.decomposition);
                let Some(sm) = sm else { continue };
                evaluations += sm.evaluations;
                let result = signatures(&sm.blocks);
                if results.iter().any(|r| same_blocks(r, &result)) {
                    continue;
                }
                results.push(result);
                let w = work(
                    &field,
                    options,
                    &obstacles,
                    &prepared,
                    m,
                    Some(sm),
                    None,
                    &mut times,
                )?;
                if best
                    .as_ref()
                    .is_none_or(|b| w.compared_time() < b.compared_time())
                {
                    best = Some(w);
                }
            }
            if let Some(mut b) = best {
                b.decomposition_evaluations = evaluations;
                candidates.push(b);
            }
        } else {
            // Boustrophedon cells often cluster the swaths into the blocks of `none`, in the
            // same order, only numbered cell by cell: its route and path are then those of
            // `none`.
            let same_as = candidates.iter().find(|c| c.method == Decomposition::None);
            candidates.push(work(
                &field, options, &obstacles, &prepared, m, None, same_as, &mut times,
            )?);
        }
    }
    let mut clock = Instant::now();
    let mut best = 0;
    for (i, c) in candidates.iter().enumerate() {
        // Near-ties go to the simpler decomposition (the candidates come simplest first).
        let b = candidates[best].compared_time();
        if c.compared_time() < b - (b * 1e-3).max(1.0) {
            best = i;
        }
    }
    let figures: Vec<DecompositionCandidate> = candidates.iter().map(Worked::figures).collect();
    let shared = candidates[best]
        .shares_path
        .then(|| {
            let none = candidates
                .iter()
                .position(|c| c.method == Decomposition::None)?;
            Some(std::mem::take(&mut candidates[none].path))
        })
        .flatten();
    let mut chosen = candidates.swap_remove(best);
    if let Some(path) = shared {
        chosen.path = path;
    }
    let mut reason = if figures.len() == 1 {
        format!("{} as asked", chosen.method.as_str())
    } else {
        let times: Vec<String> = figures
            .iter()
            .map(|f| format!("{} {}", f.method.as_str(), minutes(f.estimated_time_s)))
            .collect();
        format!(
            "{} has the lowest estimated operation time ({}; crop left uncovered counted as worked at working speed, a connection straight across the crop as worse than any time; within 0.1 % the simpler wins)",
            chosen.method.as_str(),
            times.join(", ")
        )
    };
    if let Some(why) = left_out {
        reason.push_str(&format!("; split-merge was not tried: {why}"));
    }
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
    summary.decomposition = DecompositionReport {
        requested: options.decomposition,
        method: methods[best],
        reason,
        candidates: figures,
    };
    summary.route.pattern = options.pattern;
    summary.coverage = crate::coverage::of_plan(&field, &swaths, &route, &path, width);
    times.lap(&mut clock, |t| &mut t.metrics);
    summary.stages_ms = times;
    warnings.extend(own_warnings);
    warnings.extend(coarsened(&path, options.sample_spacing));
    Ok(Plan {
        field,
        options: options.clone(),
        obstacles,
        headlands,
        swaths,
        blocks,
        route,
        path,
        summary,
        warnings,
    })
}

/// What the stages before the decomposition found, shared by every decomposition tried.
struct Prepared<'a> {
    mode: DirectionMode,
    bearing: f64,
    evaluations: usize,
    search_cost: Option<f64>,
    objective: &'a dyn Objective,
    headlands: Headlands,
    /// The headland graph of the passes in `headlands`.
    graph: HeadlandGraph,
    /// The swaths at the field's direction, when a single-direction decomposition is planned.
    single: Option<SingleDirection>,
    /// Where turns must stay (the field less its obstacles): the same for every candidate.
    area: DrivingArea,
}

/// A plan from the decomposition on.
struct Worked {
    method: Decomposition,
    headlands: Headlands,
    swaths: Swaths,
    blocks: Blocks,
    route: Route,
    /// The path; empty where it is that of the `none` candidate (`shares_path`), which is taken
    /// from it if this one is chosen (a plan of 100,000 swaths has 200 MB of path).
    path: Path,
    shares_path: bool,
    summary: Summary,
    warnings: Vec<Warning>,
    decomposition_evaluations: usize,
    block_headland_passes: usize,
    machine: Machine,
}

impl Worked {
    /// Inner field area the swaths leave uncovered, square metres.
    fn uncovered_m2(&self) -> f64 {
        (self.summary.inner_field_area_m2 - self.summary.objectives.covered_area_m2).max(0.0)
    }

    /// What decompositions are compared by: the estimated operation time, with the crop the
    /// swaths leave uncovered counted as if worked at working speed (else a plan would look
    /// faster for leaving crop standing).
    fn compared_time(&self) -> f64 {
        let m = &self.machine;
        // A connection straight across the crop damages it: a plan with one loses to any plan
        // without, whatever the time.
        let crossings = self.summary.route.straight_connections as f64;
        self.summary.estimated_time_s
            + self.uncovered_m2() / (m.width * m.working_speed)
            + crossings * CROSSING_PENALTY_S
    }

    fn figures(&self) -> DecompositionCandidate {
        // Each direction once: within a degree (a bearing of 179.6 and one of 0.3 are one).
        let mut bearings_deg: Vec<f64> = Vec::new();
        for b in &self.blocks.blocks {
            let deg = ((b.bearing.to_degrees() * 10.0).round() / 10.0).rem_euclid(180.0);
            let near = |d: &f64| {
                let x = (deg - d).rem_euclid(180.0);
                x.min(180.0 - x) < 1.0
            };
            if !bearings_deg.iter().any(near) {
                bearings_deg.push(deg);
            }
        }
        DecompositionCandidate {
            method: self.method,
            block_count: self.blocks.blocks.len(),
            bearings_deg,
            swath_count: self.summary.swath_count,
            turn_count: self.summary.turn_count,
            block_headland_passes: self.block_headland_passes,
            estimated_time_s: self.summary.estimated_time_s,
            uncovered_area_m2: self.uncovered_m2(),
            evaluations: self.decomposition_evaluations,
        }
    }
}

/// "12 min" or "1 h 05 min".
fn minutes(seconds: f64) -> String {
    let m = (seconds / 60.0).round() as i64;
    if m >= 60 {
        format!("{} h {:02} min", m / 60, m % 60)
    } else {
        format!("{m} min")
    }
}

/// The swaths at the field's one direction before any decomposition, shared by `none` and
/// `boustrophedon`: those of the inner field less the prohibited regions that forbid the
/// direction (`main`, of `main_area`), and those of each such region at its own best direction.
struct SingleDirection {
    main_area: geo::MultiPolygon,
    main: Swaths,
    regions: Vec<Swaths>,
    warnings: Vec<Warning>,
    evaluations: usize,
}

/// Lays the swaths of the inner field at `bearing` (see [`SingleDirection`]).
fn single_direction(
    field: &Field,
    options: &PlanOptions,
    inner: &geo::MultiPolygon,
    bearing: f64,
    placement: LinePlacement,
    search: &AreaSearch,
) -> Result<SingleDirection, PlanError> {
    // Prohibited regions that forbid the direction are cut out and worked in their own.
    let cut = forbidding(&field.prohibited, bearing);
    let (main_area, parts) = if cut.is_empty() {
        (inner.clone(), Vec::new())
    } else {
        split(
            inner,
            &field.prohibited,
            &cut,
            &options.forbidden_bearings_deg,
        )
    };
    let main = generate_with(
        &main_area,
        &SwathSettings {
            bearing,
            width: options.width,
            min_length: options.min_swath_length_m(),
            placement,
        },
    )?;
    let mut out = SingleDirection {
        main_area,
        main,
        regions: Vec::new(),
        warnings: Vec::new(),
        evaluations: 0,
    };
    for part in parts {
        let region = &field.prohibited[part.region];
        if forbids_every_direction(&part.forbidden) {
            out.warnings.push(region_not_worked(region));
            continue;
        }
        let best = search_area(&part.area, &part.forbidden, search)?;
        out.evaluations += best.evaluations;
        out.regions.push(area_swaths(
            part.area,
            best.bearing,
            Some(part.region),
            options,
        )?);
        out.warnings.push(
            Warning::new(
                WarningCode::RegionOwnDirection,
                format!(
                    "{} forbids the field's direction of {:.1} degrees; it is worked at {:.1} degrees",
                    region.subject(),
                    bearing.to_degrees(),
                    best.bearing.to_degrees()
                ),
            )
            .at_feature(region.feature),
        );
    }
    Ok(out)
}

/// The warning for a prohibited region whose ranges, with the others that hold in it, leave no
/// direction.
fn region_not_worked(region: &ProhibitedRegion) -> Warning {
    Warning::new(
        WarningCode::RegionNotWorked,
        format!(
            "{} and the other forbidden ranges that hold in it leave no driving direction; it gets no swaths",
            region.subject()
        ),
    )
    .at_feature(region.feature)
}

/// The swaths of an area worked at a direction of its own (a block, or a prohibited region),
/// the first line half a width inside it, as one area.
fn area_swaths(
    area: geo::MultiPolygon,
    bearing: f64,
    region: Option<usize>,
    options: &PlanOptions,
) -> Result<Swaths, PlanError> {
    let mut own = generate_with(
        &area,
        &SwathSettings {
            bearing,
            width: options.width,
            min_length: options.min_swath_length_m(),
            placement: LinePlacement::FromEdge,
        },
    )?;
    own.areas.push(SwathArea {
        swaths: 0..own.swaths.len(),
        bearing,
        region,
        area,
    });
    Ok(own)
}

/// An empty set of swaths at a direction.
fn no_swaths(bearing: f64, width: f64) -> Swaths {
    Swaths {
        bearing,
        width,
        frame: SweepFrame::new(bearing),
        swaths: Vec::new(),
        dropped: 0,
        lifts: Vec::new(),
        areas: Vec::new(),
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
        entrance: options.entrance.map(|p| field.frame.to_local(p)),
        exit: options.exit.map(|p| field.frame.to_local(p)),
        seed: ROUTE_SEED,
        crop: None,
    }
}

/// The warning for the turns that leave the field, with their cause: how far beyond the swath
/// ends the cheapest of them reaches against the depth of the headland.
fn turns_leaving(path: &Path, options: &PlanOptions) -> Option<Warning> {
    let outside: Vec<&crate::path::TurnReport> = path
        .segments
        .iter()
        .filter_map(|s| s.turn.as_ref())
        .filter(|t| !t.inside)
        .collect();
    if outside.is_empty() {
        return None;
    }
    let reach = outside.iter().map(|t| t.reach_m).fold(0.0, f64::max);
    let depth = options.headland_passes as f64 * options.width;
    let hint = if options.reverse {
        ""
    } else {
        "; allowing the machine to reverse (three-point turns) would need about one turning radius"
    };
    Some(Warning::new(
        WarningCode::TurnLeavesField,
        format!(
            "{} leave the field or cross an obstacle: no turn the machine can drive fits there (they reach up to {reach:.1} m beyond the swath ends, against a headland {depth:.1} m deep at most){hint}",
            if outside.len() == 1 {
                "1 turn".to_string()
            } else {
                format!("{} turns", outside.len())
            }
        ),
    ))
}

/// What a connection straight across the crop adds to a candidate's time when decompositions
/// are compared, seconds: more than any field takes to work.
const CROSSING_PENALTY_S: f64 = 1e7;

/// Seed of the block sequence's ant colony: the same field and options give the same route.
const ROUTE_SEED: u64 = 0x5eed_f077;

/// The split-and-merge decomposition of the inner field from `seed`; `None` when the seed's
/// cells are those of a seed in `starts` (improving them again would give the same blocks).
/// Cells seeds add their cells' signatures to `starts`.
fn decompose_seed(
    field: &Field,
    options: &PlanOptions,
    prep: &Prepared,
    seed: Seed,
    starts: &mut Vec<Vec<BlockSignature>>,
) -> Result<Option<SplitMerge>, PlanError> {
    let orders = route_settings(options, field).orders;
    let settings = SplitMergeSettings {
        width: options.width,
        min_length: options.min_swath_length_m(),
        machine: options.machine(),
        method: options.search,
        step_deg: options.search_step_deg,
        forbidden: &options.forbidden_bearings_deg,
        regions: &field.prohibited,
        criterion: Criterion::default(),
        min_end_angle: MIN_END_ANGLE_DEG.to_radians(),
        tolerance: options.width * DECOMPOSITION_TOLERANCE,
        orders: &orders,
    };
    let inner = &prep.headlands.inner;
    let rule = match seed {
        Seed::Greedy(substantial_share) => {
            let criterion = Criterion {
                substantial_share,
                ..Criterion::default()
            };
            return split_merge(
                inner,
                &SplitMergeSettings {
                    criterion,
                    ..settings
                },
            )
            .map(Some);
        }
        Seed::Cells => MergeRule::Boustrophedon,
        Seed::OksanenCells => MergeRule::SplitMerge {
            min_end_angle: settings.min_end_angle,
        },
    };
    let (blocks, not_worked) = cells_at(inner, prep.bearing, rule, &settings);
    let start = signatures(&blocks);
    if starts.iter().any(|s| same_blocks(s, &start)) {
        return Ok(None);
    }
    starts.push(start);
    let (blocks, evaluations) = improve(blocks, &settings)?;
    Ok(Some(SplitMerge {
        blocks,
        evaluations,
        not_worked,
    }))
}

/// What tells blocks apart when seeds are compared: direction, area and centroid. Two
/// decompositions whose blocks agree in these (to rounding) are the same decomposition, with
/// their rings perhaps starting at other corners.
#[derive(Debug, Clone, Copy)]
struct BlockSignature {
    bearing: f64,
    area_m2: f64,
    centroid: geo::Coord,
}

fn signatures(blocks: &[BlockArea]) -> Vec<BlockSignature> {
    blocks
        .iter()
        .map(|b| BlockSignature {
            bearing: b.bearing,
            area_m2: b.area.unsigned_area(),
            centroid: b.area.centroid().map_or(geo::Coord::zero(), |p| p.0),
        })
        .collect()
}

/// Whether two decompositions have the same blocks, in any order: bearings within a
/// microradian, areas within a millionth, centroids within a tenth of a millimetre.
fn same_blocks(a: &[BlockSignature], b: &[BlockSignature]) -> bool {
    if a.len() != b.len() {
        return false;
    }
    let same = |x: &BlockSignature, y: &BlockSignature| {
        let turn = (x.bearing - y.bearing).rem_euclid(std::f64::consts::PI);
        turn.min(std::f64::consts::PI - turn) < 1e-6
            && (x.area_m2 - y.area_m2).abs() <= 1e-6 * x.area_m2.max(1.0)
            && (x.centroid.x - y.centroid.x).planar_hypot(x.centroid.y - y.centroid.y) < 1e-4
    };
    let mut taken = vec![false; b.len()];
    a.iter().all(|x| {
        let found = (0..b.len()).find(|&k| !taken[k] && same(x, &b[k]));
        found.inspect(|&k| taken[k] = true).is_some()
    })
}

/// Where the blocks of `b` are those of `a` in the same order, of the same swaths in the same
/// order (numbered otherwise), the index in `b` of each swath of `a` that a block holds.
fn renumbering(
    a: &Swaths,
    a_blocks: &Blocks,
    b: &Swaths,
    b_blocks: &Blocks,
) -> Option<Vec<Option<usize>>> {
    if a_blocks.blocks.len() != b_blocks.blocks.len() || a.swaths.len() != b.swaths.len() {
        return None;
    }
    let mut new_index = vec![None; a.swaths.len()];
    for (x, y) in a_blocks.blocks.iter().zip(&b_blocks.blocks) {
        if x.bearing != y.bearing || x.swaths.len() != y.swaths.len() {
            return None;
        }
        for (&i, &j) in x.swaths.iter().zip(&y.swaths) {
            let (s, t) = (a.swaths.get(i)?, b.swaths.get(j)?);
            if (Swath { index: j, ..*s }) != *t {
                return None;
            }
            *new_index.get_mut(i)? = Some(j);
        }
    }
    Some(new_index)
}

/// Decomposes the inner field, lays the swaths, and routes, paths and measures the plan. Where
/// the blocks are those of `same_as` (a candidate worked before) with their swaths numbered
/// otherwise, its route (renumbered) and path are taken: they depend on nothing else.
#[allow(clippy::too_many_arguments)]
fn work(
    field: &Field,
    options: &PlanOptions,
    obstacles: &ObstacleClasses,
    prep: &Prepared,
    method: Decomposition,
    split: Option<SplitMerge>,
    same_as: Option<&Worked>,
    times: &mut StageTimes,
) -> Result<Worked, PlanError> {
    let mut clock = Instant::now();
    let width = options.width;
    let forbidden = &options.forbidden_bearings_deg;
    let mut headlands = prep.headlands.clone();
    let mut warnings: Vec<Warning> = Vec::new();
    let mut evaluations = prep.evaluations;
    let mut decomposition_evaluations = 0;
    let mut block_headland_passes = 0;
    let mut swaths;
    if let Some(sm) = split {
        decomposition_evaluations = sm.evaluations;
        evaluations += sm.evaluations;
        warnings.extend(
            sm.not_worked
                .iter()
                .filter_map(|&r| field.prohibited.get(r))
                .map(region_not_worked),
        );
        let cut = cut_block_headlands(
            &sm.blocks,
            width,
            options.headland_passes,
            forbidden,
            &field.prohibited,
        );
        if !cut.bands.0.is_empty() {
            block_headland_passes = cut.passes.len();
            headlands.area_m2 += cut.bands.unsigned_area();
            headlands.inner = headlands.inner.difference(&cut.bands);
            headlands.passes.extend(cut.passes);
        }
        swaths = no_swaths(
            cut.blocks.first().map_or(prep.bearing, |b| b.bearing),
            width,
        );
        for b in cut.blocks {
            swaths.append(area_swaths(b.area, b.bearing, None, options)?);
        }
    } else {
        let Some(single) = &prep.single else {
            return Err(PlanError::new(
                ErrorCode::Internal,
                "a single-direction plan without its swaths",
            ));
        };
        swaths = single.main.clone();
        if method == Decomposition::Boustrophedon {
            let tolerance = width * DECOMPOSITION_TOLERANCE;
            let cells = boustrophedon::decompose(&single.main_area, prep.bearing, tolerance);
            cluster_into_cells(&mut swaths, &cells);
        } else {
            swaths.areas.push(SwathArea {
                swaths: 0..swaths.swaths.len(),
                bearing: prep.bearing,
                region: None,
                area: single.main_area.clone(),
            });
        }
        for own in &single.regions {
            swaths.append(own.clone());
        }
        warnings.extend(single.warnings.iter().cloned());
        evaluations += single.evaluations;
    }
    let small: Vec<(usize, &geo::Polygon)> = field
        .obstacles
        .iter()
        .enumerate()
        .filter(|&(i, _)| obstacles.class[i] == ObstacleClass::A)
        .map(|(i, o)| (i, &o.polygon))
        .collect();
    swaths.lifts = lifts(&swaths, &small);
    for &(i, _) in &small {
        warnings.push(
            Warning::new(
                WarningCode::ImplementLifted,
                format!(
                    "{} is less than {:.1} m across the driving direction; swaths run past it with the implement lifted",
                    field.obstacles[i].subject(),
                    options.obstacle_threshold_m()
                ),
            )
            .at_feature(field.obstacles[i].feature),
        );
    }
    if swaths.dropped > 0 {
        warnings.push(Warning::new(
            WarningCode::ShortSwathsDropped,
            format!(
                "{} shorter than {:.1} m left to the headland passes",
                if swaths.dropped == 1 {
                    "1 swath piece".to_string()
                } else {
                    format!("{} swath pieces", swaths.dropped)
                },
                options.min_swath_length_m()
            ),
        ));
    }
    let blocks = cluster_swaths(&swaths);
    times.lap(&mut clock, |t| &mut t.decomposition);
    let earlier = same_as.and_then(|w| {
        if w.headlands.passes != headlands.passes {
            return None;
        }
        let new_index = renumbering(&w.swaths, &w.blocks, &swaths, &blocks)?;
        Some((w.route.with_swaths_renumbered(&new_index)?, &w.path))
    });
    let route = match &earlier {
        Some((route, _)) => route.clone(),
        // The passes (and the inner field) of `prep` alone: their graph is built.
        None if headlands.passes.len() == prep.headlands.passes.len() => plan_route_on(
            &prep.graph,
            &swaths,
            &blocks,
            &headlands.passes,
            &route_settings(options, field),
        ),
        None => plan_route(
            &swaths,
            &blocks,
            &headlands.passes,
            &RouteSettings {
                crop: Some(headlands.inner.clone()),
                ..route_settings(options, field)
            },
        ),
    };
    times.lap(&mut clock, |t| &mut t.route);
    let straight = route.all_connections().filter(|c| c.straight).count();
    if straight > 0 {
        warnings.push(Warning::new(
            WarningCode::StraightConnections,
            format!(
                "{} found no way along the headland and {} straight across the field",
                if straight == 1 {
                    "1 connection".to_string()
                } else {
                    format!("{straight} connections")
                },
                if straight == 1 { "runs" } else { "run" }
            ),
        ));
    }
    let built = match &earlier {
        Some(_) => None,
        None => Some(build_path(
            &route,
            &swaths,
            &headlands.passes,
            &options.vehicle(),
            Some(&prep.area),
        )),
    };
    let path: &Path = match (&built, &earlier) {
        (Some(path), _) => path,
        (None, Some((_, path))) => path,
        (None, None) => {
            return Err(PlanError::new(
                ErrorCode::Internal,
                "a candidate without its path",
            ))
        }
    };
    times.lap(&mut clock, |t| &mut t.path);
    if let Some(w) = turns_leaving(path, options) {
        warnings.push(w);
    }
    let machine = options.machine();
    let stats = measure_all(&swaths, &machine);
    let direction = DirectionReport {
        mode: prep.mode,
        method: (prep.mode == DirectionMode::Search).then_some(options.search),
        objective: prep.objective.name(),
        evaluations,
        cost: prep.objective.cost(&stats, &machine),
        search_cost: prep.search_cost,
    };
    let summary = summarise(
        field,
        obstacles,
        &headlands,
        &swaths,
        &blocks,
        &route,
        path,
        &DirectionFigures {
            direction,
            objectives: ObjectiveValues::of(&stats, &machine),
            machine,
        },
    );
    times.lap(&mut clock, |t| &mut t.metrics);
    let shares_path = built.is_none();
    Ok(Worked {
        method,
        headlands,
        swaths,
        blocks,
        route,
        path: built.unwrap_or_default(),
        shares_path,
        summary,
        warnings,
        decomposition_evaluations,
        block_headland_passes,
        machine,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use geo::MultiPolygon;
    use std::f64::consts::PI;

    fn block(ring: &[(f64, f64)], bearing: f64) -> BlockArea {
        let exterior: Vec<geo::Coord> = ring.iter().map(|&(x, y)| geo::Coord { x, y }).collect();
        BlockArea {
            area: MultiPolygon::new(vec![geo::Polygon::new(exterior.into(), vec![])]),
            bearing,
        }
    }

    #[test]
    fn seeds_with_the_same_blocks_are_the_same_decomposition() {
        let west = [
            (0.0, 0.0),
            (50.0, 0.0),
            (50.0, 80.0),
            (0.0, 80.0),
            (0.0, 0.0),
        ];
        // The same square, its ring starting at another corner.
        let west_again = [
            (50.0, 80.0),
            (0.0, 80.0),
            (0.0, 0.0),
            (50.0, 0.0),
            (50.0, 80.0),
        ];
        let east = [
            (50.0, 0.0),
            (90.0, 0.0),
            (90.0, 80.0),
            (50.0, 80.0),
            (50.0, 0.0),
        ];
        let a = signatures(&[block(&west, 0.3), block(&east, 1.2)]);
        // In the other order, a bearing and its reverse alike.
        let b = signatures(&[block(&east, 1.2), block(&west_again, 0.3 + PI)]);
        assert!(same_blocks(&a, &b));
        // Another direction, another area, or another number of blocks: not the same.
        assert!(!same_blocks(
            &a,
            &signatures(&[block(&west, 0.3), block(&east, 1.25)])
        ));
        let shifted = [
            (50.0, 0.0),
            (91.0, 0.0),
            (91.0, 80.0),
            (50.0, 80.0),
            (50.0, 0.0),
        ];
        assert!(!same_blocks(
            &a,
            &signatures(&[block(&west, 0.3), block(&shifted, 1.2)])
        ));
        assert!(!same_blocks(&a, &signatures(&[block(&west, 0.3)])));
        // Two copies of one block do not match one block and another.
        let twice = signatures(&[block(&west, 0.3), block(&west, 0.3)]);
        assert!(!same_blocks(&a, &twice));
    }

    #[test]
    fn a_route_renumbered_is_the_route_of_the_same_blocks_numbered_otherwise() {
        // On obstacles-4 the boustrophedon cells hold the blocks of `none`, in the same order,
        // their swaths numbered cell by cell.
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/tests/fields/obstacles-4.geojson"
        );
        let text = std::fs::read_to_string(path).expect("the corpus copy");
        let options = PlanOptions {
            width: 12.0,
            headland_passes: 1,
            turn_radius: 6.0,
            decomposition: Decomposition::None,
            ..PlanOptions::default()
        };
        let none = plan_geojson(&text, &options).expect("plans");
        let mut cells = none.swaths.clone();
        let main = &none.swaths.areas[0];
        let tolerance = none.options.width * DECOMPOSITION_TOLERANCE;
        cluster_into_cells(
            &mut cells,
            &boustrophedon::decompose(&main.area, main.bearing, tolerance),
        );
        let cell_blocks = cluster_swaths(&cells);
        let new_index =
            renumbering(&none.swaths, &none.blocks, &cells, &cell_blocks).expect("the same blocks");
        let moved = new_index
            .iter()
            .enumerate()
            .filter(|&(i, j)| *j != Some(i))
            .count();
        assert!(
            moved > 10,
            "the cells number the swaths otherwise ({moved} moved)"
        );
        let fresh = plan_route(
            &cells,
            &cell_blocks,
            &none.headlands.passes,
            &route_settings(&none.options, &none.field),
        );
        assert_eq!(none.route.with_swaths_renumbered(&new_index), Some(fresh));
        // Blocks that differ are not renumbered.
        let mut fewer = cell_blocks.clone();
        fewer.blocks.pop();
        assert!(renumbering(&none.swaths, &none.blocks, &cells, &fewer).is_none());
        let mut other = cell_blocks;
        other.blocks[0].swaths.reverse();
        assert!(renumbering(&none.swaths, &none.blocks, &cells, &other).is_none());
    }
}
