//! Douglas-Peucker simplification for the planner's many estimates: point for point the
//! algorithm of geo's `Simplify` and `SimplifyIdx` (the same recursion, ties and minimum ring
//! sizes), with distances by [`PlanarHypot`] instead of the guarded `hypot` (in WebAssembly a
//! routine in software, which made geo's simplification a few per cent of a plan) and one mask
//! instead of a vector per step of the recursion.

use super::PlanarHypot;
use geo::{Coord, LineString, MultiPolygon, Polygon};

/// Simplification by Douglas-Peucker within `epsilon` metres.
///
/// ```
/// use furrow::geometry::PlanarSimplify;
/// use geo::{line_string, polygon, MultiPolygon};
///
/// let line = line_string![(x: 0., y: 0.), (x: 5., y: 0.1), (x: 10., y: 0.), (x: 10., y: 8.)];
/// assert_eq!(line.planar_simplify(0.5), line_string![(x: 0., y: 0.), (x: 10., y: 0.), (x: 10., y: 8.)]);
///
/// // A ring keeps at least four points (three corners and the closing one).
/// let field = MultiPolygon::new(vec![polygon![
///     (x: 0., y: 0.), (x: 50., y: 0.2), (x: 100., y: 0.), (x: 100., y: 60.), (x: 0., y: 60.)
/// ]]);
/// assert_eq!(field.planar_simplify(1.0).0[0].exterior().0.len(), 5);
/// ```
pub trait PlanarSimplify {
    /// The simplified geometry.
    fn planar_simplify(&self, epsilon: f64) -> Self;
}

impl PlanarSimplify for LineString {
    fn planar_simplify(&self, epsilon: f64) -> Self {
        LineString::new(kept(&self.0, epsilon, LINE_MIN_POINTS))
    }
}

impl PlanarSimplify for Polygon {
    fn planar_simplify(&self, epsilon: f64) -> Self {
        let ring = |r: &LineString| LineString::new(kept(&r.0, epsilon, RING_MIN_POINTS));
        Polygon::new(
            ring(self.exterior()),
            self.interiors().iter().map(ring).collect(),
        )
    }
}

impl PlanarSimplify for MultiPolygon {
    fn planar_simplify(&self, epsilon: f64) -> Self {
        MultiPolygon::new(self.0.iter().map(|p| p.planar_simplify(epsilon)).collect())
    }
}

/// The indices of the points of `line` that its [`PlanarSimplify::planar_simplify`] keeps, in
/// order (as geo's `SimplifyIdx`).
///
/// ```
/// use furrow::geometry::simplify::planar_simplify_idx;
/// use geo::line_string;
///
/// let line = line_string![(x: 0., y: 0.), (x: 5., y: 0.1), (x: 10., y: 0.), (x: 10., y: 8.)];
/// assert_eq!(planar_simplify_idx(&line, 0.5), [0, 2, 3]);
/// ```
pub fn planar_simplify_idx(line: &LineString, epsilon: f64) -> Vec<usize> {
    keep_mask(&line.0, epsilon, LINE_MIN_POINTS)
        .iter()
        .enumerate()
        .filter_map(|(i, &k)| k.then_some(i))
        .collect()
}

/// A line keeps at least its two ends.
const LINE_MIN_POINTS: usize = 2;
/// A ring keeps at least four points: a triangle and its closing point.
const RING_MIN_POINTS: usize = 4;

fn kept(points: &[Coord], epsilon: f64, min_points: usize) -> Vec<Coord> {
    let keep = keep_mask(points, epsilon, min_points);
    points
        .iter()
        .zip(keep)
        .filter_map(|(&p, k)| k.then_some(p))
        .collect()
}

/// Which points the simplification keeps.
fn keep_mask(points: &[Coord], epsilon: f64, min_points: usize) -> Vec<bool> {
    let mut keep = vec![true; points.len()];
    if epsilon > 0.0 && points.len() > 2 {
        let mut left = points.len();
        cull(
            points,
            0,
            points.len() - 1,
            epsilon,
            min_points,
            &mut left,
            &mut keep,
        );
    }
    keep
}

