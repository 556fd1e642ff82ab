//! The path as points at a set spacing: for drawing it, and for guiding the machine along it.
//!
//! Every piece of every segment is cut into equal steps no longer than the spacing, so that the
//! ends of pieces (where an arc starts, a cusp, where the implement goes down) are samples.
//! Each sample has its position, heading, curvature, gear, segment kind, whether the implement
//! works, and the distance and time from the start of the path (working segments at working
//! speed, the rest at turning speed). Columns, not points: the arrays go to JavaScript as typed
//! arrays without an object per point.
//!
//! ```
//! use furrow::path::curve::{Gear, Pose, Segment};
//! use furrow::path::sample::sample;
//! use furrow::path::turn::Vehicle;
//! use furrow::path::{Path, PathSegment, SegmentKind};
//!
//! let line = Segment::line(Pose::new(0.0, 0.0, 0.0), 10.0, Gear::Forward);
//! let swath = PathSegment::new(SegmentKind::Swath, vec![line], None);
//! let path = Path { segments: vec![swath] };
//! let s = sample(&path, 0.5, &Vehicle::default());
//! assert_eq!(s.len(), 21);
//! assert_eq!(s.distance_m[20], 10.0);
//! assert_eq!(s.heading_deg[0], 90.0); // east
//! ```

use super::curve::Gear;
use super::turn::Vehicle;
use super::Path;

/// The sampled path, column by column (all of the same length).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Samples {
    /// East, in the plan's local metres (the output converts to the input's coordinates).
    pub x: Vec<f64>,
    /// North, local metres.
    pub y: Vec<f64>,
    /// Heading as a compass bearing, degrees (0 = north, clockwise): where the machine faces,
    /// also when it reverses.
    pub heading_deg: Vec<f64>,
    /// Steering curvature, 1/m, positive to the left.
    pub curvature: Vec<f64>,
    /// Distance driven from the start of the path, metres.
    pub distance_m: Vec<f64>,
    /// Time from the start of the path, seconds.
    pub time_s: Vec<f64>,
    /// Segment kind ([`super::SegmentKind::code`]).
    pub kind: Vec<u8>,
    /// 1 where the machine reverses, else 0.
    pub reverse: Vec<u8>,
    /// 1 where the implement works, else 0.
    pub working: Vec<u8>,
    /// Index of the path segment (and of its drivable feature in the plan output).
    pub segment: Vec<u32>,
}

impl Samples {
    /// Number of samples.
    pub fn len(&self) -> usize {
        self.x.len()
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.x.is_empty()
    }
}

/// Samples `path` at most `spacing` metres apart (see the module documentation).
pub fn sample(path: &Path, spacing: f64, v: &Vehicle) -> Samples {
    let spacing = if spacing.is_finite() && spacing > 0.0 {
        spacing
    } else {
        0.5
    };
    let total: f64 = path.segments.iter().map(|s| s.length()).sum();
    let capacity = ((total / spacing) as usize)
        .saturating_add(path.segments.len() * 4)
        .min(50_000_000);
    let mut out = Samples {
        x: Vec::with_capacity(capacity),
        y: Vec::with_capacity(capacity),
        heading_deg: Vec::with_capacity(capacity),
        curvature: Vec::with_capacity(capacity),
        distance_m: Vec::with_capacity(capacity),
        time_s: Vec::with_capacity(capacity),
        kind: Vec::with_capacity(capacity),
        reverse: Vec::with_capacity(capacity),
        working: Vec::with_capacity(capacity),
        segment: Vec::with_capacity(capacity),
    };
    let (mut distance, mut time) = (0.0, 0.0);
    let mut along: Vec<f64> = Vec::new();
    for (index, seg) in path.segments.iter().enumerate() {
        let working = seg.is_working();
        let speed = if working {
            v.working_speed
        } else {
            v.turning_speed
        };
        let speed = if speed > 0.0 { speed } else { 1.0 };
        for piece in &seg.pieces {
            let n = ((piece.length / spacing).ceil() as usize).max(1);
            let first = usize::from(!out.is_empty());
            // The distances along the piece, once: every column is made from them.
            along.clear();
            along.extend((first..=n).map(|i| piece.length * i as f64 / n as f64));
            let count = along.len();
            // Lines (most of a path: the swaths) step along without trigonometry.
            if piece.curvature == 0.0 && piece.sharpness == 0.0 {
                let g = piece.gear.sign();
                let (dy, dx) = piece.start.heading.sin_cos();
                let (x, y) = (piece.start.x, piece.start.y);
                for &s in &along {
                    out.x.push(x + g * dx * s);
                    out.y.push(y + g * dy * s);
                }
                let heading = compass_deg(piece.start.heading);
                out.heading_deg.extend(std::iter::repeat_n(heading, count));
            } else {
                let poses = piece.poses();
                for p in poses.evenly(piece.length, n).skip(first) {
                    out.x.push(p.x);
                    out.y.push(p.y);
                    out.heading_deg.push(compass_deg(p.heading));
                }
            }
            for &s in &along {
                out.curvature.push(piece.curvature_at(s));
                out.distance_m.push(distance + s);
                out.time_s.push(time + s / speed);
            }
            // The columns that stay the same along a piece, filled.
            out.kind.extend(std::iter::repeat_n(seg.kind.code(), count));
            let reverse = u8::from(piece.gear == Gear::Reverse);
            out.reverse.extend(std::iter::repeat_n(reverse, count));
            out.working
                .extend(std::iter::repeat_n(u8::from(working), count));
            out.segment.extend(std::iter::repeat_n(index as u32, count));
            distance += piece.length;
            time += piece.length / speed;
        }
    }
    out
}

/// A heading (radians counter-clockwise from east) as a compass bearing in degrees, [0, 360).
pub fn compass_deg(heading: f64) -> f64 {
    let b = 90.0 - heading.to_degrees();
    // A turn or two from [0, 360) by adding or subtracting 360 (exact, as `rem_euclid` is),
    // without the remainder routine that `rem_euclid` calls in WebAssembly.
    let b = if (0.0..360.0).contains(&b) {
        b
    } else if b > -360.0 && b < 0.0 {
        b + 360.0
    } else if (360.0..720.0).contains(&b) {
        b - 360.0
    } else {
        b.rem_euclid(360.0)
    };
    if b >= 360.0 {
        0.0
    } else {
        b
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn by_remainder(heading: f64) -> f64 {
        let b = (90.0 - heading.to_degrees()).rem_euclid(360.0);
        if b >= 360.0 {
            0.0
        } else {
            b
        }
    }

    #[test]
    fn whole_turns_and_their_edges_are_bearings_in_range() {
        use std::f64::consts::PI;
        for h in [
            0.0,
            -0.0,
            PI / 2.0,
            -PI / 2.0,
            2.5 * PI,
            -1.5 * PI,
            7.0 * PI,
            -9.0 * PI,
            1e-17,
            -1e-17,
        ] {
            assert_eq!(compass_deg(h).to_bits(), by_remainder(h).to_bits(), "{h}");
            assert!((0.0..360.0).contains(&compass_deg(h)));
        }
    }

    proptest! {
        #![proptest_config(crate::seeded::config(4096))]
        /// The same bearing, to the bit, as the remainder it replaces.
        #[test]
        fn the_same_as_the_remainder(h in -60.0..60.0f64) {
            prop_assert_eq!(compass_deg(h).to_bits(), by_remainder(h).to_bits());
        }
    }
}
