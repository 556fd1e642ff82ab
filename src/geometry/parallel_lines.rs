//! Parallel lines clipped by polygons, in one sweep.
//!
//! Swaths are straight lines at one bearing, a working width apart, cut where they leave the
//! inner field or enter an obstacle. Rather than clipping each line with a general boolean
//! operation, [`SweepFrame::clip`] rotates the polygons' edges into a frame where the lines are
//! `across = const`, and finds each line's crossings with the edges in one pass over the edges
//! sorted by their `across` range. The crossings of one line, sorted along it, pair up into the
//! pieces inside (even-odd rule, so holes cut lines without special cases). This is the hot path
//! of the direction search, which clips the field at many bearings.

use super::bearing::{bearing_of, unit_vector};
use super::distance::Extremes;
use crate::sort::{sort_floats, SharedSort};
use geo::{Coord, MultiPolygon};

/// A frame rotated to a bearing: `along` points in the driving direction, `across` to its right.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SweepFrame {
    along: Coord,
    across: Coord,
}

/// One edge of a polygon ring in sweep coordinates (`c` across, `a` along).
#[derive(Debug, Clone, Copy)]
struct SweepEdge {
    c0: f64,
    a0: f64,
    c1: f64,
    a1: f64,
    /// The lower and the higher of `c0` and `c1`.
    low: f64,
    high: f64,
}

impl SweepFrame {
    /// The frame whose `along` axis points along `bearing` (compass radians).
    pub fn new(bearing: f64) -> Self {
        let along = unit_vector(bearing);
        // The unit vector 90 degrees clockwise of `along`: to the right of the driving direction.
        let across = Coord {
            x: along.y,
            y: -along.x,
        };
        SweepFrame { along, across }
    }

    /// The unit vector of the driving direction.
    pub fn along(&self) -> Coord {
        self.along
    }

    /// A point's (across, along) coordinates.
    #[inline]
    pub fn project(&self, p: Coord) -> (f64, f64) {
        (
            p.x * self.across.x + p.y * self.across.y,
            p.x * self.along.x + p.y * self.along.y,
        )
    }

    /// The point at (across, along).
    #[inline]
    pub fn point(&self, c: f64, a: f64) -> Coord {
        Coord {
            x: c * self.across.x + a * self.along.x,
            y: c * self.across.y + a * self.along.y,
        }
    }

    /// The smallest and largest `across` coordinate of the polygons (`None` if empty).
    pub fn across_extent(&self, polygons: &MultiPolygon) -> Option<(f64, f64)> {
        let mut range: Option<(f64, f64)> = None;
        for p in polygons.0.iter() {
            for c in p.exterior().0.iter() {
                let (x, _) = self.project(*c);
                range = Some(match range {
                    None => (x, x),
                    Some((lo, hi)) => (lo.min(x), hi.max(x)),
                });
            }
        }
        range
    }

    /// Clips the lines `across = offsets[i]` (ascending) with the polygons (holes included).
    ///
    /// Returns, per line, the pieces inside as `(along_start, along_end)` with
    /// `along_start < along_end`, ordered along the line.
    ///
    /// ```
    /// use furrow::geometry::SweepFrame;
    /// use geo::{polygon, MultiPolygon};
    ///
    /// // A 10 x 10 square with a 2 x 2 hole; lines running north (bearing 0), x = 1, 5, 9.
    /// let square = polygon!(
    ///     exterior: [(x: 0., y: 0.), (x: 10., y: 0.), (x: 10., y: 10.), (x: 0., y: 10.)],
    ///     interiors: [[(x: 4., y: 4.), (x: 6., y: 4.), (x: 6., y: 6.), (x: 4., y: 6.)]],
    /// );
    /// let frame = SweepFrame::new(0.0);
    /// let pieces = frame.clip(&MultiPolygon::new(vec![square]), &[1.0, 5.0, 9.0]);
    /// assert_eq!(pieces[0], vec![(0.0, 10.0)]);
    /// assert_eq!(pieces[1], vec![(0.0, 4.0), (6.0, 10.0)]);
    /// assert_eq!(pieces[2], vec![(0.0, 10.0)]);
    /// ```
    pub fn clip(&self, polygons: &MultiPolygon, offsets: &[f64]) -> Vec<Vec<(f64, f64)>> {
        let mut out = Vec::with_capacity(offsets.len());
        self.clip_each(polygons, offsets, |_, pieces| out.push(pieces.to_vec()));
        out
    }

