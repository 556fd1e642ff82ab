//! The planner: field → direction → obstacle classes and headlands → swaths → blocks → route →
//! path → metrics. The direction comes first because obstacle classes and headlands that run
//! only where swaths end depend on it.
//!
//! Each stage is a module of its own with its own types; this module runs them in order and
//! keeps their results together in a [`Plan`].

use crate::decompose::{cluster_swaths, Blocks};
use crate::direction::{
    choose_bearing, edge_directions, reference_direction, search_area, search_field, search_region,
    AreaSearch, DirectionMode, DirectionRule, SearchMethod,
};
use crate::error::{PlanError, Warning, WarningCode};
use crate::field::simplify::tolerance_for_width;
use crate::field::Field;
use crate::geometry::forbids_every_direction;
use crate::headland::edges::{passes_per_edge, EdgeRule};
use crate::headland::{build, HeadlandSettings, Headlands};
use crate::metrics::{summarise, DirectionFigures, DirectionReport, Summary};
use crate::objective::{measure_all, ObjectiveValues};
use crate::obstacles::{classify, ClassSettings, ObstacleClass, ObstacleClasses};
use crate::options::PlanOptions;
use crate::path::{build_path, Path};
use crate::prohibited::{forbidding, split};
use crate::route::{boustrophedon, Route};
use crate::swath::{generate_with, lifts, LinePlacement, SwathArea, SwathSettings, Swaths};
use geo::BoundingRect;
use web_time::Instant;

/// Most swath lines times directions a direction search may sweep (about a third of a second
/// natively); beyond it the direction follows the longest edge.
pub const SEARCH_BUDGET_LINES: f64 = 250_000.0;

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
    let mut plan = plan_stages(field, options, warnings)?;
    plan.summary.planning_ms = started.elapsed().as_secs_f64() * 1000.0;
    Ok(plan)
}

/// Runs the stages on a field read by the caller, keeping the caller's warnings first.
pub(crate) fn plan_stages(
    mut field: Field,
    options: &PlanOptions,
    mut warnings: Vec<Warning>,
) -> Result<Plan, PlanError> {
    options.validate()?;
    let width = options.width;
    warnings.extend(field.simplify(tolerance_for_width(width)));
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
        // Each evaluation sweeps every swath line: beyond a budget the search would keep the
        // user waiting for seconds, so the swaths follow the longest edge instead.
        let lines = field
            .boundary
            .bounding_rect()
            .map_or(0.0, |r| r.width().hypot(r.height()))
            / width;
        let evaluations = match options.search {
            SearchMethod::BruteForce => 180.0 / options.search_step_deg + 8.0,
            SearchMethod::CoarseToFine => 40.0,
        };
        if lines * evaluations > SEARCH_BUDGET_LINES {
            mode = DirectionMode::LongestEdge;
            warnings.push(Warning::new(
                WarningCode::DirectionNotSearched,
                format!(
                    "at {width} m the field has up to {lines:.0} swath lines, too many to search {evaluations:.0} directions quickly; the swaths run along the longest edge"
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
    // Prohibited regions that forbid the direction are cut out and worked in their own.
    let cut = forbidding(&field.prohibited, bearing);
    let (main_area, parts) = if cut.is_empty() {
        (headlands.inner.clone(), Vec::new())
    } else {
        split(&headlands.inner, &field.prohibited, &cut, forbidden)
    };
    let mut swaths = generate_with(
        &main_area,
        &SwathSettings {
            bearing,
            width,
            min_length: options.min_swath_length_m(),
            placement,
        },
    )?;
    swaths.areas.push(SwathArea {
        swaths: 0..swaths.swaths.len(),
        bearing,
        region: None,
        area: main_area,
    });
    for part in parts {
        let region = &field.prohibited[part.region];
        if forbids_every_direction(&part.forbidden) {
            warnings.push(
                Warning::new(
                    WarningCode::RegionNotWorked,
                    format!(
                        "{} forbids the field's direction, and with the other forbidden ranges no direction is left for it; it gets no swaths",
                        region.subject()
                    ),
                )
                .at_feature(region.feature),
            );
            continue;
        }
        let best = search_area(&part.area, &part.forbidden, &search)?;
        evaluations += best.evaluations;
        let mut own = generate_with(
            &part.area,
            &SwathSettings {
                bearing: best.bearing,
                width,
                min_length: options.min_swath_length_m(),
                placement: LinePlacement::FromEdge,
            },
        )?;
        own.areas.push(SwathArea {
            swaths: 0..own.swaths.len(),
            bearing: best.bearing,
            region: Some(part.region),
            area: part.area,
        });
        swaths.append(own);
        warnings.push(
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
    if blocks.blocks.len() > 1 {
        warnings.push(Warning::new(
            WarningCode::StraightConnections,
            format!(
                "the field falls into {} blocks; they are joined by straight connections, which may cross crop or obstacles",
                blocks.blocks.len()
            ),
        ));
    }
    let route = boustrophedon(
        &swaths,
        &blocks,
        &headlands.passes,
        options.headland_order,
        None,
    );
    let path = build_path(&route, &swaths, &headlands.passes);
    let machine = options.machine();
    let stats = measure_all(&swaths, &machine);
    let direction = DirectionReport {
        mode,
        method: (mode == DirectionMode::Search).then_some(options.search),
        objective: objective.name(),
        evaluations,
        cost: objective.cost(&stats, &machine),
        search_cost,
    };
    let summary = summarise(
        &field,
        &obstacles,
        &headlands,
        &swaths,
        &blocks,
        &path,
        &DirectionFigures {
            direction,
            objectives: ObjectiveValues::of(&stats, &machine),
            machine,
        },
    );
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
