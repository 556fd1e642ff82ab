//! The driving direction of the swaths.
//!
//! Rules: a search over directions for the lowest cost by an [objective](crate::objective)
//! (brute force at a step, as Fields2Cover; or Oksanen & Visala's coarse-to-fine search, 2.6), a
//! bearing the user gives, a reference line, or the one farmers use, along the longest edge of
//! the field boundary. The edge is measured on the boundary simplified to half a working width, so that a
//! GNSS-recorded boundary with many short noisy edges still has the long straight edge it looks
//! like. Forbidden bearing ranges (Oksanen & Visala 2.8: along drainage laterals, up an
//! escarpment) are respected: a fixed bearing in one is refused; the longest-edge rule takes the
//! longest edge whose direction is allowed.

use crate::error::{ErrorCode, PlanError};
use crate::field::{Field, ProhibitedRegion};
use crate::geometry::{
    bearing_of, deg_to_bearing, forbids_every_direction, swath_direction, BearingRange, SweepFrame,
};
use crate::geometry::{PlanarHypot, PlanarSimplify};
use crate::headland::edges::drawn_edge_count;
use crate::headland::offset::inset_coarse;
use crate::numbers::{Decimals, Shortest};
use crate::objective::{measure, Machine, Objective, SwathStats};
use crate::prohibited::{forbidding, split};
use crate::sort::SharedSort;
use crate::swath::{generate_with, LinePlacement, SwathSettings};
use geo::{BoundingRect, Coord, LineString, MultiPolygon, Polygon};
use serde::Serialize;
use std::f64::consts::PI;

/// How the driving direction of a plan is chosen (the `direction` option).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum DirectionMode {
    /// The direction of lowest cost by the objective.
    Search,
    /// Along the longest boundary edge, as farmers often drive.
    LongestEdge,
    /// The `bearing` given.
    Fixed,
    /// Along a reference line or boundary edge, on its grid.
    Reference,
}

crate::named::named!(DirectionMode { "search" => Search, "longest-edge" => LongestEdge, "fixed" => Fixed, "reference" => Reference });

/// How the direction search steps through directions.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum SearchMethod {
    /// Every direction at a fixed step (Fields2Cover's brute force).
    BruteForce,
    /// Six directions 30 degrees apart; keep the best three, try half the step either side of
    /// each, and repeat until the step is under one degree (Oksanen & Visala 2.6).
    #[default]
    CoarseToFine,
}

crate::named::named!(SearchMethod { "brute-force" => BruteForce, "coarse-to-fine" => CoarseToFine });

/// The direction a search found.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SearchResult {
    /// The best swath direction, compass radians in `[0, π)`.
    pub bearing: f64,
    /// Its cost.
    pub cost: f64,
    /// How many directions were evaluated.
    pub evaluations: usize,
}

/// Amount (degrees) by which a candidate moved out of a forbidden range clears its end.
const RANGE_CLEARANCE_DEG: f64 = 1e-3;

/// The allowed swath direction nearest to `bearing` (compass radians): `bearing` itself when no
/// range forbids it, else just outside the end of a forbidden range. `None` if every direction is
/// forbidden.
///
/// ```
/// use furrow::direction::nearest_allowed;
/// use furrow::geometry::BearingRange;
///
/// let drains = [BearingRange { from_deg: 20.0, to_deg: 70.0 }];
/// let b = nearest_allowed(60f64.to_radians(), &drains).ok_or("no direction left")?;
/// assert!((b.to_degrees() - 70.0).abs() < 0.01);
/// assert_eq!(nearest_allowed(2.0, &drains), Some(2.0));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn nearest_allowed(bearing: f64, forbidden: &[BearingRange]) -> Option<f64> {
    let b = swath_direction(bearing);
    if !forbidden.iter().any(|r| r.forbids(b)) {
        return Some(b);
    }
    let mut best: Option<(f64, f64)> = None;
    for e in allowed_range_ends(forbidden) {
        let d = (e - b).rem_euclid(PI);
        let d = d.min(PI - d);
        if best.is_none_or(|(bd, _)| d < bd) {
            best = Some((d, e));
        }
    }
    best.map(|(_, e)| e)
}

