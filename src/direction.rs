//! The driving direction of the swaths.
//!
//! Rules: a bearing the user gives, or the one farmers use, along the longest edge of the field
//! boundary. The edge is measured on the boundary simplified to half a working width, so that a
//! GNSS-recorded boundary with many short noisy edges still has the long straight edge it looks
//! like. Forbidden bearing ranges (Oksanen & Visala 2.8: along drainage laterals, up an
//! escarpment) are respected: a fixed bearing in one is refused; the longest-edge rule takes the
//! longest edge whose direction is allowed.

use crate::error::{ErrorCode, PlanError};
use crate::field::Field;
use crate::geometry::{bearing_of, deg_to_bearing, swath_direction, BearingRange};
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

/// The swath direction (compass radians in `[0, π)`) the rule gives for the field, avoiding the
/// forbidden ranges.
///
/// ```
/// use furrow::direction::{choose_bearing, DirectionRule};
/// use furrow::field::Field;
/// use furrow::geometry::BearingRange;
///
/// // A field much longer east-west than north-south: the longest edge runs east (90 degrees).
/// let text = r#"{"type": "Polygon", "coordinates": [[[24.05, 60.25], [24.06, 60.25],
///     [24.06, 60.251], [24.05, 60.251], [24.05, 60.25]]]}"#;
/// let (field, _) = Field::from_geojson_str(text)?;
/// let rule = DirectionRule::LongestEdge { tolerance_m: 3.0 };
/// let b = choose_bearing(&field, rule, &[])?;
/// assert!((b.to_degrees() - 90.0).abs() < 0.1);
/// // With east-west forbidden, the longest allowed edge is a short side, running north.
/// let b = choose_bearing(&field, rule, &[BearingRange { from_deg: 80.0, to_deg: 100.0 }])?;
/// assert!(b.to_degrees().min(180.0 - b.to_degrees()) < 0.5);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn choose_bearing(
    field: &Field,
    rule: DirectionRule,
    forbidden: &[BearingRange],
) -> Result<f64, PlanError> {
    let allowed = |b: f64| !forbidden.iter().any(|r| r.forbids(b));
    match rule {
        DirectionRule::Fixed { bearing_deg } => {
            let b = swath_direction(deg_to_bearing(bearing_deg));
            match forbidden.iter().find(|r| r.forbids(b)) {
                None => Ok(b),
                Some(r) => Err(PlanError::new(
                    ErrorCode::BearingForbidden,
                    format!(
                        "bearing {bearing_deg} lies in the forbidden range {} to {} degrees",
                        r.from_deg, r.to_deg
                    ),
                )),
            }
        }
        DirectionRule::LongestEdge { tolerance_m } => {
            let edges = edges_longest_first(field.boundary.exterior(), tolerance_m);
            if let Some(&(_, b)) = edges.iter().find(|(_, b)| allowed(*b)) {
                return Ok(b);
            }
            // No edge runs in an allowed direction: the allowed direction nearest the longest.
            let longest = edges.first().map_or(0.0, |e| e.1);
            (1..=1800)
                .flat_map(|k| [k as f64, -(k as f64)])
                .map(|k| swath_direction(longest + (k * 0.1).to_radians()))
                .find(|&b| allowed(b))
                .ok_or_else(|| {
                    PlanError::new(
                        ErrorCode::NoAllowedDirection,
                        "the forbidden bearing ranges forbid every driving direction",
                    )
                })
        }
    }
}

/// (length, swath direction) of the edges of a ring simplified by `tolerance_m`, longest first.
fn edges_longest_first(ring: &LineString, tolerance_m: f64) -> Vec<(f64, f64)> {
    let simplified = ring.simplify(tolerance_m);
    let ring = if simplified.0.len() >= 4 {
        &simplified
    } else {
        ring
    };
    let mut edges: Vec<(f64, f64)> = ring
        .lines()
        .map(|line| {
            let d = line.delta();
            (
                d.x.hypot(d.y),
                swath_direction(bearing_of(line.start, line.end)),
            )
        })
        .collect();
    edges.sort_by(|a, b| b.0.total_cmp(&a.0));
    edges
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
            drawn_boundary: vec![],
            obstacles: vec![],
            prohibited: vec![],
            name: None,
            feature: 0,
            frame: Frame::Metric,
        };
        let b = choose_bearing(&f, DirectionRule::Fixed { bearing_deg: 270.0 }, &[]).unwrap();
        assert!((b.to_degrees() - 90.0).abs() < 1e-9);
        let drains = [BearingRange {
            from_deg: 260.0,
            to_deg: 280.0,
        }];
        let e =
            choose_bearing(&f, DirectionRule::Fixed { bearing_deg: 90.0 }, &drains).unwrap_err();
        assert_eq!(e.code, ErrorCode::BearingForbidden);
    }

    #[test]
    fn all_edges_forbidden_takes_the_nearest_allowed_direction() {
        use crate::field::Frame;
        let f = Field {
            boundary: polygon![(x: 0., y: 0.), (x: 100., y: 0.), (x: 100., y: 10.), (x: 0., y: 10.)],
            drawn_boundary: vec![],
            obstacles: vec![],
            prohibited: vec![],
            name: None,
            feature: 0,
            frame: Frame::Metric,
        };
        let forbidden = [
            BearingRange {
                from_deg: 60.0,
                to_deg: 100.0,
            },
            BearingRange {
                from_deg: 170.0,
                to_deg: 190.0,
            },
        ];
        let rule = DirectionRule::LongestEdge { tolerance_m: 1.0 };
        let b = choose_bearing(&f, rule, &forbidden).unwrap().to_degrees();
        assert!((b - 100.1).abs() < 0.01, "{b}");
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
        let edges = edges_longest_first(&LineString::new(pts), 3.0);
        let b = edges[0].1;
        assert!((b.to_degrees() - 90.0).abs() < 0.5, "{}", b.to_degrees());
    }
}
