//! Joining neighbouring blocks while it saves time.
//!
//! Split and merge chooses blocks greedily, one at a time, and cannot see what a choice leaves
//! behind: an arm cut off at a slightly different direction than its neighbour, a sliver along
//! an oblique edge, a corner piece. This step looks at every pair of blocks that share a border
//! at least a working width long, and at the time each would take worked as one block, at the
//! direction of either (where every prohibited region it reaches into allows it): its swaths,
//! the turns between them by the turn model, the crop it leaves uncovered at working speed, and
//! one turn to reach the block. The pair that saves the most is joined, and so on while a join
//! saves time.

use super::block_headlands::borders;
use super::split_merge::SplitMergeSettings;
use super::BlockArea;
use crate::decompose::block_members;
use crate::error::PlanError;
use crate::geometry::BooleanOps;
use crate::geometry::PlanarSimplify;
use crate::objective::{
    measure, measure_turns_in, turn_length, Objective, OperationTime, SwathStats, TurnLengths,
};
use crate::prohibited::constraints_in;
use crate::route::pattern::block_turning_m;
use crate::sort::SharedSort;
use crate::swath::{generate_with, LinePlacement, Swath, SwathSettings};
use geo::{Area, MultiPolygon};

/// Estimated time (seconds) to work `area` as one block at swath direction `bearing`: swaths,
/// turns and the uncovered area (estimated: the area less the strips') by [`OperationTime`],
/// and the way to reach the block (a turn and half a swath's length).
pub fn block_time(
    area: &MultiPolygon,
    bearing: f64,
    s: &SplitMergeSettings,
) -> Result<f64, PlanError> {
    let swaths = block_swaths(area, bearing, s)?;
    let blocks = block_members(&swaths);
    let stats = measure_turns_in(&swaths, &blocks, s.width, area.unsigned_area(), &s.machine);
    let stats = in_pattern(stats, &swaths, &blocks, s);
    Ok(OperationTime.cost(&stats, &s.machine) + entry_time(&stats, s))
}

/// [`block_time`] with the uncovered area measured exactly rather than estimated: for the
/// final word between two directions of a block.
pub fn exact_block_time(
    area: &MultiPolygon,
    bearing: f64,
    s: &SplitMergeSettings,
) -> Result<f64, PlanError> {
    let swaths = block_swaths(area, bearing, s)?;
    let stats = measure(&swaths, s.width, area, &s.machine);
    let stats = in_pattern(stats, &swaths, &block_members(&swaths), s);
    Ok(OperationTime.cost(&stats, &s.machine) + entry_time(&stats, s))
}

/// `stats` with the turns inside each block (cluster of swaths) counted in the cheapest of the
/// route's orders ([`block_turning_m`]) instead of boustrophedon: snakes that skip swaths turn
/// in U-turns where boustrophedon needs loops, and a block is worth what the route makes of it.
fn in_pattern(
    mut stats: SwathStats,
    swaths: &[Swath],
    blocks: &[Vec<usize>],
    s: &SplitMergeSettings,
) -> SwathStats {
    if s.orders.is_empty() {
        return stats;
    }
    let within: f64 = blocks
        .iter()
        .map(|ids| {
            block_turning_m(
                ids,
                swaths,
                s.orders,
                TurnLengths::new(s.machine.turn_radius),
            )
        })
        .sum();
    stats.turning_distance_m = within + stats.block_change_m;
    stats
}

/// The swaths of `area` as a block of its own at `bearing` (the first line half a width in).
fn block_swaths(
    area: &MultiPolygon,
    bearing: f64,
    s: &SplitMergeSettings,
) -> Result<Vec<Swath>, PlanError> {
    let settings = SwathSettings {
        bearing,
        width: s.width,
        min_length: s.min_length,
        placement: LinePlacement::FromEdge,
    };
    Ok(generate_with(area, &settings)?.swaths)
}

/// The time to reach a block from the one before, seconds: a turn, and on average half a
/// swath's length, since the side on which the block before ends (by the parity of its
/// swaths) and the side on which this one starts are as often the same as not.
fn entry_time(stats: &SwathStats, s: &SplitMergeSettings) -> f64 {
    let mean = if stats.swath_count > 0 {
        stats.swath_length_m / stats.swath_count as f64
    } else {
        0.0
    };
    (turn_length(s.width, s.machine.turn_radius) + mean / 2.0) / s.machine.turning_speed
}