/// The swath directions just outside the ends of the forbidden ranges that no range forbids:
/// where a constrained optimum often lies, and the allowed directions nearest a forbidden one.
fn allowed_range_ends(forbidden: &[BearingRange]) -> impl Iterator<Item = f64> + '_ {
    forbidden
        .iter()
        .flat_map(|r| {
            [
                r.from_deg - RANGE_CLEARANCE_DEG,
                r.to_deg + RANGE_CLEARANCE_DEG,
            ]
        })
        .map(|end| swath_direction(end.to_radians()))
        .filter(|&e| !forbidden.iter().any(|q| q.forbids(e)))
}

/// Searches the swath directions not in `forbidden` for the lowest `cost` (a function of the
/// swath direction, compass radians). NaN costs count as infinite.
///
/// Both methods first try the `seeds` (such as the directions of the field's longest edges,
/// along which coverage is usually best; Mier et al. 2023, IV-A): a grid misses an edge at 37.4
/// degrees by a fraction of a degree, enough to leave a sliver along it, and the coarse-to-fine
/// search refines around a seed like any other candidate. Brute force also tries the directions
/// just outside each forbidden range, where a constrained optimum often lies; the coarse-to-fine
/// search moves candidates that fall in a range to the nearest allowed direction.
///
/// ```
/// use furrow::direction::{search_direction, SearchMethod};
///
/// // A cost with its minimum at 47.3 degrees.
/// let cost = |b: f64| (b.to_degrees() - 47.3).abs();
/// let brute = search_direction(SearchMethod::BruteForce, 1.0, &[], &[], cost)?;
/// assert_eq!((brute.bearing.to_degrees().round(), brute.evaluations), (47.0, 180));
/// let fine = search_direction(SearchMethod::CoarseToFine, 1.0, &[], &[], cost)?;
/// assert!((fine.bearing.to_degrees() - 47.3).abs() < 1.0 && fine.evaluations <= 36);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn search_direction(
    method: SearchMethod,
    step_deg: f64,
    forbidden: &[BearingRange],
    seeds: &[f64],
    mut cost: impl FnMut(f64) -> f64,
) -> Result<SearchResult, PlanError> {
    search_with(method, step_deg, forbidden, seeds, &mut cost)
}

/// [`search_direction`] with the cost behind a reference: one copy of the search for every cost.
fn search_with(
    method: SearchMethod,
    step_deg: f64,
    forbidden: &[BearingRange],
    seeds: &[f64],
    cost: &mut dyn FnMut(f64) -> f64,
) -> Result<SearchResult, PlanError> {
    let mut e = Evaluated::new(cost);
    e.seeds(seeds, forbidden);
    match method {
        SearchMethod::BruteForce => {
            let step = step_deg.clamp(1e-3, 180.0);
            let n = (180.0 / step - 1e-9).ceil() as usize;
            let allowed = |b: f64| !forbidden.iter().any(|r| r.forbids(b));
            for k in 0..n {
                let b = (k as f64 * step).to_radians();
                if allowed(b) {
                    e.eval(b);
                }
            }
            for b in allowed_range_ends(forbidden) {
                e.eval(b);
            }
        }
        SearchMethod::CoarseToFine => {
            let mut step = 30.0f64;
            for k in 0..6 {
                let b = (k as f64 * step).to_radians();
                e.eval(nearest_allowed(b, forbidden).ok_or_else(no_direction)?);
            }
            while step >= 1.0 {
                let mut ranked = e.list.clone();
                ranked.shared_sort_by(|a, b| a.1.total_cmp(&b.1));
                step /= 2.0;
                for &(b, _) in ranked.iter().take(3) {
                    for side in [-1.0, 1.0] {
                        let c = b + side * step.to_radians();
                        e.eval(nearest_allowed(c, forbidden).ok_or_else(no_direction)?);
                    }
                }
            }
        }
    }
    e.result()
}

