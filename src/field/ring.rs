//! Cleaning and checking one ring of a polygon in local metres.
//!
//! A ring drawn on a tablet or recorded by GNSS comes with the last point missing or repeated,
//! doubled vertices, vertices on a straight edge and spikes (a vertex where the line goes out and
//! straight back). [`clean_ring`] removes those and says what it did; [`find_self_intersection`]
//! finds where a ring crosses or touches itself.
//!
//! Cleaning never changes the field: every vertex removed lies within [`COLLINEAR_M`] of the
//! ring that is left, measured against the ring as given, and a spike encloses no area.

use crate::geometry::{sleeve_ring, Extremes, PlanarHypot, Sleeve};
use crate::sort::SharedSort;
use geo::algorithm::line_intersection::line_intersection;
use geo::{Coord, Line, LineIntersection};

/// Vertices closer than this (metres) are the same vertex.
pub const SAME_POINT_M: f64 = 1e-3;
/// A vertex this close (metres) to the edge that replaces it is on that edge: the most cleaning
/// moves the outline.
pub const COLLINEAR_M: f64 = 1e-3;

/// Passes of spike removal: each removes every spike it meets, nested ones included, so a second
/// is only needed where a spike straddles the ring's first vertex; what a third would find (an
/// outline that doubles back on itself at several places at once) is left to the check for
/// self-intersection.
const SPIKE_PASSES: usize = 3;

/// What [`clean_ring`] repaired.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct RingRepairs {
    /// Distinct vertices before collinear vertices and spikes were removed: a ring that had 3 or
    /// more but is left with fewer encloses no area.
    pub distinct: usize,
    /// The ring's last point did not repeat its first.
    pub was_open: bool,
    /// Repeated consecutive vertices removed.
    pub repeated: usize,
    /// Vertices removed because they lay on the straight line through their neighbours.
    pub collinear: usize,
    /// Spike vertices removed.
    pub spikes: usize,
}

/// Removes the closing point, repeated vertices, collinear vertices and spikes from a ring.
///
/// Returns the open ring (first point not repeated at the end) and what was repaired. The
/// result may have fewer than 3 points; the caller decides what that means.
///
/// A vertex is repeated within [`SAME_POINT_M`] of the last vertex kept; collinear when it lies
/// within [`COLLINEAR_M`] of the edge between the vertices kept before and after it (the ring as
/// given, not as thinned, so a dense smooth outline keeps its shape); a spike when the outline
/// turns back at it and the triangle it makes with its neighbours is thinner than
/// [`COLLINEAR_M`].
///
/// ```
/// use furrow::field::ring::clean_ring;
/// use geo::coord;
///
/// let ring = vec![
///     coord! { x: 0.0, y: 0.0 },
///     coord! { x: 5.0, y: 0.0 },  // on the edge from (0,0) to (10,0)
///     coord! { x: 10.0, y: 0.0 },
///     coord! { x: 10.0, y: 0.0 }, // repeated
///     coord! { x: 10.0, y: 10.0 },
///     coord! { x: 0.0, y: 10.0 },
/// ];
/// let (clean, repairs) = clean_ring(&ring);
/// assert_eq!(clean.len(), 4);
/// assert!(repairs.was_open);
/// assert_eq!((repairs.repeated, repairs.collinear), (1, 1));
/// ```
pub fn clean_ring(ring: &[Coord]) -> (Vec<Coord>, RingRepairs) {
    let mut repairs = RingRepairs::default();
    let mut pts: Vec<Coord> = Vec::with_capacity(ring.len());
    for &p in ring {
        match pts.last() {
            Some(&q) if distance(p, q) < SAME_POINT_M => repairs.repeated += 1,
            _ => pts.push(p),
        }
    }
    // The closing point: a GeoJSON ring repeats its first point; one that does not was open.
    if pts.len() >= 2 && distance(pts[0], pts[pts.len() - 1]) < SAME_POINT_M {
        pts.pop();
    } else if !pts.is_empty() {
        repairs.was_open = true;
    }
    repairs.distinct = pts.len();
    remove_spikes(&mut pts, &mut repairs);
    let before = pts.len();
    pts = sleeve_ring(&pts, Sleeve::both(COLLINEAR_M));
    repairs.collinear += before - pts.len();
    // An edge that replaced collinear vertices may have made a spike of its end.
    remove_spikes(&mut pts, &mut repairs);
    (pts, repairs)
}

/// Removes spikes (and the repeated vertices their removal leaves) from an open ring, in a few
/// linear passes.
fn remove_spikes(pts: &mut Vec<Coord>, repairs: &mut RingRepairs) {
    for _ in 0..SPIKE_PASSES {
        let mut kept: Vec<Coord> = Vec::with_capacity(pts.len());
        for &p in pts.iter() {
            kept.push(p);
            drop_spikes_at_end(&mut kept, repairs);
        }
        *pts = kept;
        if !spike_at_start(pts) {
            return;
        }
        // A spike straddles the first vertex: start the next pass half way round.
        let half = pts.len() / 2;
        pts.rotate_left(half);
    }
}

