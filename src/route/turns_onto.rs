//! Blocks that turn onto a neighbour: where the swaths of one block end against the swaths of
//! another (a border between blocks without a headland of its own, see
//! [`block_headlands`](crate::decompose::block_headlands): one block's ends along the other's
//! parallel side), the machine turns at those ends on the neighbour's ground. Worked before its
//! neighbour, it turns over the neighbour's crop; worked after, over stubble. The block order
//! weighs that ([`Precedence`]): each swath end that turns onto a neighbour costs
//! [`TURN_OVER_CROP_M`] where the neighbour is worked later.

use super::pattern::BlockWay;
use super::sequence::Precedence;
use crate::swath::Swath;
use geo::Coord;

/// What a turn onto the crop of a block worked later costs the block order, in metres of
/// driving: a detour of up to this much along the headland per turn is taken to turn over
/// ground already worked instead.
pub const TURN_OVER_CROP_M: f64 = 100.0;

/// How far past a swath end a turn is looked for on a neighbour, metres: just past the end,
/// and at the turning radius (where a U-turn's arc is furthest out).
fn probes(turn_radius: f64) -> [f64; 2] {
    [1.0, turn_radius.max(1.0)]
}

/// A swath's centre line as the probe sees it: its start, unit direction and length.
#[derive(Clone, Copy)]
struct Line {
    start: Coord,
    along: Coord,
    length: f64,
}

impl Line {
    fn of(s: &Swath) -> Option<Line> {
        let length = s.length();
        (length > 1e-9).then(|| Line {
            start: s.centre.start,
            along: (s.centre.end - s.centre.start) / length,
            length,
        })
    }

    /// Whether `p` lies on the line's strip of `width`.
    fn strip_holds(&self, p: Coord, width: f64) -> bool {
        let d = p - self.start;
        let along = d.x * self.along.x + d.y * self.along.y;
        let across = (d.y * self.along.x - d.x * self.along.y).abs();
        (0.0..=self.length).contains(&along) && across <= width / 2.0
    }
}

/// A block's swath lines and the box round their strips.
struct Block {
    lines: Vec<Line>,
    min: Coord,
    max: Coord,
}

impl Block {
    fn of(ways: &[BlockWay], swaths: &[Swath], width: f64) -> Block {
        let lines: Vec<Line> = ways
            .first()
            .map(|w| w.swaths.as_slice())
            .unwrap_or_default()
            .iter()
            .filter_map(|&i| swaths.get(i).and_then(Line::of))
            .collect();
        let (mut min, mut max) = (
            Coord::from((f64::INFINITY, f64::INFINITY)),
            Coord::from((f64::NEG_INFINITY, f64::NEG_INFINITY)),
        );
        for l in &lines {
            for p in [l.start, l.start + l.along * l.length] {
                min = Coord::from((min.x.min(p.x), min.y.min(p.y)));
                max = Coord::from((max.x.max(p.x), max.y.max(p.y)));
            }
        }
        let pad = Coord::from((width / 2.0, width / 2.0));
        Block {
            lines,
            min: min - pad,
            max: max + pad,
        }
    }

    fn holds(&self, p: Coord, width: f64) -> bool {
        p.x >= self.min.x
            && p.y >= self.min.y
            && p.x <= self.max.x
            && p.y <= self.max.y
            && self.lines.iter().any(|l| l.strip_holds(p, width))
    }
}

/// For each two blocks (indices into `block_ways`) where swath ends of one lie against the
/// swaths of the other: the other first, costing [`TURN_OVER_CROP_M`] per such end where it
/// is worked later.
///
/// ```
/// use furrow::route::pattern::{ways, SwathOrder};
/// use furrow::route::turns_onto::{precedence, TURN_OVER_CROP_M};
/// use furrow::objective::TurnLengths;
/// use furrow::swath::generate;
/// use geo::{polygon, MultiPolygon};
///
/// // Block 0: five swaths running north, ending at y = 100; block 1: swaths running east
/// // along y = 101.5 to 110, beyond those ends.
/// let north = polygon![(x: 0., y: 0.), (x: 15., y: 0.), (x: 15., y: 100.), (x: 0., y: 100.)];
/// let east = polygon![(x: 0., y: 100.), (x: 15., y: 100.), (x: 15., y: 109.), (x: 0., y: 109.)];
/// let mut s = generate(&MultiPolygon::new(vec![north]), 0.0, 3.0, 3.0)?.swaths;
/// let first_east = s.len();
/// s.extend(generate(&MultiPolygon::new(vec![east]), 90f64.to_radians(), 3.0, 3.0)?.swaths);
/// let turns = TurnLengths::new(5.0);
/// let of = |ids: Vec<usize>| ways(&ids, &s, &SwathOrder::Boustrophedon, turns);
/// let blocks = vec![of((0..first_east).collect()), of((first_east..s.len()).collect())];
/// let p = precedence(&blocks, &s, 3.0, 5.0);
/// // Block 0's five northern ends turn on block 1: block 1 first.
/// assert_eq!(p.len(), 1);
/// assert_eq!((p[0].first, p[0].then), (1, 0));
/// assert_eq!(p[0].cost, 5.0 * TURN_OVER_CROP_M);
/// # Ok::<(), furrow::error::PlanError>(())
/// ```
pub fn precedence(
    block_ways: &[Vec<BlockWay>],
    swaths: &[Swath],
    width: f64,
    turn_radius: f64,
) -> Vec<Precedence> {
    if block_ways.len() < 2 || width.is_nan() || width <= 0.0 {
        return Vec::new();
    }
    let blocks: Vec<Block> = block_ways
        .iter()
        .map(|w| Block::of(w, swaths, width))
        .collect();
    let mut out = Vec::new();
    let mut ends_onto = vec![0usize; blocks.len()];
    for (then, block) in blocks.iter().enumerate() {
        ends_onto.iter_mut().for_each(|n| *n = 0);
        for l in &block.lines {
            let end = l.start + l.along * l.length;
            for (at, out_dir) in [(end, l.along), (l.start, -l.along)] {
                let onto = probes(turn_radius).into_iter().find_map(|d| {
                    let p = at + out_dir * d;
                    (0..blocks.len()).find(|&k| k != then && blocks[k].holds(p, width))
                });
                if let Some(k) = onto {
                    ends_onto[k] += 1;
                }
            }
        }
        for (first, &n) in ends_onto.iter().enumerate() {
            if n > 0 {
                out.push(Precedence {
                    first,
                    then,
                    cost: n as f64 * TURN_OVER_CROP_M,
                });
            }
        }
    }
    out
}
