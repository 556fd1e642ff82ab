//! The nearest point of a ring to a position, as geo's `ClosestPoint` finds it, without the
//! segments too far to hold it.

use crate::geometry::{Extremes, PlanarHypot};
use geo::{Coord, Intersects};

/// Distance to and the nearest point of a ring from a position (0 and `None` without one).
///
/// The point geo's `ClosestPoint` finds, by its own steps and comparisons, segment by segment:
/// but each best distance is computed once, and a segment whose box lies farther from the
/// position than the best point so far is passed over (planning asks this of every pass for
/// every block).
pub fn nearest_on_ring(ring: &geo::LineString, position: Option<Coord>) -> (f64, Option<Coord>) {
    let Some(p) = position else {
        return (0.0, ring.0.first().copied());
    };
    // The nearest point so far and its distance as geo measures it.
    let mut best: Option<(Coord, f64)> = None;
    for line in ring.lines() {
        let (a, b) = (line.start, line.end);
        let d = b - a;
        if d.x == 0.0 && d.y == 0.0 {
            continue; // geo: a segment of no length has no closest point
        }
        if let Some((_, so_far)) = best {
            let gap_x = (a.x.lesser(b.x) - p.x).greater(p.x - a.x.greater(b.x));
            let gap_y = (a.y.lesser(b.y) - p.y).greater(p.y - a.y.greater(b.y));
            let (gap_x, gap_y) = (gap_x.greater(0.0), gap_y.greater(0.0));
            if gap_x * gap_x + gap_y * gap_y > so_far * so_far * (1.0 + 1e-9) {
                continue;
            }
        }
        let to_p = p - a;
        let t = (to_p.x * d.x + to_p.y * d.y) / (d.x * d.x + d.y * d.y);
        let c = if t < 0.0 {
            a
        } else if t > 1.0 {
            b
        } else {
            let c = a + Coord {
                x: t * d.x,
                y: t * d.y,
            };
            if line.intersects(&p) {
                return (distance(p, c), Some(c));
            }
            c
        };
        let from_p = c - p;
        let dc = from_p.x.hypot(from_p.y);
        if best.is_none_or(|(_, so_far)| dc <= so_far) {
            best = Some((c, dc));
        }
    }
    match best {
        Some((q, _)) => (distance(p, q), Some(q)),
        None => (f64::INFINITY, None),
    }
}

#[inline]
fn distance(a: Coord, b: Coord) -> f64 {
    (a.x - b.x).planar_hypot(a.y - b.y)
}

#[cfg(test)]
mod tests {
    use super::*;
    use geo::LineString;

    proptest::proptest! {
        #![proptest_config(crate::seeded::config(1024))]
        /// The nearest point of a ring is the one geo's `ClosestPoint` finds, to the bit: rings
        /// on a coarse grid (repeated points, segments of no length, positions on the ring and
        /// at its vertices) and off it.
        #[test]
        fn the_nearest_point_of_a_ring_is_geos(
            points in proptest::collection::vec((0..12i32, 0..12i32), 1..14),
            at in (0..24i32, 0..24i32),
            off_grid in proptest::bool::ANY,
        ) {
            use geo::{Closest, ClosestPoint, Point};
            let mut ring: Vec<Coord> = points
                .iter()
                .map(|&(x, y)| Coord { x: x as f64 * 7.0, y: y as f64 * 7.0 })
                .collect();
            ring.push(ring[0]);
            let ring = LineString::new(ring);
            let shift = if off_grid { 0.37 } else { 0.0 };
            let p = Coord { x: at.0 as f64 * 3.5 + shift, y: at.1 as f64 * 3.5 - shift };
            let expected = match ring.closest_point(&Point(p)) {
                Closest::Intersection(q) | Closest::SinglePoint(q) => (distance(p, q.0), Some(q.0)),
                Closest::Indeterminate => (f64::INFINITY, None),
            };
            let got = nearest_on_ring(&ring, Some(p));
            proptest::prop_assert_eq!(got.0.to_bits(), expected.0.to_bits());
            proptest::prop_assert_eq!(
                got.1.map(|q| (q.x.to_bits(), q.y.to_bits())),
                expected.1.map(|q| (q.x.to_bits(), q.y.to_bits()))
            );
        }
    }
}