/// A block's outline simplified for the many estimates of [`block_time`]: Douglas-Peucker to a
/// tenth of a working width. Borders between blocks are mostly straight, and keep their place
/// (only vertices in line are dropped there); curved edges, such as the rounded corners of
/// headlands, lose most of their vertices, which the swath sweep would sort at every estimate.
pub fn rough(area: &MultiPolygon, s: &SplitMergeSettings) -> MultiPolygon {
    area.planar_simplify((s.width / 10.0).max(0.01))
}

/// A join considered: the blocks (slots), the time it saves, the joined block's direction and
/// time.
struct Join {
    a: usize,
    b: usize,
    saving: f64,
    bearing: f64,
    time: f64,
}

/// Joins neighbouring blocks while a join saves time (see the module documentation). The
/// blocks keep their order; a joined block takes the place of the earlier of the two.
///
/// ```
/// use furrow::decompose::join::join_blocks;
/// use furrow::decompose::split_merge::{Criterion, SplitMergeSettings};
/// use furrow::decompose::BlockArea;
/// use furrow::direction::SearchMethod;
/// use furrow::objective::Machine;
/// use geo::{polygon, MultiPolygon};
///
/// // A 300 x 60 strip cut in two halves worked east-west: one block saves a turn onto the
/// // second half.
/// let west = polygon![(x: 0., y: 0.), (x: 150., y: 0.), (x: 150., y: 60.), (x: 0., y: 60.)];
/// let east = polygon![(x: 150., y: 0.), (x: 300., y: 0.), (x: 300., y: 60.), (x: 150., y: 60.)];
/// let s = SplitMergeSettings {
///     width: 6.0, min_length: 6.0,
///     machine: Machine { width: 6.0, turn_radius: 8.0, working_speed: 2.2, turning_speed: 1.4 },
///     method: SearchMethod::CoarseToFine, step_deg: 1.0, forbidden: &[], regions: &[],
///     criterion: Criterion::default(), min_end_angle: 20f64.to_radians(), tolerance: 3.0, orders: &[],
/// };
/// let east_west = std::f64::consts::FRAC_PI_2;
/// let blocks = vec![
///     BlockArea { area: MultiPolygon::new(vec![west]), bearing: east_west },
///     BlockArea { area: MultiPolygon::new(vec![east]), bearing: 0.0 },
/// ];
/// let joined = join_blocks(blocks, &s)?;
/// assert_eq!(joined.len(), 1);
/// assert_eq!(joined[0].bearing, east_west);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn join_blocks(
    blocks: Vec<BlockArea>,
    s: &SplitMergeSettings,
) -> Result<Vec<BlockArea>, PlanError> {
    Ok(join_blocks_marked(blocks, s)?.0)
}

