//! Simplifying dense outlines: a boundary recorded by a GNSS receiver driving round the field has
//! a vertex every metre or so, most of them noise. Douglas-Peucker with a tolerance tied to the
//! working width (as in the field trials of Zhou et al. 2014, section 3) keeps the shape to a
//! few centimetres and makes planning time independent of the recorder's sampling rate.

use super::ring::find_self_intersection;
use super::Field;
use crate::error::{Warning, WarningCode};
use crate::geometry::PlanarSimplify;
use geo::LineString;

/// The Douglas-Peucker tolerance for a working width: a sixth of it, between 2 cm and 1 m. A
/// 6 m implement gets 1 m: about the noise of a DGPS-recorded boundary (the benchmark's
/// GNSS-traced field keeps 74 of its 600 vertices), and a sixth of a swath at the field edge.
///
/// ```
/// use furrow::field::simplify::tolerance_for_width;
///
/// assert_eq!(tolerance_for_width(6.0), 1.0);
/// assert_eq!(tolerance_for_width(3.0), 0.5);
/// assert_eq!(tolerance_for_width(0.05), 0.02);
/// ```
pub fn tolerance_for_width(width: f64) -> f64 {
    (width / 6.0).clamp(0.02, 1.0)
}

/// A closed ring simplified by `tolerance` metres, or `None` when simplifying removes nothing or
/// would make it cross itself or collapse (the ring is then kept as it is).
pub fn simplify_ring(ring: &LineString, tolerance: f64) -> Option<LineString> {
    let simplified = ring.planar_simplify(tolerance);
    let n = simplified.0.len();
    if n >= ring.0.len() || n < 4 {
        return None;
    }
    // Open ring for the self-intersection check.
    if find_self_intersection(&simplified.0[..n - 1]).is_some() {
        return None;
    }
    Some(simplified)
}

impl Field {
    /// Simplifies the boundary, obstacles and prohibited regions by `tolerance` metres, and says
    /// what changed.
    pub fn simplify(&mut self, tolerance: f64) -> Vec<Warning> {
        let mut warnings = Vec::new();
        let before = self.boundary.exterior().0.len() - 1;
        if let Some(ring) = simplify_ring(self.boundary.exterior(), tolerance) {
            let after = ring.0.len() - 1;
            self.boundary.exterior_mut(|r| *r = ring);
            warnings.push(
                Warning::new(
                    WarningCode::OutlineSimplified,
                    format!(
                        "the field boundary was simplified from {before} to {after} points (within {tolerance:.2} m)"
                    ),
                )
                .at_feature(self.feature),
            );
        }
        let polygons = self
            .obstacles
            .iter_mut()
            .map(|o| (o.subject(), &mut o.polygon, o.feature))
            .chain(
                self.prohibited
                    .iter_mut()
                    .map(|p| (p.subject(), &mut p.polygon, p.feature)),
            );
        for (subject, polygon, feature) in polygons {
            let before = polygon.exterior().0.len() - 1;
            if let Some(ring) = simplify_ring(polygon.exterior(), tolerance) {
                let after = ring.0.len() - 1;
                polygon.exterior_mut(|r| *r = ring);
                warnings.push(
                    Warning::new(
                        WarningCode::OutlineSimplified,
                        format!(
                            "{subject} was simplified from {before} to {after} points (within {tolerance:.2} m)"
                        ),
                    )
                    .at_feature(feature),
                );
            }
        }
        warnings
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use geo::{Area, Distance, Euclidean, Point};

    /// A 200 x 100 m rectangle recorded every metre with +-5 cm of noise.
    fn noisy_rectangle() -> LineString {
        let mut pts = Vec::new();
        let mut k = 0u32;
        let mut noise = || {
            k = k.wrapping_mul(1_103_515_245).wrapping_add(12_345);
            (f64::from(k % 1000) / 1000.0 - 0.5) * 0.1
        };
        for x in 0..200 {
            pts.push((x as f64, noise()));
        }
        for y in 0..100 {
            pts.push((200.0 + noise(), y as f64));
        }
        for x in (1..=200).rev() {
            pts.push((x as f64, 100.0 + noise()));
        }
        for y in (1..=100).rev() {
            pts.push((noise(), y as f64));
        }
        pts.push(pts[0]);
        LineString::from(pts)
    }

    #[test]
    fn noise_is_removed_and_the_shape_kept() {
        let ring = noisy_rectangle();
        let simple = simplify_ring(&ring, 0.3).unwrap();
        assert!(simple.0.len() <= 12, "{} vertices left", simple.0.len());
        for c in &ring.0 {
            let d = Euclidean.distance(&Point(*c), &simple);
            assert!(d <= 0.3 + 1e-9, "{d}");
        }
        let a = geo::Polygon::new(simple, vec![]).unsigned_area();
        assert!((a - 20_000.0).abs() < 0.01 * 20_000.0);
    }

    #[test]
    fn a_clean_ring_is_left_alone() {
        let ring = LineString::from(vec![(0., 0.), (10., 0.), (10., 10.), (0., 10.), (0., 0.)]);
        assert!(simplify_ring(&ring, 0.3).is_none());
    }
}
