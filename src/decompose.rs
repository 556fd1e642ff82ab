//! Decomposition: the inner field cut into blocks, each worked at one direction, and the swaths
//! grouped into blocks that can be worked one after the other, turning in the headland.
//!
//! Three ways to cut the field ([`Decomposition`]):
//!
//! - none: one direction for the whole inner field; where an obstacle or a bay interrupts the
//!   swath lines, the swaths are clustered into blocks line by line ([`cluster_swaths`]);
//! - boustrophedon ([`boustrophedon`], Zhou et al. 2.3): one direction, the inner field swept
//!   into cells that break only where the sweep meets or leaves an obstacle or a bay, and the
//!   swaths clustered into the cells;
//! - split-and-merge ([`split_merge`], Oksanen & Visala 2): blocks chosen one by one, each with
//!   its own best direction, so that a bay or an arm of the field is worked along its length.
//!
//! Auto plans all three and keeps the one of lowest estimated operation time. Both
//! decompositions rest on the trapezoidal split of [`cells`]; [`block_headlands`] adds headland
//! passes between blocks where both blocks' swaths end at their common border.

pub mod block_headlands;
pub mod boustrophedon;
pub mod cells;
pub mod join;
pub mod redirect;
pub mod split_merge;

use crate::field::ring::clean_ring;
use crate::swath::{Swath, Swaths};
use geo::{LineString, MultiPolygon, Polygon};
use serde::Serialize;

/// How the inner field is cut into blocks (the `decomposition` option).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Decomposition {
    /// One direction; swaths clustered into blocks where obstacles and bays break the lines.
    None,
    /// One direction; Zhou et al.'s boustrophedon cells.
    Boustrophedon,
    /// Oksanen & Visala's split and merge: blocks with a direction each.
    SplitMerge,
    /// Whichever of the three gives the lowest estimated operation time.
    #[default]
    Auto,
}

crate::named::named!(Decomposition { "none" => None, "boustrophedon" => Boustrophedon, "split-merge" => SplitMerge, "auto" => Auto });

impl Decomposition {
    /// The name, as the options spell it.
    pub fn as_str(self) -> &'static str {
        match self {
            Decomposition::None => "none",
            Decomposition::Boustrophedon => "boustrophedon",
            Decomposition::SplitMerge => "split-merge",
            Decomposition::Auto => "auto",
        }
    }
}

/// A part of the inner field worked at one direction: a block of a decomposition.
#[derive(Debug, Clone, PartialEq)]
pub struct BlockArea {
    /// Its area.
    pub area: MultiPolygon,
    /// Its swath direction, compass radians in `[0, π)`.
    pub bearing: f64,
}

/// A block: swaths on consecutive lines, each overlapping the next along the line.
#[derive(Debug, Clone, PartialEq)]
pub struct Block {
    /// Index of the block.
    pub index: usize,
    /// Indices of its swaths (into [`Swaths::swaths`]), one per line, in line order.
    pub swaths: Vec<usize>,
    /// The area its swaths cover: a staircase outline of their strips, counter-clockwise.
    pub outline: Polygon,
    /// The swath direction of the block, compass radians in `[0, π)`.
    pub bearing: f64,
}

/// The blocks of a plan.
#[derive(Debug, Clone, Default)]
pub struct Blocks {
    /// The blocks, in the order they were found across the field.
    pub blocks: Vec<Block>,
}

/// Most blocks a plan's swaths may fall into (see `plan`'s check): the worst cases of
/// `tests/termination.rs` that plan have up to about 4,000.
pub const MAX_BLOCKS: usize = 10_000;

