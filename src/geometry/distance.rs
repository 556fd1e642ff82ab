//! Distance from a point to a segment and the nearest point on it, the building block of the nearest-edge queries of the
//! headland and route stages; and the length of a vector without the library's `hypot`.

use geo::Coord;

/// Distance from `p` to the segment `a`–`b`.
///
/// ```
/// use furrow::geometry::point_segment_distance;
/// use geo::coord;
///
/// let (a, b) = (coord! { x: 0.0, y: 0.0 }, coord! { x: 10.0, y: 0.0 });
/// assert_eq!(point_segment_distance(coord! { x: 5.0, y: 3.0 }, a, b), 3.0);
/// assert_eq!(point_segment_distance(coord! { x: 13.0, y: 4.0 }, a, b), 5.0);
/// ```
pub fn point_segment_distance(p: Coord, a: Coord, b: Coord) -> f64 {
    let (q, _) = segment_foot(p, a, b);
    (p.x - q.x).planar_hypot(p.y - q.y)
}

/// The point of the segment `a`–`b` nearest to `p`, and its distance from `a` along the
/// segment.
///
/// ```
/// use furrow::geometry::segment_foot;
/// use geo::coord;
///
/// let (a, b) = (coord! { x: 0.0, y: 0.0 }, coord! { x: 10.0, y: 0.0 });
/// assert_eq!(segment_foot(coord! { x: 4.0, y: 3.0 }, a, b), (coord! { x: 4.0, y: 0.0 }, 4.0));
/// assert_eq!(segment_foot(coord! { x: 13.0, y: 4.0 }, a, b), (b, 10.0));
/// ```
pub fn segment_foot(p: Coord, a: Coord, b: Coord) -> (Coord, f64) {
    let ab = b - a;
    let len2 = ab.x * ab.x + ab.y * ab.y;
    let t = if len2 > 0.0 {
        (((p.x - a.x) * ab.x + (p.y - a.y) * ab.y) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (a + ab * t, t * len2.sqrt())
}

/// The length of the vector `(self, y)`: `x.hypot(y)` without its guards against overflow and
/// underflow, the square root of `x² + y²`. Field coordinates (metres, under 10⁷) come nowhere
/// near either limit, and the guarded `hypot` is a library call (in WebAssembly a routine in
/// software) that took about a tenth of the planning time of the largest corpus field.
///
/// ```
/// use furrow::geometry::PlanarHypot;
///
/// assert_eq!(3.0f64.planar_hypot(-4.0), 5.0);
/// ```
pub trait PlanarHypot {
    /// The square root of `self² + y²`.
    fn planar_hypot(self, y: f64) -> f64;
}

impl PlanarHypot for f64 {
    #[inline]
    fn planar_hypot(self, y: f64) -> f64 {
        (self * self + y * y).sqrt()
    }
}

/// The smaller and the larger of two numbers by one comparison: `f64::min` and `f64::max`
/// without their rule for NaN, which in WebAssembly makes each a call (to `fmin`, `fmax`). For
/// coordinates and lengths, never NaN in the planner, the result is the same (but for the sign
/// of a zero, where both are zeros).
///
/// ```
/// use furrow::geometry::Extremes;
///
/// assert_eq!(2.5f64.lesser(-1.0), -1.0);
/// assert_eq!(2.5f64.greater(-1.0), 2.5);
/// ```
pub trait Extremes {
    /// The smaller of `self` and `other`.
    fn lesser(self, other: f64) -> f64;
    /// The larger of `self` and `other`.
    fn greater(self, other: f64) -> f64;
}

impl Extremes for f64 {
    #[inline]
    fn lesser(self, other: f64) -> f64 {
        if self < other {
            self
        } else {
            other
        }
    }

    #[inline]
    fn greater(self, other: f64) -> f64 {
        if self > other {
            self
        } else {
            other
        }
    }
}