    /// [`SweepFrame::clip`] without a list per line: calls `each(line, pieces)` for every line
    /// in order, the pieces in a buffer it reuses.
    ///
    /// ```
    /// use furrow::geometry::SweepFrame;
    /// use geo::{polygon, MultiPolygon};
    ///
    /// let square = polygon![(x: 0., y: 0.), (x: 10., y: 0.), (x: 10., y: 10.), (x: 0., y: 10.)];
    /// let mut total = 0.0;
    /// SweepFrame::new(0.0).clip_each(&MultiPolygon::new(vec![square]), &[2.0, 8.0], |_, pieces| {
    ///     total += pieces.iter().map(|(a0, a1)| a1 - a0).sum::<f64>();
    /// });
    /// assert_eq!(total, 20.0);
    /// ```
    pub fn clip_each(
        &self,
        polygons: &MultiPolygon,
        offsets: &[f64],
        mut each: impl FnMut(usize, &[(f64, f64)]),
    ) {
        let vertices: usize = polygons
            .0
            .iter()
            .map(|p| p.exterior().0.len() + p.interiors().iter().map(|r| r.0.len()).sum::<usize>())
            .sum();
        let mut edges = Vec::with_capacity(vertices);
        for p in polygons.0.iter() {
            for ring in std::iter::once(p.exterior()).chain(p.interiors().iter()) {
                for w in ring.0.windows(2) {
                    let (c0, a0) = self.project(w[0]);
                    let (c1, a1) = self.project(w[1]);
                    if c0 != c1 {
                        // Comparisons, not f64::min and max: in wasm those are calls.
                        let (low, high) = if c0 < c1 { (c0, c1) } else { (c1, c0) };
                        edges.push(SweepEdge {
                            c0,
                            a0,
                            c1,
                            a1,
                            low,
                            high,
                        });
                    }
                }
            }
        }
        edges.shared_sort_by_float_key(|e| e.low);

        let mut active: Vec<SweepEdge> = Vec::new();
        let mut next = 0;
        let mut crossings: Vec<f64> = Vec::new();
        let mut pieces: Vec<(f64, f64)> = Vec::new();
        for (line, &c) in offsets.iter().enumerate() {
            while next < edges.len() && edges[next].low <= c {
                active.push(edges[next]);
                next += 1;
            }
            active.retain(|e| e.high > c);
            crossings.clear();
            for e in &active {
                // Half-open rule: an edge counts when exactly one end lies at or below c, so a
                // line through a vertex is counted once (or not at all at a local extreme).
                if (e.c0 <= c) != (e.c1 <= c) {
                    let t = (c - e.c0) / (e.c1 - e.c0);
                    crossings.push(e.a0 + t * (e.a1 - e.a0));
                }
            }
            sort_floats(&mut crossings);
            pieces.clear();
            pieces.extend(
                crossings
                    .chunks_exact(2)
                    .filter(|pair| pair[1] > pair[0])
                    .map(|pair| (pair[0], pair[1])),
            );
            each(line, &pieces);
        }
    }
}

