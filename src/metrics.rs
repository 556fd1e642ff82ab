//! Metrics: the figures by which a plan is judged (Zhou et al. table 1, Fields2Cover's objectives).

use crate::coverage::Coverage;
use crate::decompose::{Blocks, Decomposition};
use crate::direction::{DirectionMode, SearchMethod};
use crate::field::Field;
use crate::headland::Headlands;
use crate::objective::{Machine, ObjectiveValues};
use crate::obstacles::{ObstacleClass, ObstacleClasses};
use crate::path::turn::{cusps, CUSP_PENALTY_M};
use crate::path::{Path, SegmentKind};
use crate::route::pattern::SwathPattern;
use crate::route::sequence::SequenceMethod;
use crate::route::{Route, RouteStep};
use crate::swath::Swaths;
use geo::{Area, Length};
use serde::Serialize;
use std::collections::BTreeMap;

/// The summary of a plan: counts, distances and areas. Distances are metres, areas square metres.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Summary {
    /// Number of swaths.
    pub swath_count: usize,
    /// Number of turns between swaths of one block.
    pub turn_count: usize,
    /// Number of blocks.
    pub block_count: usize,
    /// Number of headland passes (a pass split at a neck counts once per part).
    pub headland_pass_count: usize,
    /// Headland passes laid around the field: the count asked for, the count `auto` chose for
    /// the machine's turns, or fewer where those left no inner field (with a warning) or where
    /// the field holds no more (as `all` lays them).
    pub headland_passes: u32,
    /// Distance driven working: swaths and headland passes.
    pub working_distance_m: f64,
    /// Of which along swaths.
    pub swath_distance_m: f64,
    /// Of which along headland passes.
    pub headland_distance_m: f64,
    /// Distance driven in turns between swaths of a block: the drivable turns of the path.
    pub turning_distance_m: f64,
    /// The same turns by the turn model the route and the decomposition optimise (a U-turn
    /// `πr + (d − 2r)`, a loop under `2r`, plus the run between staggered ends).
    pub turn_model_distance_m: f64,
    /// The forms of the turns: how many of each (`u-turn`, `loop`, `three-point`,
    /// `reeds-shepp`, `cc-u-turn`, `cc-loop`).
    pub turn_forms: BTreeMap<&'static str, usize>,
    /// Turns that leave the field or cross an obstacle (none fits the headland): each is in the
    /// warnings with its cause.
    pub turns_outside_field: usize,
    /// Connections that leave the field or cross an obstacle: each is in the warnings with its
    /// cause.
    pub connections_outside_field: usize,
    /// Changes of gear along the path (three-point turns, Reeds-Shepp paths); each costs
    /// [`CUSP_PENALTY_M`] of driving in the estimated time.
    pub cusp_count: usize,
    /// Distance driven in connections: between blocks, onto and between the headland passes,
    /// from the entrance and to the exit.
    pub connection_distance_m: f64,
    /// Of which between blocks (Zhou et al.'s block connection distance).
    pub block_connection_distance_m: f64,
    /// All the distance driven: working, turning and connections (the path's length).
    pub total_distance_m: f64,
    /// The same route with turns on the spot (Fields2Cover's comparison): swaths, headland
    /// passes and the connections' lines along the headland as routed, each turn the straight
    /// line between the swath ends.
    pub on_the_spot_distance_m: f64,
    /// Time driven working, seconds, at working speed.
    pub working_time_s: f64,
    /// Time driven not working (turns and connections, and each cusp's penalty), seconds, at
    /// turning speed.
    pub non_working_time_s: f64,
    /// Area of the field, inside the boundary and outside obstacles.
    pub field_area_m2: f64,
    /// Area of the headland: the bands of headland passes along the boundary and around the
    /// obstacles that have them.
    pub headland_area_m2: f64,
    /// Area of the inner field where the swaths lie (outside obstacles).
    pub inner_field_area_m2: f64,
    /// Inner field area over the area of the field less the obstacles that have headlands: the
    /// share left for swaths (Fields2Cover's remaining-area objective for headlands).
    pub remaining_area_ratio: f64,
    /// Headland area no pass covers: corners rounded to the turning radius, and necks too narrow
    /// to turn in.
    pub uncovered_headland_area_m2: f64,
    /// Distance along swaths and headland passes driven with the implement lifted: over small
    /// (class A) obstacles, and where it would reach out of the field or over an obstacle.
    pub lifted_distance_m: f64,
    /// Number of obstacles of each class, A to D.
    pub obstacle_classes: ClassCounts,
    /// Swath pieces shorter than the minimum swath length, left to the headland.
    pub dropped_swath_count: usize,
    /// Of the swaths, those that work parts the others and the headland passes left standing.
    pub fill_swath_count: usize,
    /// The swath direction as a compass bearing in degrees, in `[0, 180)`.
    pub bearing_deg: f64,
    /// How the direction was chosen.
    pub direction: DirectionReport,
    /// Every objective's value for the plan's swaths (Fields2Cover's and Oksanen's), with turns
    /// by the turn model.
    pub objectives: ObjectiveValues,
    /// How the inner field was cut into blocks, and the candidates compared.
    pub decomposition: DecompositionReport,
    /// How the swaths and blocks were ordered.
    pub route: RouteReport,
    /// Estimated operation time, seconds: swaths and headland passes at working speed; the
    /// path's turns and connections (and each cusp's penalty) at turning speed.
    pub estimated_time_s: f64,
    /// The implement's footprint against the field less its obstacles: covered, reachable,
    /// worked twice, left standing.
    pub coverage: Coverage,
    /// Time the planner took, milliseconds.
    pub planning_ms: f64,
    /// Of which each stage, milliseconds (summed over the decompositions compared).
    pub stages_ms: StageTimes,
}

