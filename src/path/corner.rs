//! Corners of a headland pass: rounded at the turning radius, or worked into with a manoeuvre.
//!
//! A headland pass is the exact offset of the field, its convex corners sharp. A machine that
//! works round such a corner on an arc of its turning radius leaves the crop between the arc and
//! the corner standing; one that works on into the corner, lifts, manoeuvres onto the next edge
//! (a loop, a three-point turn, a reversing turn) and lowers again at the corner works it, at
//! the cost of the manoeuvre. [`HeadlandCorners`] says which: always round (`round`), always
//! manoeuvre where rounding would leave crop (`manoeuvre`), or per corner the cheaper by the
//! estimated operation time, the crop rounding leaves counted as if worked at working speed as
//! the time objective counts it (`auto`). A manoeuvre that cannot stay in the field is never
//! chosen over a rounding that fits.
//!
//! ```
//! use furrow::path::corner::{reach_into_corner, rounding_crop_m2};
//! use std::f64::consts::FRAC_PI_2;
//!
//! // A square corner: a 6 m implement works on 3 m past the pass's corner, to the next edge.
//! assert!((reach_into_corner(6.0, FRAC_PI_2) - 3.0).abs() < 1e-9);
//! // Rounded at 8 m, the strip's outer side is an arc of 11 m: (1 - π/4) 11² m² stay standing.
//! let crop = rounding_crop_m2(8.0, 6.0, FRAC_PI_2);
//! assert!((crop - (1.0 - std::f64::consts::FRAC_PI_4) * 121.0).abs() < 1e-9);
//! ```

use super::curve;
use super::follow::follow_in;
use super::turn::{Area, Vehicle};
use geo::{Area as _, Coord, LineString, Polygon};
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// How a headland pass is driven at a corner sharper than the machine turns while working.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum HeadlandCorners {
    /// Passes are the field's offsets opened by a disc of the turning radius: every corner
    /// is an arc the machine drives while working, the crop outside it left standing.
    Round,
    /// Passes are exact offsets, worked into every corner where rounding would leave crop;
    /// the machine lifts there and manoeuvres onto the next edge.
    Manoeuvre,
    /// Passes are exact offsets; each corner is rounded or manoeuvred at, whichever takes
    /// less time with the crop rounding leaves counted as work to be done.
    #[default]
    Auto,
}

impl HeadlandCorners {
    /// Whether the passes are exact offsets of the field (not opened by the turning disc).
    pub fn exact(self) -> bool {
        self != HeadlandCorners::Round
    }
}

/// Crop rounding may leave at a corner, as a share of the width squared, under which a
/// corner is rounded even in `manoeuvre` mode (the chords of a curve drawn with many vertices).
pub const NEGLIGIBLE_CROP_SHARE: f64 = 0.01;

/// How far past a pass's corner of `deflection` radians (either way) the implement of `width`
/// can work on with all of it between the lines of the two edges' field sides: `(w/2)(1 -
/// |cos θ|) / sin θ` for the corner's inner angle `θ = π - deflection`. A square corner lets it
/// run on half a width (the bar then reaches the next edge); a sharp one (a dead end) or a
/// slight one hardly at all.
pub fn reach_into_corner(width: f64, deflection: f64) -> f64 {
    let inner = PI - deflection.abs().min(PI);
    let sin = inner.sin();
    if sin < 1e-9 {
        return 0.0;
    }
    (width / 2.0 * (1.0 - inner.cos().abs()) / sin).max(0.0)
}

/// The crop (square metres) left standing outside a corner of `deflection` radians rounded with
/// an arc of `radius`, by an implement of `width` working along it: the area between the
/// corner of the strip's outer side and its arc of `radius + width / 2`.
pub fn rounding_crop_m2(radius: f64, width: f64, deflection: f64) -> f64 {
    let d = deflection.abs();
    if d >= PI - 1e-9 {
        return f64::INFINITY;
    }
    let outer = radius + width / 2.0;
    (outer * outer * ((d / 2.0).tan() - d / 2.0)).max(0.0)
}

/// Whether the machine is to work a `stretch` of an exact headland pass (a polyline) rather
/// than the `shortcut` the turning circle takes across it: where every manoeuvre it needs stays
/// in `area`, and in `auto` mode where it also takes no longer than the shortcut and the crop
/// the shortcut leaves (the area between the two lines, counted as if worked at working
/// speed).
pub fn exact_stretch_pays(
    stretch: &[Coord],
    shortcut: &[Coord],
    v: &Vehicle,
    area: &Area,
    corners: HeadlandCorners,
) -> bool {
    let (path, manoeuvres) = follow_in(stretch, v, Some(area), corners);
    if !manoeuvres.iter().all(|m| m.inside) {
        return false;
    }
    if corners != HeadlandCorners::Auto {
        return true;
    }
    let work = v.working_speed.max(1e-9);
    let turn = v.turning_speed.max(1e-9);
    let mut exact_s = 0.0;
    let mut lifted = manoeuvres.iter().map(|m| m.pieces.clone()).peekable();
    for (i, piece) in path.iter().enumerate() {
        while lifted.peek().is_some_and(|r| r.end <= i) {
            lifted.next();
        }
        let up = lifted.peek().is_some_and(|r| r.contains(&i));
        exact_s += piece.length / if up { turn } else { work };
    }
    let (round, _) = follow_in(shortcut, v, Some(area), HeadlandCorners::Round);
    let ring: Vec<Coord> = stretch
        .iter()
        .chain(shortcut.iter().rev())
        .copied()
        .collect();
    let crop = Polygon::new(LineString::new(ring), vec![]).unsigned_area();
    let round_s = curve::length(&round) / work + crop / (v.width.max(1e-9) * work);
    exact_s <= round_s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reach_keeps_the_bar_between_the_two_edges() {
        // Corner at the origin between the field sides y = 0 (edge a, driven along -x... here
        // along +x towards the corner) and the line through the origin at inner angle θ.
        let w = 6.0;
        for deg in [20.0_f64, 45.0, 60.0, 90.0, 120.0, 150.0, 175.0] {
            let inner = deg.to_radians();
            let deflection = PI - inner;
            let e = reach_into_corner(w, deflection);
            // The field: above y = 0 and to the right of the side at angle θ (inward normal n_b).
            let n_b = (inner.sin(), -inner.cos());
            let dist_b = |x: f64, y: f64| x * n_b.0 + y * n_b.1;
            // The pass's corner, w/2 from both sides; driving along -x towards the side b.
            let p = ((w / 2.0) / (inner / 2.0).tan(), w / 2.0);
            let x = p.0 - e;
            let low = dist_b(x, 0.0).min(dist_b(x, w));
            assert!(low > -1e-9, "{deg}°: the bar reaches {low} past the side");
            // And it could not have gone further: the bar touches the side.
            assert!(low < 1e-6, "{deg}°: {low} short of the side");
        }
    }

    #[test]
    fn rounding_crop_grows_with_the_corner() {
        let slight = rounding_crop_m2(8.0, 6.0, 0.1);
        let square = rounding_crop_m2(8.0, 6.0, PI / 2.0);
        let sharp = rounding_crop_m2(8.0, 6.0, 2.5);
        assert!(slight < NEGLIGIBLE_CROP_SHARE * 36.0);
        assert!(slight < square && square < sharp);
        assert!(rounding_crop_m2(8.0, 6.0, PI).is_infinite());
    }
}
