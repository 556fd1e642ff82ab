//! What the tests of the turn modules share: random cases, and driving a path piece by piece.

use super::curve::{wrap, Pose, Segment};
use crate::rng::SplitMix64 as Rng;
use std::f64::consts::PI;

/// A random start, goal and radius: radius 1..15 m, the goal 0..100 m away (half the time
/// within four radii, where the three-arc words and the paths with cusps live), headings not necessarily wrapped.
pub fn case(rng: &mut Rng) -> (Pose, Pose, f64) {
    let r = rng.range(1.0, 15.0);
    let from = Pose::new(
        rng.range(-50.0, 50.0),
        rng.range(-50.0, 50.0),
        rng.range(-7.0, 7.0),
    );
    let dist = if rng.unit() < 0.5 {
        rng.range(0.0, 100.0)
    } else {
        rng.range(0.0, (4.0 * r).min(100.0))
    };
    let dir = rng.range(-PI, PI);
    let to = Pose::new(
        from.x + dist * dir.cos(),
        from.y + dist * dir.sin(),
        rng.range(-7.0, 7.0),
    );
    (from, to, r)
}

/// Drives the segments one after the other, each from where the one before ended.
pub fn drive(from: Pose, segments: &[Segment]) -> Pose {
    let mut at = from;
    for s in segments {
        assert!(
            s.start.distance(&at) < 1e-9,
            "{s:?} does not start at {at:?}"
        );
        assert!(wrap(s.start.heading - at.heading).abs() < 1e-12);
        at = Segment { start: at, ..*s }.end();
    }
    at
}

pub fn assert_reaches(end: Pose, to: Pose, what: &dyn std::fmt::Debug) {
    assert!(
        end.distance(&to) < 1e-6,
        "{what:?} ends at {end:?}, not {to:?}"
    );
    assert!(
        wrap(end.heading - to.heading).abs() < 1e-9,
        "{what:?}: {end:?} vs {to:?}"
    );
}
