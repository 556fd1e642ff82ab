//! Simplifying a closed ring within a sleeve: every vertex removed lies within a stated distance
//! of the edge that replaces it, on the side or sides allowed, measured against the ring as given
//! (never against a ring already thinned, so removals cannot cascade).
//!
//! The method is Zhao and Saalfeld's sleeve fitting (1997): from a kept vertex, the directions
//! of an edge that passes every vertex ahead within the sleeve narrow to a cone; the farthest
//! vertex that lies inside the cone of those before it ends the edge. Each vertex is looked at a
//! bounded number of times, so the work is linear in the ring's size whatever its shape.
//!
//! With a distance on one side only the result lies wholly on the other side of the ring
//! (provided it does not cross itself): removed vertices are all on one side of their edge, and
//! the region between a ring's stretch and the edge replacing it is then on that side.

use super::{Extremes, PlanarHypot};
use geo::Coord;

/// How far a removed vertex may lie from the edge that replaces it, on each side, metres; and
/// which vertices may be removed at all. Left and right are seen along the ring: for a
/// counter-clockwise ring left is inside.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sleeve {
    /// Largest distance left of the new edge.
    pub left: f64,
    /// Largest distance right of the new edge.
    pub right: f64,
    /// Only a vertex nearer than this to both its neighbours (as given) may be removed: the
    /// samples of a recorded outline, not the corners of a drawn one.
    pub max_gap: f64,
}

impl Sleeve {
    /// The same distance on both sides, any vertex removable.
    pub fn both(distance: f64) -> Self {
        Sleeve {
            left: distance,
            right: distance,
            max_gap: f64::INFINITY,
        }
    }
}

/// Vertices looked at beyond the last one that could end an edge before the edge is ended there
/// (or, if more, twice as many as the edge already spans): what keeps the work linear on a ring
/// that winds about within its own sleeve, while a noisy outline, whose next vertex that could
/// end an edge comes ever farther on, still gets long edges along its inner side.
const LOOKAHEAD: usize = 64;

/// The vertices of an open ring (first point not repeated) that the sleeve keeps, in order.
///
/// The edges are fitted from the lowest-left vertex (least x, then least y), so where the ring
/// starts does not matter to which vertices are kept. Every vertex removed lies within the sleeve of the edge between the
/// kept vertices before and after it, and between their feet on that edge.
///
/// ```
/// use furrow::geometry::sleeve::{sleeve_ring, Sleeve};
/// use geo::coord;
///
/// // A square with a vertex 4 cm outside its southern edge and one 4 cm inside its eastern edge.
/// let ring = [
///     coord! { x: 0.0, y: 0.0 },
///     coord! { x: 5.0, y: -0.04 },
///     coord! { x: 10.0, y: 0.0 },
///     coord! { x: 9.96, y: 5.0 },
///     coord! { x: 10.0, y: 10.0 },
///     coord! { x: 0.0, y: 10.0 },
/// ];
/// assert_eq!(sleeve_ring(&ring, Sleeve::both(0.05)).len(), 4);
/// // Only the vertex outside may go when the edges must not pass outside any vertex removed.
/// let inside = sleeve_ring(&ring, Sleeve { left: 0.0, right: 0.05, max_gap: f64::INFINITY });
/// assert_eq!(inside.len(), 5);
/// assert!(inside.contains(&coord! { x: 9.96, y: 5.0 }));
/// ```
pub fn sleeve_ring(ring: &[Coord], sleeve: Sleeve) -> Vec<Coord> {
    let n = ring.len();
    if n < 4 {
        return ring.to_vec();
    }
    let start = lowest_left(ring);
    // The ring from its lowest-left vertex round to the same vertex again.
    let at = |i: usize| ring[(start + i) % n];
    let mut ends = vec![0];
    while let Some(&anchor) = ends.last().filter(|&&a| a < n) {
        ends.push(edge_end(&at, anchor, n, sleeve));
    }
    let mut kept: Vec<usize> = ends
        .into_iter()
        .filter(|&i| i < n)
        .map(|i| (start + i) % n)
        .collect();
    // Given back starting where the ring did (at the first vertex kept), so that a ring with
    // nothing to remove comes back as it was.
    let first = kept.iter().position(|&i| i < start).unwrap_or(0);
    kept.rotate_left(first);
    kept.into_iter().map(|i| ring[i]).collect()
}

/// Whether vertex `k` is near enough to both its neighbours to be removed.
fn removable(at: &impl Fn(usize) -> Coord, k: usize, sleeve: Sleeve) -> bool {
    let p = at(k);
    let (before, after) = (p - at(k - 1), at(k + 1) - p);
    before
        .x
        .planar_hypot(before.y)
        .greater(after.x.planar_hypot(after.y))
        < sleeve.max_gap
}

/// The index of the lowest-left vertex: least x, ties to least y (a corner of the convex hull).
fn lowest_left(ring: &[Coord]) -> usize {
    let mut best = 0;
    for (i, p) in ring.iter().enumerate() {
        let b = ring[best];
        if p.x < b.x || (p.x == b.x && p.y < b.y) {
            best = i;
        }
    }
    best
}