/// Time spent in each stage of planning, milliseconds. The decomposition, route, path and
/// metrics stages run once per decomposition compared (auto compares up to five plans), and
/// their times are the sums.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct StageTimes {
    /// Reading the input and checking it, simplifying the boundary.
    pub validation: f64,
    /// Choosing the swath direction (the search, or the direction given).
    pub direction: f64,
    /// Obstacle classes and headland passes.
    pub headlands: f64,
    /// Cutting the inner field into blocks and laying the swaths.
    pub decomposition: f64,
    /// The order of work: swath patterns, block sequence, connections.
    pub route: f64,
    /// The drivable path: turns, rounded corners, joins.
    pub path: f64,
    /// The figures of the plan.
    pub metrics: f64,
}

impl StageTimes {
    /// Adds the milliseconds since `since` to the stage `stage` picks, and restarts the clock.
    pub fn lap(
        &mut self,
        since: &mut web_time::Instant,
        stage: impl FnOnce(&mut StageTimes) -> &mut f64,
    ) {
        let now = web_time::Instant::now();
        *stage(self) += (now - *since).as_secs_f64() * 1000.0;
        *since = now;
    }
}

/// What the direction stage measured: how the direction was chosen, the objectives of the
/// plan's swaths, and the machine they were measured for.
#[derive(Debug, Clone, Copy)]
pub struct DirectionFigures {
    /// How the direction was chosen.
    pub direction: DirectionReport,
    /// The objectives' values.
    pub objectives: ObjectiveValues,
    /// The machine.
    pub machine: Machine,
}

/// How the swaths and blocks were ordered.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RouteReport {
    /// The pattern the options asked for.
    pub pattern: SwathPattern,
    /// The swath order of each block in working order (`boustrophedon`, `snake-1`,
    /// `spiral-6`, `custom`).
    pub block_patterns: Vec<String>,
    /// How the block order was found: `exact` (dynamic programming), `ant-colony` (with local
    /// search) or `nearest-neighbour` (each next block the nearest, for many blocks).
    pub sequence: &'static str,
    /// Connections that found no way along the headland and run straight.
    pub straight_connections: usize,
}

impl Default for RouteReport {
    fn default() -> Self {
        RouteReport {
            pattern: SwathPattern::Auto,
            block_patterns: Vec::new(),
            sequence: SequenceMethod::Exact.as_str(),
            straight_connections: 0,
        }
    }
}

