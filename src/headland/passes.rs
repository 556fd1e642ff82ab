//! How many headland passes: the option's count, (`headlandPasses: "auto"`) as many as the
//! machine's turns need, or (`"all"`) as many as the field holds: the whole field worked along
//! its outline, pass inside pass to the middle ([`passes_to_fill`]).
//!
//! Swaths end at the inner edge of the headland, `h·w` inside the boundary for `h` passes of
//! width `w`. A turn from one swath end to the next reaches beyond the ends by a depth that
//! depends on the machine and on the spacing of the swath ends it joins: a U-turn of radius `r`
//! reaches `r` beyond them, the loop a forward-only machine drives between neighbours closer
//! than `2r` reaches further (up to about `2.7 r`), a three-point turn `r`, and a reversing
//! machine's cheapest turn between neighbours often backs into the swath it came from and reaches
//! no further than the ends. The turn stays inside
//! the field when the headland is at least that deep, so `h` is that depth in widths, rounded up.
//!
//! The spacing is one width: every swath order (boustrophedon, snake, spiral) turns between
//! neighbouring swaths somewhere, and those turns are the deepest.

use crate::path::curve::{Pose, Segment};
use crate::path::turn::{chord_poses, Vehicle};
use geo::{BoundingRect, Polygon};
use serde::de::{self, Visitor};
use serde::{Deserialize, Deserializer, Serialize, Serializer};
use std::fmt;

/// The number of headland passes asked for: a count, `auto` for the fewest passes of the
/// machine's width whose depth holds its turns between neighbouring swaths
/// ([`passes_for_turns`]), or `all` for as many as the field holds ([`passes_to_fill`]). In
/// JSON a number, `"auto"` or `"all"`.
///
/// ```
/// use furrow::headland::passes::HeadlandPasses;
///
/// let auto: HeadlandPasses = serde_json::from_str(r#""auto""#)?;
/// assert_eq!(auto, HeadlandPasses::Auto);
/// assert_eq!(serde_json::from_str::<HeadlandPasses>(r#""all""#)?, HeadlandPasses::All);
/// assert_eq!(serde_json::from_str::<HeadlandPasses>("3")?, HeadlandPasses::Count(3));
/// assert_eq!(HeadlandPasses::from(2).count(), Some(2));
/// assert!(serde_json::from_str::<HeadlandPasses>(r#""many""#).is_err());
/// # Ok::<(), serde_json::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum HeadlandPasses {
    /// This many passes.
    Count(u32),
    /// As many as the machine's turns need.
    Auto,
    /// As many as the field holds: it is worked along its outline to the middle.
    All,
}

impl HeadlandPasses {
    /// The count, `None` for `auto` and `all`.
    pub fn count(self) -> Option<u32> {
        match self {
            HeadlandPasses::Count(n) => Some(n),
            HeadlandPasses::Auto | HeadlandPasses::All => None,
        }
    }
}

impl From<u32> for HeadlandPasses {
    fn from(n: u32) -> Self {
        HeadlandPasses::Count(n)
    }
}

impl Serialize for HeadlandPasses {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        match self {
            HeadlandPasses::Count(n) => serializer.serialize_u32(*n),
            HeadlandPasses::Auto => serializer.serialize_str("auto"),
            HeadlandPasses::All => serializer.serialize_str("all"),
        }
    }
}

impl<'de> Deserialize<'de> for HeadlandPasses {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_any(PassesVisitor)
    }
}

/// Reads a count of passes, `"auto"` or `"all"`.
struct PassesVisitor;

impl Visitor<'_> for PassesVisitor {
    type Value = HeadlandPasses;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a whole number of passes, \"auto\" or \"all\"")
    }

    fn visit_u64<E: de::Error>(self, n: u64) -> Result<HeadlandPasses, E> {
        u32::try_from(n)
            .map(HeadlandPasses::Count)
            .map_err(|_| E::invalid_value(de::Unexpected::Unsigned(n), &self))
    }

    fn visit_i64<E: de::Error>(self, n: i64) -> Result<HeadlandPasses, E> {
        u64::try_from(n)
            .map_err(|_| E::invalid_value(de::Unexpected::Signed(n), &self))
            .and_then(|n| self.visit_u64(n))
    }

    fn visit_str<E: de::Error>(self, s: &str) -> Result<HeadlandPasses, E> {
        if s == "auto" {
            Ok(HeadlandPasses::Auto)
        } else if s == "all" {
            Ok(HeadlandPasses::All)
        } else {
            Err(E::invalid_value(de::Unexpected::Str(s), &self))
        }
    }
}

