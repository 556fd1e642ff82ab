//! Oksanen & Visala's split-and-merge decomposition (2.2-2.8): blocks, each with its own
//! driving direction, chosen one at a time.
//!
//! At each candidate direction the area left to plan is split into trapezoids and merged into
//! cells ([`super::cells`], sides matching exactly and ends at least 20 degrees to the
//! direction); every cell is scored by the weighted criterion of 2.5 and the direction's cost is
//! that of its best cell. The direction search (coarse-to-fine, 2.6, or brute force) finds the
//! best direction, its best cell becomes a block, is removed from the area, and the search runs
//! again on what is left, in the paper until all of it is covered; here for the first
//! [`GREEDY_BLOCKS`] blocks, and what is left after them is cut into cells. Where an edge
//! direction (or one already chosen) within two degrees of the best scores nearly as well, the
//! block takes it: drivers work along an edge where they can. Prohibited regions (2.8) take
//! part in the split: at a direction a region forbids it is an obstacle, so no block of that
//! direction reaches into it.
//!
//! Refinements over the paper: a cell's swaths and turns are counted exactly (its swath lines
//! clipped to it, turns by the turn model of [`crate::objective`]); curved edges do not shatter
//! the area into slivers, because the split only draws slab lines through the vertices a
//! Douglas-Peucker simplification keeps (and where the boundary turns back across the
//! direction); pieces too small to be blocks join a neighbour; and the greedy result is
//! improved ([`improve`]): each block at its own best direction, neighbours joined where one
//! block is faster than two.

use super::block_headlands::{borders, Border};
use super::cells::{merge_chains, outline, split_prepared, MergeRule, PreparedArea, Trapezoid};
use super::join::join_blocks_marked;
use super::redirect::{redirect_blocks, redirect_some};
use super::BlockArea;
use crate::direction::{
    edge_directions, nearest_allowed, quick_search, search_direction, SearchMethod,
};
use crate::error::PlanError;
use crate::field::ProhibitedRegion;
use crate::geometry::BooleanOps;
use crate::geometry::{forbids_every_direction, BearingRange, SweepFrame};
use crate::objective::{turn_length, Machine, TurnLengths};
use crate::prohibited::{constraints_in, forbidding, split};
use crate::route::pattern::SwathOrder;
use crate::sort::SharedSort;
use crate::swath::line_offsets;
use geo::{Area, BoundingRect, Intersects, MultiPolygon, Polygon};
use std::f64::consts::PI;

/// Oksanen & Visala's selection criterion (2.5): weights of the block's driving efficiency, its
/// share of the area left and its share of the work left, and the bonus for a direction already
/// chosen for another block, which keeps neighbouring blocks from differing by a few degrees.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Criterion {
    /// Weight of the efficiency: working time over working and turning time (0.65).
    pub efficiency: f64,
    /// Weight of the block's area over the area left (0.15).
    pub area: f64,
    /// Weight of the block's swath length against the ideal length of the area left, area over
    /// width (0.20).
    pub distance: f64,
    /// Added to the score of a direction within a tenth of a degree of a block already chosen.
    pub same_direction_bonus: f64,
    /// Share of the area left at which a block counts as substantial: its area and distance
    /// scores are its shares over this one, capped at 1, so that among substantial blocks the
    /// efficiency decides and a block is not chosen only for being large. 1 (the default) is
    /// the paper's normalisation by the area left.
    pub substantial_share: f64,
}

impl Default for Criterion {
    fn default() -> Self {
        Criterion {
            efficiency: 0.65,
            area: 0.15,
            distance: 0.20,
            same_direction_bonus: 0.02,
            substantial_share: 1.0,
        }
    }
}