/// The error of a search that finds every direction forbidden.
fn no_direction() -> PlanError {
    PlanError::new(
        ErrorCode::NoAllowedDirection,
        "the forbidden bearing ranges forbid every driving direction",
    )
}

/// The directions a search evaluated, each once, with their costs (NaN counts as infinite).
struct Evaluated<'a> {
    cost: &'a mut dyn FnMut(f64) -> f64,
    list: Vec<(f64, f64)>,
}

impl<'a> Evaluated<'a> {
    fn new(cost: &'a mut dyn FnMut(f64) -> f64) -> Self {
        Evaluated {
            cost,
            list: Vec::new(),
        }
    }

    /// Evaluates a swath direction, unless it was.
    fn eval(&mut self, b: f64) {
        let b = swath_direction(b);
        if self.list.iter().any(|e| (e.0 - b).abs() < 1e-9) {
            return;
        }
        let c = (self.cost)(b);
        self.list
            .push((b, if c.is_nan() { f64::INFINITY } else { c }));
    }

    /// Evaluates the seeds, each moved to the nearest allowed direction.
    fn seeds(&mut self, seeds: &[f64], forbidden: &[BearingRange]) {
        for &seed in seeds {
            if let Some(b) = nearest_allowed(seed, forbidden) {
                self.eval(b);
            }
        }
    }

    /// The first of the lowest: ties go to the direction evaluated first.
    fn best(&self) -> Option<(f64, f64)> {
        let mut best: Option<(f64, f64)> = None;
        for &(b, c) in &self.list {
            if best.is_none_or(|(_, bc)| c < bc) {
                best = Some((b, c));
            }
        }
        best
    }

    fn result(self) -> Result<SearchResult, PlanError> {
        let (bearing, cost) = self.best().ok_or_else(no_direction)?;
        Ok(SearchResult {
            bearing,
            cost,
            evaluations: self.list.len(),
        })
    }
}

/// A quick search for the many small searches of a decomposition (a direction for each block):
/// the `seeds`, six directions 30 degrees apart, then around the best one only, at half the
/// step each time until under one degree: about 16 evaluations besides the seeds, against 30
/// to 40 for the coarse-to-fine search, which refines around the best three. With
/// [`SearchMethod::BruteForce`] the search is the full brute force.
///
/// ```
/// use furrow::direction::{quick_search, SearchMethod};
///
/// let cost = |b: f64| (b.to_degrees() - 47.3).abs();
/// let r = quick_search(SearchMethod::CoarseToFine, 1.0, &[], &[], cost)?;
/// assert!((r.bearing.to_degrees() - 47.3).abs() < 1.0 && r.evaluations <= 16);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn quick_search(
    method: SearchMethod,
    step_deg: f64,
    forbidden: &[BearingRange],
    seeds: &[f64],
    mut cost: impl FnMut(f64) -> f64,
) -> Result<SearchResult, PlanError> {
    if method == SearchMethod::BruteForce {
        return search_with(method, step_deg, forbidden, seeds, &mut cost);
    }
    let mut e = Evaluated::new(&mut cost);
    e.seeds(seeds, forbidden);
    for k in 0..6 {
        if let Some(b) = nearest_allowed((k as f64 * 30.0).to_radians(), forbidden) {
            e.eval(b);
        }
    }
    let mut step = 30.0f64;
    while step >= 1.0 {
        step /= 2.0;
        let Some((b, _)) = e.best() else {
            break;
        };
        for side in [-1.0, 1.0] {
            if let Some(c) = nearest_allowed(b + side * step.to_radians(), forbidden) {
                e.eval(c);
            }
        }
    }
    e.result()
}

