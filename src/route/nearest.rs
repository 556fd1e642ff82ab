//! The block order for fields with many blocks: nearest neighbour.
//!
//! The block sequence ([`super::sequence`]) costs every connection from every block's exit to
//! every other block's entry along the headland graph: a table of `(4 x blocks)²` entries and a
//! shortest-path search from each exit, which for thousands of blocks (a field strewn with
//! obstacles, a ragged outline at a fine width) takes gigabytes and minutes. Beyond
//! [`MAX_SEQUENCED_WAYS`] ways in all the order is plain instead: from where the work starts,
//! always on to the nearest entry of a block not yet worked, straight-line distance, each block
//! by the way that enters there (the one of least turning where several do). An R-tree of the
//! entries left finds each next block, so the order takes `O(blocks log blocks)`.

use super::pattern::BlockWay;
use super::sequence::Sequence;
use super::sequence::SequenceMethod;
use crate::geometry::{IndexedSegment, PlanarHypot};
use crate::swath::Swath;
use geo::Coord;
use rstar::RTree;

/// The most ways (four a block, or eight where a block may also drive back along its last
/// swath) for which the block order is sequenced ([`super::sequence::solve`]); beyond it the order
/// is [`nearest_order`]. At 1,024 ways the table of connection costs is 8 MB, and the ant colony
/// and local search have a transition matrix to work on (see `sequence::compiled::DENSE_MAX_NODES`).
pub const MAX_SEQUENCED_WAYS: usize = 1024;

/// The most work the connection costs of a sequenced block order may take: one shortest-path
/// search from each of its points, each settling up to every node of the graph they go by, so
/// points times nodes. Beyond it the order is [`nearest_order`]. The register parcels and the
/// corpus stay under 130,000 at the widths of a mower, a drill and a sprayer; a noisy star at
/// 0.2 m, whose fill is sequenced over the tracks of 2,945 swaths, took 20 million, 1.8 s
/// natively for each of its two problems.
pub const MAX_SEQUENCE_SEARCH_WORK: usize = 4_000_000;