/// The pieces of the segment from `from` to `to` inside the polygons (holes cut it), in order
/// from `from`: one line of [`SweepFrame::clip`], limited to the segment. A piece that reaches
/// an end of the segment ends at that very point.
///
/// ```
/// use furrow::geometry::clip_segment;
/// use geo::{coord, polygon, MultiPolygon};
///
/// // A 10 x 10 square with a 2 x 2 hole, crossed by a segment from x = -5 to x = 8 at y = 5.
/// let square = polygon!(
///     exterior: [(x: 0., y: 0.), (x: 10., y: 0.), (x: 10., y: 10.), (x: 0., y: 10.)],
///     interiors: [[(x: 4., y: 4.), (x: 6., y: 4.), (x: 6., y: 6.), (x: 4., y: 6.)]],
/// );
/// let pieces = clip_segment(&MultiPolygon::new(vec![square]), coord! { x: -5., y: 5. }, coord! { x: 8., y: 5. });
/// assert_eq!(pieces.len(), 2);
/// assert!((pieces[0].0.x - 0.0).abs() < 1e-12 && (pieces[0].1.x - 4.0).abs() < 1e-12);
/// assert!((pieces[1].0.x - 6.0).abs() < 1e-12 && pieces[1].1 == coord! { x: 8., y: 5. });
/// ```
pub fn clip_segment(polygons: &MultiPolygon, from: Coord, to: Coord) -> Vec<(Coord, Coord)> {
    let frame = SweepFrame::new(bearing_of(from, to));
    let (c, start) = frame.project(from);
    let (_, end) = frame.project(to);
    let mut out = Vec::new();
    if end <= start {
        return out;
    }
    frame.clip_each(polygons, &[c], |_, pieces| {
        for &(a0, a1) in pieces {
            let (a0, a1) = (a0.greater(start), a1.lesser(end));
            if a1 > a0 {
                let p = if a0 == start {
                    from
                } else {
                    frame.point(c, a0)
                };
                let q = if a1 == end { to } else { frame.point(c, a1) };
                out.push((p, q));
            }
        }
    });
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use geo::{polygon, Area, BooleanOps, Intersects, Line};
    use proptest::prelude::*;

    #[test]
    fn frame_round_trip() {
        let f = SweepFrame::new(0.7);
        let p = Coord { x: 3.0, y: -2.0 };
        let (c, a) = f.project(p);
        let q = f.point(c, a);
        assert!((p.x - q.x).abs() < 1e-12 && (p.y - q.y).abs() < 1e-12);
    }

    #[test]
    fn line_through_a_vertex_is_counted_once() {
        // A diamond: the line x = 0 passes through its top and bottom vertices.
        let diamond = polygon![(x: 0., y: -5.), (x: 5., y: 0.), (x: 0., y: 5.), (x: -5., y: 0.)];
        let f = SweepFrame::new(0.0);
        let pieces = f.clip(&MultiPolygon::new(vec![diamond]), &[-5.0, 0.0, 2.5, 5.0]);
        assert_eq!(pieces[1], vec![(-5.0, 5.0)]);
        assert_eq!(pieces[2], vec![(-2.5, 2.5)]);
        // Lines touching the diamond only at a corner yield nothing (or a zero-length piece, dropped).
        assert!(pieces[0].is_empty() && pieces[3].is_empty());
    }

    proptest! {
        #![proptest_config(crate::seeded::config(256))]
        /// The pieces of a line lie inside the polygon: their midpoints are inside, and their total
        /// length matches the length of the line's intersection computed by geo's BooleanOps.
        #[test]
        fn pieces_match_boolean_clipping(
            bearing in 0.0..std::f64::consts::PI,
            offset in -40.0..40.0f64,
            pts in proptest::collection::vec((0.0..50.0f64, 0.0..50.0f64), 3..9),
        ) {
            // A star-shaped polygon around (25, 25) from random radii: always simple.
            let mut ring: Vec<(f64, f64)> = pts.iter().enumerate().map(|(i, (r, _))| {
                let t = i as f64 / pts.len() as f64 * std::f64::consts::TAU;
                (25.0 + (r + 1.0) * t.cos() / 2.0, 25.0 + (r + 1.0) * t.sin() / 2.0)
            }).collect();
            ring.push(ring[0]);
            let poly = geo::Polygon::new(ring.into(), vec![]);
            prop_assume!(poly.unsigned_area() > 1.0);
            let f = SweepFrame::new(bearing);
            let (c25, _) = f.project(Coord { x: 25.0, y: 25.0 });
            let c = c25 + offset / 2.0;
            let pieces = &f.clip(&MultiPolygon::new(vec![poly.clone()]), &[c])[0];
            let total: f64 = pieces.iter().map(|(a0, a1)| a1 - a0).sum();
            let line = geo::MultiLineString::new(vec![geo::LineString::from(vec![
                f.point(c, -100.0), f.point(c, 100.0),
            ])]);
            let clipped = poly.clip(&line, false);
            let expected: f64 = clipped.0.iter().map(|l| {
                use geo::{Euclidean, Length};
                Euclidean.length(l)
            }).sum();
            // geo clips on a snapped integer grid, good to about 1e-6 of the extent.
            prop_assert!((total - expected).abs() < 1e-4, "{} vs {}", total, expected);
            for (a0, a1) in pieces {
                let mid = f.point(c, (a0 + a1) / 2.0);
                prop_assert!(poly.intersects(&Line::new(mid, mid)));
            }
        }

        /// A segment's pieces are those geo's BooleanOps clips: the same number, the same
        /// ends (to geo's snapping grid), inside the polygon, in order from its start.
        #[test]
        fn a_segment_is_clipped_as_by_boolean_ops(
            from in (0.0..50.0f64, 0.0..50.0f64),
            to in (0.0..50.0f64, 0.0..50.0f64),
            pts in proptest::collection::vec(0.0..50.0f64, 3..9),
            hole in proptest::bool::ANY,
        ) {
            let star = |scale: f64| -> geo::LineString {
                let mut ring: Vec<(f64, f64)> = pts.iter().enumerate().map(|(i, r)| {
                    let t = i as f64 / pts.len() as f64 * std::f64::consts::TAU;
                    (25.0 + scale * (r + 1.0) * t.cos() / 2.0, 25.0 + scale * (r + 1.0) * t.sin() / 2.0)
                }).collect();
                ring.push(ring[0]);
                ring.into()
            };
            let interiors = if hole { vec![star(0.1)] } else { vec![] };
            let poly = geo::Polygon::new(star(1.0), interiors);
            prop_assume!(poly.unsigned_area() > 1.0);
            let (a, b) = (Coord { x: from.0, y: from.1 }, Coord { x: to.0, y: to.1 });
            prop_assume!((b - a).x.hypot((b - a).y) > 1.0);
            let area = MultiPolygon::new(vec![poly.clone()]);
            let ours = clip_segment(&area, a, b);
            let theirs = poly.clip(&geo::MultiLineString::new(vec![geo::LineString::from(vec![a, b])]), false);
            use geo::{Euclidean, Length};
            // geo leaves out pieces shorter than its grid, and splits none at a vertex.
            let theirs: Vec<_> = theirs.0.iter().filter(|l| Euclidean.length(*l) > 1e-3).collect();
            let ours_kept: Vec<_> = ours.iter().filter(|(p, q)| (*q - *p).x.hypot((*q - *p).y) > 1e-3).collect();
            prop_assert_eq!(ours_kept.len(), theirs.len());
            let along = |p: Coord| (p - a).x * (b - a).x + (p - a).y * (b - a).y;
            for w in ours.windows(2) {
                prop_assert!(along(w[0].1) <= along(w[1].0));
            }
            for (p, q) in &ours_kept {
                let mid = (*p + *q) / 2.0;
                prop_assert!(poly.intersects(&Line::new(mid, mid)));
                let near = |x: Coord| theirs.iter().any(|l| l.0.iter().any(|c| (*c - x).x.hypot((*c - x).y) < 1e-4));
                prop_assert!(near(*p) && near(*q), "{:?} {:?} not in {:?}", p, q, theirs);
            }
        }
    }
}