/// How the driving direction is chosen.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum DirectionRule {
    /// A fixed compass bearing, degrees.
    Fixed {
        /// The bearing, compass degrees.
        bearing_deg: f64,
    },
    /// Along the longest edge of the boundary (simplified by the given tolerance, metres).
    LongestEdge {
        /// Douglas-Peucker tolerance applied to the boundary first, metres.
        tolerance_m: f64,
    },
}

/// The swath direction (compass radians in `[0, π)`) the rule gives for the field, avoiding the
/// forbidden ranges.
///
/// ```
/// use furrow::direction::{choose_bearing, DirectionRule};
/// use furrow::field::Field;
/// use furrow::geometry::BearingRange;
///
/// // A field much longer east-west than north-south: the longest edge runs east (90 degrees).
/// let text = r#"{"type": "Polygon", "coordinates": [[[24.05, 60.25], [24.06, 60.25],
///     [24.06, 60.251], [24.05, 60.251], [24.05, 60.25]]]}"#;
/// let (field, _) = Field::from_geojson_str(text)?;
/// let rule = DirectionRule::LongestEdge { tolerance_m: 3.0 };
/// let b = choose_bearing(&field, rule, &[])?;
/// assert!((b.to_degrees() - 90.0).abs() < 0.1);
/// // With east-west forbidden, the longest allowed edge is a short side, running north.
/// let b = choose_bearing(&field, rule, &[BearingRange { from_deg: 80.0, to_deg: 100.0 }])?;
/// assert!(b.to_degrees().min(180.0 - b.to_degrees()) < 0.5);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn choose_bearing(
    field: &Field,
    rule: DirectionRule,
    forbidden: &[BearingRange],
) -> Result<f64, PlanError> {
    let allowed = |b: f64| !forbidden.iter().any(|r| r.forbids(b));
    match rule {
        DirectionRule::Fixed { bearing_deg } => {
            let b = swath_direction(deg_to_bearing(bearing_deg));
            match forbidden.iter().find(|r| r.forbids(b)) {
                None => Ok(b),
                Some(r) => Err(PlanError::new(
                    ErrorCode::BearingForbidden,
                    format!(
                        "bearing {} lies in the forbidden range {} to {} degrees",
                        Shortest(bearing_deg),
                        Shortest(r.from_deg),
                        Shortest(r.to_deg)
                    ),
                )),
            }
        }
        DirectionRule::LongestEdge { tolerance_m } => {
            let edges = edges_longest_first(field.boundary.exterior(), tolerance_m);
            if let Some(&(_, b)) = edges.iter().find(|(_, b)| allowed(*b)) {
                return Ok(b);
            }
            // No edge runs in an allowed direction: the allowed direction nearest the longest.
            let longest = edges.first().map_or(0.0, |e| e.1);
            nearest_allowed(longest, forbidden).ok_or_else(|| {
                PlanError::new(
                    ErrorCode::NoAllowedDirection,
                    "the forbidden bearing ranges forbid every driving direction",
                )
            })
        }
    }
}

/// Most edge directions a search is seeded with.
const SEED_EDGES: usize = 4;

/// The swath directions of the longest edges of the rings (each simplified by `tolerance_m`),
/// longest first, at most [`SEED_EDGES`], with near-duplicates (within 0.1 degree) left out.
///
/// ```
/// use furrow::direction::edge_directions;
/// use geo::{polygon, Polygon};
///
/// let field: Polygon = polygon![(x: 0., y: 0.), (x: 300., y: 0.), (x: 300., y: 100.), (x: 0., y: 120.)];
/// let d: Vec<f64> = edge_directions([field.exterior()].into_iter(), 1.0).iter().map(|b| b.to_degrees().round()).collect();
/// assert_eq!(d, vec![94.0, 90.0, 0.0]); // the slanted north edge (300.7 m), the south edge, east and west
/// ```
pub fn edge_directions<'a>(
    rings: impl Iterator<Item = &'a LineString>,
    tolerance_m: f64,
) -> Vec<f64> {
    let mut edges: Vec<(f64, f64)> = rings
        .flat_map(|r| edges_longest_first(r, tolerance_m))
        .collect();
    edges.shared_sort_by(|a, b| b.0.total_cmp(&a.0));
    let mut out: Vec<f64> = Vec::new();
    for (_, b) in edges {
        let near = |o: &f64| {
            let d = (o - b).rem_euclid(PI);
            d.min(PI - d) < 0.1f64.to_radians()
        };
        if !out.iter().any(near) {
            out.push(b);
            if out.len() == SEED_EDGES {
                break;
            }
        }
    }
    out
}