/// The directions an edge from the anchor may take, as angles from the direction to the first
/// vertex after it: an interval, empty when `lo > hi`.
struct Cone {
    base: f64,
    lo: f64,
    hi: f64,
}

impl Cone {
    /// The distance and angle (from the base) of `p` seen from `a`.
    fn polar(&self, a: Coord, p: Coord) -> (f64, f64) {
        let v = p - a;
        let mut angle = v.y.atan2(v.x) - self.base;
        if angle > std::f64::consts::PI {
            angle -= std::f64::consts::TAU;
        } else if angle <= -std::f64::consts::PI {
            angle += std::f64::consts::TAU;
        }
        (v.x.planar_hypot(v.y), angle)
    }

    /// Narrows the cone to the directions whose line passes `p` (at `distance` and `angle`)
    /// within the sleeve: `p` at most `sleeve.left` left of it and `sleeve.right` right of it.
    fn narrow(&mut self, distance: f64, angle: f64, sleeve: Sleeve) {
        let reach = |d: f64| {
            if distance <= d {
                std::f64::consts::FRAC_PI_2
            } else {
                (d / distance).asin()
            }
        };
        self.lo = self.lo.max(angle - reach(sleeve.left));
        self.hi = self.hi.min(angle + reach(sleeve.right));
    }

    fn holds(&self, angle: f64) -> bool {
        self.lo <= angle && angle <= self.hi
    }
}

/// Where the edge from vertex `anchor` ends (an index up to `n`, which is vertex 0 again): the
/// farthest vertex in the cone of the vertices before it, with every one of them between the
/// anchor's foot and its own on the edge.
fn edge_end(at: &impl Fn(usize) -> Coord, anchor: usize, n: usize, sleeve: Sleeve) -> usize {
    let a = at(anchor);
    let first = at(anchor + 1);
    let d = first - a;
    let mut cone = Cone {
        base: d.y.atan2(d.x),
        lo: f64::NEG_INFINITY,
        hi: f64::INFINITY,
    };
    let mut end = anchor + 1;
    let mut feet = Feet::default();
    let mut k = anchor + 1;
    while k < n && k - end <= LOOKAHEAD.max(2 * (end - anchor)) {
        // Vertex k lies between the anchor and any end beyond it.
        if !removable(at, k, sleeve) {
            break;
        }
        let (distance, angle) = cone.polar(a, at(k));
        cone.narrow(distance, angle, sleeve);
        feet.push(at, anchor, k, distance);
        if cone.lo > cone.hi {
            break;
        }
        let candidate = at(k + 1);
        let (reach, direction) = cone.polar(a, candidate);
        if cone.holds(direction) && feet.within(at, anchor, k, candidate, reach) {
            end = k + 1;
        }
        k += 1;
    }
    end
}

/// The vertices between an anchor and a candidate end, for the test that each one's foot on the
/// edge lies between the edge's ends: the last [`FEET_WINDOW`] exactly, by projection on the edge,
/// and those before them by their distance from the anchor (no farther than the end), which
/// keeps the test short. Along a noisy outline the vertices just before an end are those that
/// may lie farther from the anchor than the end while their feet fall short of it.
#[derive(Default)]
struct Feet {
    /// The greatest distance from the anchor of any vertex looked at.
    farthest: f64,
    /// The greatest distance from the anchor of the vertices before the window.
    farthest_before_window: f64,
}

/// How many of the vertices just before a candidate end are tested by their feet.
const FEET_WINDOW: usize = 64;

impl Feet {
    /// Counts vertex `k` (at `distance` from the anchor) in.
    fn push(&mut self, at: &impl Fn(usize) -> Coord, anchor: usize, k: usize, distance: f64) {
        self.farthest = self.farthest.max(distance);
        if k > anchor + FEET_WINDOW {
            let leaving = at(k - FEET_WINDOW) - at(anchor);
            let d = leaving.x.planar_hypot(leaving.y);
            self.farthest_before_window = self.farthest_before_window.max(d);
        }
    }

