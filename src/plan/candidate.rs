//! A candidate plan: one decomposition worked from the stages before it (the field's direction
//! and headlands) through its swaths, route and path to its metrics.

use super::{route_settings, Prepared, DECOMPOSITION_TOLERANCE};
use crate::coverage::{strip_centres, worked_lines, Coverage, Tally};
use crate::decompose::block_headlands::cut_block_headlands;
use crate::decompose::boustrophedon::{self, cluster_into_cells};
use crate::decompose::split_merge::SplitMerge;
use crate::decompose::{cluster_swaths, Blocks, Decomposition, MAX_BLOCKS};
use crate::direction::{search_area, AreaSearch, DirectionMode};
use crate::error::{ErrorCode, PlanError, Warning, WarningCode};
use crate::field::{Field, ProhibitedRegion};
use crate::fill::along::passes_along;
use crate::fill::{fill, FillSettings, MIN_SLIVER_WIDTHS};
use crate::geometry::BooleanOps;
use crate::geometry::{forbids_every_direction, SweepFrame};
use crate::headland::{HeadlandPass, Headlands, PassAround};
use crate::metrics::{summarise, DirectionFigures, DirectionReport, StageTimes, Summary};
use crate::numbers::{Decimals, Shortest};
use crate::objective::{measure_all, Machine, ObjectiveValues};
use crate::obstacles::ObstacleClass;
use crate::options::PlanOptions;
use crate::path::SegmentKind;
use crate::path::{build_path, Path};
use crate::prohibited::{forbidding, split};
use crate::route::headland_graph::HeadlandGraph;
use crate::route::{headland_graph, plan_route_on, Route, RouteSettings};
use crate::swath::{
    generate_reaching, generate_with, generate_within, lifts, LinePlacement, Reach, Swath,
    SwathArea, SwathSettings, Swaths,
};
use geo::Area;
use web_time::Instant;

/// A plan from the decomposition on.
#[derive(Clone)]
pub(super) struct Worked {
    pub(super) method: Decomposition,
    pub(super) headlands: Headlands,
    pub(super) swaths: Swaths,
    pub(super) blocks: Blocks,
    pub(super) route: Route,
    /// The path; empty where it is that of the `none` candidate (`shares_path`), which is taken
    /// from it if this one is chosen (a plan of 100,000 swaths has 200 MB of path).
    pub(super) path: Path,
    pub(super) shares_path: bool,
    pub(super) summary: Summary,
    pub(super) warnings: Vec<Warning>,
    pub(super) decomposition_evaluations: usize,
    pub(super) block_headland_passes: usize,
    pub(super) machine: Machine,
}

/// Decomposes the inner field, lays the swaths, and routes, paths and measures the plan. Where
/// the blocks are those of `same_as` (a candidate worked before) with their swaths numbered
/// otherwise, its route (renumbered) and path are taken: they depend on nothing else.
pub(super) fn work(
    prep: &Prepared,
    method: Decomposition,
    split: Option<SplitMerge>,
    same_as: Option<&Worked>,
    times: &mut StageTimes,
) -> Result<Worked, PlanError> {
    let mut clock = Instant::now();
    let mut laid = match split {
        Some(sm) => lay_split_merge(prep, sm)?,
        None => lay_single_direction(prep, method)?,
    };
    lift_over_small_obstacles(prep, &mut laid);
    laid.warnings
        .extend(short_pieces_dropped(&laid.swaths, &prep.options));
    let blocks = cluster_swaths(&laid.swaths);
    within_block_limit(&blocks, prep.options.width)?;
    times.lap(&mut clock, |t| &mut t.decomposition);
    let earlier = same_as.and_then(|w| reused(w, &laid, &blocks));
    let mut warnings = std::mem::take(&mut laid.warnings);
    let (route, built, summary) =
        route_and_path(prep, &laid, &blocks, earlier.as_ref(), &mut warnings, times)?;
    laid.warnings = warnings;
    let machine = prep.options.machine();
    let shares_path = built.is_none();
    Ok(Worked {
        method,
        headlands: laid.headlands,
        swaths: laid.swaths,
        blocks,
        route,
        path: built.unwrap_or_default(),
        shares_path,
        summary,
        warnings: laid.warnings,
        decomposition_evaluations: laid.decomposition_evaluations,
        block_headland_passes: laid.block_headland_passes,
        machine,
    })
}