/// Clusters swaths into blocks: within each area of [`Swaths::areas`] (all swaths as one area
/// when it is empty), walking across line by line, a swath continues the block of the swath
/// next to it on the previous line when each is the other's only overlapping neighbour; a split
/// or a merge of pieces starts new blocks. A block's outline is its area's, when the area is one
/// polygon holding one block, else the staircase of strips its swaths cover.
///
/// ```
/// use furrow::decompose::cluster_swaths;
/// use furrow::swath::generate;
/// use geo::{polygon, MultiPolygon};
///
/// // A 60 x 100 field with a pond in the middle of it: the lines through the pond are split,
/// // giving a block below the pond and one above it, between the blocks at the sides.
/// let field = polygon!(
///     exterior: [(x: 0., y: 0.), (x: 60., y: 0.), (x: 60., y: 100.), (x: 0., y: 100.)],
///     interiors: [[(x: 20., y: 40.), (x: 40., y: 40.), (x: 40., y: 60.), (x: 20., y: 60.)]],
/// );
/// let swaths = generate(&MultiPolygon::new(vec![field]), 0.0, 6.0, 6.0)?;
/// let blocks = cluster_swaths(&swaths);
/// assert_eq!(blocks.blocks.len(), 4);
/// let total: usize = blocks.blocks.iter().map(|b| b.swaths.len()).sum();
/// assert_eq!(total, swaths.swaths.len());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn cluster_swaths(swaths: &Swaths) -> Blocks {
    let ranges: Vec<(std::ops::Range<usize>, Option<&MultiPolygon>)> = if swaths.areas.is_empty() {
        vec![(0..swaths.swaths.len(), None)]
    } else {
        swaths
            .areas
            .iter()
            .map(|a| (a.swaths.clone(), Some(&a.area)))
            .collect()
    };
    let mut blocks = Vec::new();
    for (range, area) in ranges {
        let Some(slice) = swaths.swaths.get(range.clone()) else {
            continue;
        };
        let members = block_members(slice);
        let single = members.len() == 1;
        for ids in members {
            let ids: Vec<usize> = ids.into_iter().map(|i| i + range.start).collect();
            let outline = match area {
                Some(a) if single && a.0.len() == 1 => a.0[0].clone(),
                _ => outline(swaths, &ids),
            };
            blocks.push(Block {
                index: blocks.len(),
                outline,
                bearing: swaths.swaths[ids[0]].bearing,
                swaths: ids,
            });
        }
    }
    Blocks { blocks }
}

/// The swaths of each block (indices into `s`, one per line, in line order), without outlines:
/// what the direction search needs to count turns.
pub fn block_members(s: &[Swath]) -> Vec<Vec<usize>> {
    // Swaths are ordered by line; find where each line's run starts.
    let mut runs: Vec<(usize, std::ops::Range<usize>)> = Vec::with_capacity(s.len());
    let mut i = 0;
    while i < s.len() {
        let line = s[i].line_index;
        let start = i;
        while i < s.len() && s[i].line_index == line {
            i += 1;
        }
        runs.push((line, start..i));
    }

    // Each swath's block first, then the blocks' lists at their sizes.
    let mut block_of: Vec<usize> = vec![usize::MAX; s.len()];
    let mut sizes: Vec<usize> = Vec::new();
    for (r, (line, range)) in runs.iter().enumerate() {
        let prev = r
            .checked_sub(1)
            .map(|p| &runs[p])
            .filter(|(pl, _)| pl + 1 == *line);
        for j in range.clone() {
            let continues = prev.and_then(|(_, prange)| {
                let mut over = prange.clone().filter(|&k| overlaps(&s[k], &s[j]));
                let k = over.next()?;
                if over.next().is_some() {
                    return None;
                }
                // k must overlap only j on this line too.
                let mut back = range.clone().filter(|&m| overlaps(&s[k], &s[m]));
                let only = back.next() == Some(j) && back.next().is_none();
                only.then_some(k)
            });
            match continues.and_then(|k| block_of.get(k).copied()) {
                Some(b) if b < sizes.len() => {
                    block_of[j] = b;
                    sizes[b] += 1;
                }
                _ => {
                    block_of[j] = sizes.len();
                    sizes.push(1);
                }
            }
        }
    }
    let mut members: Vec<Vec<usize>> = sizes.into_iter().map(Vec::with_capacity).collect();
    for (j, &b) in block_of.iter().enumerate() {
        if let Some(m) = members.get_mut(b) {
            m.push(j);
        }
    }
    members
}