/// What the split-and-merge decomposition needs besides the area.
#[derive(Debug, Clone, Copy)]
pub struct SplitMergeSettings<'a> {
    /// Working width, metres.
    pub width: f64,
    /// Swath pieces shorter than this (metres) are not counted as work.
    pub min_length: f64,
    /// The machine: turning radius and speeds for the efficiency.
    pub machine: Machine,
    /// How the direction of each block is searched.
    pub method: SearchMethod,
    /// Step of the brute-force search, degrees.
    pub step_deg: f64,
    /// Directions forbidden everywhere.
    pub forbidden: &'a [BearingRange],
    /// Prohibited regions: obstacles for the directions they forbid.
    pub regions: &'a [ProhibitedRegion],
    /// The selection criterion.
    pub criterion: Criterion,
    /// Trapezoids merge only if both ends are at least this steep to the direction (radians;
    /// 20 degrees in the paper).
    pub min_end_angle: f64,
    /// Douglas-Peucker tolerance of the split (metres): vertices within it of a straight line
    /// draw no slab line.
    pub tolerance: f64,
    /// The swath orders the route may work a block in ([`crate::route::pattern::candidates`]):
    /// a block's turns are estimated in the cheapest of them, as the route will drive them.
    /// Empty: boustrophedon.
    pub orders: &'a [SwathOrder],
}

/// The blocks of a split-and-merge decomposition.
#[derive(Debug, Clone, Default)]
pub struct SplitMerge {
    /// The blocks in the order they were selected, each with its direction.
    pub blocks: Vec<BlockArea>,
    /// Directions evaluated, over all selections.
    pub evaluations: usize,
    /// Prohibited regions (indices) whose ranges with the global ones leave no direction: they
    /// were left out of the area.
    pub not_worked: Vec<usize>,
}

/// How much worse (in score, 0 to 1) an edge direction near the best may be and still be taken.
const EDGE_PREFERENCE: f64 = 0.01;

/// Most directions of blocks already chosen that seed the search for the next block.
const CHOSEN_SEEDS: usize = 4;

/// Most blocks selected one by one (each a direction search); what is left after them is cut
/// into cells, whose directions `improve` searches. Five: against eight, planning the corpus's
/// obstacle fields took a fifth less time, and the plans changed by under 1 % of their time but
/// for the narrow curved strip, 2.4 % slower.
pub const GREEDY_BLOCKS: usize = 5;

/// The most cells split and merge takes on: boustrophedon cells of the area at the field's
/// direction. Its improvement ([`improve`]) searches each block's direction and weighs joining
/// each pair of neighbours, each a swath sweep, for each of its three starts: natively about
/// 10 ms a cell (the 109 cells of a small ragged field took 1.2 s, the 2,081 of a field of 2,000
/// obstacles 30 s). The corpus has up to 36.
pub const MAX_CELLS: usize = 150;

/// The most vertices of the area split and merge takes on: its greedy selection splits all of
/// it at each of a few hundred directions (the corpus has up to 1,800).
pub const MAX_VERTICES: usize = 10_000;

/// Whether split and merge takes on `area` (the inner field) at the field's direction
/// `bearing`: at most [`MAX_VERTICES`] vertices and [`MAX_CELLS`] cells (split with the
/// decomposition's `tolerance`); else why not, as a sentence.
///
/// ```
/// use furrow::decompose::split_merge::within_limits;
/// use geo::{polygon, MultiPolygon};
///
/// let field = polygon![(x: 0., y: 0.), (x: 300., y: 0.), (x: 300., y: 200.), (x: 0., y: 200.)];
/// assert!(within_limits(&MultiPolygon::new(vec![field.clone()]), 0.0, 3.0).is_ok());
/// // 200 ponds in a row across the direction: 401 cells.
/// let ponds: Vec<_> = (0..200)
///     .map(|i| {
///         let x = 1.0 + 1.4 * i as f64;
///         polygon![(x: x, y: 90.), (x: x + 0.5, y: 90.), (x: x + 0.5, y: 110.), (x: x, y: 110.)]
///             .exterior()
///             .clone()
///     })
///     .collect();
/// let holed = geo::Polygon::new(field.exterior().clone(), ponds);
/// assert!(within_limits(&MultiPolygon::new(vec![holed]), 0.0, 0.1).is_err());
/// ```
pub fn within_limits(area: &MultiPolygon, bearing: f64, tolerance: f64) -> Result<(), String> {
    use geo::CoordsIter;
    let vertices = area.coords_count();
    if vertices > MAX_VERTICES {
        return Err(format!(
            "its inner field has {vertices} vertices (split and merge takes on up to {MAX_VERTICES})"
        ));
    }
    let trapezoids = split_prepared(
        &PreparedArea::new(area, tolerance),
        &SweepFrame::new(bearing),
    );
    let cells = merge_chains(&trapezoids, MergeRule::Boustrophedon).len();
    if cells > MAX_CELLS {
        return Err(format!(
            "its inner field has {cells} cells (split and merge takes on up to {MAX_CELLS})"
        ));
    }
    Ok(())
}

