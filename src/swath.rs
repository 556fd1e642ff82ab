//! Swaths: the straight strips the machine works, one working width wide, parallel to the driving
//! direction, covering the inner field.
//!
//! Centre lines are placed a working width apart across the inner field, the first half a width
//! from its edge (Zhou et al. 2.2.3). The strip left at the far side when the field's width is
//! not a whole number of working widths is still worked: the last line is moved back so that its
//! strip ends at the edge, overlapping its neighbour, rather than dropped (which leaves crop
//! standing, a known complaint about Fields2Cover). Lines are cut where they leave the inner field
//! or cross an obstacle; pieces shorter than a minimum length are left to the headland passes.

use crate::error::{ErrorCode, PlanError};
use crate::geometry::SweepFrame;
use geo::{Coord, Line, MultiPolygon};

/// Swath-line spacing below this fraction of the width is not worth an extra, overlapping line.
const LEFTOVER_TOLERANCE: f64 = 1e-3;
/// Most swath lines a field may need at one bearing (a 40 km field at 0.4 m, a 2 km field at
/// 2 cm); beyond that the width is a mistake, and the plan would take seconds and gigabytes.
pub const MAX_SWATH_LINES: usize = 100_000;

/// One swath: a straight piece of a swath line inside the inner field.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Swath {
    /// Index among all swaths of the plan, ordered across the field, then along each line.
    pub index: usize,
    /// Index of the swath line it lies on, counted across the field (0 = leftmost looking along
    /// the driving direction).
    pub line_index: usize,
    /// Its centre line, from the end with the smaller to the end with the larger `along`
    /// coordinate, i.e. pointing in the swath direction. Driving may go either way.
    pub centre: Line,
    /// Offset of its line across the field, metres (the sweep frame's `across` coordinate).
    pub across: f64,
    /// Start and end along the line, metres (the sweep frame's `along` coordinates).
    pub along: (f64, f64),
}

impl Swath {
    /// Length of the swath, metres.
    pub fn length(&self) -> f64 {
        self.along.1 - self.along.0
    }
}

/// The swaths of a field at one driving direction.
#[derive(Debug, Clone)]
pub struct Swaths {
    /// The swath direction, compass radians in `[0, π)`.
    pub bearing: f64,
    /// The working width, metres.
    pub width: f64,
    /// The frame in which swath lines are `across = const`.
    pub frame: SweepFrame,
    /// The swaths, ordered by line, then along the line.
    pub swaths: Vec<Swath>,
    /// Pieces dropped because they were shorter than the minimum swath length.
    pub dropped: usize,
    /// Where the implement is lifted over small (class A) obstacles, ordered by swath.
    pub lifts: Vec<Lift>,
}

/// A stretch of a swath where the implement is lifted over a small obstacle (class A) that the
/// swath runs past.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Lift {
    /// Index of the swath.
    pub swath: usize,
    /// Index of the obstacle (into the field's obstacles).
    pub obstacle: usize,
    /// Start and end along the swath line, metres (the sweep frame's `along` coordinates).
    pub along: (f64, f64),
}