/// How far the machine's cheapest turn between two swath ends `spacing` apart reaches beyond
/// them, metres (along the swaths, past the line through both ends).
///
/// ```
/// use furrow::headland::passes::turn_depth;
/// use furrow::path::turn::Vehicle;
///
/// // Swaths 20 m apart and a radius of 8 m: a U-turn, as deep as its radius.
/// let wide = Vehicle { width: 20.0, turn_radius: 8.0, ..Default::default() };
/// assert!((turn_depth(&wide, 20.0) - 8.0).abs() < 0.01);
/// // Neighbours 6 m apart: the forward-only machine loops round, much deeper.
/// let drill = Vehicle { width: 6.0, turn_radius: 8.0, reverse: false, ..Default::default() };
/// assert!(turn_depth(&drill, 6.0) > 16.0);
/// ```
pub fn turn_depth(vehicle: &Vehicle, spacing: f64) -> f64 {
    if vehicle.pivots() || !(spacing.is_finite() && spacing > 0.0) {
        return 0.0;
    }
    // Out of a swath heading north at the origin, into the next one east of it heading south.
    let from = Pose::new(0.0, 0.0, std::f64::consts::FRAC_PI_2);
    let to = Pose::new(spacing, 0.0, -std::f64::consts::FRAC_PI_2);
    let turn = vehicle.shortest(from, to);
    reach_north(&turn.segments)
}

/// The northernmost point of a run of segments (0 at least).
fn reach_north(segments: &[Segment]) -> f64 {
    segments
        .iter()
        .flat_map(chord_poses)
        .map(|(p, _)| p.y)
        .fold(0.0, f64::max)
}

/// Headland passes of the machine's width deep enough for its turns between neighbouring
/// swaths: at least one, at most `most`.
///
/// ```
/// use furrow::headland::passes::passes_for_turns;
/// use furrow::path::turn::Vehicle;
///
/// // A 3 m mower turning at 5 m loops round between neighbours, 12.6 m deep: five passes.
/// let mower = Vehicle { width: 3.0, turn_radius: 5.0, ..Default::default() };
/// assert_eq!(passes_for_turns(&mower, 50), 5);
/// // A 24 m sprayer turning at 9 m makes a U-turn 9 m deep between ends in line; between ends
/// // staggered along an edge at 21° to its swaths, made level with the end further out, it
/// // reaches 73 m beyond the nearer one, where one pass is 68 m deep along the swaths: two.
/// let sprayer = Vehicle { width: 24.0, turn_radius: 9.0, ..Default::default() };
/// assert_eq!(passes_for_turns(&sprayer, 50), 2);
/// ```
pub fn passes_for_turns(vehicle: &Vehicle, most: u32) -> u32 {
    let width = vehicle.width;
    if !(width.is_finite() && width > 0.0) {
        return 1;
    }
    // Deep enough for the turn between ends staggered along an edge at any angle to the
    // swaths: made level with the end further out, a turn `d` deep between ends `s` apart
    // along an edge at angle β reaches s·cot β + d beyond the nearer end, where passes `h`
    // deep give h / sin β; the most that needs is h = √(s² + d²) (at tan β = d / s).
    let depth = turn_depth(vehicle, width).hypot(width);
    // A millimetre's grace, so that a depth of exactly whole widths is not one pass more.
    let passes = ((depth - 1e-3) / width).ceil();
    if passes.is_finite() {
        (passes as u32).clamp(1, most.max(1))
    } else {
        most.max(1)
    }
}

/// The passes of `width` that can fit into a field with `boundary`, at most, with the one round
/// what they leave in its middle: pass `k` runs `(k - 1/2) width` inside the boundary, and none
/// runs deeper than half the narrower side of the boundary's box. The headland stage lays them
/// inward until one finds no room, so a bound is enough; `headlandPasses: "all"` asks for it.
///
/// ```
/// use furrow::headland::passes::passes_to_fill;
/// use geo::polygon;
///
/// // A strip 40 m across: passes at 3, 9 and 15 m in (a fourth, 21 m in, would be past its
/// // middle), and one round the 4 m they leave.
/// let strip = polygon![(x: 0., y: 0.), (x: 500., y: 0.), (x: 500., y: 40.), (x: 0., y: 40.)];
/// assert_eq!(passes_to_fill(&strip, 6.0), 4);
/// ```
pub fn passes_to_fill(boundary: &Polygon, width: f64) -> u32 {
    let Some(rect) = boundary.bounding_rect() else {
        return 0;
    };
    // `as` saturates, and takes NaN to 0.
    (rect.width().min(rect.height()) / (2.0 * width) + 1.5).floor() as u32
}