/// Decomposes `area` into blocks, each with its own driving direction (see the module
/// documentation).
///
/// ```
/// use furrow::decompose::split_merge::{split_merge, Criterion, SplitMergeSettings};
/// use furrow::direction::SearchMethod;
/// use furrow::objective::Machine;
/// use geo::{polygon, Area, MultiPolygon};
///
/// // An L: a bar 60 m wide and 300 m long running north, and a foot 200 m long running east.
/// let l = polygon![(x: 0., y: 0.), (x: 260., y: 0.), (x: 260., y: 60.), (x: 60., y: 60.),
///                  (x: 60., y: 300.), (x: 0., y: 300.)];
/// let settings = SplitMergeSettings {
///     width: 3.0, min_length: 3.0,
///     machine: Machine { width: 3.0, turn_radius: 6.0, working_speed: 2.2, turning_speed: 1.4 },
///     method: SearchMethod::CoarseToFine, step_deg: 1.0, forbidden: &[], regions: &[],
///     criterion: Criterion::default(), min_end_angle: 20f64.to_radians(), tolerance: 1.5, orders: &[],
/// };
/// let d = split_merge(&MultiPolygon::new(vec![l.clone()]), &settings)?;
/// // Each arm worked along its length.
/// assert_eq!(d.blocks.len(), 2);
/// let mut bearings: Vec<f64> = d.blocks.iter().map(|b| b.bearing.to_degrees().round()).collect();
/// bearings.sort_by(f64::total_cmp);
/// assert_eq!(bearings, vec![0.0, 90.0]);
/// let sum: f64 = d.blocks.iter().map(|b| b.area.unsigned_area()).sum();
/// assert!((sum - l.unsigned_area()).abs() < 1e-6 * l.unsigned_area());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn split_merge(area: &MultiPolygon, s: &SplitMergeSettings) -> Result<SplitMerge, PlanError> {
    let mut out = SplitMerge::default();
    let mut remaining = area.clone();
    // Regions that leave no direction are not worked (the plan warns of them).
    for (i, r) in s.regions.iter().enumerate() {
        let mut all = s.forbidden.to_vec();
        all.extend(r.forbidden.iter().copied());
        if forbids_every_direction(&all) {
            out.not_worked.push(i);
            remaining = remaining.difference(&MultiPolygon::new(vec![r.polygon.clone()]));
        }
    }
    let total = remaining.unsigned_area();
    let min_piece = (s.width * s.width * 1e-2).max(total * 1e-9);
    remaining = drop_small(remaining, min_piece);
    // Seeds: the directions just inside each region's allowed range, so that every region has
    // a direction it allows among those evaluated.
    let mut region_seeds: Vec<f64> = Vec::new();
    for r in s.regions {
        let mut all = s.forbidden.to_vec();
        all.extend(r.forbidden.iter().copied());
        if let Some(b) = nearest_allowed(0.0, &all) {
            region_seeds.push(b);
        }
    }
    while !remaining.0.is_empty() && out.blocks.len() < GREEDY_BLOCKS {
        let left = remaining.unsigned_area();
        let chosen: Vec<f64> = out.blocks.iter().map(|b| b.bearing).collect();
        let mut seeds = edge_directions(remaining.0.iter().map(|p| p.exterior()), s.width / 2.0);
        // The directions chosen so far (each once, the most recent first, a few of them), and
        // one allowed in each region.
        let mut distinct: Vec<f64> = Vec::new();
        for &c in chosen.iter().rev() {
            let near = |d: &f64| {
                let x = (c - d).rem_euclid(PI);
                x.min(PI - x) < 0.5f64.to_radians()
            };
            if !distinct.iter().any(near) && distinct.len() < CHOSEN_SEEDS {
                distinct.push(c);
            }
        }
        seeds.extend(distinct);
        seeds.extend(region_seeds.iter().copied());
        // The area left at each set of regions cut out, prepared for splitting.
        let mut cut_cache: Vec<(Vec<usize>, (PreparedArea, PreparedArea))> = Vec::new();
        // The first block gets the full search; later ones, with the directions chosen so far
        // among the seeds, a quick one.
        let search = if out.blocks.is_empty() {
            search_direction
        } else {
            quick_search
        };
        let found = search(s.method, s.step_deg, s.forbidden, &seeds, |b| {
            let i = prepared_at(&mut cut_cache, &remaining, b, s);
            // Scored on the simplified area; the block itself is cut from the exact one.
            match best_cell(&cut_cache[i].1 .1, b, left, &chosen, s) {
                Some((score, _)) => 1.0 - score,
                None => f64::INFINITY,
            }
        });
        let best = match found {
            Ok(r) if r.cost.is_finite() => {
                out.evaluations += r.evaluations;
                // Drivers work along an edge where they can: an edge direction (or one already
                // chosen) within two degrees of the best that scores nearly as well is taken.
                let mut bearing = r.bearing;
                let mut best_cost = r.cost;
                for &seed in &seeds {
                    let Some(b) = nearest_allowed(seed, s.forbidden) else {
                        continue;
                    };
                    let d = (b - r.bearing).rem_euclid(PI);
                    if d.min(PI - d) > 2f64.to_radians() || (b - r.bearing).abs() < 1e-12 {
                        continue;
                    }
                    let i = prepared_at(&mut cut_cache, &remaining, b, s);
                    out.evaluations += 1;
                    if let Some((score, _)) = best_cell(&cut_cache[i].1 .1, b, left, &chosen, s) {
                        let cost = 1.0 - score;
                        if cost <= r.cost + EDGE_PREFERENCE && cost < best_cost + EDGE_PREFERENCE {
                            bearing = b;
                            best_cost = cost.min(best_cost);
                        }
                    }
                }
                let i = prepared_at(&mut cut_cache, &remaining, bearing, s);
                best_cell(&cut_cache[i].1 .0, bearing, left, &chosen, s).map(|(_, p)| (bearing, p))
            }
            Ok(r) => {
                out.evaluations += r.evaluations;
                None
            }
            Err(e) => return Err(e),
        };
        let Some((bearing, polygon)) = best else {
            break;
        };
        let block = MultiPolygon::new(vec![polygon]);
        remaining = drop_small(remaining.difference(&block), min_piece);
        out.blocks.push(BlockArea {
            area: block,
            bearing,
        });
    }
    // What the selection left. Beyond the first blocks a greedy step costs a full direction
    // search for little gain: larger pieces are cut into boustrophedon cells at the last
    // direction chosen (their directions are searched again by `improve`). Pieces too small to
    // be blocks of their own (a rounded inner corner between two blocks, a sliver along an
    // oblique edge) join the block they share the longest border with, if it may be driven in
    // them; others become blocks of their own, in a direction every region they reach into
    // allows.
    let mut pieces = std::mem::take(&mut remaining.0);
    pieces.shared_sort_by(|a, b| b.unsigned_area().total_cmp(&a.unsigned_area()));
    let (small, large): (Vec<Polygon>, Vec<Polygon>) = pieces
        .into_iter()
        .partition(|p| p.unsigned_area() < small_cell(s));
    if !large.is_empty() {
        let last = out.blocks.last().map_or(0.0, |b| b.bearing);
        let (cells, not_worked) =
            cells_at(&MultiPolygon::new(large), last, MergeRule::Boustrophedon, s);
        out.blocks.extend(cells);
        for r in not_worked {
            if !out.not_worked.contains(&r) {
                out.not_worked.push(r);
            }
        }
    }
    for piece in small {
        let allowed = constraints_in(
            &MultiPolygon::new(vec![piece.clone()]),
            s.regions,
            s.forbidden,
            min_piece,
        );
        let mut target: Option<(f64, usize)> = None;
        for (k, b) in out.blocks.iter().enumerate() {
            if allowed.iter().any(|r| r.forbids(b.bearing)) {
                continue;
            }
            let shared = shared_border(&b.area, &piece);
            if shared > 0.0 && target.is_none_or(|(l, _)| shared > l) {
                target = Some((shared, k));
            }
        }
        match target {
            Some((_, k)) => {
                let joined = out.blocks[k].area.union(&MultiPolygon::new(vec![piece]));
                out.blocks[k].area = joined;
            }
            None => {
                let seed = edge_directions(std::iter::once(piece.exterior()), s.width / 2.0)
                    .first()
                    .copied()
                    .unwrap_or(0.0);
                if let Some(bearing) = nearest_allowed(seed, &allowed) {
                    out.blocks.push(BlockArea {
                        area: MultiPolygon::new(vec![piece]),
                        bearing,
                    });
                }
            }
        }
    }
    let (blocks, evaluations) = improve(std::mem::take(&mut out.blocks), s)?;
    out.blocks = blocks;
    out.evaluations += evaluations;
    Ok(out)
}