/// The stretches where swaths pass over the given obstacles (index and outline): wherever an
/// obstacle reaches into a swath's strip, the implement is lifted over the obstacle's length
/// along the swath.
///
/// ```
/// use furrow::swath::{generate, lifts};
/// use geo::{polygon, MultiPolygon};
///
/// let strip = polygon![(x: 0., y: 0.), (x: 30., y: 0.), (x: 30., y: 100.), (x: 0., y: 100.)];
/// let swaths = generate(&MultiPolygon::new(vec![strip]), 0.0, 6.0, 6.0)?;
/// // A 2 m pole at x = 11..13, y = 50..52: in the strip of the swath at x = 9 and the one at x = 15.
/// let pole = polygon![(x: 11., y: 50.), (x: 13., y: 50.), (x: 13., y: 52.), (x: 11., y: 52.)];
/// let l = lifts(&swaths, &[(0, &pole)]);
/// assert_eq!(l.iter().map(|l| l.swath).collect::<Vec<_>>(), vec![1, 2]);
/// assert_eq!(l[0].along, (50.0, 52.0));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn lifts(swaths: &Swaths, obstacles: &[(usize, &geo::Polygon)]) -> Vec<Lift> {
    let half = swaths.width / 2.0;
    let mut out = Vec::new();
    for &(index, polygon) in obstacles {
        let mut c = (f64::INFINITY, f64::NEG_INFINITY);
        let mut a = (f64::INFINITY, f64::NEG_INFINITY);
        for &p in &polygon.exterior().0 {
            let (x, y) = swaths.frame.project(p);
            c = (c.0.min(x), c.1.max(x));
            a = (a.0.min(y), a.1.max(y));
        }
        for s in &swaths.swaths {
            if s.across + half <= c.0 || s.across - half >= c.1 {
                continue;
            }
            let from = a.0.max(s.along.0);
            let to = a.1.min(s.along.1);
            if from < to {
                out.push(Lift {
                    swath: s.index,
                    obstacle: index,
                    along: (from, to),
                });
            }
        }
    }
    out.sort_by(|x, y| {
        (x.swath, x.along.0)
            .partial_cmp(&(y.swath, y.along.0))
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    out
}

/// Offsets (across the field) of the swath lines covering `[lo, hi]` with strips of `width`.
///
/// The first line is `width / 2` inside `lo`; lines follow `width` apart; if a strip narrower
/// than `width` remains at `hi`, one more line is placed `width / 2` inside `hi`.
///
/// ```
/// use furrow::swath::line_offsets;
///
/// assert_eq!(line_offsets(0.0, 12.0, 6.0), vec![3.0, 9.0]);
/// assert_eq!(line_offsets(0.0, 14.0, 6.0), vec![3.0, 9.0, 11.0]);
/// assert_eq!(line_offsets(0.0, 4.0, 6.0), vec![2.0]);
/// ```
pub fn line_offsets(lo: f64, hi: f64, width: f64) -> Vec<f64> {
    let extent = hi - lo;
    if extent.is_nan() || width.is_nan() || extent <= 0.0 || width <= 0.0 {
        return Vec::new();
    }
    if extent <= width {
        return vec![(lo + hi) / 2.0];
    }
    let full = (extent / width + LEFTOVER_TOLERANCE).floor() as usize;
    let mut offsets: Vec<f64> = (0..full).map(|i| lo + (i as f64 + 0.5) * width).collect();
    if extent - full as f64 * width > LEFTOVER_TOLERANCE * width {
        offsets.push(hi - width / 2.0);
    }
    offsets
}

/// Generates the swaths covering `inner` at swath direction `bearing` (compass radians).
///
/// ```
/// use furrow::swath::generate;
/// use geo::{polygon, MultiPolygon};
///
/// // A 30 m wide, 100 m long strip running north, worked 6 m wide: 5 swaths of 100 m.
/// let strip = polygon![(x: 0., y: 0.), (x: 30., y: 0.), (x: 30., y: 100.), (x: 0., y: 100.)];
/// let swaths = generate(&MultiPolygon::new(vec![strip]), 0.0, 6.0, 6.0)?;
/// assert_eq!(swaths.swaths.len(), 5);
/// assert!((swaths.swaths[0].centre.start.x - 3.0).abs() < 1e-9);
/// assert!((swaths.swaths[0].length() - 100.0).abs() < 1e-9);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn generate(
    inner: &MultiPolygon,
    bearing: f64,
    width: f64,
    min_length: f64,
) -> Result<Swaths, PlanError> {
    let frame = SweepFrame::new(bearing);
    let mut swaths = Vec::new();
    let mut dropped = 0;
    if let Some((lo, hi)) = frame.across_extent(inner) {
        let lines = (hi - lo) / width;
        if lines.is_nan() || lines > MAX_SWATH_LINES as f64 {
            return Err(PlanError::new(
                ErrorCode::FieldTooLarge,
                format!(
                    "at {width} m working width the field needs {lines:.0} swaths; the planner plans up to {MAX_SWATH_LINES}"
                ),
            ));
        }
        let offsets = line_offsets(lo, hi, width);
        let pieces = frame.clip(inner, &offsets);
        for (line_index, (&across, line)) in offsets.iter().zip(&pieces).enumerate() {
            for &(a0, a1) in line {
                if a1 - a0 < min_length.max(1e-6) {
                    dropped += 1;
                    continue;
                }
                swaths.push(Swath {
                    index: swaths.len(),
                    line_index,
                    centre: Line::new(frame.point(across, a0), frame.point(across, a1)),
                    across,
                    along: (a0, a1),
                });
            }
        }
    }
    Ok(Swaths {
        bearing,
        width,
        frame,
        swaths,
        dropped,
        lifts: Vec::new(),
    })
}

impl Swaths {
    /// The end of swath `i` at its start (`at_end == false`) or end.
    pub fn end_point(&self, i: usize, at_end: bool) -> Option<Coord> {
        self.swaths
            .get(i)
            .map(|s| if at_end { s.centre.end } else { s.centre.start })
    }

    /// Total length of all swaths, metres.
    pub fn total_length(&self) -> f64 {
        self.swaths.iter().map(Swath::length).sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use geo::{polygon, Contains, Point};
    use std::f64::consts::FRAC_PI_2;

    #[test]
    fn leftover_strip_gets_an_overlapping_swath() {
        // 32 m across at 6 m: five full strips and a 2 m strip, worked by a sixth line at 29 m.
        let offsets = line_offsets(0.0, 32.0, 6.0);
        assert_eq!(offsets, vec![3.0, 9.0, 15.0, 21.0, 27.0, 29.0]);
    }

    #[test]
    fn swaths_split_at_holes_and_stay_inside() {
        let field = polygon!(
            exterior: [(x: 0., y: 0.), (x: 100., y: 0.), (x: 100., y: 60.), (x: 0., y: 60.)],
            interiors: [[(x: 40., y: 20.), (x: 60., y: 20.), (x: 60., y: 40.), (x: 40., y: 40.)]],
        );
        let inner = MultiPolygon::new(vec![field.clone()]);
        // Swaths running east (bearing 90 degrees): ten lines at y = 57, 51, ..., 3.
        let s = generate(&inner, FRAC_PI_2, 6.0, 6.0).unwrap();
        let through_hole = s
            .swaths
            .iter()
            .filter(|w| (20.0..=40.0).contains(&w.centre.start.y));
        assert_eq!(through_hole.count(), 8); // lines at y = 21, 27, 33, 39, each in two
        for w in &s.swaths {
            let mid = Point((w.centre.start + w.centre.end) / 2.0);
            assert!(field.contains(&mid));
            assert!(w.centre.start.x < w.centre.end.x, "swaths point east");
        }
        assert_eq!(s.swaths.len(), 6 + 4 * 2);
    }

    #[test]
    fn short_pieces_are_dropped() {
        // A triangle: the lines near its tip are short.
        let tri = polygon![(x: 0., y: 0.), (x: 100., y: 0.), (x: 0., y: 50.)];
        let s = generate(&MultiPolygon::new(vec![tri]), 0.0, 6.0, 10.0).unwrap();
        assert!(s.dropped > 0);
        assert!(s.swaths.iter().all(|w| w.length() >= 10.0));
    }
}