/// How the inner field was cut into blocks.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DecompositionReport {
    /// What the `decomposition` option asked for.
    pub requested: Decomposition,
    /// What the plan uses: for `auto`, the candidate of lowest estimated operation time.
    pub method: Decomposition,
    /// Why, in words.
    pub reason: String,
    /// Every decomposition planned, with its figures.
    pub candidates: Vec<DecompositionCandidate>,
}

impl Default for DecompositionReport {
    fn default() -> Self {
        DecompositionReport {
            requested: Decomposition::None,
            method: Decomposition::None,
            reason: String::new(),
            candidates: Vec::new(),
        }
    }
}

/// The figures of one decomposition planned.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DecompositionCandidate {
    /// The decomposition.
    pub method: Decomposition,
    /// Number of blocks.
    pub block_count: usize,
    /// The swath directions of its blocks, compass degrees in `[0, 180)`, each once (within a
    /// degree), in the order of the blocks.
    pub bearings_deg: Vec<f64>,
    /// Number of swaths.
    pub swath_count: usize,
    /// Number of turns within blocks.
    pub turn_count: usize,
    /// Headland passes along borders between blocks.
    pub block_headland_passes: usize,
    /// Estimated operation time, seconds (as [`Summary::estimated_time_s`]), before what the
    /// plan leaves is filled: the decompositions are compared by it, and only the chosen one
    /// is filled.
    pub estimated_time_s: f64,
    /// Inner field area its swaths leave uncovered, square metres: counted as if worked at
    /// working speed when the decompositions are compared.
    pub uncovered_area_m2: f64,
    /// Directions the decomposition itself evaluated (split and merge's per-block searches).
    pub evaluations: usize,
}

/// How the direction of a plan was chosen.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct DirectionReport {
    /// The direction mode.
    pub mode: DirectionMode,
    /// The search method, when the direction was searched.
    pub method: Option<SearchMethod>,
    /// The objective minimised (and by which `cost` is measured).
    pub objective: &'static str,
    /// Number of directions evaluated (the field's, its prohibited regions', and with split
    /// and merge its blocks').
    pub evaluations: usize,
    /// The objective's cost of the plan's swaths.
    pub cost: f64,
    /// The lowest cost the search found, measured on its area (the field less a constant
    /// headland), when the direction was searched.
    pub search_cost: Option<f64>,
}

/// Number of obstacles of each class.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize)]
pub struct ClassCounts {
    /// Passed over with the implement lifted.
    #[serde(rename = "A")]
    pub a: usize,
    /// Merged into the field headland.
    #[serde(rename = "B")]
    pub b: usize,
    /// Merged with a neighbouring obstacle.
    #[serde(rename = "C")]
    pub c: usize,
    /// With their own headland.
    #[serde(rename = "D")]
    pub d: usize,
}