/// Improves a decomposition (the greedy selection's, or another such as the boustrophedon
/// cells of the field's best direction): each block at its own best direction
/// ([`redirect_blocks`]), neighbouring blocks joined while that saves time
/// ([`join_blocks`](super::join::join_blocks)), and the directions searched once more for the
/// joined blocks. Returns the blocks and the
/// directions evaluated.
pub fn improve(
    blocks: Vec<BlockArea>,
    s: &SplitMergeSettings,
) -> Result<(Vec<BlockArea>, usize), PlanError> {
    let (blocks, first) = redirect_blocks(blocks, s)?;
    let (blocks, joined) = join_blocks_marked(blocks, s)?;
    let (blocks, second) = redirect_some(blocks, &joined, s)?;
    Ok((blocks, first + second))
}

/// The cells of `area` at `bearing` (merged by `rule`) as blocks, with the prohibited regions that
/// forbid the bearing cut out and each part given the allowed direction nearest to it (their
/// best directions are for [`improve`] to find). Returns the blocks and the regions (indices)
/// that with the global ranges leave no direction.
///
/// ```
/// use furrow::decompose::cells::MergeRule;
/// use furrow::decompose::split_merge::{cells_at, Criterion, SplitMergeSettings};
/// use furrow::direction::SearchMethod;
/// use furrow::objective::Machine;
/// use geo::{polygon, MultiPolygon};
///
/// let field = polygon!(
///     exterior: [(x: 0., y: 0.), (x: 60., y: 0.), (x: 60., y: 100.), (x: 0., y: 100.)],
///     interiors: [[(x: 20., y: 40.), (x: 40., y: 40.), (x: 40., y: 60.), (x: 20., y: 60.)]],
/// );
/// let s = SplitMergeSettings {
///     width: 6.0, min_length: 6.0,
///     machine: Machine { width: 6.0, turn_radius: 8.0, working_speed: 2.2, turning_speed: 1.4 },
///     method: SearchMethod::CoarseToFine, step_deg: 1.0, forbidden: &[], regions: &[],
///     criterion: Criterion::default(), min_end_angle: 20f64.to_radians(), tolerance: 3.0, orders: &[],
/// };
/// let (blocks, not_worked) = cells_at(&MultiPolygon::new(vec![field]), 0.0, MergeRule::Boustrophedon, &s);
/// assert_eq!((blocks.len(), not_worked.len()), (4, 0));
/// ```
pub fn cells_at(
    area: &MultiPolygon,
    bearing: f64,
    rule: MergeRule,
    s: &SplitMergeSettings,
) -> (Vec<BlockArea>, Vec<usize>) {
    let cut = forbidding(s.regions, bearing);
    let (main, parts) = split(area, s.regions, &cut, s.forbidden);
    let frame = SweepFrame::new(bearing);
    let trapezoids = split_prepared(&PreparedArea::new(&main, s.tolerance), &frame);
    let mut blocks: Vec<BlockArea> = merge_chains(&trapezoids, rule)
        .iter()
        .map(|c| BlockArea {
            area: MultiPolygon::new(vec![outline(&trapezoids, c, &frame)]),
            bearing,
        })
        .collect();
    let mut not_worked = Vec::new();
    for part in parts {
        match nearest_allowed(bearing, &part.forbidden) {
            Some(b) => blocks.push(BlockArea {
                area: part.area,
                bearing: b,
            }),
            None => not_worked.push(part.region),
        }
    }
    (blocks, not_worked)
}