/// Refuses swaths that fall into more than [`MAX_BLOCKS`] blocks: routing and driving between
/// them grows with their number (a noisy 199,000-vertex outline at 0.1 m without headland cuts
/// its swaths into 20,000 pieces, 22 s of planning), and no field worked in one is farmed so.
fn within_block_limit(blocks: &Blocks, width: f64) -> Result<(), PlanError> {
    let n = blocks.blocks.len();
    if n <= MAX_BLOCKS {
        return Ok(());
    }
    Err(PlanError::new(
        ErrorCode::FieldTooComplex,
        format!("the swaths at {} m fall into {n} blocks, more than the planner takes on ({MAX_BLOCKS}): the outline or its obstacles cut them into short pieces; simplify the outlines, or use headland passes or a wider working width", Shortest(width)),
    ))
}

/// Fills what the chosen candidate leaves standing ([`crate::fill`]): the fill's swaths join
/// its swaths as blocks of their own, its passes along what those leave ([`passes_along`]) the
/// headland passes, and the plan is routed, pathed and measured again. Gives the plan with the
/// coverage of its path: the filled plan, or the plan as it was where the filled one works less
/// of the field.
pub(super) fn fill_leftovers(
    prep: &Prepared,
    worked: Worked,
    times: &mut StageTimes,
) -> Result<(Worked, Coverage), PlanError> {
    let mut clock = Instant::now();
    let options = &prep.options;
    let width = options.width;
    let obstacles: Vec<geo::Polygon> = prep
        .field
        .obstacles
        .iter()
        .map(|o| o.polygon.clone())
        .collect();
    // Where strips' centre lines may run: the tally draws the implement's reach from them.
    let centres = strip_centres(&prep.field.boundary, &obstacles, width);
    let Some(mut tally) = Tally::with_centres(&prep.field.boundary, &obstacles, width, &centres)
    else {
        return Ok((worked, Coverage::default()));
    };
    tally.work(&worked_lines(&worked.path));
    let before = tally.coverage();
    // The route reaches a piece along the headland passes and the field's swaths, worked by then.
    let tracks: Vec<geo::LineString> = worked
        .swaths
        .swaths
        .iter()
        .map(|s| geo::LineString::new(vec![s.centre.start, s.centre.end]))
        .collect();
    let graph = HeadlandGraph::with_tracks(&worked.headlands.passes, &tracks, width);
    let settings = FillSettings {
        width,
        bearing: worked.swaths.bearing,
        forbidden: &options.forbidden_bearings_deg,
        regions: &prep.field.prohibited,
        min_length: options.min_swath_length_m(),
        reachable: &|p| graph.reaches(p),
        // Long slivers a width or more from the inner field: the middle of an arm or a strip its
        // passes work round.
        slivers: &|part| {
            geo::Area::unsigned_area(part) >= MIN_SLIVER_WIDTHS * width * width
                && geo::Centroid::centroid(part).is_some_and(|c| {
                    geo::Distance::distance(&geo::Euclidean, &c, &worked.headlands.inner) >= width
                })
        },
    };
    let pieces = if before.uncovered.is_empty() {
        Vec::new()
    } else {
        fill(&before.uncovered, &centres, &settings)
    };
    let fill_lines: Vec<Vec<geo::Coord>> = pieces
        .iter()
        .flat_map(|p| p.swaths.iter().map(|s| vec![s.centre.start, s.centre.end]))
        .collect();
    tally.work(&fill_lines);
    // What the straight pieces leave of narrow arms and bent strips: passes along its outline.
    let along = if pieces.is_empty() && before.uncovered.is_empty() {
        Vec::new()
    } else {
        let left = if pieces.is_empty() {
            before.uncovered.clone()
        } else {
            tally.coverage().uncovered
        };
        // Reached along the straight pieces' tracks too: they are worked before the passes
        // when these come last.
        let with_pieces = (!pieces.is_empty()).then(|| {
            let mut tracks = tracks.clone();
            tracks.extend(fill_lines.iter().map(|l| geo::LineString::new(l.clone())));
            HeadlandGraph::with_tracks(&worked.headlands.passes, &tracks, width)
        });
        let reaches = |p: geo::Coord| with_pieces.as_ref().unwrap_or(&graph).reaches(p);
        let settings = FillSettings {
            reachable: &reaches,
            ..settings
        };
        passes_along(&left, &centres, &settings)
    };
    times.lap(&mut clock, |t| &mut t.metrics);
    if pieces.is_empty() && along.is_empty() {
        return Ok((worked, before));
    }
    // The plan as it was is kept until the filled one is known to work more.
    let (mut headlands, mut swaths) = (worked.headlands.clone(), worked.swaths.clone());
    for p in pieces {
        swaths.append(p);
    }
    headlands
        .passes
        .extend(along.into_iter().map(|p| HeadlandPass {
            index: 1,
            line: p.line,
            closed: p.closed,
            around: PassAround::Fill,
        }));
    let blocks = cluster_swaths(&swaths);
    let laid = Laid {
        headlands,
        swaths,
        warnings: Vec::new(),
        evaluations: worked.summary.direction.evaluations,
        decomposition_evaluations: worked.decomposition_evaluations,
        block_headland_passes: worked.block_headland_passes,
    };
    let mut warnings = worked.warnings.clone();
    warnings.retain(|w| {
        !matches!(
            w.code,
            WarningCode::StraightConnections
                | WarningCode::TurnLeavesField
                | WarningCode::ImplementLiftedAtEdges
                | WarningCode::ConnectionLeavesField
                | WarningCode::ConnectionCrossesCrop
                | WarningCode::TurnCrossesCrop
        )
    });
    let (route, path, summary) = route_and_path(prep, &laid, &blocks, None, &mut warnings, times)?;
    let path = path.unwrap_or_default();
    let mut clock = Instant::now();
    // Counted again along the path as driven now: where the new route enters a headland pass
    // decides where its manoeuvres lift the implement.
    tally.forget();
    tally.work(&worked_lines(&path));
    let after = tally.coverage();
    times.lap(&mut clock, |t| &mut t.metrics);
    // The route round the fill enters the passes elsewhere, and its manoeuvres may lift the
    // implement over more than the fill works: then the plan without it is kept.
    if after.covered_area_m2 < before.covered_area_m2 {
        return Ok((worked, before));
    }
    let filled = Worked {
        method: worked.method,
        headlands: laid.headlands,
        swaths: laid.swaths,
        blocks,
        route,
        path,
        shares_path: false,
        summary,
        warnings,
        decomposition_evaluations: worked.decomposition_evaluations,
        block_headland_passes: worked.block_headland_passes,
        machine: worked.machine,
    };
    Ok((filled, after))
}

