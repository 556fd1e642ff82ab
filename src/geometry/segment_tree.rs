//! Segments of lines and rings in an R-tree (rstar): the element of every segment index of the
//! planner (the headland graph's nearest lines, the turns' field edges, the tracks' junctions).
//! One element type compiles one copy of rstar's bulk loading and searches, where one per
//! stage cost about 15 KB of WebAssembly each.

use super::distance::point_segment_distance;
use geo::{Coord, Line};
use rstar::{PointDistance, RTreeObject, AABB};

/// The segment from `a` to `b`, the `index`-th of line `line` (numbers for the caller to give a
/// meaning: a headland pass, a track, or nothing).
///
/// ```
/// use furrow::geometry::IndexedSegment;
/// use geo::coord;
/// use rstar::RTree;
///
/// let tree = RTree::bulk_load(vec![
///     IndexedSegment::new(coord! { x: 0., y: 0. }, coord! { x: 10., y: 0. }, 0, 0),
///     IndexedSegment::new(coord! { x: 10., y: 0. }, coord! { x: 10., y: 10. }, 0, 1),
/// ]);
/// let nearest = tree.nearest_neighbor(&[12., 6.]).ok_or("no segment")?;
/// assert_eq!((nearest.line, nearest.index), (0, 1));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IndexedSegment {
    /// Start.
    pub a: Coord,
    /// End.
    pub b: Coord,
    /// The line (ring, track) it belongs to.
    pub line: usize,
    /// Its place in that line: the segment from point `index` to point `index + 1`.
    pub index: usize,
}

impl IndexedSegment {
    /// The segment from `a` to `b`, the `index`-th of line `line`.
    pub fn new(a: Coord, b: Coord, line: usize, index: usize) -> Self {
        IndexedSegment { a, b, line, index }
    }

    /// As a geo `Line`.
    pub fn as_line(&self) -> Line {
        Line::new(self.a, self.b)
    }
}

impl RTreeObject for IndexedSegment {
    type Envelope = AABB<[f64; 2]>;
    fn envelope(&self) -> Self::Envelope {
        AABB::from_corners([self.a.x, self.a.y], [self.b.x, self.b.y])
    }
}

impl PointDistance for IndexedSegment {
    fn distance_2(&self, p: &[f64; 2]) -> f64 {
        let d = point_segment_distance(Coord { x: p[0], y: p[1] }, self.a, self.b);
        d * d
    }
}