/// Cells smaller than this (square metres) are not blocks of their own: four swath widths
/// squared.
fn small_cell(s: &SplitMergeSettings) -> f64 {
    4.0 * s.width * s.width
}

/// Length of the border a block and a piece share, metres.
fn shared_border(block: &MultiPolygon, piece: &Polygon) -> f64 {
    let two = [
        BlockArea {
            area: block.clone(),
            bearing: 0.0,
        },
        BlockArea {
            area: MultiPolygon::new(vec![piece.clone()]),
            bearing: 0.0,
        },
    ];
    borders(&two, 1e-3).iter().map(Border::length).sum()
}

/// The index in `cache` of the area left at `bearing` (less the regions forbidding it),
/// prepared for splitting, exact and simplified; computed once per set of regions.
fn prepared_at(
    cache: &mut Vec<(Vec<usize>, (PreparedArea, PreparedArea))>,
    remaining: &MultiPolygon,
    bearing: f64,
    s: &SplitMergeSettings,
) -> usize {
    let cut = forbidding(s.regions, bearing);
    if let Some(i) = cache.iter().position(|(k, _)| *k == cut) {
        return i;
    }
    let mut a = remaining.clone();
    for &k in &cut {
        if let Some(r) = s.regions.get(k) {
            if intersects_box(&a, &r.polygon) {
                a = a.difference(&MultiPolygon::new(vec![r.polygon.clone()]));
            }
        }
    }
    let exact = PreparedArea::new(&a, s.tolerance);
    let rough = exact.simplified();
    cache.push((cut, (exact, rough)));
    cache.len() - 1
}

