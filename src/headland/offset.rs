//! Offsets of regions and lines with round joins: insets (inward buffers), outsets, and the
//! morphological opening that rounds corners to a turning radius.
//!
//! Round joins are approximated by chords; their step is chosen so that no chord falls more than
//! [`ARC_TOLERANCE_M`] short of the true arc (geo's default step leaves 4.5 cm at 9 m).

use crate::geometry::{buffer_line, buffer_region};
use geo::{Area, LineString, MultiPolygon};

/// The largest gap (metres) between a rounded corner of an offset and the true circular arc.
/// An arc offset again keeps its chords' gap, so passes built from two offsets stay within it.
/// The cost of a positive buffer grows with the number of arc points it is given, so this
/// is as coarse as the 1 cm the passes are held to allows.
pub const ARC_TOLERANCE_M: f64 = 3e-3;
/// Offset parts smaller than this (square metres) are slivers of the buffer and are dropped.
pub const MIN_PART_AREA_M2: f64 = 1e-2;

/// The chord angle (radians) that keeps an arc of `radius` within [`ARC_TOLERANCE_M`].
pub fn round_step(radius: f64) -> f64 {
    step_within(radius, ARC_TOLERANCE_M)
}

fn step_within(radius: f64, tolerance: f64) -> f64 {
    // A chord of angle a on radius r falls short of the arc by r (1 - cos(a / 2)).
    let step = 2.0 * (1.0 - tolerance / radius.max(tolerance)).acos();
    step.clamp(0.01, 0.2)
}

/// The part of `region` at least `distance` metres inside its boundary (holes included).
///
/// ```
/// use furrow::headland::offset::inset;
/// use geo::{polygon, Area, MultiPolygon};
///
/// let square = MultiPolygon::new(vec![polygon![(x: 0., y: 0.), (x: 10., y: 0.), (x: 10., y: 10.), (x: 0., y: 10.)]]);
/// assert!((inset(&square, 2.0).unsigned_area() - 36.0).abs() < 1e-9);
/// ```
pub fn inset(region: &MultiPolygon, distance: f64) -> MultiPolygon {
    if distance <= 0.0 {
        return region.clone();
    }
    drop_slivers(buffer_region(region, -distance, round_step(distance)))
}

/// [`inset`] with round joins held only to `tolerance` metres: fewer points, for an estimate
/// (the direction search measures many directions on one coarse inset).
pub fn inset_coarse(region: &MultiPolygon, distance: f64, tolerance: f64) -> MultiPolygon {
    if distance <= 0.0 {
        return region.clone();
    }
    let step = 2.0 * (1.0 - tolerance / distance.max(tolerance)).acos();
    drop_slivers(buffer_region(region, -distance, step.clamp(0.01, 1.0)))
}

/// The points within `distance` metres of `region` (a positive buffer with round joins).
pub fn outset(region: &MultiPolygon, distance: f64) -> MultiPolygon {
    if distance <= 0.0 {
        return region.clone();
    }
    drop_slivers(buffer_region(region, distance, round_step(distance)))
}

/// [`outset`] with arcs held to a fifth of [`ARC_TOLERANCE_M`], for outlines as drawn (no arcs
/// of their own, so cheap) whose offsets are offset again.
pub fn outset_fine(region: &MultiPolygon, distance: f64) -> MultiPolygon {
    if distance <= 0.0 {
        return region.clone();
    }
    let step = step_within(distance, ARC_TOLERANCE_M / 5.0);
    drop_slivers(buffer_region(region, distance, step))
}

/// The points within `distance` metres of a line, with round joins and round ends.
///
/// Its arcs are held to a fifth of [`ARC_TOLERANCE_M`]: they are offset again when the pass is
/// rounded, and the lines buffered here are boundary edges, without arcs of their own, so the
/// finer step costs little.
pub fn line_band(line: &LineString, distance: f64) -> MultiPolygon {
    let step = step_within(distance, ARC_TOLERANCE_M / 5.0);
    buffer_line(line, distance, step)
}

/// The opening of `region` by a disc of `radius`: the union of all discs of that radius inside
/// it. Its convex corners are arcs of at least `radius`, and necks narrower than `2 * radius`
/// are cut; it never reaches outside `region`.
///
/// ```
/// use furrow::headland::offset::open;
/// use geo::{polygon, Area, MultiPolygon};
///
/// // Opening a 20 m square by 5 m rounds its four corners: each loses (1 - π/4) 25 m².
/// let square = MultiPolygon::new(vec![polygon![(x: 0., y: 0.), (x: 20., y: 0.), (x: 20., y: 20.), (x: 0., y: 20.)]]);
/// let lost = 400.0 - open(&square, 5.0).unsigned_area();
/// assert!((lost - 4.0 * (1.0 - std::f64::consts::FRAC_PI_4) * 25.0).abs() < 0.2);
/// ```
pub fn open(region: &MultiPolygon, radius: f64) -> MultiPolygon {
    if radius <= 0.0 {
        return region.clone();
    }
    outset(&inset(region, radius), radius)
}

/// Drops the parts of a buffer result smaller than [`MIN_PART_AREA_M2`].
pub fn drop_slivers(m: MultiPolygon) -> MultiPolygon {
    MultiPolygon::new(
        m.0.into_iter()
            .filter(|p| p.unsigned_area() >= MIN_PART_AREA_M2)
            .collect(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use geo::polygon;

    #[test]
    fn opening_keeps_what_is_wide_enough_and_cuts_necks() {
        // Two 40 m squares joined by a 6 m neck: opened by 5 m the neck goes.
        let dumbbell = MultiPolygon::new(vec![polygon![
            (x: 0., y: 0.), (x: 40., y: 0.), (x: 40., y: 17.), (x: 60., y: 17.), (x: 60., y: 0.),
            (x: 100., y: 0.), (x: 100., y: 40.), (x: 60., y: 40.), (x: 60., y: 23.), (x: 40., y: 23.),
            (x: 40., y: 40.), (x: 0., y: 40.)
        ]]);
        assert_eq!(open(&dumbbell, 5.0).0.len(), 2);
        assert_eq!(open(&dumbbell, 2.0).0.len(), 1);
    }

    #[test]
    fn outset_of_a_region_with_a_hole_fills_the_hole_when_it_is_small() {
        let ring = MultiPolygon::new(vec![polygon!(
            exterior: [(x: 0., y: 0.), (x: 20., y: 0.), (x: 20., y: 20.), (x: 0., y: 20.)],
            interiors: [[(x: 8., y: 8.), (x: 12., y: 8.), (x: 12., y: 12.), (x: 8., y: 12.)]],
        )]);
        let grown = outset(&ring, 3.0);
        assert_eq!(grown.0.len(), 1);
        assert!(grown.0[0].interiors().is_empty());
        let area = 400.0 + 4.0 * 60.0 + std::f64::consts::PI * 9.0;
        assert!((grown.unsigned_area() - area).abs() < 0.2);
    }
}
