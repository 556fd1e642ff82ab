//! Compass bearings in the local frame: radians, 0 = north (+y), clockwise, so east (+x) is π/2.
//!
//! A driving direction and its reverse are the same swath direction: [`swath_direction`] folds a
//! bearing into `[0, π)`.

use geo::Coord;
use std::f64::consts::{PI, TAU};

/// The unit vector pointing along a compass bearing (radians).
///
/// ```
/// use furrow::geometry::unit_vector;
///
/// let east = unit_vector(std::f64::consts::FRAC_PI_2);
/// assert!((east.x - 1.0).abs() < 1e-12 && east.y.abs() < 1e-12);
/// ```
#[inline]
pub fn unit_vector(bearing: f64) -> Coord {
    let (s, c) = bearing.sin_cos();
    Coord { x: s, y: c }
}

/// The compass bearing (radians, `[0, 2π)`) of the direction from `a` to `b`.
///
/// ```
/// use furrow::geometry::bearing_of;
/// use geo::coord;
///
/// let b = bearing_of(coord! { x: 0.0, y: 0.0 }, coord! { x: 0.0, y: -5.0 });
/// assert!((b - std::f64::consts::PI).abs() < 1e-12); // due south
/// ```
#[inline]
pub fn bearing_of(a: Coord, b: Coord) -> f64 {
    (b.x - a.x).atan2(b.y - a.y).rem_euclid(TAU)
}

/// A bearing folded into `[0, π)`: the swath direction, which is the same both ways.
///
/// ```
/// use furrow::geometry::swath_direction;
/// use std::f64::consts::PI;
///
/// assert!((swath_direction(1.25 * PI) - 0.25 * PI).abs() < 1e-12);
/// ```
#[inline]
pub fn swath_direction(bearing: f64) -> f64 {
    let d = bearing.rem_euclid(PI);
    // rem_euclid can round up to exactly π for tiny negative inputs.
    if d >= PI {
        0.0
    } else {
        d
    }
}

/// A compass bearing in degrees (as the API speaks) to radians in `[0, 2π)`.
#[inline]
pub fn deg_to_bearing(deg: f64) -> f64 {
    deg.to_radians().rem_euclid(TAU)
}

#[cfg(test)]
mod tests {
    use super::*;
    use geo::coord;

    #[test]
    fn bearing_and_unit_vector_agree() {
        for i in 0..36 {
            let b = i as f64 * 10f64.to_radians();
            let u = unit_vector(b);
            let back = bearing_of(coord! { x: 0.0, y: 0.0 }, u);
            assert!((back - b).abs() < 1e-12, "{b} {back}");
        }
    }

    #[test]
    fn swath_direction_is_in_half_circle() {
        for deg in [-370.0, -180.0, -1.0, 0.0, 90.0, 179.9, 180.0, 359.0, 725.0] {
            let d = swath_direction(deg_to_bearing(deg));
            assert!((0.0..PI).contains(&d), "{deg} -> {d}");
        }
        assert!(swath_direction(-1e-18).abs() < 1e-12);
    }
}