/// The pieces of `m` of at least `min_area` square metres.
fn drop_small(m: MultiPolygon, min_area: f64) -> MultiPolygon {
    MultiPolygon::new(
        m.0.into_iter()
            .filter(|p| p.unsigned_area() >= min_area)
            .collect(),
    )
}

/// Whether the bounding boxes of `a` and `p` meet.
fn intersects_box(a: &MultiPolygon, p: &Polygon) -> bool {
    match (a.bounding_rect(), p.bounding_rect()) {
        (Some(x), Some(y)) => x.intersects(&y),
        _ => false,
    }
}

/// The best cell of `area` at `bearing` by the criterion, and its outline.
fn best_cell(
    area: &PreparedArea,
    bearing: f64,
    left_m2: f64,
    chosen: &[f64],
    s: &SplitMergeSettings,
) -> Option<(f64, Polygon)> {
    let frame = SweepFrame::new(bearing);
    let trapezoids = split_prepared(area, &frame);
    let cells = merge_chains(
        &trapezoids,
        MergeRule::SplitMerge {
            min_end_angle: s.min_end_angle,
        },
    );
    let same = chosen.iter().any(|&c| {
        let d = (c - bearing).rem_euclid(PI);
        d.min(PI - d) < 0.1f64.to_radians()
    });
    let bonus = if same {
        s.criterion.same_direction_bonus
    } else {
        0.0
    };
    // Largest first: the score is bounded by the area (efficiency is at most 1), so once a cell
    // scores well the smaller ones that cannot beat it are not counted.
    let c = &s.criterion;
    let substantial = left_m2 * c.substantial_share.clamp(1e-6, 1.0);
    let mut by_area: Vec<(f64, usize)> = cells
        .iter()
        .enumerate()
        .map(|(i, cell)| {
            let a: f64 = cell
                .iter()
                .filter_map(|&t| trapezoids.get(t))
                .map(Trapezoid::area)
                .sum();
            (a, i)
        })
        .filter(|&(a, _)| a >= small_cell(s))
        .collect();
    by_area.shared_sort_unstable_by(|x, y| y.0.total_cmp(&x.0).then(x.1.cmp(&y.1)));
    let mut best: Option<(f64, usize)> = None;
    for (a, i) in by_area {
        let bound = c.efficiency + (c.area + c.distance) * (a / substantial).min(1.0) + bonus;
        if best.is_some_and(|(b, _)| bound < b) {
            break;
        }
        let work = cell_work(&trapezoids, &cells[i], s);
        let score = score(&work, left_m2, s) + bonus;
        // Ties go to the cell found first across the field, whatever the order of counting.
        if best.is_none_or(|(b, bi)| score > b || (score == b && i < bi)) {
            best = Some((score, i));
        }
    }
    let (score, i) = best?;
    cells
        .get(i)
        .map(|c| (score, outline(&trapezoids, c, &frame)))
}