/// Measures a plan.
// One argument per pipeline stage it measures.
#[allow(clippy::too_many_arguments)]
pub fn summarise(
    field: &Field,
    obstacles: &ObstacleClasses,
    headlands: &Headlands,
    swaths: &Swaths,
    blocks: &Blocks,
    route: &Route,
    path: &Path,
    direction: &DirectionFigures,
) -> Summary {
    let DirectionFigures {
        direction,
        objectives,
        machine,
    } = *direction;
    let swath_distance_m = path.length_of(SegmentKind::Swath);
    let headland_distance_m = path.length_of(SegmentKind::HeadlandPass);
    let turning_distance_m = path.length_of(SegmentKind::Turn);
    let connection_distance_m = path.length_of(SegmentKind::Connection);
    let mut turn_forms: BTreeMap<&'static str, usize> = BTreeMap::new();
    let mut turns_outside_field = 0;
    let connections_outside_field = path.segments.iter().filter(|s| s.leaves_field).count();
    let mut on_the_spot_turns_m = 0.0;
    for seg in &path.segments {
        if let Some(t) = &seg.turn {
            *turn_forms.entry(t.form.name()).or_default() += 1;
            if !t.inside {
                turns_outside_field += 1;
            }
        }
        if seg.kind == SegmentKind::Turn {
            if let (Some(a), Some(b)) = (seg.start(), seg.end()) {
                on_the_spot_turns_m += a.distance(&b);
            }
        }
    }
    let cusp_count: usize = path.segments.iter().map(|s| cusps(&s.pieces)).sum();
    let routed_connections_m: f64 = route
        .all_connections()
        .map(|c| geo::Euclidean.length(&c.line))
        .sum();
    let block_connection_distance_m: f64 = route
        .connections
        .iter()
        .enumerate()
        .filter(|&(k, _)| {
            k > 0
                && matches!(route.steps.get(k), Some(RouteStep::Swath { .. }))
                && matches!(route.steps.get(k - 1), Some(RouteStep::Swath { .. }))
        })
        .filter_map(|(_, c)| c.as_ref())
        .map(|c| geo::Euclidean.length(&c.line))
        .sum();
    let working_time_s = (swath_distance_m + headland_distance_m) / machine.working_speed;
    let non_working_time_s =
        (turning_distance_m + connection_distance_m + cusp_count as f64 * CUSP_PENALTY_M)
            / machine.turning_speed;
    let working_distance_m = swath_distance_m + headland_distance_m;
    let field_area_m2 = field.area_m2();
    let inner_field_area_m2 = headlands.inner.unsigned_area();
    Summary {
        swath_count: swaths.swaths.len(),
        turn_count: path.count_of(SegmentKind::Turn),
        block_count: blocks.blocks.len(),
        headland_pass_count: headlands.passes.len(),
        // The plan's options give it (`assemble`).
        headland_passes: 0,
        working_distance_m,
        swath_distance_m,
        headland_distance_m,
        turning_distance_m,
        turn_model_distance_m: route.turning_m,
        turn_forms,
        turns_outside_field,
        connections_outside_field,
        cusp_count,
        connection_distance_m,
        block_connection_distance_m,
        total_distance_m: working_distance_m + turning_distance_m + connection_distance_m,
        on_the_spot_distance_m: working_distance_m + on_the_spot_turns_m + routed_connections_m,
        working_time_s,
        non_working_time_s,
        field_area_m2,
        headland_area_m2: headlands.area_m2,
        inner_field_area_m2,
        remaining_area_ratio: {
            // Of the field less the obstacles the headland runs round (class A ones are worked
            // over, so they count as field).
            let region = inner_field_area_m2 + headlands.area_m2;
            if region > 0.0 {
                (inner_field_area_m2 / region).min(1.0)
            } else {
                0.0
            }
        },
        uncovered_headland_area_m2: headlands.uncovered_area_m2,
        lifted_distance_m: path
            .segments
            .iter()
            .flat_map(|s| &s.lifted)
            .fold(0.0, |sum, l| sum + (l.1 - l.0)),
        obstacle_classes: ClassCounts {
            a: obstacles.count(ObstacleClass::A),
            b: obstacles.count(ObstacleClass::B),
            c: obstacles.count(ObstacleClass::C),
            d: obstacles.count(ObstacleClass::D),
        },
        dropped_swath_count: swaths.dropped,
        fill_swath_count: swaths
            .areas
            .iter()
            .filter(|a| a.fill)
            .map(|a| a.swaths.len())
            .sum(),
        bearing_deg: swaths.bearing.to_degrees(),
        direction,
        objectives,
        decomposition: DecompositionReport::default(),
        route: RouteReport {
            pattern: SwathPattern::Auto,
            block_patterns: route
                .block_order
                .iter()
                .filter_map(|&b| route.block_patterns.get(b).cloned())
                .collect(),
            sequence: route.sequence.method.as_str(),
            straight_connections: route.all_connections().filter(|c| c.straight).count(),
        },
        estimated_time_s: working_time_s + non_working_time_s,
        coverage: Coverage::default(),
        planning_ms: 0.0,
        stages_ms: StageTimes::default(),
    }
}