/// Routes, paths and measures the swaths laid, taking the route and path of a candidate worked
/// before where `earlier` gives them (the path is then not built: `None`). Warns in `warnings`
/// of straight connections, of turns that leave the field and of connections and turns over
/// crop worked later.
fn route_and_path(
    prep: &Prepared,
    laid: &Laid,
    blocks: &Blocks,
    earlier: Option<&(Route, &Path)>,
    warnings: &mut Vec<Warning>,
    times: &mut StageTimes,
) -> Result<(Route, Option<Path>, Summary), PlanError> {
    let mut clock = Instant::now();
    // The field's headland graph where the candidate adds no passes of its own, else a graph
    // of its passes (with the inner field as the crop its hops keep off).
    let own = (laid.headlands.passes.len() != prep.headlands.passes.len() && earlier.is_none())
        .then(|| {
            let settings = RouteSettings {
                crop: Some(laid.headlands.inner.clone()),
                ..route_settings(&prep.options, &prep.field)
            };
            (headland_graph(&laid.headlands.passes, &settings), settings)
        });
    let field_settings;
    let (graph, settings) = match &own {
        Some((graph, settings)) => (graph, settings),
        None => {
            field_settings = route_settings(&prep.options, &prep.field);
            (&prep.graph, &field_settings)
        }
    };
    let route = match earlier {
        Some((route, _)) => route.clone(),
        None => plan_route_on(
            graph,
            &laid.swaths,
            blocks,
            &laid.headlands.passes,
            settings,
        ),
    };
    times.lap(&mut clock, |t| &mut t.route);
    warnings.extend(straight_connections(&route));
    let built = earlier.is_none().then(|| {
        build_path(
            &route,
            &laid.swaths,
            &laid.headlands.passes,
            &prep.options.vehicle(),
            Some(&prep.area),
            Some(graph),
        )
    });
    let Some(path) = built.as_ref().or(earlier.map(|&(_, path)| path)) else {
        return Err(PlanError::new(
            ErrorCode::Internal,
            "a candidate without its path",
        ));
    };
    times.lap(&mut clock, |t| &mut t.path);
    warnings.extend(turns_leaving(path, &prep.options));
    warnings.extend(lifted_at_edges(path, prep));
    warnings.extend(connections_leaving(path, &prep.options));
    warnings.extend(crop_crossed(path, &prep.options, SegmentKind::Connection));
    warnings.extend(crop_crossed(path, &prep.options, SegmentKind::Turn));
    let summary = measure(prep, laid, blocks, &route, path, prep.options.machine());
    times.lap(&mut clock, |t| &mut t.metrics);
    Ok((route, built, summary))
}