/// Removes the last vertices of `kept` while they repeat or the one before the last is a spike.
fn drop_spikes_at_end(kept: &mut Vec<Coord>, repairs: &mut RingRepairs) {
    loop {
        let n = kept.len();
        if n >= 2 && distance(kept[n - 1], kept[n - 2]) < SAME_POINT_M {
            kept.pop();
            repairs.repeated += 1;
        } else if n >= 3 && is_spike(kept[n - 3], kept[n - 2], kept[n - 1]) {
            kept.swap_remove(n - 2);
            repairs.spikes += 1;
        } else {
            return;
        }
    }
}

/// Whether the ring repeats a vertex or has a spike where its end meets its start.
fn spike_at_start(pts: &[Coord]) -> bool {
    let n = pts.len();
    n >= 3
        && (distance(pts[n - 1], pts[0]) < SAME_POINT_M
            || is_spike(pts[n - 2], pts[n - 1], pts[0])
            || is_spike(pts[n - 1], pts[0], pts[1]))
}

/// Whether the outline turns back at `v` (its two edges less than a right angle apart) along a
/// triangle thinner than [`COLLINEAR_M`]: out and straight back, enclosing no area.
fn is_spike(prev: Coord, v: Coord, next: Coord) -> bool {
    let a = prev - v;
    let b = next - v;
    let dot = a.x * b.x + a.y * b.y;
    if dot <= 0.0 {
        return false;
    }
    let cross = a.x * b.y - a.y * b.x;
    let longest = a.x.planar_hypot(a.y).greater(b.x.planar_hypot(b.y));
    cross.abs() < COLLINEAR_M * longest
}

#[inline]
fn distance(a: Coord, b: Coord) -> f64 {
    (a.x - b.x).planar_hypot(a.y - b.y)
}

/// Twice the signed area of an open ring: positive when counter-clockwise.
pub fn signed_area2(ring: &[Coord]) -> f64 {
    let n = ring.len();
    (0..n)
        .map(|i| {
            let (p, q) = (ring[i], ring[(i + 1) % n]);
            p.x * q.y - q.x * p.y
        })
        .sum()
}

/// Finds a point where an open ring crosses or touches itself, if there is one.
///
/// Returns the point and the indices of the two edges (edge `i` runs from vertex `i` to
/// vertex `i + 1`), the first such pair along the ring. Neighbouring edges share their common
/// vertex and are not reported for it.
///
/// A sweep across x: the edges ordered by their western end, each tested against the earlier
/// ones that still reach it and overlap it in y.
///
/// ```
/// use furrow::field::ring::find_self_intersection;
/// use geo::coord;
///
/// let bowtie = [
///     coord! { x: 0.0, y: 0.0 },
///     coord! { x: 10.0, y: 10.0 },
///     coord! { x: 10.0, y: 0.0 },
///     coord! { x: 0.0, y: 10.0 },
/// ];
/// let (p, i, j) = find_self_intersection(&bowtie).ok_or("no crossing")?;
/// assert!((p.x - 5.0).abs() < 1e-9 && (p.y - 5.0).abs() < 1e-9);
/// assert_eq!((i, j), (0, 2));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn find_self_intersection(ring: &[Coord]) -> Option<(Coord, usize, usize)> {
    let n = ring.len();
    if n < 3 {
        return None;
    }
    let edge = |i: usize| Line::new(ring[i], ring[(i + 1) % n]);
    let mut order: Vec<usize> = (0..n).collect();
    order.shared_sort_by_float_key(|&i| {
        let l = edge(i);
        l.start.x.lesser(l.end.x)
    });
    // The edges seen so far that may still reach the sweep: (east end, index).
    let mut active: Vec<(f64, usize)> = Vec::new();
    let mut first: Option<(usize, usize, Coord)> = None;
    for &k in &order {
        let l = edge(k);
        let (west, east) = (l.start.x.lesser(l.end.x), l.start.x.greater(l.end.x));
        let (south, north) = (l.start.y.lesser(l.end.y), l.start.y.greater(l.end.y));
        active.retain(|&(reach, _)| reach >= west);
        for &(_, m) in &active {
            let o = edge(m);
            if o.start.y.greater(o.end.y) < south || o.start.y.lesser(o.end.y) > north {
                continue;
            }
            let Some(hit) = line_intersection(l, o) else {
                continue;
            };
            let (i, j) = (k.min(m), k.max(m));
            let point = match hit {
                LineIntersection::SinglePoint { intersection, .. } => {
                    let neighbours = j == i + 1 || (i == 0 && j == n - 1);
                    // Neighbours meet at their shared vertex; anything else is an overlap.
                    let shared = if j == i + 1 { ring[j] } else { ring[0] };
                    if neighbours && distance(intersection, shared) <= SAME_POINT_M {
                        continue;
                    }
                    intersection
                }
                LineIntersection::Collinear { intersection } => intersection.start,
            };
            if first.is_none_or(|(a, b, _)| (i, j) < (a, b)) {
                first = Some((i, j, point));
            }
        }
        active.push((east, k));
    }
    first.map(|(i, j, p)| (p, i, j))
}