    /// Whether every vertex after the anchor up to `k` has its foot on the edge from the anchor
    /// to `end` (at `reach`) no farther along than the end.
    fn within(
        &self,
        at: &impl Fn(usize) -> Coord,
        anchor: usize,
        k: usize,
        end: Coord,
        reach: f64,
    ) -> bool {
        if reach >= self.farthest {
            return true;
        }
        if reach < self.farthest_before_window {
            return false;
        }
        let a = at(anchor);
        let edge = end - a;
        let length_squared = edge.x * edge.x + edge.y * edge.y;
        let window = (k + 1).saturating_sub(FEET_WINDOW).max(anchor + 1);
        (window..=k).all(|i| {
            let v = at(i) - a;
            v.x * edge.x + v.y * edge.y <= length_squared
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::point_segment_distance;
    use geo::coord;

    fn circle(n: usize, radius: f64, start: usize) -> Vec<Coord> {
        (0..n)
            .map(|i| {
                let t = ((i + start) % n) as f64 / n as f64 * std::f64::consts::TAU;
                coord! { x: radius * t.cos(), y: radius * t.sin() }
            })
            .collect()
    }

    /// Distance of each vertex of `ring` from the kept ring (as a closed polyline).
    fn worst_distance(ring: &[Coord], kept: &[Coord]) -> f64 {
        ring.iter()
            .map(|&p| {
                (0..kept.len())
                    .map(|i| point_segment_distance(p, kept[i], kept[(i + 1) % kept.len()]))
                    .fold(f64::INFINITY, f64::min)
            })
            .fold(0.0, f64::max)
    }

    #[test]
    fn a_dense_circle_keeps_its_shape_within_the_sleeve() {
        // 1,000 vertices on a 50 m circle, 31 cm apart: each is 0.24 mm off its neighbours' chord.
        for start in [0, 1, 333, 999] {
            let ring = circle(1000, 50.0, start);
            let kept = sleeve_ring(&ring, Sleeve::both(1e-3));
            assert!(kept.len() > 100, "{} kept", kept.len());
            assert!(worst_distance(&ring, &kept) <= 1e-3 + 1e-12);
        }
    }

    #[test]
    fn where_the_ring_starts_does_not_matter() {
        let kept = sleeve_ring(&circle(500, 50.0, 0), Sleeve::both(0.05));
        for start in [1, 17, 250, 499] {
            let mut other = sleeve_ring(&circle(500, 50.0, start), Sleeve::both(0.05));
            let first = other.iter().position(|p| *p == kept[0]).unwrap();
            other.rotate_left(first);
            assert_eq!(other, kept);
        }
    }

    #[test]
    fn one_sided_edges_stay_inside_a_convex_ring() {
        let ring = circle(2000, 100.0, 7);
        let kept = sleeve_ring(
            &ring,
            Sleeve {
                left: 0.0,
                right: 0.2,
                max_gap: f64::INFINITY,
            },
        );
        assert!(kept.len() < 200, "{} kept", kept.len());
        // Every kept vertex is a vertex of the ring, so every edge is a chord: inside the circle.
        assert!(kept.iter().all(|k| ring.contains(k)));
        assert!(worst_distance(&ring, &kept) <= 0.2 + 1e-12);
    }

    #[test]
    fn a_concave_arc_keeps_its_vertices_on_the_inside_side() {
        // Clockwise circle: seen along the ring, its inside is on the right.
        let mut ring = circle(400, 100.0, 0);
        ring.reverse();
        let outside_only = sleeve_ring(
            &ring,
            Sleeve {
                left: 0.0,
                right: 0.5,
                max_gap: f64::INFINITY,
            },
        );
        assert_eq!(outside_only.len(), ring.len());
    }

    #[test]
    fn noise_wider_than_the_spacing_still_gives_long_edges_on_one_side() {
        // A 100 m edge recorded every centimetre, every other point 40 cm outside it: the
        // points outside lie farther from the edge's start than the next point on it, though
        // their feet on the edge fall short of it.
        let mut ring: Vec<Coord> = (0..10_000)
            .map(|i| coord! { x: i as f64 * 0.01, y: if i % 2 == 1 { -0.4 } else { 0.0 } })
            .collect();
        ring.extend([
            coord! { x: 100.0, y: 0.0 },
            coord! { x: 100.0, y: 50.0 },
            coord! { x: 0.0, y: 50.0 },
        ]);
        let kept = sleeve_ring(
            &ring,
            Sleeve {
                left: 1e-3,
                right: 0.5,
                max_gap: f64::INFINITY,
            },
        );
        assert!(kept.len() <= 8, "{} kept", kept.len());
        assert!(
            kept.iter().all(|p| p.y >= 0.0),
            "only the points on the edge are kept"
        );
    }

    #[test]
    fn an_edge_reaches_past_long_runs_of_vertices_that_cannot_end_it() {
        // A 100 m edge recorded every centimetre, only every hundredth point on it and the
        // others 30 cm outside: each point that can end the edge comes 100 vertices after the
        // last, more than the fixed lookahead.
        let mut ring: Vec<Coord> = (0..10_000)
            .map(|i| coord! { x: i as f64 * 0.01, y: if i % 100 == 0 { 0.0 } else { -0.3 } })
            .collect();
        ring.extend([
            coord! { x: 100.0, y: 0.0 },
            coord! { x: 100.0, y: 50.0 },
            coord! { x: 0.0, y: 50.0 },
        ]);
        let kept = sleeve_ring(
            &ring,
            Sleeve {
                left: 1e-3,
                right: 0.5,
                max_gap: f64::INFINITY,
            },
        );
        assert!(kept.len() <= 8, "{} kept", kept.len());
    }

    #[test]
    fn only_vertices_near_both_neighbours_are_removed() {
        // 3.14 m apart: none goes when only vertices nearer than 3 m to their neighbours may.
        let ring = circle(100, 50.0, 0);
        let sleeve = Sleeve::both(1.0);
        assert!(sleeve_ring(&ring, sleeve).len() < 20);
        let sparse = Sleeve {
            max_gap: 3.0,
            ..sleeve
        };
        assert_eq!(sleeve_ring(&ring, sparse).len(), 100);
    }
}