/// [`join_blocks`], with a mark for each block that is the join of several.
///
/// While blocks join, a joined block is its parts side by side (and its rough outline those of
/// its parts), which the swath sweep works as one; each joined block's outline is made once, at
/// the end, by one union of all its parts. (Made at every join, the unions were a tenth of the
/// planning time of the obstacle fields, a sixth of the 210 ha field's: a block grown join by
/// join was united again at each.)
pub fn join_blocks_marked(
    blocks: Vec<BlockArea>,
    s: &SplitMergeSettings,
) -> Result<(Vec<BlockArea>, Vec<bool>), PlanError> {
    let min_area = s.width * s.width * 1e-2;
    let mut slots: Vec<Option<BlockArea>> = blocks.into_iter().map(Some).collect();
    let mut changed = vec![false; slots.len()];
    let mut roughs: Vec<MultiPolygon> = slots.iter().flatten().map(|b| rough(&b.area, s)).collect();
    let mut times: Vec<f64> = Vec::with_capacity(slots.len());
    for (b, r) in slots.iter().flatten().zip(&roughs) {
        times.push(block_time(r, b.bearing, s)?);
    }
    // Blocks that share a border of a width or more; kept up to date as blocks join (the
    // joined block borders what either did).
    let all_borders = borders(&blocks_of(&slots), s.width);
    let mut pairs: Vec<(usize, usize)> = all_borders.iter().map(|b| (b.first, b.second)).collect();
    pairs.shared_sort_unstable_by(Ord::cmp);
    pairs.dedup();
    // A block with no swath of its own (a strip narrower than a swath beside an edge that
    // runs along the direction) is not worth a visit, but the crop in it is: it joins the
    // neighbour it shares the longest border with, where that neighbour's direction is allowed,
    // whatever the time.
    for k in 0..slots.len() {
        let Some(b) = &slots[k] else {
            continue;
        };
        if swath_count(&roughs[k], b.bearing, s)? > 0 {
            continue;
        }
        let allowed = constraints_in(&b.area, s.regions, s.forbidden, min_area);
        let mut target: Option<(f64, usize)> = None;
        for &(x, y) in &pairs {
            let other = match (x == k, y == k) {
                (true, _) => y,
                (_, true) => x,
                _ => continue,
            };
            let Some(o) = &slots[other] else {
                continue;
            };
            if allowed.iter().any(|r| r.forbids(o.bearing)) {
                continue;
            }
            let shared: f64 = all_borders
                .iter()
                .filter(|d| (d.first, d.second) == (x, y))
                .map(|d| d.length())
                .sum();
            if target.is_none_or(|(l, _)| shared > l) {
                target = Some((shared, other));
            }
        }
        let Some((_, other)) = target else {
            continue;
        };
        let (Some(o), Some(b)) = (&slots[other], &slots[k]) else {
            continue;
        };
        let joined = BlockArea {
            area: side_by_side(&[&o.area, &b.area]),
            bearing: o.bearing,
        };
        roughs[other] = side_by_side(&[&roughs[other], &roughs[k]]);
        times[other] = block_time(&roughs[other], joined.bearing, s)?;
        slots[other] = Some(joined);
        changed[other] = true;
        slots[k] = None;
        rename(&mut pairs, k, other);
    }
    // Joins evaluated, by pair of slots; `None` where a join does not fit or saves nothing.
    let mut cache: Vec<((usize, usize), Option<Join>)> = Vec::new();
    // Joins of three evaluated that saved nothing.
    let mut tried: Vec<[usize; 3]> = Vec::new();
    loop {
        for &(a, b) in &pairs {
            if cache.iter().any(|(k, _)| *k == (a, b)) {
                continue;
            }
            let (Some(x), Some(y)) = (&slots[a], &slots[b]) else {
                continue;
            };
            // Evaluated on the two blocks side by side: the swath sweep joins pieces that meet
            // at the border. A joined block stays its parts side by side while blocks join;
            // its outline (a boolean union) is made once, at the end.
            let union = side_by_side(&[&roughs[a], &roughs[b]]);
            let mut best: Option<Join> = None;
            if !union.0.is_empty() {
                let allowed = constraints_in(&union, s.regions, s.forbidden, min_area);
                // A block much smaller than its neighbour joins at the neighbour's direction;
                // blocks of a size try both.
                let (ax, ay) = (x.area.unsigned_area(), y.area.unsigned_area());
                let bearings: &[f64] = if ax > 2.0 * ay {
                    &[x.bearing]
                } else if ay > 2.0 * ax {
                    &[y.bearing]
                } else {
                    &[x.bearing, y.bearing]
                };
                for &bearing in bearings {
                    if allowed.iter().any(|r| r.forbids(bearing)) {
                        continue;
                    }
                    let time = block_time(&union, bearing, s)?;
                    let saving = times[a] + times[b] - time;
                    if saving > 1e-6 && best.as_ref().is_none_or(|j| saving > j.saving) {
                        best = Some(Join {
                            a,
                            b,
                            saving,
                            bearing,
                            time,
                        });
                    }
                }
            }
            cache.push(((a, b), best));
        }
        let mut pick: Option<usize> = None;
        for (k, (pair, join)) in cache.iter().enumerate() {
            let Some(j) = join else {
                continue;
            };
            if !pairs.contains(pair) {
                continue;
            }
            let better = match pick.and_then(|p| cache[p].1.as_ref()) {
                Some(best) => j.saving > best.saving,
                None => true,
            };
            if better {
                pick = Some(k);
            }
        }
        let Some(k) = pick else {
            // No two blocks are faster as one: perhaps a sliver between two blocks of one
            // direction, which neither takes on its own, joins them into one.
            let Some((keep, joined, time, gone)) =
                best_triple(&slots, &roughs, &times, &pairs, s, min_area, &mut tried)?
            else {
                break;
            };
            tried.retain(|t| !t.contains(&keep) && !t.contains(&gone[0]) && !t.contains(&gone[1]));
            roughs[keep] = side_by_side(&[&roughs[keep], &roughs[gone[0]], &roughs[gone[1]]]);
            changed[keep] = true;
            slots[keep] = Some(joined);
            times[keep] = time;
            for g in gone {
                slots[g] = None;
                rename(&mut pairs, g, keep);
            }
            cache.retain(|((x, y), _)| {
                ![keep, gone[0], gone[1]].contains(x) && ![keep, gone[0], gone[1]].contains(y)
            });
            continue;
        };
        let Some(join) = cache.swap_remove(k).1 else {
            break;
        };
        let (Some(x), Some(y)) = (&slots[join.a], &slots[join.b]) else {
            break;
        };
        let area = side_by_side(&[&x.area, &y.area]);
        roughs[join.a] = side_by_side(&[&roughs[join.a], &roughs[join.b]]);
        changed[join.a] = true;
        slots[join.a] = Some(BlockArea {
            area,
            bearing: join.bearing,
        });
        slots[join.b] = None;
        times[join.a] = join.time;
        tried.retain(|t| !t.contains(&join.a) && !t.contains(&join.b));
        rename(&mut pairs, join.b, join.a);
        cache.retain(|((x, y), _)| ![join.a, join.b].contains(x) && ![join.a, join.b].contains(y));
    }
    // The joined blocks' outlines, each made once from all its parts.
    let mut out = Vec::with_capacity(slots.len());
    let mut joined = Vec::with_capacity(slots.len());
    for (slot, &c) in slots.into_iter().zip(&changed) {
        let Some(mut b) = slot else {
            continue;
        };
        if c {
            b.area = outline_of(&b.area, min_area);
        }
        out.push(b);
        joined.push(c);
    }
    Ok((out, joined))
}

