//! How much of a plan its output holds: the points of its lines and its samples.
//!
//! A plan's output grows with its path: the GeoJSON draws each curve in chords within 5 mm of it
//! and the samples come every `sampleSpacing` metres. 100,000 swaths at 0.1 m, each joined to the
//! next by a loop of a 8 m turning radius, make 10 million points of turns (430 MB of GeoJSON),
//! and 100,000 swaths 10 km long a billion metres of path (two billion samples at 0.5 m): more
//! than a browser tab holds. Beyond [`MAX_OUTPUT_POINTS`] the lines are drawn with coarser
//! chords, and beyond [`MAX_SAMPLES`] the samples are spaced wider, so that each stays within
//! its bound; the plan says so in a warning ([`coarsened`]). The plan itself is the same.

use crate::error::{Warning, WarningCode};
use crate::numbers::{Decimals, Shortest};
use crate::path::turn::{chords_within, CHORD_TOLERANCE_M};
use crate::path::Path;

/// The most points the lines of a plan's drivable features hold (about 80 MB of GeoJSON). The
/// corpus's plans hold at most a few tens of thousands.
pub const MAX_OUTPUT_POINTS: usize = 2_000_000;

/// The most samples of a plan's path (55 bytes each, in six columns of numbers and four of
/// codes: 220 MB). The corpus's plans have at most some 700,000 at 0.5 m.
pub const MAX_SAMPLES: usize = 4_000_000;

/// The points of the path's lines with chords within `tolerance` metres of its curves: each
/// segment's first point and the end of each chord.
fn points_within(path: &Path, tolerance: f64) -> usize {
    path.segments
        .iter()
        .filter(|s| !s.pieces.is_empty())
        .map(|s| {
            1 + s
                .pieces
                .iter()
                .map(|p| chords_within(p, tolerance))
                .sum::<usize>()
        })
        .sum()
}

/// How far (metres) the chords of the output's lines may fall short of the path's curves: 5 mm,
/// or, where that would make more than [`MAX_OUTPUT_POINTS`] points, four, sixteen, ... times
/// that (each time about half as many points on the curves), the first that fits.
///
/// ```
/// use furrow::output::budget::chord_tolerance;
/// use furrow::path::curve::{Gear, Pose, Segment};
/// use furrow::path::{Path, PathSegment, SegmentKind};
///
/// // A circle of 8 m radius driven once: 89 chords within 5 mm.
/// let circle = Segment::arc(Pose::new(0.0, 0.0, 0.0), 16.0 * std::f64::consts::PI, 1.0 / 8.0, Gear::Forward);
/// let turn = |_| PathSegment::new(SegmentKind::Turn, vec![circle.clone()], None);
/// let path = Path { segments: (0..10).map(turn).collect() };
/// assert_eq!(chord_tolerance(&path), 0.005);
/// // 100,000 of them: 9 million points at 5 mm, 2.4 million at 8 cm; 12 chords each at 32 cm.
/// let many = Path { segments: (0..100_000).map(turn).collect() };
/// assert_eq!(chord_tolerance(&many), 0.32);
/// ```
pub fn chord_tolerance(path: &Path) -> f64 {
    let mut tolerance = CHORD_TOLERANCE_M;
    // Four times the tolerance, half the chords of a curve: a few rounds at most.
    for _ in 0..32 {
        if points_within(path, tolerance) <= MAX_OUTPUT_POINTS {
            break;
        }
        tolerance *= 4.0;
    }
    tolerance
}

/// The spacing (metres) of the path's samples: `spacing`, or the path's length over
/// [`MAX_SAMPLES`] where that is wider.
///
/// ```
/// use furrow::output::budget::sample_spacing;
/// use furrow::path::curve::{Gear, Pose, Segment};
/// use furrow::path::{Path, PathSegment, SegmentKind};
///
/// let line = |length| Segment::line(Pose::new(0.0, 0.0, 0.0), length, Gear::Forward);
/// let path = |length| Path { segments: vec![PathSegment::new(SegmentKind::Swath, vec![line(length)], None)] };
/// assert_eq!(sample_spacing(&path(1000.0), 0.5), 0.5);
/// // 10,000 km: a sample every 2.5 m.
/// assert_eq!(sample_spacing(&path(1e7), 0.5), 2.5);
/// ```
pub fn sample_spacing(path: &Path, spacing: f64) -> f64 {
    let length: f64 = path.segments.iter().map(|s| s.length()).sum();
    spacing.max(length / MAX_SAMPLES as f64)
}

