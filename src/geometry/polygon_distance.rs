//! Whether two polygons come within a distance of each other: the test that groups obstacles
//! closer than a working width. Only "closer than" is asked, so the search stops at the first
//! pair of edges close enough, and edges outside the other polygon's box (grown by the
//! distance) are never paired.

use super::distance::point_segment_distance;
use geo::{BoundingRect, Coord, Intersects, Line, Polygon, Rect};

/// Whether `a` and `b` are closer than `distance` (metres): they overlap, one lies inside the
/// other, or an edge of one passes within `distance` of an edge of the other. Holes count as
/// edges: a polygon inside another's hole is as far from it as from the hole's edge.
///
/// ```
/// use furrow::geometry::polygons_within;
/// use geo::polygon;
///
/// let a = polygon![(x: 0., y: 0.), (x: 10., y: 0.), (x: 10., y: 10.), (x: 0., y: 10.)];
/// let b = polygon![(x: 14., y: 0.), (x: 20., y: 0.), (x: 20., y: 10.), (x: 14., y: 10.)];
/// assert!(polygons_within(&a, &b, 4.5));
/// assert!(!polygons_within(&a, &b, 3.5));
/// // One inside the other: distance 0.
/// let inner = polygon![(x: 4., y: 4.), (x: 6., y: 4.), (x: 6., y: 6.), (x: 4., y: 6.)];
/// assert!(polygons_within(&a, &inner, 0.1));
/// ```
pub fn polygons_within(a: &Polygon, b: &Polygon, distance: f64) -> bool {
    let (Some(ra), Some(rb)) = (a.bounding_rect(), b.bounding_rect()) else {
        return false;
    };
    let (ga, gb) = (grown(ra, distance), grown(rb, distance));
    if !ga.intersects(&rb) {
        return false;
    }
    let near_b: Vec<Line> = edges(a).filter(|l| touches(&gb, l)).collect();
    let near_a: Vec<Line> = edges(b).filter(|l| touches(&ga, l)).collect();
    let close = near_b.iter().any(|p| {
        near_a.iter().any(|q| {
            p.intersects(q)
                || point_segment_distance(p.start, q.start, q.end) < distance
                || point_segment_distance(p.end, q.start, q.end) < distance
                || point_segment_distance(q.start, p.start, p.end) < distance
                || point_segment_distance(q.end, p.start, p.end) < distance
        })
    });
    // No edges close: apart, or one wholly inside the other.
    close || inside(a, b) || inside(b, a)
}

/// Whether the first vertex of `a` lies in `b` (its holes excluded).
fn inside(a: &Polygon, b: &Polygon) -> bool {
    a.exterior().0.first().is_some_and(|&c| b.intersects(&c))
}

/// Every edge of every ring of `p`.
fn edges(p: &Polygon) -> impl Iterator<Item = Line> + '_ {
    std::iter::once(p.exterior())
        .chain(p.interiors())
        .flat_map(|r| r.lines())
}

fn grown(r: Rect, d: f64) -> Rect {
    let o = Coord { x: d, y: d };
    Rect::new(r.min() - o, r.max() + o)
}

/// Whether the box of `l` meets `r`.
fn touches(r: &Rect, l: &Line) -> bool {
    let (lo, hi) = (r.min(), r.max());
    let (x0, x1) = if l.start.x < l.end.x {
        (l.start.x, l.end.x)
    } else {
        (l.end.x, l.start.x)
    };
    let (y0, y1) = if l.start.y < l.end.y {
        (l.start.y, l.end.y)
    } else {
        (l.end.y, l.start.y)
    };
    x1 >= lo.x && x0 <= hi.x && y1 >= lo.y && y0 <= hi.y
}

#[cfg(test)]
mod tests {
    use super::*;
    use geo::{polygon, Distance, Euclidean};
    use proptest::prelude::*;

    fn star(cx: f64, cy: f64, radii: &[f64]) -> geo::LineString {
        let mut ring: Vec<(f64, f64)> = radii
            .iter()
            .enumerate()
            .map(|(i, r)| {
                let t = i as f64 / radii.len() as f64 * std::f64::consts::TAU;
                (cx + (r + 1.0) * t.cos(), cy + (r + 1.0) * t.sin())
            })
            .collect();
        ring.push(ring[0]);
        ring.into()
    }

    #[test]
    fn a_polygon_in_a_hole_is_as_far_as_the_hole_edge() {
        let ring = polygon!(
            exterior: [(x: 0., y: 0.), (x: 100., y: 0.), (x: 100., y: 100.), (x: 0., y: 100.)],
            interiors: [[(x: 20., y: 20.), (x: 80., y: 20.), (x: 80., y: 80.), (x: 20., y: 80.)]],
        );
        let island =
            polygon![(x: 40., y: 40.), (x: 60., y: 40.), (x: 60., y: 60.), (x: 40., y: 60.)];
        assert!(!polygons_within(&ring, &island, 19.0));
        assert!(polygons_within(&ring, &island, 21.0));
        assert!(!polygons_within(&island, &ring, 19.0));
    }

    proptest! {
        #![proptest_config(crate::seeded::config(256))]
        /// The same answer as geo's distance, away from the threshold itself.
        #[test]
        fn agrees_with_geo_distance(
            ra in proptest::collection::vec(0.0..20.0f64, 3..12),
            rb in proptest::collection::vec(0.0..20.0f64, 3..12),
            (bx, by) in (-60.0..60.0f64, -60.0..60.0f64),
            d in 0.1..15.0f64,
        ) {
            let a = Polygon::new(star(0.0, 0.0, &ra), vec![]);
            let b = Polygon::new(star(bx, by, &rb), vec![]);
            let exact = Euclidean.distance(&a, &b);
            prop_assume!((exact - d).abs() > 1e-9);
            prop_assert_eq!(polygons_within(&a, &b, d), exact < d, "distance {}", exact);
            prop_assert_eq!(polygons_within(&b, &a, d), exact < d);
        }
    }
}