#[cfg(test)]
mod tests {
    use super::*;
    use geo::coord;

    fn square() -> Vec<Coord> {
        vec![
            coord! { x: 0.0, y: 0.0 },
            coord! { x: 10.0, y: 0.0 },
            coord! { x: 10.0, y: 10.0 },
            coord! { x: 0.0, y: 10.0 },
        ]
    }

    #[test]
    fn closed_clean_ring_is_unchanged() {
        let mut ring = square();
        ring.push(ring[0]);
        let (clean, repairs) = clean_ring(&ring);
        assert_eq!(clean, square());
        assert_eq!(
            repairs,
            RingRepairs {
                distinct: 4,
                ..Default::default()
            }
        );
    }

    #[test]
    fn removes_a_spike() {
        // Up the east side, out to (20, 5) and straight back, then on up.
        let ring = vec![
            coord! { x: 0.0, y: 0.0 },
            coord! { x: 10.0, y: 0.0 },
            coord! { x: 10.0, y: 5.0 },
            coord! { x: 20.0, y: 5.0 },
            coord! { x: 10.0, y: 5.0001 },
            coord! { x: 10.0, y: 10.0 },
            coord! { x: 0.0, y: 10.0 },
        ];
        let (clean, repairs) = clean_ring(&ring);
        assert_eq!(repairs.spikes, 1, "{repairs:?}");
        assert_eq!(clean, square());
    }

    #[test]
    fn collinear_points_collapse_to_nothing() {
        let ring = vec![
            coord! { x: 0.0, y: 0.0 },
            coord! { x: 10.0, y: 0.0 },
            coord! { x: 20.0, y: 0.0 },
            coord! { x: 0.0, y: 0.0 },
        ];
        let (clean, _) = clean_ring(&ring);
        assert!(clean.len() < 3, "{clean:?}");
    }

    #[test]
    fn orientation_sign() {
        assert!(signed_area2(&square()) > 0.0);
        let mut cw = square();
        cw.reverse();
        assert!(signed_area2(&cw) < 0.0);
    }

    #[test]
    fn simple_ring_has_no_self_intersection() {
        assert!(find_self_intersection(&square()).is_none());
    }

    #[test]
    fn ring_touching_itself_at_a_vertex_is_found() {
        // An hourglass pinched at (5, 5): the fourth vertex touches the first edge pair's corner.
        let ring = vec![
            coord! { x: 0.0, y: 0.0 },
            coord! { x: 10.0, y: 0.0 },
            coord! { x: 5.0, y: 5.0 },
            coord! { x: 10.0, y: 10.0 },
            coord! { x: 0.0, y: 10.0 },
            coord! { x: 5.0, y: 5.0 },
        ];
        let (p, _, _) = find_self_intersection(&ring).unwrap();
        assert!((p.x - 5.0).abs() < 1e-9 && (p.y - 5.0).abs() < 1e-9);
    }

    /// Every pair of edges that meets other than at a shared vertex, by geo's sweep.
    fn crossings_by_geo(ring: &[Coord]) -> Vec<(usize, usize)> {
        use geo::algorithm::sweep::{Cross, Intersections};
        #[derive(Debug, Clone, Copy)]
        struct Edge(usize, Line);
        impl Cross for Edge {
            type Scalar = f64;
            fn line(&self) -> Line {
                self.1
            }
        }
        let n = ring.len();
        let edges = (0..n).map(|i| Edge(i, Line::new(ring[i], ring[(i + 1) % n])));
        let mut pairs: Vec<(usize, usize)> = Intersections::from_iter(edges)
            .filter_map(|(a, b, hit)| {
                let (i, j) = (a.0.min(b.0), a.0.max(b.0));
                let neighbours = j == i + 1 || (i == 0 && j == n - 1);
                let shared = if j == i + 1 { ring[j] } else { ring[0] };
                match hit {
                    LineIntersection::SinglePoint { intersection, .. }
                        if neighbours && distance(intersection, shared) <= SAME_POINT_M =>
                    {
                        None
                    }
                    _ => Some((i, j)),
                }
            })
            .collect();
        pairs.sort();
        pairs
    }

    proptest::proptest! {
        #![proptest_config(crate::seeded::config(512))]
        /// The sweep finds a crossing exactly when geo's does, and the first pair along the ring.
        #[test]
        fn the_first_crossing_along_the_ring_is_found(
            pts in proptest::collection::vec((0i32..12, 0i32..12), 3..14),
        ) {
            // Points on a coarse grid: edges through each other's vertices, collinear overlaps
            // and shared points are common.
            let ring: Vec<Coord> = pts.iter().map(|&(x, y)| coord! { x: x as f64, y: y as f64 }).collect();
            let expected = crossings_by_geo(&ring);
            let found = find_self_intersection(&ring).map(|(_, i, j)| (i, j));
            proptest::prop_assert_eq!(found, expected.first().copied());
        }
    }
}