/// A candidate's swaths, the headlands they are laid in, and what laying them found.
struct Laid {
    /// The field's headlands, with passes round the blocks where split and merge adds them.
    headlands: Headlands,
    swaths: Swaths,
    warnings: Vec<Warning>,
    /// Directions evaluated for the plan: the field's and the candidate's own.
    evaluations: usize,
    /// Directions evaluated by the decomposition.
    decomposition_evaluations: usize,
    /// Headland passes laid round the blocks.
    block_headland_passes: usize,
}

/// Split and merge's blocks: their own headland passes where they need them, and the swaths of
/// each at its own direction.
fn lay_split_merge(prep: &Prepared, sm: SplitMerge) -> Result<Laid, PlanError> {
    let (field, options) = (&prep.field, &prep.options);
    let width = options.width;
    let mut headlands = prep.headlands.clone();
    let warnings = sm
        .not_worked
        .iter()
        .filter_map(|&r| field.prohibited.get(r))
        .map(region_not_worked)
        .collect();
    let cut = cut_block_headlands(
        &sm.blocks,
        width,
        options.headland_pass_count(),
        &options.forbidden_bearings_deg,
        &field.prohibited,
    );
    let mut block_headland_passes = 0;
    if !cut.bands.0.is_empty() {
        block_headland_passes = cut.passes.len();
        headlands.area_m2 += cut.bands.unsigned_area();
        headlands.inner = headlands.inner.difference(&cut.bands);
        headlands.passes.extend(cut.passes);
    }
    let mut swaths = no_swaths(
        cut.blocks
            .first()
            .map_or(prep.direction.bearing, |b| b.bearing),
        width,
    );
    // The blocks' swaths end where their centre lines leave the blocks: run on into the
    // headland, they changed which of split and merge's seeds looked fastest, and the plans
    // chosen then left more for the fill (h-shape, 6 m drill: 99.2 → 98.7 % covered, 14 %
    // longer).
    for b in cut.blocks {
        swaths.append(area_swaths(b.area, b.bearing, None, None, options)?);
    }
    Ok(Laid {
        headlands,
        swaths,
        warnings,
        evaluations: prep.direction.evaluations + sm.evaluations,
        decomposition_evaluations: sm.evaluations,
        block_headland_passes,
    })
}

/// The swaths at the field's direction, in one block (`none`) or clustered into boustrophedon
/// cells, and those of the prohibited regions worked at their own directions.
fn lay_single_direction(prep: &Prepared, method: Decomposition) -> Result<Laid, PlanError> {
    let Some(single) = &prep.single else {
        return Err(PlanError::new(
            ErrorCode::Internal,
            "a single-direction plan without its swaths",
        ));
    };
    let bearing = prep.direction.bearing;
    let mut swaths = single.main.clone();
    if method == Decomposition::Boustrophedon {
        let tolerance = prep.options.width * DECOMPOSITION_TOLERANCE;
        let cells = boustrophedon::decompose(&single.main_area, bearing, tolerance);
        cluster_into_cells(&mut swaths, &cells);
    } else {
        swaths.areas.push(SwathArea {
            swaths: 0..swaths.swaths.len(),
            bearing,
            region: None,
            area: single.main_area.clone(),
            fill: false,
        });
    }
    for own in &single.regions {
        swaths.append(own.clone());
    }
    Ok(Laid {
        headlands: prep.headlands.clone(),
        swaths,
        warnings: single.warnings.clone(),
        evaluations: prep.direction.evaluations + single.evaluations,
        decomposition_evaluations: 0,
        block_headland_passes: 0,
    })
}