/// (length, swath direction) of the edges of a ring simplified by `tolerance_m`, longest first.
fn edges_longest_first(ring: &LineString, tolerance_m: f64) -> Vec<(f64, f64)> {
    let simplified = ring.planar_simplify(tolerance_m);
    let ring = if simplified.0.len() >= 4 {
        &simplified
    } else {
        ring
    };
    let mut edges: Vec<(f64, f64)> = ring
        .lines()
        .map(|line| {
            let d = line.delta();
            (
                d.x.planar_hypot(d.y),
                swath_direction(bearing_of(line.start, line.end)),
            )
        })
        .collect();
    edges.shared_sort_by(|a, b| b.0.total_cmp(&a.0));
    edges
}

/// The area the direction search measures: the field less its obstacles (but those too small
/// to split it at any direction: narrower than `obstacle_threshold` every way) and less a
/// constant headland `headland_depth` deep. The planner's headland may depend on the direction
/// (in `needed` mode, and through the obstacle classes); measuring every candidate on one area
/// keeps the search to one offset. Its arcs are held to a twentieth of the width: the area is an
/// estimate, and its points are what the search's sweeps cost.
///
/// ```
/// use furrow::direction::search_region;
/// use furrow::field::Field;
/// use geo::Area;
///
/// let text = r#"{"type": "Polygon", "coordinates": [[[0, 0], [100, 0], [100, 60], [0, 60], [0, 0]]]}"#;
/// let (field, _) = Field::from_geojson_str_in(text, furrow::field::Coordinates::Metric)?;
/// let area = search_region(&field, 6.0, 12.0, 6.0);
/// assert!((area.unsigned_area() - 76.0 * 36.0).abs() < 1e-6);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn search_region(
    field: &Field,
    obstacle_threshold: f64,
    headland_depth: f64,
    width: f64,
) -> MultiPolygon {
    let mut holes = field.boundary.interiors().to_vec();
    for o in &field.obstacles {
        let diagonal = o
            .polygon
            .bounding_rect()
            .map_or(0.0, |r| r.width().planar_hypot(r.height()));
        if diagonal >= obstacle_threshold {
            holes.push(o.polygon.exterior().clone());
        }
    }
    let region = MultiPolygon::new(vec![Polygon::new(field.boundary.exterior().clone(), holes)]);
    inset_coarse(&region, headland_depth, width / 20.0)
}

/// The vertices of the outlines the direction search sweeps ([`search_region`]): the boundary's
/// rings and the obstacles at least `obstacle_threshold` across.
pub fn search_vertices(field: &Field, obstacle_threshold: f64) -> usize {
    let boundary: usize = std::iter::once(field.boundary.exterior())
        .chain(field.boundary.interiors())
        .map(|r| r.0.len())
        .sum();
    let obstacles: usize = field
        .obstacles
        .iter()
        .filter(|o| {
            o.polygon
                .bounding_rect()
                .is_some_and(|r| r.width().planar_hypot(r.height()) >= obstacle_threshold)
        })
        .map(|o| o.polygon.exterior().0.len())
        .sum();
    boundary + obstacles
}

/// What the direction search of an area needs besides the area.
pub struct AreaSearch<'a> {
    /// Search method.
    pub method: SearchMethod,
    /// Step of the brute-force search, degrees.
    pub step_deg: f64,
    /// Working width, metres.
    pub width: f64,
    /// Swath pieces shorter than this (metres) are dropped.
    pub min_length: f64,
    /// The machine, for the objectives.
    pub machine: Machine,
    /// What is minimised.
    pub objective: &'a dyn Objective,
}