/// The work in a cell at its direction: its swaths clipped to it and the turns between them.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct CellWork {
    /// Area of the cell, square metres.
    pub area_m2: f64,
    /// Number of swaths at least the minimum length.
    pub swath_count: usize,
    /// Their total length, metres.
    pub swath_length_m: f64,
    /// Turns between them by the turn model, with the run along the end, metres.
    pub turning_m: f64,
}

/// Counts the swaths and turns of a cell of a split (see [`CellWork`]).
pub fn cell_work(trapezoids: &[Trapezoid], cell: &[usize], s: &SplitMergeSettings) -> CellWork {
    let ts: Vec<&Trapezoid> = cell.iter().filter_map(|&i| trapezoids.get(i)).collect();
    let (Some(first), Some(last)) = (ts.first(), ts.last()) else {
        return CellWork::default();
    };
    let mut work = CellWork {
        area_m2: ts.iter().map(|t| t.area()).sum(),
        ..CellWork::default()
    };
    let mut previous: Option<(f64, (f64, f64))> = None;
    let mut k = 0;
    let mut lengths = TurnLengths::new(s.machine.turn_radius);
    for c in line_offsets(first.across.0, last.across.1, s.width) {
        let t = ts.partition_point(|t| t.across.1 < c).min(ts.len() - 1);
        let (a0, a1) = ts[t].ends_at(c);
        if a1 - a0 < s.min_length.max(1e-6) {
            continue;
        }
        work.swath_count += 1;
        work.swath_length_m += a1 - a0;
        if let Some((pc, (p0, p1))) = previous {
            // Boustrophedon: turns alternate between the upper and the lower end.
            let run = if k % 2 == 0 {
                (a1 - p1).abs()
            } else {
                (a0 - p0).abs()
            };
            work.turning_m += lengths.of(c - pc) + run;
            k += 1;
        }
        previous = Some((c, (a0, a1)));
    }
    work
}