/// Marks where the swaths pass over obstacles too small for a headland of their own (class A),
/// to be driven with the implement lifted, with a warning for each.
fn lift_over_small_obstacles(prep: &Prepared, laid: &mut Laid) {
    let field = &prep.field;
    let small: Vec<(usize, &geo::Polygon)> = field
        .obstacles
        .iter()
        .enumerate()
        .filter(|&(i, _)| prep.obstacles.class[i] == ObstacleClass::A)
        .map(|(i, o)| (i, &o.polygon))
        .collect();
    laid.swaths.lifts = lifts(&laid.swaths, &small);
    for &(i, _) in &small {
        laid.warnings.push(
            Warning::new(
                WarningCode::ImplementLifted,
                format!(
                    "{} is less than {} m across the driving direction; swaths and headland passes run past it with the implement lifted",
                    field.obstacles[i].subject(),
                    Decimals(prep.options.obstacle_threshold_m(), 1)
                ),
            )
            .at_feature(field.obstacles[i].feature),
        );
    }
}

/// The warning for the swath pieces too short to work, left to the headland passes.
fn short_pieces_dropped(swaths: &Swaths, options: &PlanOptions) -> Option<Warning> {
    if swaths.dropped == 0 {
        return None;
    }
    Some(Warning::new(
        WarningCode::ShortSwathsDropped,
        format!(
            "{} shorter than {} m left to the headland passes",
            if swaths.dropped == 1 {
                "1 swath piece".to_string()
            } else {
                format!("{} swath pieces", swaths.dropped)
            },
            Decimals(options.min_swath_length_m(), 1)
        ),
    ))
}

/// The route and path of `earlier` (a candidate worked before) where its headland passes and
/// blocks are this one's, the route renumbered for this one's swaths.
fn reused<'w>(earlier: &'w Worked, laid: &Laid, blocks: &Blocks) -> Option<(Route, &'w Path)> {
    if earlier.headlands.passes != laid.headlands.passes {
        return None;
    }
    let new_index = renumbering(&earlier.swaths, &earlier.blocks, &laid.swaths, blocks)?;
    Some((
        earlier.route.with_swaths_renumbered(&new_index)?,
        &earlier.path,
    ))
}

/// The warning for the connections that found no way along the headland and run straight
/// across the field.
fn straight_connections(route: &Route) -> Option<Warning> {
    let straight = route.all_connections().filter(|c| c.straight).count();
    if straight == 0 {
        return None;
    }
    Some(Warning::new(
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
    ))
}

/// The candidate's figures: its direction report (the objective's cost of these swaths) and
/// the summary of every stage.
fn measure(
    prep: &Prepared,
    laid: &Laid,
    blocks: &Blocks,
    route: &Route,
    path: &Path,
    machine: Machine,
) -> Summary {
    let options = &prep.options;
    let stats = measure_all(&laid.swaths, &machine);
    let mode = prep.direction.mode;
    let direction = DirectionReport {
        mode,
        method: (mode == DirectionMode::Search).then_some(options.search),
        objective: prep.objective.name(),
        evaluations: laid.evaluations,
        cost: prep.objective.cost(&stats, &machine),
        search_cost: prep.direction.search_cost,
    };
    summarise(
        &prep.field,
        &prep.obstacles,
        &laid.headlands,
        &laid.swaths,
        blocks,
        route,
        path,
        &DirectionFigures {
            direction,
            objectives: ObjectiveValues::of(&stats, &machine),
            machine,
        },
    )
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
    let depth = options.headland_pass_count() as f64 * options.width;
    let hint = if options.reverse {
        ""
    } else {
        "; allowing the machine to reverse (three-point turns) would need about one turning radius"
    };
    Some(Warning::new(
        WarningCode::TurnLeavesField,
        format!(
            "{} the field or cross an obstacle: no turn the machine can drive fits there (reaching up to {} m beyond the swath ends, against a headland {} m deep at most){hint}",
            leave(outside.len(), "turn"),
            Decimals(reach, 1),
            Decimals(depth, 1)
        ),
    ))
}

/// Lifted stretches shorter than this in all (metres) are not worth a warning: a chord a
/// centimetre too close to the boundary.
const LIFTED_AT_EDGES_WARNED_M: f64 = 1.0;

/// The warning for the swaths and passes lifted where the implement would reach past the
/// field's boundary.
fn lifted_at_edges(path: &Path, prep: &Prepared) -> Option<Warning> {
    let half = prep.options.width / 2.0;
    let lifted = crate::path::lift::lifted_at_edges_m(path, &prep.area, half);
    (lifted >= LIFTED_AT_EDGES_WARNED_M).then(|| {
        Warning::new(
            WarningCode::ImplementLiftedAtEdges,
            format!(
                "the implement is lifted along {} m of swaths and passes where it would reach past the field's boundary, and the crop beside is left standing; headland passes along those edges would work it",
                Decimals(lifted, 0)
            ),
        )
    })
}