/// The direction of lowest cost for swaths covering `area`, among those `forbidden` allows.
///
/// ```
/// use furrow::direction::{search_area, AreaSearch, SearchMethod};
/// use furrow::objective::{Machine, OperationTime};
/// use geo::{polygon, MultiPolygon};
///
/// // A 40 m x 300 m strip running north-east: work it lengthwise.
/// let strip = polygon![(x: 0., y: 0.), (x: 28.3, y: -28.3), (x: 240.4, y: 183.8), (x: 212.1, y: 212.1)];
/// let search = AreaSearch {
///     method: SearchMethod::CoarseToFine, step_deg: 1.0, width: 6.0, min_length: 6.0,
///     machine: Machine { width: 6.0, turn_radius: 6.0, working_speed: 2.0, turning_speed: 1.5 },
///     objective: &OperationTime,
/// };
/// let best = search_area(&MultiPolygon::new(vec![strip]), &[], &search)?;
/// assert!((best.bearing.to_degrees() - 45.0).abs() < 1.0);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn search_area(
    area: &MultiPolygon,
    forbidden: &[BearingRange],
    search: &AreaSearch,
) -> Result<SearchResult, PlanError> {
    let mut error = None;
    let seeds = edge_directions(area.0.iter().map(|p| p.exterior()), search.width / 2.0);
    let result =
        search_direction(
            search.method,
            search.step_deg,
            forbidden,
            &seeds,
            |b| match area_stats(area, b, search) {
                Ok(s) => search.objective.cost(&s, &search.machine),
                Err(e) => {
                    error.get_or_insert(e);
                    f64::INFINITY
                }
            },
        )?;
    match error {
        Some(e) => Err(e),
        None => Ok(result),
    }
}

/// The measures of the swaths covering `area` at swath direction `bearing`.
pub fn area_stats(
    area: &MultiPolygon,
    bearing: f64,
    search: &AreaSearch,
) -> Result<SwathStats, PlanError> {
    let swaths = generate_with(
        area,
        &SwathSettings {
            bearing,
            width: search.width,
            min_length: search.min_length,
            placement: LinePlacement::FromEdge,
        },
    )?;
    Ok(measure(&swaths.swaths, search.width, area, &search.machine))
}

/// The parts of a field for one set of prohibited regions cut out: the part worked at the
/// field's direction, and the measures of the regions' parts at their own best directions.
struct CutOut {
    main: MultiPolygon,
    regions: SwathStats,
}

/// The direction of lowest cost for the whole field: the swaths of `area` (the inner field) at
/// each candidate direction, with every prohibited region that forbids the candidate cut out and
/// worked at its own best direction.
pub fn search_field(
    area: &MultiPolygon,
    regions: &[ProhibitedRegion],
    global: &[BearingRange],
    seeds: &[f64],
    search: &AreaSearch,
) -> Result<SearchResult, PlanError> {
    let mut cache: Vec<(Vec<usize>, CutOut)> = Vec::new();
    let mut region_evaluations = 0;
    let mut error = None;
    let result = search_direction(search.method, search.step_deg, global, seeds, |b| {
        let cut = forbidding(regions, b);
        let found = cache.iter().position(|(k, _)| *k == cut);
        let index = match found {
            Some(i) => i,
            None => {
                let (main, parts) = split(area, regions, &cut, global);
                let mut stats = SwathStats::default();
                for part in parts {
                    if forbids_every_direction(&part.forbidden) {
                        continue;
                    }
                    match search_area(&part.area, &part.forbidden, search) {
                        Ok(best) => {
                            region_evaluations += best.evaluations;
                            match area_stats(&part.area, best.bearing, search) {
                                Ok(s) => stats += s,
                                Err(e) => {
                                    error.get_or_insert(e);
                                }
                            }
                        }
                        Err(e) => {
                            error.get_or_insert(e);
                        }
                    }
                }
                cache.push((
                    cut,
                    CutOut {
                        main,
                        regions: stats,
                    },
                ));
                cache.len() - 1
            }
        };
        let cut_out = &cache[index].1;
        match area_stats(&cut_out.main, b, search) {
            Ok(mut s) => {
                s += cut_out.regions;
                search.objective.cost(&s, &search.machine)
            }
            Err(e) => {
                error.get_or_insert(e);
                f64::INFINITY
            }
        }
    })?;
    match error {
        Some(e) => Err(e),
        None => Ok(SearchResult {
            evaluations: result.evaluations + region_evaluations,
            ..result
        }),
    }
}