/// The criterion's score of a cell (higher is better), `left_m2` the area left to plan.
fn score(w: &CellWork, left_m2: f64, s: &SplitMergeSettings) -> f64 {
    if w.swath_count == 0 || left_m2 <= 0.0 {
        return f64::NEG_INFINITY;
    }
    let m = &s.machine;
    // A sliver narrower than a width has a swath line, but not a swath's work.
    let useful = w.swath_length_m.min(w.area_m2 / s.width);
    let working = useful / m.working_speed;
    // Reaching the block and leaving it costs a turn, so a block of one swath is not "perfectly
    // efficient".
    let turning = (w.turning_m + turn_length(s.width, m.turn_radius)) / m.turning_speed;
    let efficiency = working / (working + turning);
    let c = &s.criterion;
    let substantial = left_m2 * c.substantial_share.clamp(1e-6, 1.0);
    let area = (w.area_m2 / substantial).min(1.0);
    let distance = (useful * s.width / substantial).min(1.0);
    c.efficiency * efficiency + c.area * area + c.distance * distance
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use geo::polygon;

    /// Settings of a 6 m machine turning on 8 m, working 8 km/h and turning 5 km/h, for tests
    /// here and of the other decomposition steps.
    pub(crate) fn settings<'a>(regions: &'a [ProhibitedRegion]) -> SplitMergeSettings<'a> {
        SplitMergeSettings {
            width: 6.0,
            min_length: 6.0,
            machine: Machine {
                width: 6.0,
                turn_radius: 8.0,
                working_speed: 8.0 / 3.6,
                turning_speed: 5.0 / 3.6,
            },
            method: SearchMethod::CoarseToFine,
            step_deg: 1.0,
            forbidden: &[],
            regions,
            criterion: Criterion::default(),
            min_end_angle: 20f64.to_radians(),
            tolerance: 3.0,
            orders: &[],
        }
    }

    #[test]
    fn a_rectangle_is_one_block_along_its_length() {
        let r = polygon![(x: 0., y: 0.), (x: 400., y: 0.), (x: 400., y: 100.), (x: 0., y: 100.)];
        let d = split_merge(&MultiPolygon::new(vec![r]), &settings(&[])).unwrap();
        assert_eq!(d.blocks.len(), 1);
        assert!((d.blocks[0].bearing.to_degrees() - 90.0).abs() < 1e-6);
    }

    #[test]
    fn a_prohibited_region_is_an_obstacle_for_its_forbidden_directions() {
        // A 400 x 100 field, its east end (100 x 100) may not be driven east-west.
        let r = polygon![(x: 0., y: 0.), (x: 400., y: 0.), (x: 400., y: 100.), (x: 0., y: 100.)];
        let region = ProhibitedRegion {
            polygon: polygon![(x: 300., y: 0.), (x: 400., y: 0.), (x: 400., y: 100.), (x: 300., y: 100.)],
            forbidden: vec![BearingRange {
                from_deg: 60.0,
                to_deg: 120.0,
            }],
            feature: 1,
            name: None,
        };
        let regions = [region];
        let d = split_merge(&MultiPolygon::new(vec![r.clone()]), &settings(&regions)).unwrap();
        assert!(d.blocks.len() >= 2);
        let sum: f64 = d.blocks.iter().map(|b| b.area.unsigned_area()).sum();
        assert!((sum - r.unsigned_area()).abs() < 1e-6 * r.unsigned_area());
        for b in &d.blocks {
            let inside = b
                .area
                .intersection(&MultiPolygon::new(vec![regions[0].polygon.clone()]))
                .unsigned_area();
            if inside > 1.0 {
                assert!(
                    !regions[0].forbidden[0].forbids(b.bearing),
                    "block at {} in the region",
                    b.bearing.to_degrees()
                );
            }
        }
    }
}