/// The warning for the connections that leave the field or cross an obstacle, with their cause.
fn connections_leaving(path: &Path, options: &PlanOptions) -> Option<Warning> {
    let outside = path.segments.iter().filter(|s| s.leaves_field).count();
    if outside == 0 {
        return None;
    }
    let hint = reversing_hint(options);
    Some(Warning::new(
        WarningCode::ConnectionLeavesField,
        format!(
            "{} the field or cross an obstacle: no turn the machine can drive onto, off or along the headland passes keeps within a headland {} m deep there{hint}",
            leave(outside, "connection"),
            Decimals(options.headland_pass_count() as f64 * options.width, 1)
        ),
    ))
}

/// The warning for the connections between blocks (`kind` connection) or the turns between
/// swaths (`kind` turn) that drive over crop the plan works later, with their cause: the
/// headland's depth for the machine's turns (and, for a forward machine's turns, the loop
/// between neighbouring swaths).
fn crop_crossed(path: &Path, options: &PlanOptions, kind: SegmentKind) -> Option<Warning> {
    let crossing = path
        .segments
        .iter()
        .filter(|s| s.crosses_crop && s.kind == kind)
        .count();
    if crossing == 0 {
        return None;
    }
    let turns = kind == SegmentKind::Turn;
    let (code, one, between) = if turns {
        (WarningCode::TurnCrossesCrop, "turn", "swaths")
    } else {
        (WarningCode::ConnectionCrossesCrop, "connection", "blocks")
    };
    let what = match crossing {
        1 => format!("1 {one} between {between} drives"),
        n => format!("{n} {one}s between {between} drive"),
    };
    let cause = if turns && !options.reverse {
        format!(
            " (a loop between neighbouring swaths reaches {} m beyond their ends)",
            Decimals(
                crate::objective::forward_turn_depth(options.width, options.turn_radius),
                1
            )
        )
    } else {
        String::new()
    };
    Some(Warning::new(
        code,
        format!(
            "{what} over crop the plan works later (crosses_crop on the {one}): no turn the machine can drive there keeps to a headland {} m deep with a turning radius of {} m{cause}{}",
            Decimals(options.headland_pass_count() as f64 * options.width, 1),
            Shortest(options.turn_radius),
            reversing_hint(options)
        ),
    ))
}

/// What the connections' and turns' warnings suggest to a machine that only drives forward.
fn reversing_hint(options: &PlanOptions) -> &'static str {
    if options.reverse {
        ""
    } else {
        "; more headland passes or allowing the machine to reverse may let it turn within the headland"
    }
}

