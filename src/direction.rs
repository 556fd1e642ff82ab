//! The driving direction of the swaths.
//!
//! Rules: a bearing the user gives, or the one farmers use, along the longest edge of the field
//! boundary. The edge is measured on the boundary simplified to half a working width, so that a
//! GNSS-recorded boundary with many short noisy edges still has the long straight edge it looks
//! like.

use crate::field::Field;
use crate::geometry::{bearing_of, deg_to_bearing, swath_direction};
use geo::{LineString, Simplify};

/// How the driving direction is chosen.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum DirectionRule {
    /// A fixed compass bearing, degrees.
    Fixed {
        /// The bearing, compass degrees.
        bearing_deg: f64,
    },
    /// Along the longest edge of the boundary (simplified by the given tolerance, metres).
    LongestEdge {
        /// Douglas-Peucker tolerance applied to the boundary first, metres.
        tolerance_m: f64,
    },
}

/// The swath direction (compass radians in `[0, π)`) the rule gives for the field.
///
/// ```
/// use furrow::direction::{choose_bearing, DirectionRule};
/// use furrow::field::Field;
///
/// // A field much longer east-west than north-south: the longest edge runs east (90 degrees).
/// let text = r#"{"type": "Polygon", "coordinates": [[[24.05, 60.25], [24.06, 60.25],
///     [24.06, 60.251], [24.05, 60.251], [24.05, 60.25]]]}"#;
/// let (field, _) = Field::from_geojson_str(text)?;
/// let b = choose_bearing(&field, DirectionRule::LongestEdge { tolerance_m: 3.0 });
/// assert!((b.to_degrees() - 90.0).abs() < 0.1);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn choose_bearing(field: &Field, rule: DirectionRule) -> f64 {
    match rule {
        DirectionRule::Fixed { bearing_deg } => swath_direction(deg_to_bearing(bearing_deg)),
        DirectionRule::LongestEdge { tolerance_m } => {
            longest_edge_bearing(field.boundary.exterior(), tolerance_m)
        }
    }
}

/// Swath direction of the longest edge of a ring after simplification.
fn longest_edge_bearing(ring: &LineString, tolerance_m: f64) -> f64 {
    let simplified = ring.simplify(tolerance_m);
    let ring = if simplified.0.len() >= 4 {
        &simplified
    } else {
        ring
    };
    let mut best = (0.0, 0.0);
    for line in ring.lines() {
        let d = line.delta();
        let len = d.x.hypot(d.y);
        if len > best.0 {
            best = (len, bearing_of(line.start, line.end));
        }
    }
    swath_direction(best.1)
}

#[cfg(test)]
mod tests {
    use super::*;
    use geo::{coord, polygon};

    #[test]
    fn fixed_bearing_is_folded() {
        use crate::field::Frame;
        let f = Field {
            boundary: polygon![(x: 0., y: 0.), (x: 1., y: 0.), (x: 1., y: 1.)],
            obstacles: vec![],
            prohibited: vec![],
            name: None,
            frame: Frame::Metric,
        };
        let b = choose_bearing(&f, DirectionRule::Fixed { bearing_deg: 270.0 });
        assert!((b.to_degrees() - 90.0).abs() < 1e-9);
    }

    #[test]
    fn noisy_long_edge_still_wins() {
        // A 300 m edge recorded as 60 noisy 5 m pieces, against 200 m straight sides.
        let mut pts = vec![];
        for i in 0..=60 {
            let wobble = if i % 2 == 0 { 0.3 } else { -0.3 };
            pts.push(coord! { x: i as f64 * 5.0, y: wobble });
        }
        pts.push(coord! { x: 300.0, y: 200.0 });
        pts.push(coord! { x: 0.0, y: 200.0 });
        pts.push(pts[0]);
        let b = longest_edge_bearing(&LineString::new(pts), 3.0);
        assert!((b.to_degrees() - 90.0).abs() < 0.5, "{}", b.to_degrees());
    }
}