/// Number of swaths of `area` at `bearing`.
fn swath_count(
    area: &MultiPolygon,
    bearing: f64,
    s: &SplitMergeSettings,
) -> Result<usize, PlanError> {
    Ok(block_swaths(area, bearing, s)?.len())
}

/// Blocks side by side: their polygons in one multipolygon, not yet joined.
fn side_by_side(areas: &[&MultiPolygon]) -> MultiPolygon {
    MultiPolygon::new(areas.iter().flat_map(|a| a.0.iter().cloned()).collect())
}

/// The outline of blocks side by side: their union, less the slivers the boolean operation
/// leaves along the borders. (Blocks from different boolean operations may keep a gap of a
/// fraction of a millimetre and stay two parts; swath pieces that close are one swath.)
fn outline_of(side_by_side: &MultiPolygon, min_area: f64) -> MultiPolygon {
    let union = side_by_side.union(&MultiPolygon::new(vec![]));
    MultiPolygon::new(
        union
            .0
            .into_iter()
            .filter(|p| p.unsigned_area() >= min_area)
            .collect(),
    )
}

/// The blocks of the slots, all of them present at the start.
fn blocks_of(slots: &[Option<BlockArea>]) -> Vec<BlockArea> {
    slots.iter().flatten().cloned().collect()
}

/// Pairs of neighbouring slots after slot `from` joined slot `to`: its neighbours are `to`'s.
fn rename(pairs: &mut Vec<(usize, usize)>, from: usize, to: usize) {
    for p in pairs.iter_mut() {
        let r = |x: usize| if x == from { to } else { x };
        let (a, b) = (r(p.0), r(p.1));
        *p = (a.min(b), a.max(b));
    }
    pairs.retain(|p| p.0 != p.1);
    pairs.shared_sort_unstable_by(Ord::cmp);
    pairs.dedup();
}

/// A join of three blocks: the slot it goes in, the joined block, its time, and the two slots
/// it empties.
type Triple = (usize, BlockArea, f64, [usize; 2]);