/// The warning that the output of a plan of this path is coarser than asked, if it is: its
/// lines' chords, its samples' spacing (`spacing` asked), or both.
pub fn coarsened(path: &Path, spacing: f64) -> Option<Warning> {
    let tolerance = chord_tolerance(path);
    let spaced = sample_spacing(path, spacing);
    let mut what = Vec::new();
    if tolerance > CHORD_TOLERANCE_M {
        what.push(format!(
            "its lines are drawn with chords within {} mm of the curves (rather than {} mm), to stay within {MAX_OUTPUT_POINTS} points",
            Decimals(tolerance * 1000.0, 0),
            Decimals(CHORD_TOLERANCE_M * 1000.0, 0)
        ));
    }
    if spaced > spacing {
        what.push(format!(
            "its path is sampled every {} m (rather than {} m), to stay within {MAX_SAMPLES} samples",
            Decimals(spaced, 2),
            Shortest(spacing)
        ));
    }
    (!what.is_empty()).then(|| {
        Warning::new(
            WarningCode::OutputCoarsened,
            format!(
                "the plan is too large to draw at full detail: {}",
                what.join("; and ")
            ),
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::path::curve::{Gear, Pose, Segment};
    use crate::path::sample::sample;
    use crate::path::turn::Vehicle;
    use crate::path::{PathSegment, SegmentKind};

    /// `turns` loops of 8 m radius between swaths `length` metres long.
    fn path(turns: usize, length: f64) -> Path {
        let swath = PathSegment::new(
            SegmentKind::Swath,
            vec![Segment::line(
                Pose::new(0.0, 0.0, 0.0),
                length,
                Gear::Forward,
            )],
            None,
        );
        let arc = Segment::arc(Pose::new(0.0, 0.0, 0.0), 40.0, 1.0 / 8.0, Gear::Forward);
        let turn = PathSegment::new(SegmentKind::Turn, vec![arc], None);
        let mut segments = vec![swath.clone()];
        for _ in 0..turns {
            segments.push(turn.clone());
            segments.push(swath.clone());
        }
        Path { segments }
    }

    #[test]
    fn small_plans_are_output_in_full() {
        let p = path(100, 300.0);
        assert_eq!(chord_tolerance(&p), CHORD_TOLERANCE_M);
        assert_eq!(sample_spacing(&p, 0.5), 0.5);
        assert!(coarsened(&p, 0.5).is_none());
    }

    #[test]
    fn large_plans_stay_within_their_bounds_and_say_so() {
        // 100,000 turns between swaths 10 km long.
        let p = path(100_000, 10_000.0);
        let tolerance = chord_tolerance(&p);
        assert!(tolerance > CHORD_TOLERANCE_M);
        assert!(points_within(&p, tolerance) <= MAX_OUTPUT_POINTS);
        assert!(points_within(&p, tolerance / 4.0) > MAX_OUTPUT_POINTS);
        let spacing = sample_spacing(&p, 0.5);
        assert!(spacing > 200.0);
        // The samples: one at each piece's ends at least, and within the bound besides.
        let pieces = p.segments.len();
        let samples = sample(&p, spacing, &Vehicle::default());
        assert!(samples.len() <= MAX_SAMPLES + pieces, "{}", samples.len());
        let w = coarsened(&p, 0.5).expect("a warning");
        assert_eq!(w.code, WarningCode::OutputCoarsened);
        assert!(
            w.message.contains("chords") && w.message.contains("sampled"),
            "{}",
            w.message
        );
    }
}