/// Whether two swaths on neighbouring lines overlap along the line.
fn overlaps(a: &Swath, b: &Swath) -> bool {
    a.along.0 < b.along.1 && b.along.0 < a.along.1
}

/// The staircase outline of a block's strips: each strip reaches half a width beyond its outer
/// lines and halfway to its neighbours between them.
fn outline(swaths: &Swaths, ids: &[usize]) -> Polygon {
    let s = &swaths.swaths;
    let half = swaths.width / 2.0;
    let n = ids.len();
    // Strip edges across the field: before the first line, between lines, after the last.
    let edge = |k: usize| -> f64 {
        if k == 0 {
            s[ids[0]].across - half
        } else if k == n {
            s[ids[n - 1]].across + half
        } else {
            (s[ids[k - 1]].across + s[ids[k]].across) / 2.0
        }
    };
    let f = &s[ids[0]].frame;
    let mut pts = Vec::with_capacity(4 * n + 1);
    // Up the start side, then back down the end side.
    for (k, &id) in ids.iter().enumerate() {
        pts.push(f.point(edge(k), s[id].along.0));
        pts.push(f.point(edge(k + 1), s[id].along.0));
    }
    for (k, &id) in ids.iter().enumerate().rev() {
        pts.push(f.point(edge(k + 1), s[id].along.1));
        pts.push(f.point(edge(k), s[id].along.1));
    }
    // Equal neighbours leave zero-height steps: drop those vertices.
    let (pts, _) = clean_ring(&pts);
    // (across, along) is a right-handed frame like (east, north): the outline runs counter-clockwise.
    let mut ring = LineString::new(pts);
    ring.close();
    Polygon::new(ring, vec![])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::swath::generate;
    use geo::{polygon, Area, MultiPolygon};

    #[test]
    fn a_convex_field_is_one_block() {
        let field = polygon![(x: 0., y: 0.), (x: 100., y: 0.), (x: 80., y: 60.), (x: 10., y: 50.)];
        let swaths = generate(&MultiPolygon::new(vec![field]), 0.3, 6.0, 6.0).unwrap();
        let blocks = cluster_swaths(&swaths);
        assert_eq!(blocks.blocks.len(), 1);
        assert_eq!(blocks.blocks[0].swaths.len(), swaths.swaths.len());
    }

    #[test]
    fn outline_covers_the_strips() {
        let field = polygon![(x: 0., y: 0.), (x: 30., y: 0.), (x: 30., y: 100.), (x: 0., y: 100.)];
        let swaths = generate(&MultiPolygon::new(vec![field]), 0.0, 6.0, 6.0).unwrap();
        let blocks = cluster_swaths(&swaths);
        let b = &blocks.blocks[0];
        assert!((b.outline.unsigned_area() - 3000.0).abs() < 1e-6);
        assert!(b.outline.signed_area() > 0.0, "counter-clockwise");
    }

    #[test]
    fn a_u_shaped_field_gives_three_blocks() {
        // A U open to the north: lines running east cross both arms above the base.
        let u = polygon![
            (x: 0., y: 0.), (x: 90., y: 0.), (x: 90., y: 90.), (x: 60., y: 90.),
            (x: 60., y: 30.), (x: 30., y: 30.), (x: 30., y: 90.), (x: 0., y: 90.)
        ];
        let swaths = generate(
            &MultiPolygon::new(vec![u]),
            std::f64::consts::FRAC_PI_2,
            6.0,
            6.0,
        )
        .unwrap();
        let blocks = cluster_swaths(&swaths);
        assert_eq!(blocks.blocks.len(), 3);
    }
}