/// The blocks in nearest-neighbour order from `start` (or, without one, from the entry farthest
/// from the middle of all entries: an end of the field), each with the index of its way; blocks
/// without ways are left out. The cost is that of the sequence problem with straight
/// connections: the ways' turning and the straight distances between them (and from `start`).
///
/// ```
/// use furrow::objective::TurnLengths;
/// use furrow::route::nearest::nearest_order;
/// use furrow::route::pattern::{ways, SwathOrder};
/// use furrow::swath::generate;
/// use geo::{coord, polygon, MultiPolygon};
///
/// // Three strips 5 m wide running north, at x = 0, 20 and 10: a swath each.
/// let strip = |x: f64| polygon![(x: x, y: 0.), (x: x + 5., y: 0.), (x: x + 5., y: 100.), (x: x, y: 100.)];
/// let swaths = generate(&MultiPolygon::new(vec![strip(0.), strip(20.), strip(10.)]), 0.0, 5.0, 5.0)?;
/// let block_ways: Vec<_> = (0..swaths.swaths.len())
///     .map(|i| ways(&[i], &swaths.swaths, &SwathOrder::Boustrophedon, TurnLengths::new(0.0)))
///     .collect();
/// let sequence = nearest_order(&block_ways, &swaths.swaths, Some(coord! { x: 0.0, y: -5.0 }));
/// // West to east: each next strip is entered where the one before was left.
/// let xs: Vec<f64> = sequence.order.iter().map(|&(b, _)| swaths.swaths[b].centre.start.x).collect();
/// assert_eq!(xs, vec![2.5, 12.5, 22.5]);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn nearest_order(
    block_ways: &[Vec<BlockWay>],
    swaths: &[Swath],
    start: Option<Coord>,
) -> Sequence {
    // One entry a block and entry point: the way of least turning that enters there (the first
    // of equals).
    let mut entries: Vec<IndexedSegment> = Vec::new();
    for (b, ways) in block_ways.iter().enumerate() {
        let first = entries.len();
        for (wi, w) in ways.iter().enumerate() {
            let Some(p) = w.entry(swaths) else { continue };
            match entries[first..].iter_mut().find(|e| e.a == p) {
                Some(e) if w.turning_m < block_ways[b][e.index].turning_m => e.index = wi,
                Some(_) => {}
                None => entries.push(IndexedSegment::new(p, p, b, wi)),
            }
        }
    }
    let begin = start.or_else(|| farthest_from_middle(&entries));
    let mut order = Vec::new();
    let mut cost = 0.0;
    let Some(mut at) = begin else {
        return Sequence {
            order,
            cost,
            method: SequenceMethod::NearestNeighbour,
        };
    };
    // The entries of blocks not yet worked, and how many of the tree's are of blocks worked
    // since it was built. (rstar's removal leaves boxes that its nearest-neighbour search trusts
    // too wide: the tree is rebuilt instead once half of it is of blocks worked, and the search
    // passes over those.)
    let mut entries_of = vec![0usize; block_ways.len()];
    for e in &entries {
        entries_of[e.line] += 1;
    }
    let mut done = vec![false; block_ways.len()];
    let mut left = RTree::bulk_load(entries);
    let mut dead = 0;
    loop {
        let next = left
            .nearest_neighbor_iter(&[at.x, at.y])
            .find(|e| !done[e.line])
            .copied();
        let Some(next) = next else { break };
        let way = &block_ways[next.line][next.index];
        cost += (next.a - at).x.planar_hypot((next.a - at).y) + way.turning_m;
        order.push((next.line, next.index));
        done[next.line] = true;
        dead += entries_of[next.line];
        if 2 * dead > left.size() {
            let rest: Vec<IndexedSegment> =
                left.iter().filter(|e| !done[e.line]).copied().collect();
            left = RTree::bulk_load(rest);
            dead = 0;
        }
        at = way.exit(swaths).unwrap_or(next.a);
    }
    Sequence {
        order,
        cost,
        method: SequenceMethod::NearestNeighbour,
    }
}