/// The best join of a block with two neighbours of one direction (within a degree) that saves
/// time: the slot it goes in, the joined block, its time, and the two slots it empties.
fn best_triple(
    slots: &[Option<BlockArea>],
    roughs: &[MultiPolygon],
    times: &[f64],
    pairs: &[(usize, usize)],
    s: &SplitMergeSettings,
    min_area: f64,
    tried: &mut Vec<[usize; 3]>,
) -> Result<Option<Triple>, PlanError> {
    let mut best: Option<(f64, usize, BlockArea, f64, [usize; 2])> = None;
    for m in 0..slots.len() {
        let Some(middle) = &slots[m] else {
            continue;
        };
        let around: Vec<usize> = pairs
            .iter()
            .filter_map(|&(a, b)| match (a == m, b == m) {
                (true, _) => Some(b),
                (_, true) => Some(a),
                _ => None,
            })
            .collect();
        for (i, &a) in around.iter().enumerate() {
            for &b in &around[i + 1..] {
                let (Some(x), Some(y)) = (&slots[a], &slots[b]) else {
                    continue;
                };
                // Only a block smaller than both is a sliver between them.
                if middle.area.unsigned_area() > x.area.unsigned_area().min(y.area.unsigned_area())
                    || tried.contains(&[a, m, b])
                {
                    continue;
                }
                tried.push([a, m, b]);
                let d = (x.bearing - y.bearing).rem_euclid(std::f64::consts::PI);
                if d.min(std::f64::consts::PI - d) > 1f64.to_radians() {
                    continue;
                }
                let union = side_by_side(&[&roughs[a], &roughs[m], &roughs[b]]);
                if union.0.is_empty() {
                    continue;
                }
                let allowed = constraints_in(&union, s.regions, s.forbidden, min_area);
                if allowed.iter().any(|r| r.forbids(x.bearing)) {
                    continue;
                }
                let time = block_time(&union, x.bearing, s)?;
                let saving = times[a] + times[m] + times[b] - time;
                if saving > 1e-6 && best.as_ref().is_none_or(|t| saving > t.0) {
                    let mut three = [a, m, b];
                    three.shared_sort_unstable_by(Ord::cmp);
                    best = Some((
                        saving,
                        three[0],
                        BlockArea {
                            area: side_by_side(&[&x.area, &middle.area, &y.area]),
                            bearing: x.bearing,
                        },
                        time,
                        [three[1], three[2]],
                    ));
                }
            }
        }
    }
    Ok(best.map(|(_, keep, joined, time, gone)| (keep, joined, time, gone)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::decompose::split_merge::Criterion;
    use crate::direction::SearchMethod;
    use crate::objective::Machine;
    use crate::route::pattern::{candidates, SwathPattern};
    use geo::polygon;

    #[test]
    fn blocks_joined_several_times_come_out_as_one_outline() {
        // A 300 x 60 strip cut in four, each worked east-west: they join into one block, whose
        // outline is made once from its four parts.
        let s = crate::decompose::split_merge::tests::settings(&[]);
        let east_west = std::f64::consts::FRAC_PI_2;
        let blocks: Vec<BlockArea> = (0..4)
            .map(|k| {
                let (x0, x1) = (75.0 * k as f64, 75.0 * (k + 1) as f64);
                BlockArea {
                    area: MultiPolygon::new(vec![
                        polygon![(x: x0, y: 0.), (x: x1, y: 0.), (x: x1, y: 60.), (x: x0, y: 60.)],
                    ]),
                    bearing: east_west,
                }
            })
            .collect();
        let (joined, marks) = join_blocks_marked(blocks, &s).unwrap();
        assert_eq!(joined.len(), 1);
        assert_eq!(marks, vec![true]);
        // One polygon, not four side by side.
        assert_eq!(joined[0].area.0.len(), 1);
        assert!(joined[0].area.0[0].interiors().is_empty());
        assert!((joined[0].area.unsigned_area() - 300.0 * 60.0).abs() < 1e-6);
        assert_eq!(joined[0].bearing, east_west);
    }

    #[test]
    fn a_block_is_timed_in_the_pattern_the_route_will_drive() {
        // 3 m swaths, a 6 m turning radius: boustrophedon loops at every end, a snake that
        // skips three swaths turns in U-turns.
        let block = MultiPolygon::new(vec![
            polygon![(x: 0., y: 0.), (x: 48., y: 0.), (x: 48., y: 200.), (x: 0., y: 200.)],
        ]);
        let orders = candidates(SwathPattern::Auto, 1, 6, &[], 3.0, 6.0);
        let s = SplitMergeSettings {
            width: 3.0,
            min_length: 3.0,
            machine: Machine {
                width: 3.0,
                turn_radius: 6.0,
                working_speed: 2.2,
                turning_speed: 1.4,
            },
            method: SearchMethod::CoarseToFine,
            step_deg: 1.0,
            forbidden: &[],
            regions: &[],
            criterion: Criterion::default(),
            min_end_angle: 20f64.to_radians(),
            tolerance: 1.5,
            orders: &[],
        };
        let with_orders = SplitMergeSettings {
            orders: &orders,
            ..s
        };
        let boustrophedon = block_time(&block, 0.0, &s).unwrap();
        let auto = block_time(&block, 0.0, &with_orders).unwrap();
        // 15 turns, each a loop of r(π + 4 acos(5/8)) ≈ 40.6 m against a U-turn of about
        // πr + 0 ≈ 18.8 m (the snake's few longer turns aside).
        assert!(
            auto < boustrophedon - 150.0,
            "{auto} against {boustrophedon}"
        );
        let swaths = block_swaths(&block, 0.0, &s).unwrap();
        let ids: Vec<usize> = (0..swaths.len()).collect();
        let stats =
            crate::objective::measure_turns(&swaths, 3.0, block.unsigned_area(), &s.machine);
        let patterned = in_pattern(stats, &swaths, &block_members(&swaths), &with_orders);
        let expected = block_turning_m(&ids, &swaths, &orders, TurnLengths::new(6.0));
        assert!((patterned.turning_distance_m - expected).abs() < 1e-9);
    }
}