/// The swath direction and line placement of a reference: an AB line (in local metres) or
/// boundary edge `edge` of the outer ring as drawn, shifted by `offset_m` to the right looking
/// along it (default 0 for a line, half a width for an edge). The grid repeats every width, so
/// only the offset's remainder after whole widths counts: it is taken exactly (an offset under
/// one width is used as given), and an offset of 1e17 m places the grid as its remainder does.
///
/// ```
/// use furrow::direction::reference_direction;
/// use furrow::swath::LinePlacement;
/// use geo::coord;
///
/// // An AB line running north along x = 10: the grid goes through x = 10 (across = x at bearing 0).
/// let (b, placement) = reference_direction(
///     Some([coord! { x: 10., y: 0. }, coord! { x: 10., y: 50. }]), None, &[], None, 6.0, &[],
/// )?;
/// assert_eq!(b, 0.0);
/// assert_eq!(placement, LinePlacement::Aligned { across: 10.0 });
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn reference_direction(
    line: Option<[Coord; 2]>,
    edge: Option<usize>,
    drawn: &[Coord],
    offset_m: Option<f64>,
    width: f64,
    forbidden: &[BearingRange],
) -> Result<(f64, LinePlacement), PlanError> {
    let (a, b, default_offset) = match (line, edge) {
        (Some([a, b]), _) => (a, b, 0.0),
        (None, Some(i)) => {
            let n = drawn_edge_count(drawn);
            match (drawn.get(i), drawn.get((i + 1) % n.max(1))) {
                (Some(&a), Some(&b)) if i < n => (a, b, width / 2.0),
                _ => {
                    return Err(PlanError::new(
                        ErrorCode::OptionOutOfRange,
                        format!(
                        "option `referenceEdge` is {i}; the boundary as drawn has edges 0 to {}",
                        n.saturating_sub(1)
                    ),
                    ))
                }
            }
        }
        (None, None) => {
            return Err(PlanError::new(
                ErrorCode::InvalidOption,
                "a reference direction needs `referenceLine` or `referenceEdge`",
            ))
        }
    };
    if (b.x - a.x).planar_hypot(b.y - a.y) < 1e-6 {
        return Err(PlanError::new(
            ErrorCode::InvalidOption,
            "the reference line's two points coincide; it gives no direction",
        ));
    }
    let driving = bearing_of(a, b);
    let bearing = swath_direction(driving);
    if let Some(r) = forbidden.iter().find(|r| r.forbids(bearing)) {
        return Err(PlanError::new(
            ErrorCode::BearingForbidden,
            format!(
                "the reference runs at {} degrees, in the forbidden range {} to {} degrees",
                Decimals(driving.to_degrees().rem_euclid(360.0), 1),
                Shortest(r.from_deg),
                Shortest(r.to_deg)
            ),
        ));
    }
    let frame = SweepFrame::new(bearing);
    // The frame's across axis points right of the swath direction; right of a→b is the same
    // side when a→b runs the swath direction, the other when it runs against it.
    let same_way = (driving - bearing).abs() < 1e-9;
    let right = if same_way { 1.0 } else { -1.0 };
    // `%` on floats is exact; without it a huge offset would swallow the line's position.
    let offset = offset_m.unwrap_or(default_offset) % width;
    let across = frame.project(a).0 + right * offset;
    Ok((bearing, LinePlacement::Aligned { across }))
}