#[cfg(test)]
mod tests {
    use super::*;

    fn machine(width: f64, turn_radius: f64, reverse: bool) -> Vehicle {
        Vehicle {
            width,
            turn_radius,
            reverse,
            ..Default::default()
        }
    }

    /// The loop between ends `s` apart, by its three circles of radius `r`: the outer two
    /// centred `r` beyond each end sideways, the middle one touching both, `r` deeper than its
    /// centre.
    fn loop_depth(s: f64, r: f64) -> f64 {
        r + (4.0 * r * r - (r + s / 2.0).powi(2)).sqrt()
    }

    #[test]
    fn a_forward_machine_loops_between_close_swaths_and_u_turns_between_far_ones() {
        for r in [3.0, 5.0, 8.0, 12.5] {
            for k in 1..40 {
                let s = r * k as f64 / 10.0;
                let depth = turn_depth(&machine(s, r, false), s);
                let expected = if s < 2.0 * r { loop_depth(s, r) } else { r };
                assert!(
                    (depth - expected).abs() < 0.01,
                    "r {r}, spacing {s}: {depth} against {expected}"
                );
            }
        }
    }

    #[test]
    fn a_reversing_machine_needs_no_more_than_its_radius() {
        for (w, r) in [(3.0, 5.0), (6.0, 8.0), (2.0, 12.0)] {
            let depth = turn_depth(&machine(w, r, true), w);
            assert!(depth <= r + 0.01, "{w} m, r {r}: {depth}");
            assert!(
                passes_for_turns(&machine(w, r, true), 50)
                    < passes_for_turns(&machine(w, r, false), 50)
            );
        }
    }

    #[test]
    fn passes_hold_the_depth_and_no_more() {
        for (w, r) in [(3.0, 5.0), (6.0, 8.0), (24.0, 9.0), (12.0, 6.0), (0.5, 2.0)] {
            let v = machine(w, r, false);
            let n = passes_for_turns(&v, 50) as f64;
            let depth = turn_depth(&v, w);
            // The turn between ends staggered along an edge at β to the swaths, made level
            // with the end further out, reaches w·cot β + depth beyond the nearer end, where
            // passes h deep give h / sin β: it fits at every angle, and one pass fewer would
            // leave it out at some.
            let needs = |beta: f64| (w / beta.tan() + depth) * beta.sin();
            let most = (1..900)
                .map(|i| needs((i as f64 / 10.0).to_radians()))
                .fold(0.0, f64::max);
            assert!(
                n * w >= most - 1e-3 && (n - 1.0) * w < most,
                "{w} m, r {r}: {n} passes for {most}"
            );
        }
        // The bounds: at least one pass, at most the limit.
        assert_eq!(passes_for_turns(&machine(6.0, 0.0, false), 50), 1);
        assert_eq!(passes_for_turns(&machine(0.1, 200.0, false), 50), 50);
        assert_eq!(passes_for_turns(&machine(f64::NAN, 5.0, false), 50), 1);
    }

    #[test]
    fn json_is_a_count_auto_or_all() {
        let read = serde_json::from_str::<HeadlandPasses>;
        assert_eq!(read("0").ok(), Some(HeadlandPasses::Count(0)));
        assert_eq!(read("\"auto\"").ok(), Some(HeadlandPasses::Auto));
        for bad in ["-1", "2.5", "\"Auto\"", "null", "[2]", "4294967296"] {
            let e = read(bad).err().map(|e| e.to_string()).unwrap_or_default();
            assert!(
                e.contains("a whole number of passes, \"auto\" or \"all\""),
                "{bad}: {e}"
            );
        }
        assert_eq!(read("\"all\"").ok(), Some(HeadlandPasses::All));
        for p in [
            HeadlandPasses::Count(7),
            HeadlandPasses::Auto,
            HeadlandPasses::All,
        ] {
            let text = serde_json::to_string(&p).unwrap_or_default();
            assert_eq!(serde_json::from_str::<HeadlandPasses>(&text).ok(), Some(p));
        }
    }
}
