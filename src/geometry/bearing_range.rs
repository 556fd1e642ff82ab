//! Ranges of forbidden driving directions.
//!
//! A range `[from, to]` holds the compass bearings clockwise from `from` to `to` (degrees). Since
//! a swath driven one way or the other is the same swath, a range forbids swath directions: the
//! bearings in it and their reverses. `[20, 70]` forbids driving at 20-70 degrees and at 200-250.

use crate::sort::SharedSort;
use serde::{Deserialize, Serialize};

/// A range of compass bearings, clockwise from `from_deg` to `to_deg` (degrees, 0 = north).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(from = "[f64; 2]", into = "[f64; 2]")]
pub struct BearingRange {
    /// Start of the range, compass degrees.
    pub from_deg: f64,
    /// End of the range, compass degrees, reached clockwise from `from_deg`.
    pub to_deg: f64,
}

impl From<[f64; 2]> for BearingRange {
    fn from([from_deg, to_deg]: [f64; 2]) -> Self {
        BearingRange { from_deg, to_deg }
    }
}

impl From<BearingRange> for [f64; 2] {
    fn from(r: BearingRange) -> Self {
        [r.from_deg, r.to_deg]
    }
}

impl BearingRange {
    /// Width of the range, degrees, in `[0, 360]`: a range whose end lies 360 degrees or more
    /// clockwise of its start (`[0, 360]`, `[-90, 270]`) goes all the way round.
    fn width_deg(&self) -> f64 {
        let span = self.to_deg - self.from_deg;
        if span >= 360.0 {
            360.0
        } else {
            span.rem_euclid(360.0)
        }
    }

    /// Whether driving along `bearing` (compass radians), either way, is forbidden.
    ///
    /// ```
    /// use furrow::geometry::BearingRange;
    ///
    /// let drains = BearingRange { from_deg: 350.0, to_deg: 10.0 };
    /// assert!(drains.forbids(0f64.to_radians()));
    /// assert!(drains.forbids(185f64.to_radians())); // the same swath, driven south
    /// assert!(!drains.forbids(90f64.to_radians()));
    /// ```
    pub fn forbids(&self, bearing: f64) -> bool {
        let width = self.width_deg();
        if width >= 180.0 {
            return true;
        }
        // A millionth of a degree of slack: a bearing on the range's end is in it, whatever the
        // rounding of degrees to radians and back.
        let d = (bearing.to_degrees() - self.from_deg + 1e-6).rem_euclid(180.0);
        d <= width + 2e-6
    }

    /// Whether both ends are finite numbers.
    pub fn is_finite(&self) -> bool {
        self.from_deg.is_finite() && self.to_deg.is_finite()
    }
}

/// Whether a set of ranges forbids every swath direction.
///
/// ```
/// use furrow::geometry::{forbids_every_direction, BearingRange};
///
/// let r = |a, b| BearingRange { from_deg: a, to_deg: b };
/// assert!(forbids_every_direction(&[r(0.0, 100.0), r(90.0, 180.0)]));
/// assert!(!forbids_every_direction(&[r(0.0, 100.0), r(101.0, 179.0)]));
/// assert!(forbids_every_direction(&[r(300.0, 130.0)])); // 190 degrees wide
/// assert!(forbids_every_direction(&[r(0.0, 360.0)])); // all the way round
/// ```
pub fn forbids_every_direction(ranges: &[BearingRange]) -> bool {
    // Intervals on the circle of swath directions [0, 180), unrolled so none wraps.
    let mut intervals: Vec<(f64, f64)> = Vec::with_capacity(ranges.len() * 2);
    for r in ranges {
        let width = r.width_deg();
        if width >= 180.0 {
            return true;
        }
        let start = r.from_deg.rem_euclid(180.0);
        let end = start + width;
        if end > 180.0 {
            intervals.push((start, 180.0));
            intervals.push((0.0, end - 180.0));
        } else {
            intervals.push((start, end));
        }
    }
    intervals.shared_sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut reached = 0.0;
    for (start, end) in intervals {
        if start > reached {
            return false;
        }
        reached = f64::max(reached, end);
    }
    reached >= 180.0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_and_writes_as_a_pair() {
        let r: BearingRange = serde_json::from_str("[20, 70]").unwrap();
        assert_eq!(
            r,
            BearingRange {
                from_deg: 20.0,
                to_deg: 70.0
            }
        );
        assert_eq!(serde_json::to_string(&r).unwrap(), "[20.0,70.0]");
    }

    #[test]
    fn ranges_forbid_both_ways() {
        let r = BearingRange {
            from_deg: 200.0,
            to_deg: 250.0,
        };
        for deg in [20.0, 45.0, 70.0, 200.0, 250.0] {
            assert!(r.forbids(f64::to_radians(deg)), "{deg}");
        }
        for deg in [19.0, 71.0, 110.0, 199.0, 251.0] {
            assert!(!r.forbids(f64::to_radians(deg)), "{deg}");
        }
    }

    #[test]
    fn a_range_all_the_way_round_forbids_everything() {
        let r = |a, b| BearingRange {
            from_deg: a,
            to_deg: b,
        };
        for full in [
            r(0.0, 360.0),
            r(-90.0, 270.0),
            r(10.0, 370.0),
            r(0.0, 720.5),
        ] {
            assert!(forbids_every_direction(&[full]), "{full:?}");
            for deg in [0.0, 45.0, 90.0, 179.0, 271.0] {
                assert!(full.forbids(f64::to_radians(deg)), "{full:?} {deg}");
            }
        }
        // Start and end at the same bearing, without going round: that bearing alone.
        for single in [r(10.0, 10.0), r(370.0, 10.0)] {
            assert!(!forbids_every_direction(&[single]), "{single:?}");
            assert!(single.forbids(f64::to_radians(10.0)));
            assert!(!single.forbids(f64::to_radians(90.0)));
        }
    }

    #[test]
    fn empty_set_forbids_nothing() {
        assert!(!forbids_every_direction(&[]));
    }
}
