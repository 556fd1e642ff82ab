//! The crop still standing as the machine drives between blocks: a connection should not cross
//! the swaths the route works later (Zhou et al. 2.4.1: the machine moves between blocks along
//! the headland, not across crop), where one of the forms of turn the machine can drive keeps
//! off them.
//!
//! Each swath of the route is lines tagged with the route step that works it: its centre line
//! and, on a strip wider than two metres, the outline of the strip taken a metre in from its
//! sides, all shortened by a metre at both ends ([`IN_M`]), so that a turn onto a swath's end,
//! or along the edge of a strip, crosses none, and a run that comes into the strip anywhere,
//! over its side or along it from its end, does. A run of segments driven before step `k`
//! crosses crop where one of its chords crosses a line tagged `k` or later.
//!
//! ```
//! use furrow::path::crop::StandingCrop;
//! use furrow::path::curve::{Gear, Pose, Segment};
//! use furrow::route::{Route, RouteStep};
//! use furrow::swath::generate;
//! use geo::{polygon, MultiPolygon};
//! use std::f64::consts::PI;
//!
//! // Two swaths running north, 6 m apart, worked by steps 0 and 1.
//! let field = polygon![(x: 0., y: 0.), (x: 12., y: 0.), (x: 12., y: 100.), (x: 0., y: 100.)];
//! let swaths = generate(&MultiPolygon::new(vec![field]), 0.0, 6.0, 6.0)?;
//! let route = Route {
//!     steps: (0..2).map(|swath| RouteStep::Swath { swath, reversed: false, block: 0 }).collect(),
//!     ..Route::default()
//! };
//! let crop = StandingCrop::of_route(&route, &swaths);
//! // Driving east across the middle of the field crosses both swaths' crop.
//! let across = [Segment::line(Pose::new(-5.0, 50.0, 0.0), 20.0, Gear::Forward)];
//! assert!(crop.crossed(&across, 0));
//! // After the first swath is worked, the second is still standing; after both, nothing is.
//! assert!(crop.crossed(&across, 1));
//! assert!(!crop.crossed(&across, 2));
//! // Across the swaths' ends, within a metre of them, no crop is crossed.
//! let ends = [Segment::line(Pose::new(-5.0, 99.5, 0.0), 20.0, Gear::Forward)];
//! assert!(!crop.crossed(&ends, 0));
//! // Along the first swath's strip, 2 m off its centre line, crop is crossed where the drive
//! // slants in over the strip's edge.
//! let along = [Segment::line(Pose::new(1.0, 20.0, 1.4), 30.0, Gear::Forward)];
//! assert!(crop.crossed(&along, 0));
//! // Into the second swath's strip from its end, 1.5 m off its centre line and along it: over
//! // its crop too, though it crosses neither its centre line nor its sides.
//! let in_from_the_end = [Segment::line(Pose::new(7.5, 105.0, -PI / 2.0), 20.0, Gear::Forward)];
//! assert!(crop.crossed(&in_from_the_end, 1));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use super::curve::Segment;
use super::turn::Area;
use crate::route::{Route, RouteStep};
use crate::swath::Swaths;

/// How far in from its strip's ends and sides (metres) a swath's crop is taken to begin: a turn
/// onto a swath's end, or along the edge of a strip, crosses none.
pub const IN_M: f64 = 1.0;

/// The swaths of a route as crop standing until their step (see the module documentation).
#[derive(Debug, Clone)]
pub struct StandingCrop {
    lines: Area,
}

impl StandingCrop {
    /// The crop of the swaths `route` works, each standing until its step.
    pub fn of_route(route: &Route, swaths: &Swaths) -> Self {
        let side = swaths.width / 2.0 - IN_M;
        let mut lines = Vec::new();
        for (k, step) in route.steps.iter().enumerate() {
            let RouteStep::Swath { swath, .. } = *step else {
                continue;
            };
            let Some(s) = swaths.swaths.get(swath) else {
                continue;
            };
            let (a, b) = (s.centre.start, s.centre.end);
            let length = s.length();
            if length.is_nan() || length <= 0.0 {
                continue;
            }
            let cut = IN_M.min(length / 4.0);
            let d = (b - a) / length;
            let (a, b) = (a + d * cut, b - d * cut);
            lines.push((a, b, k));
            if side > 0.0 {
                let n = geo::Coord {
                    x: -d.y * side,
                    y: d.x * side,
                };
                lines.push((a + n, b + n, k));
                lines.push((a - n, b - n, k));
                // Across both ends: a run that comes in along the strip from its end, between
                // the lines, runs over its crop too.
                lines.push((a + n, a - n, k));
                lines.push((b + n, b - n, k));
            }
        }
        StandingCrop {
            lines: Area::of_lines(lines),
        }
    }

    /// Whether a run of segments driven before route step `step` crosses crop that step or a
    /// later one works.
    pub fn crossed(&self, segments: &[Segment], step: usize) -> bool {
        // Piece by piece: the lines near a long run are most of a block's.
        segments
            .iter()
            .any(|s| !self.lines.crosses_none_from(std::slice::from_ref(s), step))
    }

    /// The length of the pieces of a run of segments driven before route step `step` that
    /// cross crop that step or a later one works, metres: how much of the run lies over crop,
    /// to the piece.
    pub fn crossed_length(&self, segments: &[Segment], step: usize) -> f64 {
        segments
            .iter()
            .filter(|s| !self.lines.crosses_none_from(std::slice::from_ref(*s), step))
            .map(|s| s.length)
            .sum()
    }
}