/// The entry farthest from the mean of all entries (the first of equals).
fn farthest_from_middle(entries: &[IndexedSegment]) -> Option<Coord> {
    let n = entries.len() as f64;
    let sum = entries.iter().fold(Coord::<f64>::zero(), |s, e| s + e.a);
    let middle = Coord {
        x: sum.x / n,
        y: sum.y / n,
    };
    let mut best: Option<(f64, Coord)> = None;
    for e in entries {
        let d = (e.a - middle).x.planar_hypot((e.a - middle).y);
        if best.is_none_or(|(bd, _)| d > bd) {
            best = Some((d, e.a));
        }
    }
    best.map(|(_, p)| p)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::decompose::cluster_swaths;
    use crate::objective::TurnLengths;
    use crate::rng::SplitMix64 as Rng;
    use crate::route::pattern::{ways, SwathOrder};
    use crate::swath::generate;
    use geo::{polygon, MultiPolygon};

    /// `n` strips 4 m wide and 20 to 60 m long at random places in a 2 km square, each worked
    /// as a block of its own: their swaths and the four ways of each.
    fn strips(n: usize, seed: u64) -> (Vec<Swath>, Vec<Vec<BlockWay>>) {
        let mut rng = Rng::new(seed);
        let parts = (0..n)
            .map(|i| {
                // On a grid of 50 m cells, so that no two strips touch.
                let (x, y) = ((i % 40) as f64 * 50.0, (i / 40) as f64 * 50.0);
                let (x, y) = (x + 40.0 * rng.unit(), y + 5.0 * rng.unit());
                let length = 20.0 + 40.0 * rng.unit();
                polygon![(x: x, y: y), (x: x + 4.0, y: y), (x: x + 4.0, y: y + length), (x: x, y: y + length)]
            })
            .collect();
        let swaths = generate(&MultiPolygon::new(parts), 0.0, 2.0, 2.0).expect("swaths");
        let block_ways = cluster_swaths(&swaths)
            .blocks
            .iter()
            .map(|b| {
                ways(
                    &b.swaths,
                    &swaths.swaths,
                    &SwathOrder::Boustrophedon,
                    TurnLengths::new(1.0),
                )
            })
            .collect();
        (swaths.swaths, block_ways)
    }

    /// Nearest neighbour the plain way: every way of every block left, each time.
    fn brute_force(block_ways: &[Vec<BlockWay>], s: &[Swath], start: Coord) -> Vec<(usize, usize)> {
        let mut done = vec![false; block_ways.len()];
        let mut at = start;
        let mut order = Vec::new();
        loop {
            let mut best: Option<(f64, f64, usize, usize)> = None;
            for (b, ways) in block_ways.iter().enumerate().filter(|&(b, _)| !done[b]) {
                for (wi, w) in ways.iter().enumerate() {
                    let Some(p) = w.entry(s) else { continue };
                    let d = (p - at).x.hypot((p - at).y);
                    let key = (d, w.turning_m);
                    if best.is_none_or(|(bd, bt, ..)| key < (bd, bt)) {
                        best = Some((d, w.turning_m, b, wi));
                    }
                }
            }
            let Some((_, _, b, wi)) = best else {
                return order;
            };
            done[b] = true;
            order.push((b, wi));
            at = block_ways[b][wi].exit(s).unwrap_or(at);
        }
    }

    #[test]
    fn the_order_is_nearest_neighbour() {
        let (swaths, block_ways) = strips(400, 11);
        assert!(block_ways.len() > 300);
        let start = Coord { x: -10.0, y: -10.0 };
        let sequence = nearest_order(&block_ways, &swaths, Some(start));
        assert_eq!(sequence.method, SequenceMethod::NearestNeighbour);
        let bf = brute_force(&block_ways, &swaths, start);
        assert_eq!(sequence.order, bf);
        // Its cost: the ways' turning and the straight distances between them.
        let mut cost = 0.0;
        let mut at = start;
        for &(b, wi) in &sequence.order {
            let w = &block_ways[b][wi];
            let p = w.entry(&swaths).expect("an entry");
            cost += (p - at).x.hypot((p - at).y) + w.turning_m;
            at = w.exit(&swaths).expect("an exit");
        }
        assert!((cost - sequence.cost).abs() < 1e-6 * cost);
    }

    #[test]
    fn every_block_with_ways_once_from_an_end_without_a_start() {
        let (swaths, mut block_ways) = strips(300, 12);
        block_ways[7].clear();
        let sequence = nearest_order(&block_ways, &swaths, None);
        let mut blocks: Vec<usize> = sequence.order.iter().map(|&(b, _)| b).collect();
        blocks.sort_unstable();
        let expected: Vec<usize> = (0..block_ways.len()).filter(|&b| b != 7).collect();
        assert_eq!(blocks, expected);
        // It starts at the entry farthest from the middle of all entries.
        let entries: Vec<Coord> = block_ways
            .iter()
            .flatten()
            .filter_map(|w| w.entry(&swaths))
            .collect();
        let n = entries.len() as f64;
        let middle = entries.iter().fold(Coord::zero(), |s, &p| s + p) / n;
        let far = |p: Coord| (p - middle).x.hypot((p - middle).y);
        let farthest = entries.iter().map(|&p| far(p)).fold(0.0, f64::max);
        let (b, wi) = sequence.order[0];
        assert_eq!(
            far(block_ways[b][wi].entry(&swaths).expect("entry")),
            farthest
        );
        // The same again.
        assert_eq!(nearest_order(&block_ways, &swaths, None), sequence);
    }

    #[test]
    fn nothing_to_order() {
        let sequence = nearest_order(&[Vec::new(), Vec::new()], &[], None);
        assert!(sequence.order.is_empty());
        assert_eq!(sequence.cost, 0.0);
    }
}