#[cfg(test)]
mod tests {
    use super::*;
    use geo::{coord, polygon};

    #[test]
    fn fixed_bearing_is_folded() {
        use crate::field::Frame;
        let f = Field {
            boundary: polygon![(x: 0., y: 0.), (x: 1., y: 0.), (x: 1., y: 1.)],
            drawn_boundary: vec![],
            obstacles: vec![],
            prohibited: vec![],
            name: None,
            feature: 0,
            frame: Frame::Metric,
            entrance: None,
            reference_line: None,
        };
        let b = choose_bearing(&f, DirectionRule::Fixed { bearing_deg: 270.0 }, &[]).unwrap();
        assert!((b.to_degrees() - 90.0).abs() < 1e-9);
        let drains = [BearingRange {
            from_deg: 260.0,
            to_deg: 280.0,
        }];
        let e =
            choose_bearing(&f, DirectionRule::Fixed { bearing_deg: 90.0 }, &drains).unwrap_err();
        assert_eq!(e.code, ErrorCode::BearingForbidden);
    }

    #[test]
    fn all_edges_forbidden_takes_the_nearest_allowed_direction() {
        use crate::field::Frame;
        let f = Field {
            boundary: polygon![(x: 0., y: 0.), (x: 100., y: 0.), (x: 100., y: 10.), (x: 0., y: 10.)],
            drawn_boundary: vec![],
            obstacles: vec![],
            prohibited: vec![],
            name: None,
            feature: 0,
            frame: Frame::Metric,
            entrance: None,
            reference_line: None,
        };
        let forbidden = [
            BearingRange {
                from_deg: 60.0,
                to_deg: 100.0,
            },
            BearingRange {
                from_deg: 170.0,
                to_deg: 190.0,
            },
        ];
        let rule = DirectionRule::LongestEdge { tolerance_m: 1.0 };
        let b = choose_bearing(&f, rule, &forbidden).unwrap().to_degrees();
        assert!((b - 100.0).abs() < 0.01, "{b}");
    }

    #[test]
    fn reference_offsets_count_modulo_the_width() {
        let line = Some([coord! { x: 10., y: 0. }, coord! { x: 10., y: 50. }]);
        let across = |offset: f64| {
            let (_, placement) =
                reference_direction(line, None, &[], Some(offset), 6.0, &[]).unwrap();
            match placement {
                LinePlacement::Aligned { across } => across,
                LinePlacement::FromEdge => panic!("a reference aligns the grid"),
            }
        };
        // Under one width the offset is used as given.
        assert_eq!(across(3.0), 13.0);
        assert_eq!(across(-3.0), 7.0);
        // 10^17 = 6 * 16666666666666666 + 4, in integers.
        assert_eq!(100_000_000_000_000_000u64 % 6, 4);
        assert_eq!(across(1e17), across(4.0));
        assert_eq!(across(1e17), 14.0);
        assert_eq!(across(-1e17), 6.0);
        assert_eq!(across(6.0 * 1000.0 + 1.5), 11.5);
    }

    #[test]
    fn noisy_long_edge_still_wins() {
        // A 300 m edge recorded as 60 noisy 5 m pieces, against 200 m straight sides.
        let mut pts = vec![];
        for i in 0..=60 {
            let wobble = if i % 2 == 0 { 0.3 } else { -0.3 };
            pts.push(coord! { x: i as f64 * 5.0, y: wobble });
        }
        pts.push(coord! { x: 300.0, y: 200.0 });
        pts.push(coord! { x: 0.0, y: 200.0 });
        pts.push(pts[0]);
        let edges = edges_longest_first(&LineString::new(pts), 3.0);
        let b = edges[0].1;
        assert!((b.to_degrees() - 90.0).abs() < 0.5, "{}", b.to_degrees());
    }
}