/// Douglas-Peucker on `points[first..=last]`: the farthest point from the chord (the last of
/// equals) splits the run where it is over `epsilon` away, else the points between go, unless
/// that would leave fewer than `min_points` of the `left` still kept.
fn cull(
    points: &[Coord],
    first: usize,
    last: usize,
    epsilon: f64,
    min_points: usize,
    left: &mut usize,
    keep: &mut [bool],
) {
    if last < first + 2 {
        return;
    }
    let (a, b) = (points[first], points[last]);
    let (mut farthest, mut distance) = (first, 0.0);
    for (i, &p) in points.iter().enumerate().take(last).skip(first + 1) {
        let d = segment_distance(p, a, b);
        if d >= distance {
            farthest = i;
            distance = d;
        }
    }
    if distance > epsilon {
        cull(points, first, farthest, epsilon, min_points, left, keep);
        cull(points, farthest, last, epsilon, min_points, left, keep);
        return;
    }
    let culled = last - first - 1;
    if *left < culled + min_points {
        return;
    }
    *left -= culled;
    keep[first + 1..last].iter_mut().for_each(|k| *k = false);
}

/// Distance from `p` to the segment from `a` to `b`, computed as geo computes it.
fn segment_distance(p: Coord, a: Coord, b: Coord) -> f64 {
    if a == b {
        return (a.x - p.x).planar_hypot(a.y - p.y);
    }
    let (dx, dy) = (b.x - a.x, b.y - a.y);
    let d2 = dx * dx + dy * dy;
    let r = ((p.x - a.x) * dx + (p.y - a.y) * dy) / d2;
    if r <= 0.0 {
        return (a.x - p.x).planar_hypot(a.y - p.y);
    }
    if r >= 1.0 {
        return (b.x - p.x).planar_hypot(b.y - p.y);
    }
    let s = ((a.y - p.y) * dx - (a.x - p.x) * dy) / d2;
    s.abs() * dx.planar_hypot(dy)
}

#[cfg(test)]
mod tests {
    use super::*;
    use geo::{Simplify, SimplifyIdx};

    /// Rings with bumps of every size, some as far from the chord as others (ties).
    fn wiggly(n: usize, seed: u64) -> LineString {
        let mut x = seed;
        let mut next = || {
            x = x
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (x >> 33) as f64 / (1u64 << 31) as f64
        };
        let mut pts: Vec<Coord> = (0..n)
            .map(|i| {
                let t = i as f64 / n as f64 * std::f64::consts::TAU;
                let r = 100.0 + (next() * 8.0).round() * 0.25;
                Coord {
                    x: r * t.cos(),
                    y: r * t.sin(),
                }
            })
            .collect();
        pts.push(pts[0]);
        LineString::new(pts)
    }

    #[test]
    fn keeps_the_points_geo_keeps() {
        for seed in 0..40 {
            for n in [3, 4, 5, 9, 40, 300] {
                let ring = wiggly(n, seed);
                for eps in [0.0, 0.05, 0.3, 1.0, 5.0, 500.0] {
                    assert_eq!(
                        ring.planar_simplify(eps),
                        ring.simplify(eps),
                        "line, {n} points, seed {seed}, epsilon {eps}"
                    );
                    assert_eq!(
                        planar_simplify_idx(&ring, eps),
                        ring.simplify_idx(eps),
                        "indices, {n} points, seed {seed}, epsilon {eps}"
                    );
                    let field = MultiPolygon::new(vec![Polygon::new(
                        ring.clone(),
                        vec![wiggly(n, seed + 100).0.iter().map(|c| *c * 0.3).collect()],
                    )]);
                    assert_eq!(
                        field.planar_simplify(eps),
                        field.simplify(eps),
                        "polygon, {n} points, seed {seed}, epsilon {eps}"
                    );
                }
            }
        }
    }
}