/// "1 turn leaves", "3 turns leave".
fn leave(count: usize, what: &str) -> String {
    if count == 1 {
        format!("1 {what} leaves")
    } else {
        format!("{count} {what}s leave")
    }
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

/// The swaths at the field's one direction before any decomposition, shared by `none` and
/// `boustrophedon`: those of the inner field less the prohibited regions that forbid the
/// direction (`main`, of `main_area`), and those of each such region at its own best direction.
pub(super) struct SingleDirection {
    pub(super) main_area: geo::MultiPolygon,
    pub(super) main: Swaths,
    pub(super) regions: Vec<Swaths>,
    pub(super) warnings: Vec<Warning>,
    pub(super) evaluations: usize,
}

/// Lays the swaths of the inner field at `bearing` (see [`SingleDirection`]).
pub(super) fn single_direction(
    field: &Field,
    options: &PlanOptions,
    headlands: &Headlands,
    bearing: f64,
    placement: LinePlacement,
    search: &AreaSearch,
) -> Result<SingleDirection, PlanError> {
    let inner = &headlands.inner;
    let reach = Reach {
        region: &headlands.region,
        inner,
        avoid: None,
    };
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
    let main = swaths_of(
        options,
        &main_area,
        Some((reach, &field.prohibited)),
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
            Some((reach, &field.prohibited)),
            options,
        )?);
        out.warnings.push(
            Warning::new(
                WarningCode::RegionOwnDirection,
                format!(
                    "{} forbids the field's direction of {} degrees; it is worked at {} degrees",
                    region.subject(),
                    Decimals(bearing.to_degrees(), 1),
                    Decimals(best.bearing.to_degrees(), 1)
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
    reach: Option<(Reach<'_>, &[ProhibitedRegion])>,
    options: &PlanOptions,
) -> Result<Swaths, PlanError> {
    let mut own = swaths_of(
        options,
        &area,
        reach,
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
        fill: false,
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

/// The swaths of `area`: where the field has no headland (no passes asked for, or none fit),
/// they end at the boundary itself, and only where the implement's whole strip is inside
/// ([`generate_within`]); else, given the headland round them (`reach`), they run on into it
/// as far as their strips work the area ([`generate_reaching`]), without it they end where
/// their centre lines leave the area ([`generate_with`]).
fn swaths_of(
    options: &PlanOptions,
    area: &geo::MultiPolygon,
    reach: Option<(Reach<'_>, &[ProhibitedRegion])>,
    settings: &SwathSettings,
) -> Result<Swaths, PlanError> {
    if options.headland_pass_count() == 0 {
        return generate_within(area, settings);
    }
    let Some((reach, regions)) = reach else {
        return generate_with(area, settings);
    };
    // The strips stay out of the prohibited regions that forbid their direction, where those
    // reach into the headland.
    let avoid = geo::MultiPolygon::new(
        forbidding(regions, settings.bearing)
            .into_iter()
            .filter_map(|i| regions.get(i))
            .map(|r| r.polygon.clone())
            .collect(),
    );
    let reach = Reach {
        avoid: (!avoid.0.is_empty()).then_some(&avoid),
        ..reach
    };
    generate_reaching(area, settings, reach)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plan::plan_geojson;
    use crate::route::plan_route;

    #[test]
    fn a_fill_never_leaves_more_crop_standing_than_the_plan_it_fills() {
        // Register parcels where the route round the fill entered the headland passes elsewhere
        // and its manoeuvres lifted the implement over more than the fill worked (the `none`
        // candidate: a reversing 6 m drill 28 m² short, a 3 m mower 18 and 14 m² short).
        let cases = [
            ("dk_marker_2026_sample", 21, 6.0, 8.0, true),
            ("dk_marker_2026_sample", 49, 3.0, 5.0, false),
            ("nl_brp_2023_sample", 3, 3.0, 5.0, false),
        ];
        for (name, index, width, turn_radius, reverse) in cases {
            let file = format!(
                "{}/tests/fields/real/{name}.geojson",
                env!("CARGO_MANIFEST_DIR")
            );
            let text = std::fs::read_to_string(file).expect("the register sample");
            let all: serde_json::Value = serde_json::from_str(&text).expect("JSON");
            let feature = all["features"][index].to_string();
            let options = PlanOptions {
                width,
                turn_radius,
                reverse,
                decomposition: Decomposition::None,
                ..PlanOptions::default()
            };
            let (field, _) =
                Field::from_geojson_str_in(&feature, options.coordinates).expect("read");
            let prep = super::super::stage(field, &options, vec![], false).expect("prepared");
            let mut times = StageTimes::default();
            let chosen = work(&prep, Decomposition::None, None, None, &mut times).expect("worked");
            let before = crate::coverage::of_plan(&prep.field, &chosen.path, width);
            let (filled, after) = fill_leftovers(&prep, chosen, &mut times).expect("filled");
            assert!(
                after.covered_area_m2 >= before.covered_area_m2,
                "{name} {index}: {} m² worked before the fill, {} after",
                before.covered_area_m2,
                after.covered_area_m2
            );
            let measured = crate::coverage::of_plan(&prep.field, &filled.path, width);
            assert_eq!(measured.covered_area_m2, after.covered_area_m2);
        }
    }

    #[test]
    fn swaths_in_more_blocks_than_the_limit_are_refused() {
        let block = |index| crate::decompose::Block {
            index,
            swaths: vec![index],
            outline: geo::Polygon::new(geo::LineString::new(vec![]), vec![]),
            bearing: 0.0,
        };
        let mut blocks = Blocks {
            blocks: (0..MAX_BLOCKS).map(block).collect(),
        };
        assert!(within_block_limit(&blocks, 0.1).is_ok());
        blocks.blocks.push(block(MAX_BLOCKS));
        let e = within_block_limit(&blocks, 0.1).unwrap_err();
        assert_eq!(e.code, ErrorCode::FieldTooComplex);
        assert!(e.message.contains("10001 blocks"), "{}", e.message);
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
            headland_passes: 1.into(),
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
